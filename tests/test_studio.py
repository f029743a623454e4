"""The pattern studio's gestures on the drafts (issue #25): tools, transforms, undo and redo."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from apf_viz.core import shapes
from apf_viz.core.formats import InputError
from apf_viz.workbench.editor import Editor
from apf_viz.workbench.session import Session
from apf_viz.workbench.studio import TOOLS, TRANSFORMS, Studio

START = [(0, 0), (3, 0), (5, 1), (2, 2)]
PATTERN = [(0, 0), (1, 0), (2, 0), (0, 1)]


def session() -> Session:
    s = Session(START, PATTERN, y_up=[True] * 4, scheduler="async")
    s.set_mode("edit-pattern")
    return s


def test_two_clicks_of_the_line_tool_draw_every_cell_between():
    s = session()
    s.clear_pattern()
    s.set_tool("line")
    assert "first point" in s.click((0, 0))
    s.click((4, 2))
    assert s.editor.pattern == shapes.line((0, 0), (4, 2))


def test_placed_shapes_take_the_size_and_the_text():
    s = session()
    s.clear_pattern()
    s.set_tool("ring")
    s.set_tool_size(3)
    s.click((10, 10))
    assert set(s.editor.pattern) == set(shapes.ring((10, 10), 3))
    s.clear_pattern()
    s.set_tool("text")
    s.set_tool_text("HI")
    s.click((0, 4))
    assert s.editor.pattern == shapes.text("HI", (0, 4))
    with pytest.raises(ValueError, match="no glyph"):
        s.set_tool_text("H@")
    with pytest.raises(InputError):
        s.set_tool_size(0)


def test_a_dragged_box_fills_and_a_shift_drag_erases():
    s = session()
    s.clear_pattern()
    s.draw_box((0, 0), (5, 3), erase=False)
    assert len(s.editor.pattern) == 24
    s.draw_box((1, 1), (2, 2), erase=True)
    assert len(s.editor.pattern) == 20 and (1, 1) not in s.editor.pattern


def test_move_translates_the_pattern_and_moves_one_robot_in_one_action():
    s = session()
    before = list(s.editor.pattern)
    s.set_tool("move")
    s.click((0, 0))
    s.click((3, -1))
    assert s.editor.pattern == [(x + 3, y - 1) for x, y in before]
    s.set_mode("edit-robots")
    s.click((5, 1))
    assert s.click((9, 9)) == "moved the robot at (5, 1) to (9, 9)"
    assert (9, 9) in s.editor.robots and (5, 1) not in s.editor.robots and len(s.editor.robots) == 4


def test_a_fit_is_previewed_and_says_what_it_did_and_undo_brings_back_either():
    """More cells than robots: the preview says what each fit would do before it is clicked; Fit pattern
    trims the last-drawn cells (as the command line's --count does), and Undo brings them back; Fit
    robots places robots instead, the start solvable."""
    s = session()
    s.clear_pattern()
    s.draw_box((0, 0), (2, 1), erase=False)  # 6 cells for 4 robots
    drawn = list(s.editor.pattern)
    preview = s.screen.studio.fit_preview(s.editor)
    assert preview == "Fit pattern trims the 2 last-drawn cells · Fit robots adds 2 robots"
    said = s.transform("Fit pattern")
    assert s.editor.pattern == drawn[:4] and "removed the 2 last-drawn cells" in said
    s.transform("Undo")
    assert s.editor.pattern == drawn
    said = s.transform("Fit robots")
    assert len(s.editor.robots) == 6 and "added 2 robots" in said and s.editor.pattern == drawn
    assert s.editor.problem() is None  # sizes equal, and the start is solvable
    s.transform("Undo")
    assert len(s.editor.robots) == 4
    s.draw_box((0, 0), (2, 1), erase=True)
    s.draw_box((0, 0), (1, 0), erase=False)  # 2 cells for 4 robots
    said = s.transform("Fit pattern")
    assert len(s.editor.pattern) == 4 and s.editor.pattern[:2] == [(0, 0), (1, 0)] and "added 2" in said
    s.transform("Undo")
    said = s.transform("Fit robots")
    assert len(s.editor.robots) == 2 and "removed 2 robots" in said
    s.transform("Undo")
    assert len(s.editor.robots) == 4


@given(
    st.lists(st.tuples(st.integers(-4, 4), st.integers(-4, 4)), unique=True, max_size=12), st.integers(1, 20)
)
def test_fit_robots_gives_k_robots_keeping_a_solvable_start_solvable(robots, k):
    from apf_viz.core.symmetry import unsolvable_axis

    out, said = shapes.robots_fitted(robots, k, lambda r: unsolvable_axis(r) is None)
    assert len(out) == k == len(set(out)) and said
    assert out[: min(k, len(robots))] == robots[: min(k, len(robots))] or len(out) < len(robots)
    if robots and unsolvable_axis(robots) is None and k > len(robots):
        assert unsolvable_axis(out) is None


def test_every_tool_and_transform_is_listed_and_an_unknown_one_refused():
    assert set(TOOLS) >= {"cell", "box", "line", "ring", "disc", "text", "move", "flip"}
    s = session()
    with pytest.raises(ValueError, match="no tool"):
        s.set_tool("rm -rf")
    with pytest.raises(ValueError, match="no transform"):
        s.transform("explode")
    for name in TRANSFORMS:
        s.transform(name)


operations = st.lists(
    st.one_of(
        st.tuples(st.just("click"), st.sampled_from(["cell", "line", "ring", "row", "text"]),
                  st.tuples(st.integers(-5, 5), st.integers(-5, 5))),
        st.tuples(st.just("transform"), st.sampled_from(TRANSFORMS), st.none()),
        st.tuples(st.just("box"), st.booleans(), st.tuples(st.integers(-5, 5), st.integers(-5, 5))),
    ),
    max_size=12,
)  # fmt: skip


@settings(max_examples=60, deadline=None)
@given(operations)
def test_undo_after_any_sequence_restores_each_earlier_draft_and_redo_replays_them(ops):
    editor, studio = Editor(START, [True] * 4, PATTERN), Studio()
    studio.size = 2
    drafts = [editor.draft]

    def kept() -> None:
        if editor.draft != drafts[-1]:
            drafts.append(editor.draft)

    for kind, what, cell in ops:
        if kind == "click":
            studio.choose(what)
            studio.click(editor, "edit-pattern", cell)
            kept()
            studio.click(editor, "edit-pattern", (cell[0] + 2, cell[1] + 1))  # a two-click tool's second
        elif kind == "transform":
            before = editor.draft
            try:
                studio.transform(editor, "edit-pattern", what)
            except shapes.ShapeError:  # e.g. Scale ×2 three times over 10,000 cells: refused, unchanged
                assert editor.draft == before
        else:
            studio.box(editor, "edit-pattern", cell, (cell[0] + 1, cell[1] + 2), erase=what)
        kept()
    for earlier in reversed(drafts[:-1]):
        editor.undo()
        assert editor.draft == earlier
    assert editor.undo() == "nothing to undo"
    for later in drafts[1:]:
        editor.redo()
        assert editor.draft == later


def test_the_library_saves_by_name_lists_and_loads_never_a_path(tmp_path):
    from apf_viz.workbench.library import PatternLibrary

    s = session()
    s.use_library(PatternLibrary(tmp_path / "lib"))
    s.clear_pattern()
    s.draw_box((0, 0), (1, 1), erase=False)
    said = s.save_pattern("my square")
    assert "saved 4 cells as 'my square'" in said and s.saved == ["my square"]
    assert (tmp_path / "lib" / "my_square.json").is_file()
    for bad in ("../etc/passwd", "/tmp/x", "", "a" * 61, "dot.json"):
        with pytest.raises(InputError):
            s.save_pattern(bad)
    with pytest.raises(InputError, match="no saved pattern"):
        s.load_saved_pattern("../my square")
    s.clear_pattern()
    s.load_saved_pattern("my square")
    assert s.mode == "edit-pattern" and len(s.editor.pattern) == 4
    xs = [x for x, _ in s.editor.pattern]
    assert min(xs) > max(x for x, _ in s.editor.robots)  # beside the robots
    assert not list(tmp_path.glob("lib/*.tmp"))  # written atomically, nothing left over


def test_save_takes_the_pattern_the_page_shows_in_edit_robots_mode_too(tmp_path):
    """Drawn in Edit pattern, then Edit robots (which shows and counts the drawn targets): Save saves
    the drawing, not the run's pattern."""
    from apf_viz.workbench.library import PatternLibrary

    s = session()
    s.use_library(PatternLibrary(tmp_path / "lib"))
    s.set_mode("edit-pattern")
    s.clear_pattern()
    s.draw_box((0, 0), (2, 2), erase=False)
    drawn = sorted(s.editor.pattern)
    assert len(drawn) == 9 and drawn != sorted(s.config.pattern)
    s.set_mode("edit-robots")
    assert "saved 9 cells" in s.save_pattern("drawn")
    s.clear_pattern()
    s.load_saved_pattern("drawn")
    xs = [x for x, _ in drawn]
    assert sorted((x - min(xs), y) for x, y in drawn) == sorted(
        (x - min(p[0] for p in s.editor.pattern), y) for x, y in s.editor.pattern
    )


def test_the_move_all_buttons_translate_the_draft_by_one_cell():
    s = session()
    before = list(s.editor.pattern)
    s.transform("→")
    s.transform("↑")
    assert s.editor.pattern == [(x + 1, y + 1) for x, y in before]


def test_next_stage_while_editing_says_why_not_a_scheduler_it_does_not_need():
    """Found playing every Demo by keyboard: PageDown on the Unsolvable box (Edit robots) said "need a
    scheduler other than Manual" under the async scheduler."""
    s = session()
    s.set_mode("edit-robots")
    said = s.run_until("stage")
    assert said.startswith("Next move / Next stage runs in Run mode") and "Manual" not in said


def test_the_eraser_erases_a_click_and_a_dragged_stroke_is_one_undo():
    s = session()
    s.clear_pattern()
    s.draw_box((0, 0), (5, 0), erase=False)
    s.set_tool("eraser")
    s.click((0, 0))
    assert (0, 0) not in s.editor.pattern
    s.stroke("start", (1, 0))
    s.stroke("update", (4, 0))  # a fast pointer: every cell between is erased
    s.stroke("end", None)
    assert s.editor.pattern == [(5, 0)]
    s.transform("Undo")  # the whole stroke, at once
    assert sorted(s.editor.pattern) == [(1, 0), (2, 0), (3, 0), (4, 0), (5, 0)]
    s.set_tool("cell")
    s.stroke("start", (0, 3))
    s.stroke("update", (2, 5))
    s.stroke("end", None)
    assert {(0, 3), (1, 4), (2, 5)} <= set(s.editor.pattern)  # painted along the drag
    s.transform("Undo")
    assert not {(0, 3), (1, 4), (2, 5)} & set(s.editor.pattern)
    s.stroke("start", (9, 9))
    s.stroke("end", None)
    s.stroke("start", (9, 9))  # a drag over a painted cell only: nothing changed, no step kept
    s.stroke("end", None)
    s.transform("Undo")
    assert (9, 9) not in s.editor.pattern


def test_flood_fill_fills_a_closed_outline_refuses_an_open_one_and_undoes():
    s = session()
    s.clear_pattern()
    s.set_tool("outline")
    s.click((0, 0))
    s.click((4, 3))  # 14 border cells, 6 inside
    s.set_tool("fill")
    assert "filled 6 cells" in s.click((2, 1))
    assert len(s.editor.pattern) == 20
    s.transform("Undo")
    assert len(s.editor.pattern) == 14
    s.set_tool("eraser")
    s.click((0, 1))  # a gap in the outline
    s.set_tool("fill")
    with pytest.raises(ValueError, match="open"):
        s.click((2, 1))
    assert len(s.editor.pattern) == 13  # the refused fill changed nothing


def test_the_live_mirror_copies_every_cell_drawn_or_erased_across_its_axes():
    s = session()
    s.clear_pattern()
    s.draw_box((0, 0), (4, 0), erase=False)  # the axis x = 2 is its middle
    assert "x = 2" in s.set_mirror("x ↔")
    s.set_tool("cell")
    s.click((0, 2))
    assert (0, 2) in s.editor.pattern and (4, 2) in s.editor.pattern
    s.set_tool("eraser")
    s.click((1, 0))
    assert (1, 0) not in s.editor.pattern and (3, 0) not in s.editor.pattern
    s.set_mirror("both")  # about the box's centre now: x = 2, y = 1
    s.set_tool("cell")
    s.click((0, -1))
    assert {(0, -1), (4, -1), (0, 3), (4, 3)} <= set(s.editor.pattern)
    s.transform("Undo")  # one click, four cells: one Undo
    assert not {(0, -1), (4, -1), (0, 3), (4, 3)} & set(s.editor.pattern)
    s.set_mirror("off")
    s.click((7, 7))
    assert (7, 7) in s.editor.pattern and (-3, 7) not in s.editor.pattern


def test_a_selection_is_copied_pasted_cut_and_moved():
    s = session()
    s.clear_pattern()
    s.draw_box((0, 0), (1, 1), erase=False)
    s.draw_box((5, 5), (5, 5), erase=False)
    s.set_tool("select")
    assert "selected 4 cell(s)" in s.draw_box((-1, -1), (2, 2), erase=False)
    assert len(s.editor.pattern) == 5  # selecting draws nothing
    s.selection_command("Copy")
    s.set_tool("paste")
    s.click((10, 0))
    assert {(10, 0), (11, 0), (10, 1), (11, 1)} <= set(s.editor.pattern)
    s.transform("→")  # Move all moves the selection only
    assert (2, 0) in s.editor.pattern and (0, 0) not in s.editor.pattern and (5, 5) in s.editor.pattern
    assert "cut: 4 cell(s)" in s.selection_command("Cut")
    assert set(s.editor.pattern) == {(5, 5), (10, 0), (11, 0), (10, 1), (11, 1)}
    s.click((20, 20))  # the cut cells are on the clipboard
    assert (21, 21) in s.editor.pattern
    assert "nothing selected" in s.selection_command("Delete")


def test_a_fit_that_takes_seconds_is_said_first_and_goes_on_when_asked_again():
    s = session()
    s.clear_pattern()
    s.draw_box((0, 0), (29, 19), erase=False)  # 600 cells for 4 robots
    said = s.transform("Fit robots")
    assert "will place 596 robots" in said and "again" in said and len(s.editor.robots) == 4
    said = s.transform("Fit robots")
    assert len(s.editor.robots) == 600


def test_no_robots_is_not_called_solvable():
    s = session()
    s.set_mode("edit-robots")
    for p in list(s.editor.robots):
        s.click(p)  # the cell tool removes each robot
    assert s.editor.robots == []
    counts = s.view().counts
    assert "no robots" in counts and "solvable:" not in counts


def test_a_download_carries_the_name_the_pattern_was_saved_or_loaded_under_wherever_it_is_drawn(tmp_path):
    """Saved as "APF", moved (a drawing goes beside the robots), loaded back: the download is named
    "APF" inside and saved as APF.pattern.json; an unnamed drawing is "pattern of N cells" in
    pattern.json; an uploaded file's name is kept too."""
    import json

    from apf_viz.workbench.library import PatternLibrary

    s = session()
    s.use_library(PatternLibrary(tmp_path / "lib"))
    s.set_mode("edit-pattern")
    s.clear_pattern()
    s.draw_box((0, 0), (2, 1), erase=False)
    assert (
        json.loads(s.pattern_file())["name"] == "pattern of 6 cells"
        and s.pattern_file_name() == "pattern.json"
    )
    s.save_pattern("APF")
    s.transform("→")  # moved: the same shape
    s.transform("↑")
    assert json.loads(s.pattern_file())["name"] == "APF" and s.pattern_file_name() == "APF.pattern.json"
    s.clear_pattern()
    s.load_saved_pattern("APF")
    assert json.loads(s.pattern_file())["name"] == "APF"
    s.draw_box((40, 40), (40, 40), erase=False)  # another shape: no longer the one saved
    assert json.loads(s.pattern_file())["name"] == "pattern of 7 cells"
    s.load_pattern("mine.json", json.dumps({"name": "my L / 1", "points": [[0, 0], [0, 1], [1, 0]]}).encode())
    assert (
        json.loads(s.pattern_file())["name"] == "my L / 1" and s.pattern_file_name() == "my-L-1.pattern.json"
    )


def test_a_drawing_at_its_bound_keeps_its_history_small_and_one_cell_more_is_one_line():
    """10,000 cells drawn (100 boxes of a row each), then 300 edits of one cell: the whole history (200
    steps) holds what each step changed, not 200 copies of the drawing (which would be 16 MB of references
    alone); past the bound, a change is refused in one line and the drawing is kept."""
    import tracemalloc

    from apf_viz.workbench.editor import MAX_DRAWN, UNDO_DEPTH

    s = session()
    s.set_mode("edit-pattern")
    s.clear_pattern()
    tracemalloc.start()
    try:
        base = tracemalloc.get_traced_memory()[0]
        for row in range(100):
            s.draw_box((0, row), (99, row), erase=False)
        assert len(s.editor.pattern) == MAX_DRAWN
        for i in range(150):
            s.draw_box((i % 100, 50), (i % 100, 50), erase=True)
            s.draw_box((i % 100, 50), (i % 100, 50), erase=False)
        held = tracemalloc.get_traced_memory()[0] - base
    finally:
        tracemalloc.stop()
    assert held < 5_000_000, f"{held:,} bytes for the drawing and its history"
    drawn = list(s.editor.pattern)
    with pytest.raises(InputError, match="a drawing holds at most 10,000") as refused:
        s.draw_box((200, 0), (200, 0), erase=False)
    assert "\n" not in str(refused.value) and s.editor.pattern == drawn
    for _ in range(UNDO_DEPTH):  # every step of the history still undoes exactly
        s.editor.undo()
    assert len(s.editor.pattern) == MAX_DRAWN  # the last 200 steps: one-cell erases and adds, undone
    assert s.editor.undo() == "nothing to undo"


@given(st.lists(st.tuples(st.sampled_from(["toggle", "box", "undo", "redo", "erase"]), st.integers(0, 6),
                          st.integers(0, 6)), max_size=40))  # fmt: skip
@settings(max_examples=150, deadline=None)
def test_undo_and_redo_by_differences_restore_exactly_what_copies_would(steps):
    """The history kept as differences against a model that keeps a copy of every draft."""
    editor = Editor([(0, 0)], [True], [])
    undo: list = []
    redo: list = []
    for what, x, y in steps:
        before = editor.draft
        if what == "undo":
            editor.undo()
            if undo:
                redo.append(before)
                assert editor.draft == undo.pop()
            continue
        if what == "redo":
            editor.redo()
            if redo:
                undo.append(before)
                assert editor.draft == redo.pop()
            continue
        if what == "toggle":
            editor.toggle_target((x, y))
        elif what == "box":
            editor.set_pattern([*editor.pattern, *shapes.box((x, y), (x + 1, y + 1))], "box")
        else:
            editor.set_pattern([p for p in editor.pattern if p[0] != x], "erase")
        if editor.draft != before:
            undo.append(before)
            redo.clear()


def test_the_selection_outline_and_the_edit_line_never_outlive_what_they_describe():
    """Found drawing: after a Clear (or an Undo) that took every selected cell, the outline stayed; back
    in an Edit mode, the line under the tool still told the last edit of before."""
    s = session()
    s.set_mode("edit-pattern")
    s.clear_pattern()
    s.draw_box((0, 0), (2, 2), erase=False)
    s.set_tool("select")
    s.draw_box((0, 0), (1, 1), erase=False)  # the select tool: the box selects
    assert s.view().selection_box == ((0, 0), (1, 1))
    s.transform("Undo")  # the drawn box undone: nothing the selection took is drawn
    assert s.view().selection_box is None
    s.transform("Redo")
    assert s.view().selection_box == ((0, 0), (1, 1))
    s.clear_pattern()
    assert s.view().selection_box is None
    s.screen.studio.said = "cleared"  # as the panel says an edit (ui/panels/edit.py)
    s.set_mode("edit-robots")
    assert s.screen.studio.said == ""
