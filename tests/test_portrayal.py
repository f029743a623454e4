"""The visualiser draws what an algorithm describes (core/portrayal.py) and knows no algorithm itself."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest
import viser

from apf_viz.algorithms.examples import CompactLeft, Stay
from apf_viz.core.formats import InputError
from apf_viz.core.portrayal import PALETTE, Cells, HalfPlane, LightStyle, Line, explain, legend_of
from apf_viz.core.view import Seen, Snapshot
from apf_viz.ui.app import demo_session, free_port
from apf_viz.ui.scene import SceneRenderer
from apf_viz.workbench.session import Session

UI = Path(__file__).resolve().parent.parent / "apf_viz" / "ui"


def test_the_ui_imports_no_algorithm():
    """docs/ARCHITECTURE.md: the UI draws what an algorithm describes and imports none, nor the registry
    (which imports them all): every file of ui/, its folders included (the workbench names them)."""
    paths = sorted(UI.rglob("*.py"))
    assert len(paths) > 40 and any(p.parent.name == "panels" for p in paths)
    for path in paths:
        for node in ast.walk(ast.parse(path.read_text())):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""]
            assert not any(n.startswith("apf_viz.algorithms") for n in names), f"{path} imports {names}"


def test_an_algorithm_without_a_portrayal_gets_defaults():
    assert legend_of(Stay()) == {"off": LightStyle(PALETTE[0])}
    view = Snapshot("off", (Seen(1, 0, "off"),))
    assert explain(Stay(), view, ((0, 0), (1, 0))).decision == Stay().decide(view, ((0, 0), (1, 0)))
    s = Session([(0, 0), (2, 1)], [(0, 0), (0, 1)], algorithm="stay", y_up=[True, True])
    v = s.view()
    assert v.overlays.marks == () and v.stage == "" and v.targets == ()


@pytest.fixture
def renderer():
    server = viser.ViserServer(port=free_port(), verbose=False)
    yield SceneRenderer(server)
    server.stop()


def test_a_second_algorithm_renders_with_its_own_colours_and_overlay_and_no_K(renderer):
    s = Session([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (0, 1)], algorithm="compact-left")
    for _ in range(6):
        s.step()
    v = s.view()
    own = CompactLeft().legend()
    assert v.legend == own
    assert [m.label for m in v.overlays.marks] == ["the wall: the leftmost column"]
    renderer.render(v)
    drawn = {}  # each drawn robot's place and colour, from the point cloud of its light
    for light in {r.light for r in v.robots}:
        handle = renderer.nodes()[f"/robots/{light}"]
        colour = np.asarray(handle.colors).reshape(-1, 3)[0].tolist()
        drawn |= {tuple(map(int, p[:2])): colour for p in np.asarray(handle.points)}
    assert drawn == {r.position: list(own[r.light].color) for r in v.robots}
    wall = np.asarray(renderer.nodes()["/marks/line0"].points)
    assert np.allclose(wall[0, :, 0], 0.0)  # a vertical line at x = 0, the leftmost column
    labels = [h.text for n, h in renderer.nodes().items() if n.startswith("/marks/labels/") and h.visible]
    assert labels == ["the wall: the leftmost column"] and "K" not in labels


def test_the_papers_overlays_label_K_on_the_canvas(renderer):
    s = Session([(0, 0), (0, 2), (1, 0), (1, 2), (2, 5)], [(0, 0), (1, 0), (2, 0), (3, 0), (4, 0)])
    s.set_scheduler("fsync")
    while not any(isinstance(m, Line) and m.label == "K" for m in s.view().overlays.marks):
        assert s.step()
    renderer.render(s.view())
    labels = [h.text for n, h in renderer.nodes().items() if n.startswith("/marks/labels/") and h.visible]
    assert "K" in labels


def test_why_shows_the_selected_robots_last_decision_and_its_regions_in_its_frame(renderer):
    s = demo_session()
    up = next(r for r in range(10) if s.y_up[r])
    flipped = next(r for r in range(10) if not s.y_up[r])
    for r in (up, flipped):
        s.set_scheduler("Manual")
        s.click(s.engine.current_points()[r])  # Look
        s.click(s.engine.current_points()[r])  # Compute
    for r in (up, flipped):
        s.selected = r
        why = s.view().why
        assert why is not None and why.explanation is not None
        assert why.explanation.decision == s.engine.state.pending[r]
        assert why.explanation.decision.rule_id.startswith("A1.")
        assert why.origin == s.engine.current_points()[r]
        assert any(p.symbol == "H_L^O(r) = ∅" for p in why.explanation.predicates)
        uppers = [m for m in why.regions if isinstance(m, HalfPlane) and m.label == "H_U^C"]
        for m in uppers:  # "above me" in its own frame falls below it on the grid when flipped
            assert m.side == (1 if s.y_up[r] else -1) and m.at == why.origin[1]
    renderer.render(s.view())
    assert any(n.startswith("/why/area") for n in renderer.nodes())  # H_L^O shaded on the grid


def test_a_robot_that_moved_is_explained_where_it_stood_when_it_looked():
    s = Session([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (0, 1)], algorithm="compact-left")
    s.set_scheduler("Manual")
    start = s.engine.current_points()[1]
    for _ in range(3):
        s.click(s.engine.current_points()[1])  # Look, Compute, Move (left)
    s.selected = 1
    why = s.view().why
    assert why.explanation.decision.rule_id == "compact-left.slide"
    assert s.engine.current_points()[1] == (start[0] - 1, start[1]) and why.origin == start


def test_switching_the_algorithm_restarts_the_same_start_and_pattern():
    s = demo_session()
    for _ in range(20):
        s.step()
    start, pattern = s.robots, s.pattern
    s.set_algorithm("apf-opaque-grid-literal")
    assert s.engine.algorithm.name == "apf-opaque-grid-literal" and s.engine.step_index == 0
    assert (s.robots, s.pattern) == (start, pattern)
    s.set_algorithm("apf-opaque-grid@G1,LA")
    assert s.engine.algorithm.name == "apf-opaque-grid@G1,LA"
    with pytest.raises(ValueError, match="unknown algorithm"):
        s.set_algorithm("os:abort")
    assert s.engine.algorithm.name == "apf-opaque-grid@G1,LA"  # a refused switch changes nothing
    s.set_light_semantics("lc-atomic")
    assert s.engine.light_semantics == "lc-atomic" and s.engine.algorithm.name == "apf-opaque-grid@G1,LA"
    with pytest.raises(InputError):
        s.set_light_semantics("instant")


def test_play_state_changes_only_through_the_run_controller():
    s = demo_session()
    with pytest.raises(AttributeError):
        s.playing = True  # type: ignore[misc]
    s.toggle_play()
    assert s.playing
    s.set_mode("edit-pattern")
    assert not s.playing
    assert not s.play_steps()


def test_reset_and_loads_rebuild_the_run_from_its_configuration():
    s = demo_session()
    config = s.config
    for _ in range(30):
        s.step()
    s.reset()
    assert s.config == config and s.engine.step_index == 0 and s.engine.start == config.robots
    s.load_pattern("p.json", b'{"points": [[0,0],[1,0],[2,0],[3,0],[4,0],[5,0],[6,0],[7,0],[8,0],[9,0]]}')
    assert s.config == config.but(pattern=tuple((x, 0) for x in range(10)))
    cells = [m for m in s.view().overlays.marks if isinstance(m, Cells)]
    assert cells and cells[0].style == "preview"  # no leader yet: the pattern is a preview


def test_the_legend_follows_the_overlays_as_they_appear():
    from apf_viz.ui.panels import Panels

    server = viser.ViserServer(port=free_port(), verbose=False)
    try:
        s = Session([(0, 0), (0, 2), (1, 0), (1, 2), (2, 5)], [(0, 0), (1, 0), (2, 0), (3, 0), (4, 0)])
        s.set_scheduler("fsync")
        panels = Panels(server, s, lambda: None)
        panels.refresh(s.view())
        assert ">K</span></div>" not in panels.legend.content
        while not any(isinstance(m, Line) and m.label == "K" for m in s.view().overlays.marks):
            assert s.step()
        panels.refresh(s.view())
        assert ">K</span></div>" in panels.legend.content  # the swatch of K, in K's colour
    finally:
        server.stop()


def test_while_playing_the_slow_folders_follow_at_most_four_times_a_second(monkeypatch):
    """The Paper, History and Moves folders skip a playing frame within PLAYING_REFRESH_S of their last
    refresh; the Run folder never does, and a paused view (the frame that ends Play) refreshes all."""
    from apf_viz.ui import panels as panels_module
    from apf_viz.ui.panels import PLAYING_REFRESH_S, Panels

    server = viser.ViserServer(port=free_port(), verbose=False)
    clock = [100.0]
    monkeypatch.setattr(panels_module.time, "monotonic", lambda: clock[0])
    try:
        s = demo_session()
        panels = Panels(server, s, lambda: None)
        paper = next(f for f in panels.folders if type(f).__name__ == "PaperFolder")
        run = next(f for f in panels.folders if type(f).__name__ == "RunFolder")
        s.toggle_play()
        while True:  # a playing frame refreshes all (the first), then the slow ones wait
            assert s.step()
            view = s.view()
            if view.paper_text and view.paper_text != paper.html.content:
                break
        panels.refresh(view)
        assert view.playing and paper.html.content == view.paper_text
        shown = paper.html.content
        while s.view().paper_text == shown:
            assert s.step()
        clock[0] += PLAYING_REFRESH_S / 2
        view = s.view()
        panels.refresh(view)
        assert run.event.value == view.event  # every frame
        assert paper.html.content == shown != view.paper_text  # not yet
        clock[0] += PLAYING_REFRESH_S / 2
        panels.refresh(view)
        assert paper.html.content == view.paper_text  # a quarter of a second later
        while s.view().paper_text == view.paper_text:
            assert s.step()
        s.pause()
        view = s.view()
        panels.refresh(view)  # at once: the run is paused
        assert not view.playing and paper.html.content == view.paper_text
    finally:
        server.stop()
