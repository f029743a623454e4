"""Join from the wall: the class address as large text and a QR code a laptop's camera reads, drawn
here (segno, pure Python: no network, no script in the page)."""

from __future__ import annotations

import html
from urllib.parse import urlparse

import segno

QR_SCALE = 10  # pixels a module: a version-3 code is about 330 px, read from the back of a room
LOOPBACK = ("127.0.0.1", "localhost", "::1")


def only_this_machine(address: str) -> bool:
    """Whether the address names this machine only (a laptop cannot reach it)."""
    return (urlparse(address).hostname or "") in LOOPBACK


def qr_svg_uri(address: str) -> str:
    """The address as a QR code (medium error correction), an SVG data URI for an ``<img>``."""
    return segno.make(address, micro=False, error="m").svg_data_uri(scale=QR_SCALE, border=2)


def join_html(address: str) -> str:
    """What the projector shows: the address, large, and its QR code; on a loopback address, how to
    serve the class instead (a laptop cannot reach this machine's 127.0.0.1)."""
    words = html.escape(address)
    note = ""
    if only_this_machine(address):
        note = (
            '<div style="font-size:20px;color:#a00;margin-top:8px">This server listens on this machine '
            "only: start it with <code>apf-viz serve --host 0.0.0.0</code> for the class's laptops.</div>"
        )
    return (
        '<div style="text-align:center">'
        f'<div style="font-size:40px;font-weight:bold;word-break:break-all" data-apf="class-address">{words}'
        "</div>"
        f'<img alt="QR code of {words}" data-apf="class-qr" src="{qr_svg_uri(address)}" '
        'style="image-rendering:pixelated;margin-top:12px">'
        f"{note}</div>"
    )
