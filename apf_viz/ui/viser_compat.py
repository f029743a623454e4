"""The one door to viser's insides: every name apf-viz uses that viser does not publish is read here, and
nowhere else (tests/test_house.py holds it). Each access has a contract test (tests/test_viser_compat.py)
that fails when a viser release changes it, and a fallback that works with public API only. At start
the server checks them all (:func:`missing`) and says in one terminal line what it could not use and what
that costs, so a lecturer finds out before the class does.

The accesses, and what each costs when it is missing:

- ``websocket path``: the path a page opened its websocket at (``server._websock_server._live_connections
  [id].request.path``), which tells a presenter page from a class page. Without it every page opens as a
  class page; a presenter takes control by typing the presenter code (printed in the terminal) into the
  page's ``Presenter code`` field.
- ``remote address``: the network address a page connected from (``…_live_connections[id]
  .remote_address``), to which the class's seats are issued (workbench/seats.py). Without it every page
  counts as from one unknown address: ``apf-viz serve --seats-per-address N`` gives the class N seats.
- ``shared producer``: viser's per-page message producer (``viser.infra._infra._message_producer``, and
  ``_append_aligned_buffers``), replaced by a copy that serialises a broadcast window once for all pages
  (ui/broadcast.py). Without it each page's windows are serialised for that page: slower with many pages.
- ``timeline marks``: a slider's marks (``handle._marks``; viser has no public setter). Without them the
  timeline shows no stage marks; the Run folder lists the stages anyway.
- ``notification state``: whether a notification was closed (``handle._impl.removed``). Without it a
  page's notification is removed again when replaced (harmless: viser ignores it).
- ``player time field`` (in the page, not the server): the time field of the player an exported page
  embeds (:data:`PLAYER_TIME_FIELD_JS`), through which ui/lecture_page.py seeks stop to stop. Without it
  the exported lecture says so in its caption and plays as a slideshow. Its contract test is a browser's
  (tests/test_lecture_projector.py, the exported page).
- ``notification corner`` (in the page): the class of the box viser's notifications stand in
  (:data:`NOTICES_BESIDE_THE_RUN`), moved from over the canvas to the bottom-right corner, over the panel.
  Without it notifications stand where viser puts them, over the canvas's top-left corner. Its contract
  test is a browser's (tests/test_bench_browser.py).
- ``class address window`` (in the page): the class of viser's windows (Mantine's modal), widened while it
  holds the class address (:data:`WIDE_CLASS_ADDRESS`) and closed by Escape through its Close button
  (:data:`ESCAPE_CLOSES_CLASS_ADDRESS`). Without it the window stays narrow (the address, made to fit on
  one line, is smaller) and Escape leaves it open. Its contract test is a browser's
  (tests/test_bench_browser.py, J at a LAN address).
"""

from __future__ import annotations

import hashlib
import inspect
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import viser

try:  # the module viser's producer lives in; a release may move it
    from viser.infra import _infra
except ImportError:  # pragma: no cover - exercised by hiding it in tests/test_viser_compat.py
    _infra = None  # type: ignore[assignment]

try:
    from viser._messages import GuiSliderMark
except ImportError:  # pragma: no cover
    GuiSliderMark = None  # type: ignore[assignment,misc]

# sha256 of the source of viser 1.1.1's ``_message_producer``, the function ui/broadcast.py copies.
COPIED_SHA256 = "8283328d06cfa014576888930c49a857a2d79892dc89f9694444895945018ea3"


@dataclass(frozen=True)
class Access:
    """One of viser's insides: its name, whether this viser has it, and what its absence costs."""

    name: str
    present: Callable[[], bool]
    cost: str


# ---------------------------------------------------------------- the websocket path (roles)
def _live_connection(server: viser.ViserServer, client_id: int) -> object | None:
    """A page's websocket connection, as viser keeps it (None: no such page, or viser keeps none there)."""
    connections = getattr(getattr(server, "_websock_server", None), "_live_connections", None)
    return connections.get(client_id) if isinstance(connections, dict) else None


def websocket_path(server: viser.ViserServer, client_id: int) -> str | None:
    """The path a page opened its websocket at, or None when viser does not say (see the module's
    docstring: the presenter code then stands in)."""
    request = getattr(_live_connection(server, client_id), "request", None)
    path = getattr(request, "path", None)
    return path if isinstance(path, str) else None


def remote_address(server: viser.ViserServer, client_id: int) -> str | None:
    """The network address a page connected from (its host, no port), or None when viser does not say."""
    address = getattr(_live_connection(server, client_id), "remote_address", None)
    host = address[0] if isinstance(address, tuple) and address else None
    return host if isinstance(host, str) else None


def _has_remote_addresses() -> bool:
    return "remote_address" in dir(getattr(_infra, "ServerConnection", None)) and _has_websocket_paths()


def _has_websocket_paths() -> bool:
    server_class = getattr(getattr(viser, "infra", None), "WebsockServer", None)
    if server_class is None:
        return False
    source = _source(server_class)
    return "_live_connections" in source and "request" in _source(getattr(_infra, "ServerConnection", None))


# ---------------------------------------------------------------- the message producer (broadcast)
def producer() -> object | None:
    """viser's per-page message producer, as it is now (None: this viser has none where it was)."""
    return getattr(_infra, "_message_producer", None)


def producer_is_the_copied_one(candidate: object | None = None) -> bool:
    """Whether viser's producer is the one ui/broadcast.py copied (its source, hashed)."""
    found = producer() if candidate is None else candidate
    source = _source(found)
    return bool(source) and hashlib.sha256(source.encode()).hexdigest() == COPIED_SHA256


def swap_producer(replacement: Callable[..., Any], original: object) -> bool:
    """Put ``replacement`` in the place of viser's producer when viser's is the one copied (or is already
    the replacement); whether it is there now."""
    if _infra is None:
        return False
    if producer() is replacement:
        return True
    if not producer_is_the_copied_one(original) or producer() is not original:
        return False
    if not hasattr(_infra, "_append_aligned_buffers"):
        return False
    _infra._message_producer = replacement
    return True


def append_aligned_buffers(parts: list, buffers: list, offset: int) -> None:
    """viser's own framing of a window's binary buffers (each 8-byte aligned after ``offset`` bytes)."""
    _infra._append_aligned_buffers(parts, buffers, offset)


# ---------------------------------------------------------------- a slider's marks
def set_slider_marks(slider: object, marks: Sequence[tuple[float, str | None]]) -> None:
    """The marks under a slider (the timeline's stages); nothing where this viser cannot."""
    if GuiSliderMark is None or not hasattr(slider, "_marks"):
        return
    wanted = tuple(GuiSliderMark(float(v), label) for v, label in marks) or None
    if slider._marks != wanted:
        slider._marks = wanted


def _has_slider_marks() -> bool:
    from viser import _messages

    props = getattr(_messages, "GuiSliderProps", None)
    return GuiSliderMark is not None and "_marks" in getattr(props, "__annotations__", {})


# ---------------------------------------------------------------- a notification's state
def notification_removed(handle: object) -> bool:
    """Whether a page's notification was already removed (unknown: not removed, so it is removed again,
    which viser ignores)."""
    impl = getattr(handle, "_impl", None)
    return bool(getattr(impl, "removed", False))


def _has_notification_state() -> bool:
    return "removed" in _source(getattr(viser, "NotificationHandle", None)) or "removed" in _source(
        getattr(getattr(viser, "_notification_handle", None), "_NotificationHandleState", None)
    )


# ---------------------------------------------------------------- the exported player's time field
# A JavaScript function: the number field of the playback bar (a Mantine Paper) of viser's embedded
# player, or null. Setting it (the native setter, then an input event) seeks the recording and pauses it.
PLAYER_TIME_FIELD_JS = """function () {
    var all = document.querySelectorAll('input');
    for (var i = 0; i < all.length; i++) {
      var e = all[i];
      if (e.closest('.mantine-Paper-root') && /^[0-9.]*$/.test(e.value) && e.type !== 'hidden') return e;
    }
    return null;
  }"""


# ---------------------------------------------------------------- where notifications stand
# CSS for the page: viser's notifications (Mantine's) in the bottom-right corner, over the panel (or, in
# presentation mode, the caption's end), the panel's width at 1024 px, so that they never cover the run;
# and clicked through, so that none hides a button under it (they close themselves; the × still closes).
NOTICES_BESIDE_THE_RUN = (
    "<style>.mantine-Notifications-root{position:fixed!important;top:auto!important;left:auto!important;"
    "right:12px!important;bottom:12px!important;max-width:360px}"
    ".mantine-Notification-root{pointer-events:none!important;opacity:0.94}"
    ".mantine-Notification-closeButton{pointer-events:auto!important}</style>"
)


# CSS and a listener for the class address's window (panels/join.py): wide enough for the address on one
# line at 40 px (viser's windows are narrow), and closed by Escape as by its Close button (a window
# opened by J holds no focus, so its own Escape never hears the key). The listener is installed once a
# page, by an image that fails to load.
WIDE_CLASS_ADDRESS = (
    "<style>.mantine-Modal-content:has([data-apf=class-address])"
    "{flex:0 0 min(94vw,980px) !important;max-width:none !important}</style>"
)
ESCAPE_CLOSES_CLASS_ADDRESS = (
    '<img alt="" src="data:,join" style="display:none" onerror="'
    "if(!window.apfJoinEscape){window.apfJoinEscape=1;document.addEventListener('keydown',function(e){"
    "if(e.key!=='Escape'){return;}var a=document.querySelector('[data-apf=class-address]');if(!a){return;}"
    "var m=a.closest('.mantine-Modal-content');var b=m&&Array.prototype.find.call("
    "m.querySelectorAll('button'),function(x){return x.textContent.trim()==='Close';});"
    "if(b){b.click();}},true);}"
    '">'
)


# ---------------------------------------------------------------- the check at start
ACCESSES = (
    Access("websocket path", _has_websocket_paths,
           "every page opens as a class page; a presenter types the presenter code into Presenter code"),
    Access("remote address", _has_remote_addresses,
           "every page counts as from one address: the class has --seats-per-address seats"),
    Access("shared producer", lambda: producer_is_the_copied_one() or _installed(),
           "class pages are serialised once each: slower with many pages"),
    Access("timeline marks", _has_slider_marks, "the timeline shows no stage marks"),
    Access("notification state", _has_notification_state, "none (a closed message is closed again)"),
)  # fmt: skip

_replacements: list[object] = []  # the producer put in viser's place, once it is (ui/broadcast.py)


def _installed() -> bool:
    return bool(_replacements) and producer() is _replacements[0]


def remember_replacement(replacement: object) -> None:
    _replacements[:] = [replacement]


def missing() -> list[Access]:
    """The accesses this viser does not offer as apf-viz uses them."""
    out = []
    for access in ACCESSES:
        try:
            ok = access.present()
        except Exception:  # an inside that changed shape is missing, whatever it raised
            ok = False
        if not ok:
            out.append(access)
    return out


def startup_line(absent: Sequence[Access]) -> str | None:
    """One terminal line naming what could not be used and its cost (None: everything is there)."""
    if not absent:
        return None
    version = getattr(viser, "__version__", "?")
    said = "; ".join(f"{a.name} ({a.cost})" for a in absent)
    return f"apf-viz: viser {version} lacks what apf-viz uses of its insides: {said}"


def _source(thing: object) -> str:
    if thing is None:
        return ""
    try:
        return inspect.getsource(thing)  # type: ignore[arg-type]
    except (OSError, TypeError):
        return ""
