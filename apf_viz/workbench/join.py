"""Join from the wall: the class address as large text and a QR code a laptop's camera reads, drawn
here (segno, pure Python: no network, no script in the page)."""

from __future__ import annotations

import html
from urllib.parse import urlparse

import segno

QR_SCALE = 10  # pixels a module: a version-3 code is about 330 px, read from the back of a room
ADDRESS_PX = 40  # the address's size where it fits on one line; a longer one is made smaller to fit
CHAR_EM = 0.62  # a bold character's width, in ems, in the page's font (measured at 1024×768: 0.58–0.61)
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
    # One line, never broken inside the port: as large as ADDRESS_PX, smaller when the address is long
    # for the width it is shown in (cqw: a hundredth of the block holding it, whatever its window).
    size = f"min({ADDRESS_PX}px, calc(100cqw / {CHAR_EM * len(address):.1f}))"
    return (
        '<div style="text-align:center;container-type:inline-size">'
        f'<div style="font-size:{size};font-weight:bold;white-space:nowrap" data-apf="class-address">{words}'
        "</div>"
        f'<img alt="QR code of {words}" data-apf="class-qr" src="{qr_svg_uri(address)}" '
        'style="image-rendering:pixelated;margin-top:12px">'
        f"{note}</div>"
    )
