"""A class page's seat: the key its answers are held under (workbench/poll.py), the same after a reload.

A laptop keeps a random token in its browser's storage and opens its websocket at ``/seat/<token>``: the
page it first loads (the class address, with no ``websocket`` in it) goes once to the same address with
``?websocket=…/seat/<token>``, which viser's client connects at (as the presenter address does with
its secret), and a reload keeps it. The server reads the seat from that path (ui/viser_compat.py); where
it cannot, a page's key is its connection's, and a reload is a new page."""

from __future__ import annotations

import re

SEAT_PATH = "/seat/"
_TOKEN = re.compile(r"[0-9a-f]{32}")

# Runs once in each page (the image fails to load, and its onerror runs): a page opened at an address
# with no websocket in it goes to its seat's. 128 random bits: a seat cannot be guessed from another.
SEAT_JS = (
    '<img alt="" src="data:,seat" style="display:none" onerror="'
    "if(!/[?&amp;]websocket=/.test(location.search)){var k='apfSeat',t=null;"
    "try{t=localStorage.getItem(k);}catch(e){}"
    "if(!t||!/^[0-9a-f]{32}$/.test(t)){var a=new Uint8Array(16);crypto.getRandomValues(a);"
    "t=Array.prototype.map.call(a,function(b){return ('0'+b.toString(16)).slice(-2);}).join('');"
    "try{localStorage.setItem(k,t);}catch(e){}}"
    "var w=(location.protocol==='https:'?'wss://':'ws://')+location.host+'/seat/'+t;"
    "location.replace(location.pathname+'?websocket='+w);}"
    '">'
)


def seat_key(path: str | None, client_id: int) -> str:
    """The key a page's answers are held under: its seat's, else its connection's."""
    if path is not None and path.startswith(SEAT_PATH) and _TOKEN.fullmatch(path[len(SEAT_PATH) :]):
        return f"seat {path[len(SEAT_PATH) :]}"
    return f"page {client_id}"
