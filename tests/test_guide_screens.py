"""The GUIDE quotes screens: each quote is made here by the code that writes it, so that a change of
wording on either side fails (docs/GUIDE.md)."""

from __future__ import annotations

import re
from pathlib import Path

from apf_viz.core import shapes
from apf_viz.ui.app import demo_session
from apf_viz.workbench.session import Session
from tests.apf_helpers import compare_on_the_collision_counterexample

ROOT = Path(__file__).resolve().parent.parent
DEMOS = ROOT / "demo_patterns"
GUIDE = " ".join((ROOT / "docs" / "GUIDE.md").read_text().split())


def _plain(markdown: str) -> str:
    return " ".join(markdown.replace("**", "").replace("  \n", " ").split())


def _following_a_trace() -> str:
    s = demo_session()
    path = DEMOS / "traces" / "literal-collision-4.jsonl"
    s.load_trace(path.name, path.read_bytes())
    for _ in range(5):
        s.step()
    return _plain(s.view().trace_line)


def _a_branch() -> str:
    s = Session([(0, 0), (0, 2), (1, 0), (1, 3)], [(0, 0), (1, 0), (2, 0), (3, 0)], y_up=[True] * 4)
    s.set_scheduler("async")
    s.set_seed(3)
    for _ in range(40):
        s.step()
    s.seek(20)
    s.set_scheduler("round-robin")
    for _ in range(8):
        s.step()
    s.return_to_set_aside()
    return s.view().branches[0]


def _drawing_of(cells: int) -> Session:
    s = demo_session()
    s.set_mode("edit-pattern")
    s.clear_pattern()
    s.draw_box((9, 0), (14, 3), erase=False)
    assert len(s.editor.pattern) == cells
    return s


def _compare() -> str:
    s = compare_on_the_collision_counterexample(demo_session())
    return _plain(s.view().compare_text)


def _class_caption() -> str:
    from apf_viz.workbench.view_model.caption import KEYS

    return KEYS["following"].replace("<b>", "").replace("</b>", "")


SCREENS = {
    "Following the lecture": _class_caption,
    "Following the trace: event 5 of 41": _following_a_trace,
    "#2: left at step 20, 8 step(s), stopped at event 28": _a_branch,
    "Fit pattern trims the 14 last-drawn cells · Fit robots adds 14 robots": lambda: (
        _drawing_of(24).view().fit_preview
    ),
    "Targets: 24 / robots: 10": lambda: _plain(_drawing_of(24).view().counts),
    "First differing decision at event 26, robot 1 (◆): A robot 1 · Compute by A3.off.line-wait → light "
    "off, to stay": _compare,
}


def test_every_screen_the_guide_quotes_is_what_the_code_writes():
    for quote, made in SCREENS.items():
        assert quote in GUIDE, f"the GUIDE no longer quotes {quote!r}"
        assert quote in made(), f"the screen no longer reads {quote!r}"


def test_the_guide_quotes_no_screen_line_this_test_does_not_make():
    """A quote in the GUIDE that reads like one of these screens is one of them."""
    screen_like = re.compile(r'"((?:Following|Targets:|Robots:|Fit pattern|#\d+:|First differing)[^"]*)"')
    quoted = {m.group(1) for m in screen_like.finditer(GUIDE)}
    made = set(SCREENS)
    assert all(any(q.startswith(m) or m.startswith(q) for m in made) for q in quoted), quoted - made


def test_the_text_in_the_guide_is_drawn_by_its_font():
    assert shapes.text("HI", (0, 0))  # the GUIDE's studio example is in the 3×5 font
