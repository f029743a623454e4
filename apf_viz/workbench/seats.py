"""The class's seats: the keys a class page's answers are held under, issued by the server, never chosen
by a page. Pure: no viser (ui/seat.py carries a seat to the page and back).

A seat is a token the server signs (a random number and its HMAC under a secret of this server's run):
a page cannot mint one, and a forged or stale token is no seat. The server issues at most
``per_address`` seats to one network address and gives a page from an address that has them all one of
those again: a client that opens connection after connection, with fresh or forged tokens, answers as at
most ``per_address`` pages. One an address (the default) is one for each laptop or phone on a classroom's
network; a hall behind one router (every page from one address) needs ``apf-viz serve
--seats-per-address N``. A page whose address the server cannot read (a viser that does not say) is
issued seats as if every such page shared one unknown address."""

from __future__ import annotations

import hashlib
import hmac
import re
import secrets
import threading
from collections import OrderedDict

SEAT_PREFIX = "seat "
"""An answer's key is this and the seat's number (the token's random part), never the token itself."""
MAX_ADDRESSES = 10_000
"""Addresses remembered, at most (the oldest forgotten first): a scan from many addresses cannot grow the
server without bound."""
TOKEN_PATTERN = "[0-9a-f]{16}-[0-9a-f]{16}"
"""A seat's token: its number, a dash, its signature (the page's script checks a kept one's shape by it)."""
_TOKEN = re.compile(r"([0-9a-f]{16})-([0-9a-f]{16})")
UNKNOWN_ADDRESS = "unknown"


class Seats:
    """Issues seats and reads them back."""

    def __init__(self, per_address: int = 1, secret: bytes | None = None) -> None:
        if per_address < 1:
            raise ValueError("seats per address must be at least 1")
        self.per_address = per_address
        self._secret = secret if secret is not None else secrets.token_bytes(32)
        self._issued: OrderedDict[str, list[str]] = OrderedDict()  # address -> its seats' tokens
        self._lock = threading.Lock()

    def _sign(self, number: str) -> str:
        return hmac.new(self._secret, number.encode(), hashlib.sha256).hexdigest()[:16]

    def key(self, token: str | None) -> str | None:
        """The answers' key of a seat's token; None for no token, a forged one or another run's."""
        found = _TOKEN.fullmatch(token or "")
        if found is None or not hmac.compare_digest(self._sign(found.group(1)), found.group(2)):
            return None
        return SEAT_PREFIX + found.group(1)

    def issue(self, address: str | None) -> str:
        """A seat's token for a page from ``address`` that has none: a new one while the address has fewer
        than ``per_address``, else the one it was issued longest ago (a page that forgot its seat, a
        private window, gets it back)."""
        where = address or UNKNOWN_ADDRESS
        with self._lock:
            tokens = self._issued.get(where)
            if tokens is None:
                tokens = self._issued[where] = []
                while len(self._issued) > MAX_ADDRESSES:
                    self._issued.popitem(last=False)
            self._issued.move_to_end(where)
            if len(tokens) < self.per_address:
                number = secrets.token_hex(8)
                tokens.append(f"{number}-{self._sign(number)}")
                return tokens[-1]
            tokens.append(tokens.pop(0))  # the next page without one gets the next of them
            return tokens[-1]
