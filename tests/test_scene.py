"""The scene module against a real viser server (no browser): which nodes a view becomes, and that
nodes are updated in place rather than re-created (a re-created node costs the browser a shader compile)."""

from __future__ import annotations

import dataclasses
import random

import numpy as np
import pytest
import viser

from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.ui.app import free_port
from apf_viz.ui.scene import (
    DENSE,
    GRID_SECTION_PX,
    VIEW_PX,
    SceneRenderer,
    cells_label_at,
    frame_label_at,
    grid_steps,
    scene_detail,
)
from apf_viz.workbench.session import Session


@pytest.fixture
def renderer():
    server = viser.ViserServer(port=free_port(), verbose=False)
    yield SceneRenderer(server)
    server.stop()


def session_of(k: int) -> Session:
    rng = random.Random(k)
    return Session(random_solvable_start(k, rng), random_pattern(k, rng), seed=1)


def _colour(renderer, name: str) -> list[int]:
    return np.asarray(renderer.nodes()[name].colors).reshape(-1, 3)[0].tolist()


def test_robots_are_flat_discs_in_their_legend_colour_with_a_nose_on_their_own_plus_y(renderer):
    s = Session([(0, 0), (2, 1), (3, 3)], [(0, 0), (1, 0), (2, 0)], y_up=[True, False, True])
    view = s.view()
    renderer.render(view)
    robots = renderer.nodes()["/robots/off"]
    assert robots.point_shading == "flat" and robots.point_shape == "circle"  # unlit: the swatch's colour
    assert _colour(renderer, "/robots/off") == list(view.legend["off"].color)
    noses = np.asarray(renderer.nodes()["/robots/y_axes"].points)
    assert noses[0, 1] > 0 and noses[1, 1] < 1  # robot 1 at y = 1 is flipped: its nose points down


def test_phase_last_actor_and_selection_are_rings_under_the_robot(renderer):
    s = Session([(0, 0), (2, 1), (3, 3)], [(0, 0), (1, 0), (2, 0)], scheduler="manual")
    s.click((2, 1))  # robot 1 looks: it is selected, acted last and has looked
    renderer.render(s.view())
    robot = 2 * 0.3  # the robot's disc
    for name in ("/phase/looked", "/ring/last", "/ring/selected"):
        handle = renderer.nodes()[name]
        assert handle.point_shape == "circle" and handle.visible
        assert np.asarray(handle.points)[:, :2].tolist() == [[2.0, 1.0]]
    sizes = [renderer.nodes()[n].point_size for n in ("/phase/looked", "/ring/last", "/ring/selected")]
    assert robot * 0.5 < sizes[0] < sizes[1] < sizes[2]  # each a ring around the smaller one


def test_many_robots_are_one_point_cloud_per_light(renderer):
    s = session_of(DENSE + 50)
    renderer.render(s.view())
    clouds = {
        n: h
        for n, h in renderer.nodes().items()
        if n.startswith("/robots/") and n != "/robots/y_axes" and not n.startswith("/robots/outline")
    }
    assert set(clouds) == {"/robots/off"}
    assert len(clouds["/robots/off"].points) == DENSE + 50
    assert len(renderer.nodes()["/robots/y_axes"].points) == DENSE + 50


def test_y_axis_diamonds_are_drawn_only_where_a_browser_is_zoomed_in_enough_to_see_them(renderer):
    s = session_of(1000)  # framed whole, a cell is about a pixel: a diamond would be a speck
    renderer.render(s.view())
    renderer.frame_initial_camera(renderer.server.initial_camera)
    renderer.render(s.view())
    assert not scene_detail(renderer.visible_height())[0]
    assert renderer.nodes()["/robots/y_axes"].visible is False
    renderer.view_cells = 20.0  # a browser zoomed in on a corner of the run
    renderer.render(s.view())
    noses = renderer.nodes()["/robots/y_axes"]
    assert noses.visible and len(noses.points) == 1000
    assert scene_detail(20.0)[0] and not scene_detail(200.0)[0]


def test_a_crowd_framed_whole_plays_without_outlines_and_gets_them_back_when_paused_or_zoomed_in(renderer):
    s = session_of(1000)
    renderer.render(s.view())
    renderer.frame_initial_camera(renderer.server.initial_camera)
    outline = renderer.nodes()["/robots/outline"]
    playing = dataclasses.replace(s.view(), playing=True)
    renderer.render(playing)
    assert outline.visible is False  # a cell a few pixels wide: the discs alone, while it plays
    renderer.render(s.view())  # paused: every robot on its outline
    assert outline.visible and len(outline.points) == 1000
    renderer.view_cells = 20.0  # a browser zoomed in on a corner of the run
    renderer.render(playing)
    assert outline.visible and len(outline.points) == 1000
    assert scene_detail(30.0)[1] and not scene_detail(60.0)[1]
    small = session_of(100)  # a hundred robots framed whole: outlined while playing too
    renderer.view_cells = None
    renderer.render(small.view())
    renderer.frame_initial_camera(renderer.server.initial_camera)
    renderer.render(dataclasses.replace(small.view(), playing=True))
    assert outline.visible and len(outline.points) == 100


def test_line_sets_and_halos_are_updated_in_place_and_hidden_when_empty(renderer):
    s = session_of(12)
    s.selected = 0
    renderer.render(s.view())
    s.step()  # robot picked by the scheduler looks: a halo appears
    renderer.render(s.view())
    halos = dict(renderer.nodes())
    for _ in range(40):
        s.step()
        renderer.render(s.view())
    for name, handle in halos.items():
        assert renderer.nodes()[name] is handle, f"{name} was re-created"
    assert renderer.selection is not None
    renderer.selection._segments("/rays", np.zeros((0, 2, 3)), (0, 0, 0), 0.1)
    assert renderer.nodes()["/rays"].visible is False


def test_target_cells_change_colour_in_edit_pattern_mode(renderer):
    s = Session([(0, 0), (2, 1), (3, 3)], [(0, 0), (1, 0), (2, 0)], y_up=[True, True, True])
    renderer.render(s.view())
    targets = renderer.nodes()["/targets"]
    run_colour = np.asarray(targets.colors).tolist()
    s.set_mode("edit-pattern")
    renderer.render(s.view())
    assert renderer.nodes()["/targets"] is targets
    assert np.asarray(targets.colors).tolist() != run_colour


def _pending_session(k: int) -> Session:
    """A run stepped until some robot has computed a move it has not made yet."""
    s = session_of(k)
    while not any(r.pending is not None for r in s.view().robots):
        assert s.step(), "the run ended before any robot computed a move"
    return s


def test_pending_moves_of_few_robots_are_line_segments(renderer):
    s = _pending_session(6)
    renderer.render(s.view())
    moves = {(r.position, r.pending) for r in s.view().robots if r.pending is not None}
    segments = np.asarray(renderer.nodes()["/pending"].points)
    assert {(tuple(map(int, a[:2])), tuple(map(int, b[:2]))) for a, b in segments} == moves
    assert "/pending_cells" not in renderer.nodes()


def test_pending_moves_of_many_robots_are_dots_on_their_destinations(renderer):
    s = _pending_session(DENSE + 1)
    renderer.render(s.view())
    destinations = {r.pending for r in s.view().robots if r.pending is not None}
    dots = np.asarray(renderer.nodes()["/pending_cells"].points)
    assert {(int(x), int(y)) for x, y, _ in dots} == destinations
    assert "/pending" not in renderer.nodes()


def test_grid_density_follows_the_width_of_the_run():
    assert grid_steps(39) == (True, 5)  # the built-in demo: a line per cell, every fifth darker
    assert grid_steps(61) == (False, 5)  # 100 robots: cells are too small to rule
    assert grid_steps(135) == (False, 10)  # 1,000 robots
    steps = (5, 10, 50, 100, 500, 1000, 5000, 10000)
    for width in range(1, 200_000, 7):
        cells, step = grid_steps(width)
        assert cells == (VIEW_PX / width >= 20)
        smaller = steps[: steps.index(step)]
        # the densest step whose lines are still GRID_SECTION_PX apart, so at most VIEW_PX /
        # GRID_SECTION_PX lines across (a software-rendered browser pays for every line)
        assert all(s * VIEW_PX / width < GRID_SECTION_PX for s in smaller)
        if step < steps[-1]:
            assert step * VIEW_PX / width >= GRID_SECTION_PX and width / step <= VIEW_PX / GRID_SECTION_PX


def test_a_run_at_the_edge_of_the_grid_is_drawn_exactly_around_a_nearby_origin(renderer):
    from apf_viz.core.grid import COORD_LIMIT

    far = COORD_LIMIT - 10  # float32 alone would round these to multiples of 65,536
    start = [(far, -far), (far + 2, -far + 1), (far + 3, -far + 3)]
    s = Session(start, [(0, 0), (1, 0), (2, 0)], y_up=[True, False, True])
    s.selected = 0
    renderer.render(s.view())
    ox, oy = renderer.origin
    assert abs(ox - far) < 10 and abs(oy + far) < 10
    drawn = np.asarray(renderer.nodes()["/robots/off"].points)[:, :2]
    assert drawn.tolist() == [[x - ox, y - oy] for x, y in start]  # exact, not rounded
    rays = np.asarray(renderer.nodes()["/rays"].points)[:, :, :2]
    assert {tuple(map(float, p)) for p in rays.reshape(-1, 2)} <= {(x - ox, y - oy) for x, y in start}
    # A click ray straight down onto a robot's drawn position names that robot's grid cell.
    x, y = renderer.to_scene(start[1])
    assert renderer.cell_of_ray((x, y, 50.0), (0.0, 0.0, -1.0)) == start[1]
    assert renderer.cell_of_ray((x, y, 50.0), (float("nan"), 0.0, -1.0)) is None


def test_numbers_beside_robots_and_a_red_mark_where_a_collision_happened(renderer):
    from pathlib import Path

    from apf_viz.ui.app import demo_session

    s = demo_session()
    renderer.render(s.view())
    texts = sorted(h.text for n, h in renderer.nodes().items() if n.startswith("/numbers/") and h.visible)
    assert texts == sorted(str(i) for i in range(10))
    s.set_numbers(False)
    renderer.render(s.view())
    assert not any(h.visible for n, h in renderer.nodes().items() if n.startswith("/numbers/"))
    trace = Path(__file__).parent / "literal_traces" / "collision.jsonl"
    s.load_trace(trace.name, trace.read_bytes())
    while s.engine.redo() is not None:
        pass
    v = s.view()
    renderer.render(v)
    marked = np.asarray(renderer.nodes()["/collision"].points)[:, :2]
    assert sorted(map(tuple, marked.tolist())) == sorted(renderer.to_scene(c) for c in v.collision[1])


def test_the_cameras_are_framed_again_when_a_new_run_starts():
    """Also when the new run is smaller than the old (framing used to follow growth only)."""
    import time

    from apf_viz.ui.app import App, demo_session

    app = App(demo_session(), port=free_port(), verbose=False)
    try:
        before = app.renderer.framed_pose
        small = [(x, y) for x in range(5) for y in range(2)]
        small[-1] = (5, 1)  # not mirror-symmetric about a robot-free row (Theorem 1)
        app.session.load_robots("small.json", ('{"robots": ' + str([list(p) for p in small]) + "}").encode())
        app.request_render()
        deadline = time.time() + 30
        while app.renderer.framed_pose == before or app.renderer.framed_pose != app.renderer.camera_pose():
            assert time.time() < deadline, "the cameras were not framed on the new run"
            time.sleep(0.1)
    finally:
        app.stop()


def test_a_cells_label_never_covers_a_robot():
    """Above the cells by default; below when robots stand above; beside them when robots stand both
    above and below (the Unsolvable box demo: its pattern is drawn between two rows of robots)."""
    cells = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], dtype=np.float32)
    far = np.array([[10, 10]], dtype=np.float32)
    assert cells_label_at(cells, far)[1] == pytest.approx(1.6)
    above = np.array([[0, 2], [1, 2]], dtype=np.float32)
    assert cells_label_at(cells, above)[1] == pytest.approx(-0.9)
    both = np.array([[0, 2], [1, 2], [0, -1], [1, -1]], dtype=np.float32)
    x, y, _ = cells_label_at(cells, both)
    assert x > 1 and y == 1  # to the right of the top row
    for rx, ry in both:  # and not on a robot
        assert not (abs(ry - y) < 0.8 and x - 0.5 <= rx)


def test_a_frames_label_goes_under_its_origin_unless_a_robot_or_its_number_is_there():
    alone = np.array([[10.0, 10.0]], dtype=np.float32)
    assert frame_label_at((0.0, 0.0), 1, alone)[:2] == (0.0, pytest.approx(-0.8))  # under its robot's disc
    assert frame_label_at((0.0, 0.0), -1, alone)[:2] == (0.0, pytest.approx(0.5))  # away from +y
    # A robot just under the origin (its number at its upper right reaches the label's row): beyond the
    # x arm instead, on the origin's row.
    under = np.array([[0.0, -1.0]], dtype=np.float32)
    x, y, _ = frame_label_at((0.0, 0.0), 1, under)
    assert x > 2 and y == 0


def test_a_camera_reframed_for_a_growing_run_leaves_room_beyond_the_sides_it_grew():
    from apf_viz.ui.browser_screen import inside as _inside
    from apf_viz.ui.scene import grown_box

    framed = (0.0, 0.0, 10.0, 5.0)
    grown = grown_box((0.0, 0.0, 11.0, 5.0), framed)  # the line reached one cell further right
    assert grown == (0.0, 0.0, 11.0 + 0.2 * 11.0, 5.0)  # only the side it grew past moves
    # Growing a cell at a time, the camera moves every few cells, not at every one.
    reframes, f = 0, framed
    for right in range(11, 41):
        box = (0.0, 0.0, float(right), 5.0)
        if not _inside(box, f):
            f, reframes = grown_box(box, f), reframes + 1
        assert _inside(box, f)
    assert 0 < reframes <= 8
    assert grown_box((-3.0, -1.0, 10.0, 5.0), framed)[:2] == (-3.0 - 2.6, -1.0 - 2.6)  # left and down


def test_zoomed_out_a_frames_label_does_not_cover_the_targets_label():
    """Over a 100-robot run a label is a cell or two tall (labels keep their size on screen): the targets'
    label under their bottom row and the leader's frame's label under its origin, just below, used to
    be drawn over each other."""
    from apf_viz.ui.scene import label_box, text_cells

    height = text_cells(80.0)  # the canvas shows 80 cells top to bottom
    assert height > 1.0 and text_cells(5.0) == pytest.approx(0.35)  # zoomed in: the least
    cells = np.array([[x, y] for x in range(10) for y in range(1, 11)], dtype=np.float32)
    robots = np.array([[x, 10.0] for x in range(10)] + [[x, 0.0] for x in range(12, 40)], dtype=np.float32)
    spot = cells_label_at(cells, robots, "targets", height)  # robots on the top row: below the cells
    assert spot[1] < 1.0 - height
    targets = label_box("targets", (spot[0], spot[1], spot[0]), height)
    frame = frame_label_at((0.0, 0.0), 1, robots, "the leader's frame", height, [targets])
    box = label_box("the leader's frame", (frame[0], frame[1], frame[0]), height)
    assert not (box[0] < targets[2] and targets[0] < box[2] and box[1] < targets[3] and targets[1] < box[3])
    # Without the targets' label in the way it goes under the origin, as when zoomed in.
    assert frame_label_at((0.0, 0.0), 1, robots, "the leader's frame", height)[1] == pytest.approx(
        -0.45 - height
    )


def test_the_first_click_of_a_two_click_tool_is_marked_until_the_second(renderer):
    """Edit, the move tool: after the first click the cell it picked shows a diamond and a word; the
    second click clears both (the Edit panel's hint says the same: test_ui_browser)."""
    s = Session([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (0, 1)], y_up=[True] * 4)
    s.set_mode("edit-pattern")
    s.set_tool("move")
    s.click((1, 0))
    view = s.view()
    assert view.anchor == (1, 0)
    renderer.render(view)
    mark = renderer.nodes()["/anchor"]
    assert mark.visible and mark.point_shape == "diamond"
    assert np.asarray(mark.points)[0, :2].tolist() == list(renderer.to_scene((1, 0)))
    assert renderer.nodes()["/anchor_label/0"].text.startswith("first click")
    s.click((4, 2))
    view = s.view()
    assert view.anchor is None
    renderer.render(view)
    assert not renderer.nodes()["/anchor"].visible and not renderer.nodes()["/anchor_label/0"].visible
    s.set_mode("run")
    assert s.view().anchor is None


def test_every_region_label_the_heart_shows_is_typeset_on_the_canvas():
    """The canvas writes the paper's symbols in Unicode; a label it could not set whole stayed raw
    (``H_B^C`` beside ``Hᵤᶜ``). Every region a decision of the heart's run tested, for every robot."""
    from apf_viz.ui.app import demo_session
    from apf_viz.workbench.view_model.legend import canvas_symbol

    s = demo_session()
    labels: set[str] = set()
    while s.step():
        for r in range(s.engine.k):
            s.selected = r
            why = s.view().why
            labels |= {m.label for m in why.regions} if why is not None else set()
    raw = sorted(label for label in labels if "_" in canvas_symbol(label) or "^" in canvas_symbol(label))
    assert "H_B^C" in " ".join(labels) and raw == []


class _ViserLikeCamera:
    """A browser's camera as viser 1.1 holds it: a value equal (np.allclose) to the one held is dropped,
    and what is held is the last value sent *or reported* (viser/_viser.py, CameraHandle's setters)."""

    def __init__(self, position, look_at, fov) -> None:
        self.held = {
            "position": np.asarray(position, float),
            "look_at": np.asarray(look_at, float),
            "fov": fov,
        }
        self.aspect = 1024 / 700
        self.sent: list[tuple[str, object]] = []

    def __getattr__(self, name):
        if name in ("position", "look_at", "fov"):
            return self.held[name]
        raise AttributeError(name)

    def __setattr__(self, name, value) -> None:
        if name in ("position", "look_at", "fov"):
            if np.allclose(self.held[name], value):
                return
            self.held[name] = np.asarray(value, float) if name != "fov" else value
            self.sent.append((name, value))
        else:
            object.__setattr__(self, name, value)


def test_a_framing_equal_to_a_late_report_is_still_sent():
    """Sent pose B; the page's late report says it is at A; framing A again must reach the page (it is
    on its way to B). Viser drops a value equal to the one it holds: the framing goes a hair off it."""
    from apf_viz.ui.browser_screen import _same_pose

    renderer = SceneRenderer(viser.ViserServer(port=free_port(), verbose=False))
    try:
        renderer.bounds = (0.0, 0.0, 6.0, 4.0)
        wanted, look_at, fov = renderer.camera_pose(1024 / 700)
        camera = _ViserLikeCamera(wanted, look_at, fov)  # what viser holds: the late report, equal to A
        position, _ = renderer.frame_camera(camera)
        sent = dict(camera.sent)
        assert "position" in sent and "look_at" in sent and "fov" in sent
        assert _same_pose(np.asarray(sent["position"]), np.asarray(position))  # the same pose to the eye
        elsewhere = _ViserLikeCamera((50.0, 50.0, 90.0), (50.0, 50.0, 0.0), 0.3)
        position, _ = renderer.frame_camera(elsewhere)
        assert dict(elsewhere.sent)["position"] == position  # unequal values go exactly as framed
    finally:
        renderer.server.stop()


def test_what_is_said_of_a_robot_is_one_label_beside_it():
    """Its number, Manual's next phase, "stale" and "diverges here" join in one label at the robot's upper
    right: none can pile onto another or be read as a neighbour's (Compare's diverging robot once had a
    label of its own half a cell under its number)."""
    from apf_viz.ui.scene import number_labels

    pts = [[0.0, 0.0], [3.0, 0.0], [6.0, 0.0]]
    labels = number_labels(pts, True, stale=(1, 2), diverged=2, next_phase=("look", "move", "compute"))
    assert [text for text, _ in labels] == [
        "0 → look",
        "1 → move stale",
        "2 → compute stale diverges here",
    ]
    assert [spot[:2] for _, spot in labels] == [(0.25, 0.3), (3.25, 0.3), (6.25, 0.3)]
    # Without numbers, only the robots something is said of.
    assert [text for text, _ in number_labels(pts, False, stale=(1,), diverged=2)] == [
        "stale",
        "diverges here",
    ]


def test_under_manual_each_robot_says_on_the_canvas_what_a_click_on_it_runs():
    server = viser.ViserServer(port=free_port(), verbose=False)
    try:
        s = Session([(0, 0), (2, 1), (4, 0)], [(0, 0), (1, 0), (2, 0)])
        s.set_scheduler("manual")
        renderer = SceneRenderer(server, selection=False)
        renderer.render(s.view())
        texts = [renderer.nodes()[f"/numbers/{i}"].text for i in range(3)]
        assert texts == ["0 → look", "1 → look", "2 → look"]
        s.click((2, 1))  # robot 1 Looks: its next phase is Compute
        renderer.render(s.view())
        assert renderer.nodes()["/numbers/1"].text == "1 → compute"
        s.set_scheduler("async")  # a scheduler that chooses: no phase words
        renderer.render(s.view())
        assert [renderer.nodes()[f"/numbers/{i}"].text for i in range(3)] == ["0", "1", "2"]
    finally:
        server.stop()


def test_a_long_label_makes_way_for_its_neighbours_numbers():
    """Robots a cell apart (Compare's runs, zoomed out): a robot's "2 stale diverges here" would cover
    its neighbour's number at its upper right; it moves below or to the left, and no two labels, nor a
    label and another robot, overlap where a free place exists."""
    from apf_viz.ui.scene.labels import _overlaps, number_labels, spec_box, spread

    pts = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]
    height = 0.6
    laid = spread(number_labels(pts, True, stale=(0,), diverged=0), pts, height)
    assert [text for text, *_ in laid] == ["0 stale diverges here", "1", "2", "3"]
    plain = number_labels(pts, True, ())[1:]
    assert [(t, p) for t, p, _ in laid[1:]] == plain  # the plain numbers stay where they were
    boxes = [spec_box(spec, height) for spec in laid]
    assert not any(_overlaps(a, b) for i, a in enumerate(boxes) for b in boxes[i + 1 :])
    discs = [(x - 0.4, y - 0.4, x + 0.4, y + 0.4) for x, y in pts[1:]]
    assert not any(_overlaps(boxes[0], d) for d in discs)
    # and it still touches its robot: within half a cell of its centre
    x0, y0, x1, y1 = boxes[0]
    assert max(x0 - 0.0, 0.0, 0.0 - x1) <= 0.5 and max(y0 - 0.0, 0.0, 0.0 - y1) <= 0.5


def test_without_numbers_manual_draws_no_label_per_robot_and_a_lone_stale_word_may_move():
    """A crowd shown without numbers gets no "→ look" per robot (a thousand labels in every frame); a word
    standing alone ("stale") is not a number: it moves aside like any long label."""
    from apf_viz.ui.scene.labels import number_labels, spread

    server = viser.ViserServer(port=free_port(), verbose=False)
    try:
        s = Session([(0, 0), (2, 1), (4, 0)], [(0, 0), (1, 0), (2, 0)])
        s.set_scheduler("manual")
        s.set_numbers(False)
        renderer = SceneRenderer(server, selection=False)
        renderer.render(s.view())
        assert not any(name.startswith("/numbers/") and h.visible for name, h in renderer.nodes().items())
    finally:
        server.stop()
    pts = [[0.0, 0.0], [1.0, 0.0]]
    laid = spread(number_labels(pts, False, stale=(0,)), [*pts, [0.5, 1.0]], 0.6)
    assert laid[0][0] == "stale" and laid[0][1][:2] != (0.25, 0.3)  # its place covered the robot above


def test_a_websocket_path_that_is_not_ascii_is_a_class_page():
    from apf_viz.workbench.classroom import Roles

    roles = Roles("secret")
    assert roles.role_of("/present/secret") == "presenter"
    assert roles.role_of("/present/sécret") == "class" and roles.role_of("/") == "class"


def test_a_dragged_box_takes_the_cells_it_was_pressed_and_released_in_both_included():
    from apf_viz.ui.scene.camera import covered_cells

    assert covered_cells((0.6, 0.6), (3.4, 2.4)) == ((1, 1), (3, 2))  # the cells pressed and released in
    assert covered_cells((3.4, 2.4), (0.6, 0.6)) == ((1, 1), (3, 2))  # dragged either way
    assert covered_cells((9.0001, -0.0001), (13.9999, 3.0)) == ((9, 0), (14, 3))  # from centre to centre
    assert covered_cells((2.2, 5.1), (2.4, 5.3)) == ((2, 5), (2, 5))  # inside one cell: that cell
    # Released short of the last cell's centre: that cell's row and column are still the box's.
    assert covered_cells((9.3, 0.2), (13.6, 2.7)) == ((9, 0), (14, 3))


def test_a_drawing_that_grew_far_and_shrank_back_gets_its_line_per_cell_again(renderer):
    """A cell painted far away widens the grid past a line per cell; erased, the grid is laid out for the
    drawing again (it kept the far one's coarse grid until a Demo was loaded)."""
    s = Session([(0, 0), (3, 0), (1, 2)], [(0, 0), (1, 0), (2, 0)], seed=1)
    s.set_mode("edit-pattern")

    def cell_lines() -> int:
        renderer.render(s.view())
        node = renderer.nodes()["/grid/cells"]
        return len(np.asarray(node.points)) if node.visible else 0

    assert cell_lines() > 0
    s.click((-30, 140))
    assert cell_lines() == 0  # 170 cells tall: too small to rule each
    s.click((-30, 140))  # erased again
    assert cell_lines() > 0


def test_the_leader_is_a_square_robot_on_the_canvas_in_the_legend_and_in_a_figure(renderer):
    """Told from a done robot (green, perhaps ringed orange) by more than hue: the leader's light has
    shape "square" in the algorithm's legend, and each renderer draws that shape, the others discs."""
    from apf_viz.figure.drawing import drawing_of
    from apf_viz.figure.svg import to_svg
    from apf_viz.figure.tikz import to_tikz
    from apf_viz.workbench.view_model.legend import legend_html, slide_legend

    s = session_of(7)
    for _ in range(20_000):
        if any(r.light == "leader" for r in s.view().robots):
            break
        s.step()
    view = s.view()
    lights = [r.light for r in view.robots]
    assert "leader" in lights and view.legend["leader"].shape == "square"
    renderer.render(view)
    nodes = renderer.nodes()
    leader = nodes["/robots/leader-square"]
    assert leader.point_shape == "square" and len(leader.points) == lights.count("leader")
    assert "/robots/leader" not in nodes or len(nodes["/robots/leader"].points) == 0
    assert len(nodes["/robots/outline-square"].points) == lights.count("leader")  # its rim is square too
    assert len(nodes["/robots/outline"].points) == len(lights) - lights.count("leader")
    for light in set(lights) - {"leader"}:
        assert nodes[f"/robots/{light}"].point_shape == "circle"
    assert "border-radius:1px;background:rgb(213, 94, 0);border:1.5px" in legend_html(view)
    assert {e.label: e.shape for e in slide_legend(view)}["leader"] == "tile"
    drawing = drawing_of(view)
    assert drawing.square_lights == ("leader",)
    svg = to_svg(drawing)
    assert svg.count('fill="rgb(213,94,0)"') >= 1 and "<rect" in svg
    assert "rectangle" in to_tikz(drawing)


def test_the_right_hand_runs_title_in_compare_ends_inside_the_framed_box(renderer):
    """Compare's second title ran from its run's left end off the canvas ("B: the default algorithm ·
    ru…" at a lecture stop): it now ends where the room kept right of the runs ends."""
    from apf_viz.ui.scene.compare_pair import ComparePair
    from apf_viz.ui.scene.labels import spec_box

    s = Session([(0, 0), (0, 1), (0, 2), (0, 4)], [(0, 1), (1, 1), (2, 1), (1, 0)])
    s.compare_with("apf-opaque-grid-literal")
    renderer.view_cells = 40.0  # zoomed out as a lecture's Compare stop is: a label is cells wide
    pair = ComparePair(renderer)
    pair.render(s.view(), s.config)
    second = pair.second
    assert second is not None
    nodes = second.nodes()
    title = next(h for n, h in nodes.items() if n.endswith("/title/0"))
    assert title.text.startswith("B: ") and title.anchor == "bottom-right"
    x1 = renderer.bounds[2]  # the box a framed camera shows: both runs and the room right of them
    box = spec_box((title.text, tuple(title.position), "bottom-right"), second._text_height())
    assert box[2] <= x1 and box[2] - box[0] > 10  # it ends inside, though many cells wide
