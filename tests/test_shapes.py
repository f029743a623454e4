"""The pattern studio's tools (issue #25): pure functions, cells in, cells out."""

from __future__ import annotations

import itertools
import json
import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from apf_viz.core import shapes
from apf_viz.core.shapes import ShapeError

drawings = st.lists(st.tuples(st.integers(-20, 20), st.integers(-20, 20)), unique=True, max_size=40)


def test_a_filled_box_has_width_times_height_cells():
    cells = shapes.box((2, 3), (7, 0))
    assert len(cells) == 24 and len(set(cells)) == 24
    assert {x for x, _ in cells} == set(range(2, 8)) and {y for _, y in cells} == set(range(0, 4))


def test_an_outline_is_the_box_without_its_inside():
    assert set(shapes.outline((0, 0), (3, 2))) == set(shapes.box((0, 0), (3, 2))) - {(1, 1), (2, 1)}


@given(
    st.tuples(st.integers(-30, 30), st.integers(-30, 30)),
    st.tuples(st.integers(-30, 30), st.integers(-30, 30)),
)
def test_a_digital_line_joins_its_ends_by_king_steps(a, b):
    cells = shapes.line(a, b)
    assert cells[0] == a and cells[-1] == b and len(cells) == max(abs(a[0] - b[0]), abs(a[1] - b[1])) + 1
    assert all(max(abs(p[0] - q[0]), abs(p[1] - q[1])) == 1 for p, q in itertools.pairwise(cells))


@pytest.mark.parametrize("r", [0, 1, 2, 3, 6, 10])
def test_a_ring_is_the_digital_circle_of_its_radius(r):
    cells = shapes.ring((5, -2), r)
    assert all(round(math.dist(p, (5, -2))) == r for p in cells)
    everything = {(5 + x, -2 + y) for x in range(-r - 2, r + 3) for y in range(-r - 2, r + 3)}
    assert set(cells) == {p for p in everything if round(math.dist(p, (5, -2))) == r}
    assert set(shapes.disc((5, -2), r)) == {p for p in everything if round(math.dist(p, (5, -2))) <= r}


def test_rows_columns_and_a_staircase():
    assert shapes.row((1, 1), 3) == [(1, 1), (2, 1), (3, 1)]
    assert shapes.column((0, 0), 2) == [(0, 0), (0, 1)]
    assert shapes.staircase((0, 0), 3) == [(0, 0), (1, 0), (1, 1), (2, 1), (2, 2)]


def test_text_ab_is_the_glyphs_cells_side_by_side():
    cells = shapes.text("ab", (0, 4))
    glyph = {(x, 4 - y) for y, row in enumerate(shapes.FONT["A"]) for x, c in enumerate(row) if c == "#"}
    glyph_b = {
        (4 + x, 4 - y) for y, row in enumerate(shapes.FONT["B"]) for x, c in enumerate(row) if c == "#"
    }
    assert set(cells) == glyph | glyph_b and len(cells) == len(glyph) + len(glyph_b)
    with pytest.raises(ShapeError, match="no glyph for '!'"):
        shapes.text("HI!", (0, 0))


def test_every_glyph_is_three_by_five():
    assert all(len(rows) == 5 and all(len(r) == 3 for r in rows) for rows in shapes.FONT.values())


@given(drawings)
def test_mirror_twice_is_the_identity_and_keeps_the_box(cells):
    for axis in ("x", "y"):
        once = shapes.mirrored(cells, axis)
        assert shapes.mirrored(once, axis) == cells
        if cells:
            assert shapes._anchor(once) == shapes._anchor(cells)


@given(drawings)
def test_four_quarter_turns_are_the_identity(cells):
    turned = cells
    for _ in range(4):
        turned = shapes.rotated(turned)
    assert turned == cells


@given(drawings)
def test_scaling_by_two_makes_four_cells_of_each(cells):
    assert len(shapes.scaled(cells, 2)) == 4 * len(cells)


@given(drawings, st.integers(1, 60))
def test_fit_to_k_gives_k_distinct_cells_and_keeps_the_first_drawn(cells, k):
    out, said = shapes.fitted(cells, k)
    assert len(out) == k == len(set(out)) and said
    kept = min(k, len(cells))
    assert out[:kept] == cells[:kept]  # removes the last drawn; adds after what was there


def test_ascii_art_reads_hashes_from_the_top_row_down():
    assert shapes.ascii_art(["#.", ".#"]) == [(0, 1), (1, 0)]


@pytest.mark.parametrize("call", [lambda: shapes.ring((0, 0), -1), lambda: shapes.row((0, 0), 10**9)])
def test_a_size_out_of_range_is_one_line(call):
    with pytest.raises(ShapeError, match="choose a whole number"):
        call()


def test_the_pattern_command_writes_apf_and_robots_of_its_size_form_it(tmp_path):
    from apf_viz.cli import main

    pattern, robots = tmp_path / "p.json", tmp_path / "r.json"
    assert main(["pattern", "--text", "APF", "--out", str(pattern)]) == 0
    k = len(json.loads(pattern.read_text())["points"])
    assert k == len(shapes.text("APF", (0, 0)))
    assert (
        main(["random-robots", "--count", str(k), "--width", "12", "--height", "12", "--out", str(robots)])
        == 0
    )
    assert main(["run", "--robots", str(robots), "--pattern", str(pattern)]) == 0  # formed


def test_the_pattern_command_shapes_mirrors_and_fits(tmp_path, capsys):
    from apf_viz.cli import main

    out = tmp_path / "ring.json"
    assert (
        main(
            ["pattern", "--shape", "ring", "--size", "6", "--mirror", "x", "--count", "30", "--out", str(out)]
        )
        == 0
    )
    points = json.loads(out.read_text())["points"]
    assert len(points) == 30 and "fit to 30" in capsys.readouterr().err
    art = tmp_path / "f.txt"
    art.write_text("###\n#..\n##.\n#..\n")
    robots = tmp_path / "robots.json"
    assert main(["pattern", "--ascii", str(art), "--as", "robots", "--out", str(robots)]) == 0
    assert sorted(map(tuple, json.loads(robots.read_text())["robots"])) == sorted(
        shapes.ascii_art(art.read_text().splitlines())
    )


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (["--text", "A!"], "no glyph for '!'"),
        (["--shape", "ring", "--size", "-1"], "choose a whole number"),
        (["--ascii", "/nonexistent.txt"], "no such file"),
    ],
)
def test_the_pattern_command_refuses_in_one_line_with_exit_2(args, said, capsys):
    from apf_viz.cli import main

    with pytest.raises(SystemExit) as exit_:
        main(["pattern", *args])
    err = capsys.readouterr().err.strip()
    assert exit_.value.code == 2 and said in err and len(err.splitlines()) == 1
