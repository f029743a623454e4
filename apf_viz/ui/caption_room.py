"""The share of the canvas's height a presenting page's caption may take (ui/panels/presentation.py
floats it there): a framed camera leaves that room free, so the caption never covers the run. Its own
module, so that what frames a camera (the browser's screen, an exported page) does not import the panels."""

from __future__ import annotations

__all__ = ["CAPTION_ROOM"]

CAPTION_ROOM = 0.35
