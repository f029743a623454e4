"""Who a page is: a presenter page drives the shared run; a class page follows it. A page's role is fixed
by the address it was opened at, whatever the order pages arrive in: the presenter address carries a
secret the class address does not (viser's client opens its websocket at the ``websocket`` query
parameter of the page's address, path included, and the server reads that path)."""

from __future__ import annotations

import secrets

from apf_viz.workbench.screen_state import Role

PRESENT_PATH = "/present/"
CODE_TRIES = 5


class Roles:
    """The server's presenter secret, and the addresses a lecturer hands out."""

    def __init__(self, secret: str | None = None) -> None:
        # 128 bits: the presenter address cannot be guessed from the class address, nor tried for.
        self.secret = secret or secrets.token_urlsafe(16)
        # Where the address cannot be read (ui/viser_compat.py), a code a person types: 40 bits, and a
        # page has CODE_TRIES tries.
        self.code = secrets.token_hex(5)
        self._tries: dict[object, int] = {}

    def claims(self, page: object, code: str) -> bool | None:
        """Whether ``code`` is the presenter code (None: this page has used up its tries). A field reports
        each key typed: only a code of the code's length counts as a try."""
        code = code.strip().lower()
        if len(code) != len(self.code):
            return False
        tried = self._tries.get(page, 0)
        if tried >= CODE_TRIES:
            return None
        if secrets.compare_digest(code.encode(), self.code.encode()):
            return True
        self._tries[page] = tried + 1
        return False

    def role_of(self, path: str | None) -> Role:
        """The role of a page whose websocket was opened at ``path`` (None: unknown, a class page)."""
        if path is not None and secrets.compare_digest(path.encode(), (PRESENT_PATH + self.secret).encode()):
            return "presenter"
        return "class"

    def addresses(self, host: str, port: int) -> tuple[str, str]:
        """(presenter, class): the two addresses of a server listening on ``host``:``port``."""
        page = f"http://{host}:{port}/"
        return f"{page}?websocket=ws://{host}:{port}{PRESENT_PATH}{self.secret}", page
