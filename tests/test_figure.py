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
    pdflatex = shutil.which("pdflatex")
    assert pdflatex is not None, "scripts/test.sh installs texlive-latex-base and texlive-pictures"
    document = tmp_path / "figures" / "all.tex"
    inputs = "".join(rf"\input{{{p.name}}}\par" + "\n" for p in written if p.suffix == ".tex")
    document.write_text(
        r"\documentclass{article}\usepackage{tikz}\begin{document}" + "\n" + inputs + r"\end{document}"
    )
    done = subprocess.run(
        [pdflatex, "-interaction=nonstopmode", "-halt-on-error", document.name],
        cwd=document.parent,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout[-2000:]
    assert (document.parent / "all.pdf").stat().st_size > 10_000


def test_a_figure_draws_each_robot_in_its_lights_colour_and_the_selected_robots_sight():
    s = demo_session()
    for _ in range(60):
        s.step()
    s.selected = 1
    view = s.view()
    d = drawing_of(view, "caption")
    root = ET.fromstring(to_svg(d))
    fills = [c.get("fill") for c in root.iter(f"{SVG}circle")]
    for r in view.robots:
        c = view.legend[r.light].color
        assert f"rgb({c[0]},{c[1]},{c[2]})" in fills
    assert len(d.rays) == len(view.rays) > 0 and d.selected == view.robots[1].position
    assert set(d.hidden) == {view.robots[j].position for j in view.hidden}
    texts = [t.text for t in root.iter(f"{SVG}text")]
    assert {r.light for r in view.robots} <= set(texts)  # the legend names the lights shown
    tikz = to_tikz(d)
    assert tikz.count(r"circle (0.34);") == len(view.robots) + len(d.hidden)
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
