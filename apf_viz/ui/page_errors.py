"""A page's malformed message is one line on the presenter's terminal, not a traceback.

A page may send anything over its websocket (a student's console, a stale client). viser cannot decode or
dispatch it; websockets logs "connection handler failed" with the whole traceback, and asyncio logs a
handler's exception as "Task exception was never retrieved": a screenful on the lecturer's terminal for
each message, while nothing changed (the page is let go, the run untouched). This filter, on those two
loggers, keeps the exception's type and first words in one line and drops the traceback; it says at most
one line every :data:`EVERY` seconds, counting those it held back. Nothing reaches the page. A page
that left without a goodbye (a reload, its move to its seat, a closed lid: websockets' ConnectionClosed)
sent nothing wrong and is let go as any page that leaves: nothing is said of it.
"""

from __future__ import annotations

import logging
import threading
import time

from websockets.exceptions import ConnectionClosed

EVERY = 10.0
LOGGERS = ("websockets.server", "websockets", "asyncio")


class OneLine(logging.Filter):
    """Records that carry an exception become one line; those within :data:`EVERY` s of the last are
    counted, not shown."""

    def __init__(self, clock=time.monotonic) -> None:
        super().__init__()
        self._clock = clock
        self._lock = threading.Lock()
        self._last = -EVERY
        self._held = 0

    def filter(self, record: logging.LogRecord) -> bool:
        if not record.exc_info or record.exc_info[1] is None:
            return True
        error = record.exc_info[1]
        if isinstance(error, ConnectionClosed):
            return False
        with self._lock:
            now = self._clock()
            if now - self._last < EVERY:
                self._held += 1
                return False
            held, self._held, self._last = self._held, 0, now
        words = " ".join(str(error).split())[:100]
        more = f"; {held} more since" if held else ""
        record.msg = "apf-viz: a page sent a message the server could not use (%s%s); ignored%s"
        record.args = (type(error).__name__, f": {words}" if words else "", more)
        record.exc_info = record.exc_text = None
        record.stack_info = None
        return True


def quiet_page_errors() -> OneLine:
    """Install :class:`OneLine` on the loggers that report a page's bad message (once per process)."""
    for name in LOGGERS:
        logger = logging.getLogger(name)
        for f in logger.filters:
            if isinstance(f, OneLine):
                return f
    one = OneLine()
    for name in LOGGERS:
        logging.getLogger(name).addFilter(one)
    return one
