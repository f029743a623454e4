"""A screenshot made for a slide: the browser's render with, beside it, the legend of what it shows and,
under it, the caption a lecture needs (stage, last event, outcome), drawn with Pillow (which imageio
brings), so the picture explains itself when pasted into a talk."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from apf_viz.ui.image import on_white
from apf_viz.workbench.view_model.legend import Entry

# A font with the paper's symbols (sub- and superscripts, arrows) where the system has one; Pillow's
# own scalable font otherwise (Latin only: a missing symbol shows as a box, the words stay readable).
_FONTS = (
    Path("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"),
    Path("/usr/share/fonts/dejavu/DejaVuSans.ttf"),
    Path("/Library/Fonts/Arial Unicode.ttf"),
    Path("C:/Windows/Fonts/arial.ttf"),
)
INK = (30, 30, 30)
SOFT = (90, 90, 90)


def font(size: int) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    for path in _FONTS:
        if path.exists():
            return ImageFont.truetype(str(path), size)
    return ImageFont.load_default(size=size)


def _wrap(draw: ImageDraw.ImageDraw, text: str, face, width: int) -> list[str]:
    """``text`` broken into lines no wider than ``width`` pixels, at spaces."""
    lines: list[str] = []
    for paragraph in text.split("\n"):
        line = ""
        for word in paragraph.split(" "):
            trial = f"{line} {word}".strip()
            if line and draw.textlength(trial, font=face) > width:
                lines.append(line)
                line = word
            else:
                line = trial
        lines.append(line)
    return lines


def _swatch(draw: ImageDraw.ImageDraw, entry: Entry, x: int, y: int, size: int) -> None:
    box = (x, y, x + size, y + size)
    if entry.shape == "none":  # a mark the canvas writes as a word: the words say it
        return
    if entry.shape == "disc":
        draw.ellipse(box, fill=entry.color, outline=(50, 50, 50), width=max(1, size // 10))
    elif entry.shape == "tile":  # a light drawn as a square robot
        draw.rectangle(box, fill=entry.color, outline=(50, 50, 50), width=max(1, size // 10))
    elif entry.shape == "ring":
        draw.ellipse(box, outline=entry.color, width=max(2, size // 4))
    elif entry.shape == "burst":
        c, r = (x + size / 2, y + size / 2), size / 2
        points = [
            (c[0] + (r if i % 2 == 0 else r / 3) * np.cos(np.pi * i / 4 - np.pi / 2),
             c[1] + (r if i % 2 == 0 else r / 3) * np.sin(np.pi * i / 4 - np.pi / 2))
            for i in range(8)
        ]  # fmt: skip
        draw.polygon(points, fill=entry.color)
    else:
        draw.rectangle(box, fill=entry.color)


def compose(render: np.ndarray, caption: Sequence[str], legend: Sequence[Entry]) -> np.ndarray:
    """The render (H, W, 3 or 4) with the legend in a column on its right and the caption below, on
    white; text sized to the render's height so the slide reads the same at any resolution."""
    picture = on_white(render)
    h, w = picture.shape[:2]
    size = max(13, h // 42)
    face, bold = font(size), font(round(size * 1.15))
    column = max(260, w // 3)
    probe = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    gap = size // 2
    text_width = column - 3 * size
    legend_lines = [(e, _wrap(probe, e.label + (f" — {e.meaning}" if e.meaning else ""), face, text_width))
                    for e in legend]  # fmt: skip
    caption_lines = [line for text in caption for line in _wrap(probe, text, bold, w + column - 2 * size)]
    line_height = round(size * 1.35)
    band = (len(caption_lines) * line_height + 2 * gap) if caption_lines else 0
    legend_height = gap + sum(len(lines) * line_height + gap // 2 for _, lines in legend_lines)
    canvas = Image.new("RGB", (w + column, max(h, legend_height) + band), "white")
    canvas.paste(Image.fromarray(picture), (0, 0))
    draw = ImageDraw.Draw(canvas)
    draw.line([(w, 0), (w, max(h, legend_height))], fill=(210, 210, 210), width=1)
    y = gap
    for entry, lines in legend_lines:
        _swatch(draw, entry, w + size // 2, y + (line_height - size) // 2, size)
        for line in lines:
            draw.text((w + 2 * size, y), line, fill=INK if line is lines[0] else SOFT, font=face)
            y += line_height
        y += gap // 2
    y = max(h, legend_height) + gap
    for line in caption_lines:
        draw.text((size, y), line, fill=INK, font=bold)
        y += line_height
    return np.asarray(canvas)
