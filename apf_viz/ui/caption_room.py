"""The share of the canvas's height a presenting page's caption may take (ui/panels/presentation.py
floats it there): a framed camera leaves that room free, so the caption never covers the run. Its own
module, so that what frames a camera (the browser's screen, an exported page) does not import the panels."""

from __future__ import annotations

__all__ = ["CAPTION_ROOM", "PHONE_SHEET_ROOM"]

CAPTION_ROOM = 0.35
PHONE_SHEET_ROOM = 0.6
"""On a phone held upright viser shows its panel as a sheet over the bottom of the screen, at most 60 %
of its height (its client's BottomPanel), open when the page loads: a framed camera puts the run in the
40 % above it (the question and the caption are in the sheet)."""
