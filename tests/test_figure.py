"""apf-viz figure: a run's moment, or the paper's figures, as SVG and TikZ that draw what the view shows
(robots in their lights' colours, the targets, the algorithm's lines and frames, a selected robot's rays
and hidden robots, a legend); the TikZ compiles with pdflatex and the tikz package alone."""

from __future__ import annotations

import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from apf_viz.cli import main
from apf_viz.figure.drawing import drawing_of
from apf_viz.figure.export import figure_session, paper_figures
from apf_viz.figure.svg import to_svg
from apf_viz.figure.tikz import tex_text, to_tikz
from apf_viz.lecture import figures
from apf_viz.ui.app import demo_session

SVG = "{http://www.w3.org/2000/svg}"


def test_every_figure_of_the_paper_exports_in_both_formats_and_the_tikz_compiles(tmp_path):
    written = paper_figures(tmp_path / "figures")
    assert len(written) == 2 * len(figures()) == 42
    for path in written:
        if path.suffix == ".svg":
            ET.parse(path)  # well-formed
    _compile(written)
    _compile(paper_figures(tmp_path / "captioned", caption=True))  # and with the captions --caption writes


def _compile(written: list[Path]) -> None:
    """Every TikZ of ``written`` \\input into one document, which pdflatex compiles."""
    pdflatex = shutil.which("pdflatex")
    assert pdflatex is not None, "scripts/test.sh installs texlive-latex-base and texlive-pictures"
    folder = written[0].parent
    document = folder / "all.tex"
    inputs = "".join(rf"\input{{{p.name}}}\par" + "\n" for p in written if p.suffix == ".tex")
    document.write_text(
        r"\documentclass{article}\usepackage{tikz}\begin{document}" + "\n" + inputs + r"\end{document}"
    )
    done = subprocess.run(
        [pdflatex, "-interaction=nonstopmode", "-halt-on-error", document.name],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout[-2000:]
    assert (folder / "all.pdf").stat().st_size > 10_000


def test_a_figure_draws_each_robot_in_its_lights_colour_and_the_selected_robots_sight():
    s = demo_session()
    for _ in range(60):
        s.step()
    s.selected = 1
    view = s.view()
    d = drawing_of(view, "caption")
    root = ET.fromstring(to_svg(d))
    fills = {"disc": [c.get("fill") for c in root.iter(f"{SVG}circle")]}
    fills["square"] = [c.get("fill") for c in root.iter(f"{SVG}rect")]
    for r in view.robots:  # each in its light's colour and shape (the leader a square)
        style = view.legend[r.light]
        assert f"rgb({style.color[0]},{style.color[1]},{style.color[2]})" in fills[style.shape]
    assert len(d.rays) == len(view.rays) > 0 and d.selected == view.robots[1].position
    assert set(d.hidden) == {view.robots[j].position for j in view.hidden}
    texts = [t.text for t in root.iter(f"{SVG}text")]
    assert {r.light for r in view.robots} <= set(texts)  # the legend names the lights shown
    tikz = to_tikz(d)
    squares = sum(view.legend[r.light].shape == "square" for r in view.robots)
    assert tikz.count(r"circle (0.34);") == len(view.robots) - squares + len(d.hidden)
    assert tikz.count(r"\draw[apf") >= len(d.rays)


def test_the_paper_figure_with_k_draws_the_line_k():
    session, caption = figure_session("robotOnK")
    d = drawing_of(session.view(), caption)
    assert any(label == "K" for _, _, label, _ in d.lines)
    assert "K" in to_tikz(d) and ">K</text>" in to_svg(d)


def test_tex_text_keeps_labels_safe():
    assert tex_text("L_1 & 50% #1 {x} ~ ^") == r"L\_1 \& 50\% \#1 \{x\} \~{} \^{}"
    assert tex_text("robot 3′ · 2 → 1").isascii()


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--figure", "nope"], "--figure 'nope'"),
        (["--trace", "literal-collision-4", "--select", "9"], "--select 9"),
        (["--robots", "sym-call-7", "--pattern", "cup-7", "--event", "-1"], "--event -1"),
        (["--robots", "sym-call-7"], "give --figure LABEL"),
        (["--figure", "initial", "--format", "pdf"], "invalid choice"),
    ],
)
def test_bad_input_is_one_line_exit_2_and_nothing_written(tmp_path, capsys, argv, message):
    out = tmp_path / "f.svg"
    with pytest.raises(SystemExit) as ended:
        main(["figure", *argv, "--out", str(out)])
    assert ended.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert message in err[-1] and not out.exists()


def test_the_command_writes_a_figure_of_a_run_at_an_event(tmp_path):
    out = tmp_path / "f.tex"
    assert main(["figure", "--robots", "sym-call-7", "--pattern", "cup-7", "--event", "30", "--select", "2",
                 "--format", "tikz", "--out", str(out)]) == 0  # fmt: skip
    text = out.read_text()
    assert text.startswith(r"\begin{tikzpicture}") and text.rstrip().endswith(r"\end{tikzpicture}")
    assert Path(out).stat().st_size > 1000


def test_a_png_figure_is_the_same_picture_rasterised(tmp_path):
    import imageio.v3 as iio

    out = tmp_path / "k.png"
    assert main(["figure", "--figure", "robotOnK", "--format", "png", "--out", str(out)]) == 0
    image = iio.imread(out)
    assert image.ndim == 3 and image.shape[0] > 200 and image.shape[1] > 400
    session, _ = figure_session("robotOnK")
    terminal1 = session.view().legend["terminal1"].color
    pixels = image[:, :, :3].reshape(-1, 3).astype(int)
    assert (abs(pixels - terminal1).max(axis=1) <= 3).sum() > 200  # the terminal1 robots, in their colour


def test_a_paper_figure_is_bare_unless_asked_for_its_caption_and_its_file_names_have_no_spaces(
    tmp_path, capsys
):
    """A paper sets its own \\caption: without --caption the TikZ is a bare tikzpicture and the SVG has
    no caption; with it, the caption is typeset (LaTeX quotes, not “?call1?”). Every file name is free
    of spaces ("empty left" is figure-empty-left)."""
    bare = paper_figures(tmp_path / "bare")
    assert all(" " not in p.name for p in bare) and (tmp_path / "bare" / "figure-empty-left.tex").exists()
    tikz = (tmp_path / "bare" / "figure-call1.tex").read_text()
    assert "text width" not in tikz and "Robot r (closest to K)" not in tikz
    assert tikz.startswith(r"\begin{tikzpicture}") and tikz.rstrip().endswith(r"\end{tikzpicture}")
    out = tmp_path / "call1.tex"
    assert main(["figure", "--figure", "call1", "--format", "tikz", "--caption", "--out", str(out)]) == 0
    captioned = out.read_text()
    assert "Figure ``call1'': Robot r (closest to K)" in captioned and "?" not in captioned
    assert main(["figure", "--figure", "call1", "--format", "svg"]) == 0
    assert "closest to K" not in capsys.readouterr().out


def test_the_robot_a_caption_names_is_marked_with_the_lines_it_names_and_numbers_are_legible():
    """call1: "Robot r (closest to K) sees two decider robots on L_I(r) and R_I(r) is symmetric": r is
    ringed and named, L_I(r) is the deciders' line and R_I(r) the next occupied line right of r. Robot
    numbers are set at 8 pt in TikZ (a cell is 0.5 cm) and 14 px in SVG (a cell is 24 px)."""
    figure = figures()["call1"]
    session, _ = figure_session("call1")
    view = session.view()
    d = drawing_of(view, "", figure.marked)
    r = view.robots[figure.marked.robot]
    assert r.light == "call" and d.named == ((r.position, "r"),)
    deciders = {p.position[0] for p in view.robots if p.light == "decider"}
    lines = {label: at for axis, at, label, _ in d.lines if axis == "x"}
    assert lines["L_I(r)"] == deciders.pop() and not deciders
    right = min(p.position[0] for p in view.robots if p.position[0] > r.position[0])
    assert lines["R_I(r)"] == right
    tikz, svg = to_tikz(d), to_svg(d)
    assert r"\footnotesize" in tikz and r"\tiny" not in tikz and "{$r$}" in tikz
    numbers = [t for t in ET.fromstring(svg).iter(f"{SVG}text") if (t.text or "").isdigit()]
    assert numbers and all(float(t.get("font-size")) >= 14 for t in numbers)
    assert any(t.text == "r" for t in ET.fromstring(svg).iter(f"{SVG}text"))


def test_every_marked_robot_of_figures_json_is_the_one_its_caption_describes():
    """Each figure's named robot is a robot of its scenario at its event, in the light its caption gives."""
    lights = {"call1": "call", "call2": "call", "Decider2Leader1": "leader1", "leaderConfig": "leader",
              "LineFormation": "leader", "LineFormed": "leader"}  # fmt: skip
    marked = {label: f for label, f in figures().items() if f.marked is not None}
    assert set(marked) == set(lights)
    for label, figure in marked.items():
        session, _ = figure_session(label)
        assert session.view().robots[figure.marked.robot].light == lights[label], label
