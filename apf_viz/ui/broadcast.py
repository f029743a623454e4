"""One serialisation of a broadcast window for every page that receives it.

viser sends each page the messages broadcast to all (the shared scene) as windows: a page's producer
takes what it has not yet sent, serialises it (each message to a map, the window to msgpack), compresses
it (zstd) and sends it. The pages that keep up are sent the same window, the same message objects, each
serialising it anew: with a class of 60, 60 serialisations of every frame. Here a page's producer first
looks for the window among the last few serialised (by the identity of its messages, which a window
holds from the broadcast buffer), then stamps it with the time and compresses it, as viser does.

viser's producer (``viser.infra._infra._message_producer`` of viser 1.1.1) is replaced by a copy that
differs only in that cache, and only where its source is the source copied (ui/viser_compat.py, the one
door to viser's insides, checks it and does the swap); with any other viser, viser is left as it is and
the server says so at start. tests/test_broadcast.py holds the copy to viser's own producer byte for
byte, the helpers it calls included. A page is sent what viser would have sent it: the same
messages, binary buffers and fresh time stamp (the page paces messages by those stamps), the stamp last
in the map instead of second.

viser updates a node's or element's stored properties in place when one is assigned (so that a page that
connects later is sent the current state), and pushes an update message with the change. A window that
holds the creation message and was serialised before the change may be sent again only to a page whose
window ends before that update message: the page then gets the earlier state and, in its next window,
the update, and ends where it would have.
"""

from __future__ import annotations

import dataclasses
import struct
import threading
import time
from collections import OrderedDict
from collections.abc import Sequence
from typing import Any

import msgspec.msgpack
import zstandard

from apf_viz.ui import viser_compat

ORIGINAL = viser_compat.producer()  # viser's own, as it was before any swap
KEPT = 8  # serialised windows kept
Message = Any  # viser's message (infra's Message): what a window holds


@dataclasses.dataclass(frozen=True)
class Serialized:
    """A window serialised but for its time stamp: msgpack ending in the stamp's 8 bytes (a float64,
    the last value of the map), and the binary buffers that follow the compressed part."""

    inner: bytes
    binary: tuple[memoryview, ...]

    def frame(self, zstd: zstandard.ZstdCompressor, stamp: float) -> bytes:
        """The window as viser sends it, stamped ``stamp``: the msgpack's sizes, the msgpack
        zstd-compressed, then the binary buffers each 8-byte aligned."""
        inner = self.inner[:-8] + struct.pack(">d", stamp)
        compressed = zstd.compress(inner)
        parts: list[bytes | memoryview] = [
            len(inner).to_bytes(8, "little"),
            len(compressed).to_bytes(8, "little"),
            compressed,
        ]
        viser_compat.append_aligned_buffers(parts, list(self.binary), 16 + len(compressed))
        return b"".join(parts)


def serialize(window: Sequence[Message]) -> Serialized:
    """What ``_infra._message_producer`` encodes of a window, the time stamp put last and left 0."""
    binary_buffers: list[memoryview] = []
    serialized = tuple(message.as_serializable_dict(binary_buffers) for message in window)
    inner = msgspec.msgpack.encode(
        {
            "messages": serialized,
            "binaryBufferLengths": tuple(b.nbytes for b in binary_buffers),
            "timestampSec": 0.0,
        }
    )
    assert inner[-9] == 0xCB, "msgpack's float64 marker before the stamp"
    return Serialized(inner, tuple(binary_buffers))


class WindowCache:
    """The last :data:`KEPT` serialised windows, by the identity of their messages. An entry holds the
    messages themselves, so their ids are not reused while it is kept."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._entries: OrderedDict[tuple[int, ...], tuple[Sequence[object], Serialized]] = OrderedDict()
        self.hits = 0
        self.misses = 0

    def serialized(self, window: Sequence[Message]) -> Serialized:
        key = tuple(map(id, window))
        with self._lock:
            entry = self._entries.get(key)
            if entry is not None:
                self.hits += 1
                self._entries.move_to_end(key)
                return entry[1]
            self.misses += 1
        result = serialize(window)
        with self._lock:
            self._entries[key] = (tuple(window), result)
            while len(self._entries) > KEPT:
                self._entries.popitem(last=False)
        return result

    def clear(self) -> None:
        with self._lock:
            self._entries.clear()
            self.hits = self.misses = 0


CACHE = WindowCache()


async def shared_producer(
    websocket: Any,
    buffer: Any,
    client_id: int,
    backlog_done_message: Message | None = None,
) -> None:
    """viser's producer, but a window of the broadcast buffer is serialised once for all pages."""
    window_generator = buffer.window_generator(client_id, backlog_done_message=backlog_done_message)
    zstd = zstandard.ZstdCompressor(level=1)
    shared = buffer.persistent_messages  # the broadcast buffer; a page's own is not shared
    try:
        while not buffer.done:
            try:
                outgoing = await window_generator.__anext__()
            except StopAsyncIteration:
                break
            serialized = CACHE.serialized(outgoing) if shared else serialize(outgoing)
            await websocket.send(serialized.frame(zstd, time.perf_counter()))
    finally:
        await window_generator.aclose()


def copied_from(producer: object) -> bool:
    """Whether ``producer``'s source is the source :func:`shared_producer` was copied from."""
    return viser_compat.producer_is_the_copied_one(producer)


def install() -> bool:
    """Replace viser's producer by :func:`shared_producer` where viser's is the one copied; whether
    it is (again and again: the App installs it each time it starts)."""
    viser_compat.remember_replacement(shared_producer)
    return viser_compat.swap_producer(shared_producer, ORIGINAL)
