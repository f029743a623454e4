"""A class page's seat (workbench/seats.py) carried to the page and back: the same after a reload.

A page opens its websocket at ``/seat/<token>``, a token the server issued: the page it first loads (the
class address, with no ``websocket`` in it) is given a token in its panel and goes to the same address
with ``?websocket=…/seat/<token>``, which viser's client connects at (as the presenter address does with
its secret); the browser keeps the token and a reload keeps the seat. The server reads the token from
that path (ui/viser_compat.py) and checks its signature: a token the page made up, or one of another run
of the server, is no seat, and the page is given one (a reload later, it has it)."""

from __future__ import annotations

import json

from apf_viz.workbench.seats import TOKEN_PATTERN

SEAT_PATH = "/seat/"


def seat_token(path: str | None) -> str | None:
    """The token in a page's websocket path, as the page sent it (workbench/seats.py checks it)."""
    if path is not None and path.startswith(SEAT_PATH):
        return path[len(SEAT_PATH) :] or None
    return None


def seat_js(offer: str) -> str:
    """Runs once in a page without a seat (the image fails to load, and its onerror runs): it keeps the
    token ``offer`` the server issued it and goes to its seat's address. A page opened at the class
    address with a token kept from before tries that one first (the server gives it another if it is no
    longer a seat). A page already at that seat's address stays (never a loop of reloads)."""
    issued = json.dumps(offer).replace('"', "&quot;")
    return (
        '<img alt="" src="data:,seat" style="display:none" onerror="'
        f"var k='apfSeat',o={issued},t=null;"
        "if(!/[?&amp;]websocket=/.test(location.search)){try{t=localStorage.getItem(k);}catch(e){}}"
        f"if(!t||!/^{TOKEN_PATTERN}$/.test(t)){{t=o;}}"
        "try{localStorage.setItem(k,t);}catch(e){}"
        "var w=(location.protocol==='https:'?'wss://':'ws://')+location.host+'/seat/'+t;"
        "if(location.search!=='?websocket='+w){location.replace(location.pathname+'?websocket='+w);}"
        '">'
    )
