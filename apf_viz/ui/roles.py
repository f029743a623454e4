"""Who a page is: a presenter page drives the shared run; a class page follows it. A page's role is fixed
by the address it was opened at, whatever the order pages arrive in: the presenter address carries a
secret the class address does not (viser's client opens its websocket at the ``websocket`` query
parameter of the page's address, path included, and the server reads that path)."""

from __future__ import annotations

import secrets
from typing import Literal

Role = Literal["presenter", "class"]

PRESENT_PATH = "/present/"


class Roles:
    """The server's presenter secret, and the addresses a lecturer hands out."""

    def __init__(self, secret: str | None = None) -> None:
        # 128 bits: the presenter address cannot be guessed from the class address, nor tried for.
        self.secret = secret or secrets.token_urlsafe(16)

    def role_of(self, path: str | None) -> Role:
        """The role of a page whose websocket was opened at ``path`` (None: unknown, a class page)."""
        if path is not None and secrets.compare_digest(path.encode(), (PRESENT_PATH + self.secret).encode()):
            return "presenter"
        return "class"

    def addresses(self, host: str, port: int) -> tuple[str, str]:
        """(presenter, class): the two addresses of a server listening on ``host``:``port``."""
        page = f"http://{host}:{port}/"
        return f"{page}?websocket=ws://{host}:{port}{PRESENT_PATH}{self.secret}", page
