"""The projector's join card (workbench/join.py): the class address, large, and its QR code drawn on the
server by segno (this file is also how the lowest segno version is tested: scripts/test_lowest.sh)."""

from __future__ import annotations

import re
from urllib.parse import unquote

from apf_viz.workbench.join import QR_SCALE, join_html, only_this_machine, qr_svg_uri


def test_the_qr_code_of_a_class_address_is_a_small_svg_of_large_modules():
    uri = qr_svg_uri("http://192.168.1.20:8080/")
    assert uri.startswith("data:image/svg+xml")
    svg = unquote(uri.split(",", 1)[1])
    width = int(re.search(r"width=['\"](\d+)['\"]", svg).group(1))
    # A code of version 1 to 3 (21, 25 or 29 modules) and a border of 2 on each side, QR_SCALE px a
    # module: at most about 330 px, read from the back of a room.
    assert width in {(17 + 4 * version + 4) * QR_SCALE for version in (1, 2, 3)}, width


def test_the_card_escapes_the_address_and_says_when_only_this_machine_can_reach_it():
    card = join_html("http://127.0.0.1:8080/?a=<b>")
    assert "&lt;b&gt;" in card and "<b>" not in card.split("src=")[0]
    assert "--host 0.0.0.0" in card and only_this_machine("http://localhost:1/")
    lan = join_html("http://10.0.0.5:8080/")
    assert "--host" not in lan and 'data-apf="class-qr"' in lan and not only_this_machine("http://10.0.0.5/")
