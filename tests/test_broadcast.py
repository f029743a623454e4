"""The broadcast windows encoded once for all pages (``ui/broadcast.py``): the bytes a page is sent are
viser's own, a reused window is the same window, and viser is patched only where it was copied from."""

from __future__ import annotations

import asyncio
import time

import msgspec.msgpack
import numpy as np
import pytest
import zstandard
from viser import _messages
from viser.infra import _infra
from viser.infra._async_message_buffer import AsyncMessageBuffer

from apf_viz.ui import broadcast
from apf_viz.ui.app import App, demo_session, free_port


class _Socket:
    """A page's websocket: keeps what it is sent; once every page of ``pages`` has been sent
    ``windows`` windows, the buffer is done (its producers end)."""

    def __init__(self, buffer: AsyncMessageBuffer, windows: int, pages: list[_Socket]) -> None:
        self.sent: list[bytes] = []
        self._buffer = buffer
        self._windows = windows
        self._pages = pages
        pages.append(self)

    async def send(self, data: bytes) -> None:
        self.sent.append(data)
        if all(len(p.sent) >= p._windows for p in self._pages):
            self._buffer.set_done()


def _sent(producer, messages: list, pages: int = 1, max_window: int = 128) -> list[list[bytes]]:
    """What ``producer`` sends each of ``pages`` pages of a broadcast buffer holding ``messages``."""

    async def run() -> list[list[bytes]]:
        buffer = AsyncMessageBuffer(asyncio.get_running_loop(), persistent_messages=True)
        buffer.max_window_size = max_window
        for message in messages:
            buffer.push(message)
        windows = -(-len(messages) // max_window)
        sockets: list[_Socket] = []
        for _ in range(pages):
            _Socket(buffer, windows, sockets)
        await asyncio.wait_for(
            asyncio.gather(*(producer(s, buffer, i) for i, s in enumerate(sockets))), timeout=20
        )
        return [s.sent for s in sockets]

    return asyncio.run(run())


def _decoded(data: bytes) -> tuple[object, list[bytes]]:
    """A window's messages with its time stamp blanked, and its binary buffers (each 8-byte aligned
    in the frame, so the padding before the first depends on the compressed part's length)."""
    inner_size = int.from_bytes(data[:8], "little")
    compressed_size = int.from_bytes(data[8:16], "little")
    inner = zstandard.ZstdDecompressor().decompress(data[16 : 16 + compressed_size], inner_size)
    payload = msgspec.msgpack.decode(inner)
    payload["timestampSec"] = None
    buffers, offset = [], 16 + compressed_size
    for size in payload["binaryBufferLengths"]:
        offset += -offset % 8
        buffers.append(data[offset : offset + size])
        offset += size
    assert offset == len(data), "bytes after the last binary buffer"
    return payload, buffers


@pytest.fixture(scope="module")
def scene_messages() -> list:
    """The messages of the demo's shared scene, as a served run broadcasts them (meshes with binary
    arrays, labels, visibility, poses), and a few more with arrays of every shape."""
    app = App(demo_session(), port=free_port(), verbose=False)
    try:
        app.request_render()
        deadline = time.time() + 30
        while app.frames < 2:
            assert time.time() < deadline, "the demo was not drawn"
            time.sleep(0.05)
        buffer = app.server._websock_server.get_message_buffer()
        with buffer.buffer_lock:
            messages = [buffer.message_from_id[k] for k in sorted(buffer.message_from_id)]
    finally:
        app.stop()
    rng = np.random.default_rng(7)
    for n in (0, 1, 5, 333):
        messages.append(
            _messages.PointCloudMessage(
                name=f"/extra/{n}",
                props=_messages.PointCloudProps(
                    points=rng.normal(size=(n, 3)).astype(np.float32),
                    colors=rng.integers(0, 255, size=(n, 3), dtype=np.uint8),
                    point_size=0.1,
                    point_shape="circle",
                    precision="float32",
                    scale=1.0,
                    point_shading="flat",
                ),
            )
        )
    return messages


def test_the_demo_scene_has_binary_arrays(scene_messages) -> None:
    """The comparison below would prove little if no message carried an array sent as raw bytes."""
    binary: list[memoryview] = []
    for message in scene_messages:
        message.as_serializable_dict(binary)
    assert len(scene_messages) > 20 and len(binary) > 4


@pytest.mark.parametrize("max_window", [128, 7, 1])
def test_a_page_is_sent_the_bytes_viser_sends(scene_messages, max_window: int) -> None:
    """Window by window, the same messages and binary tail as viser's own producer (time stamps
    aside), in windows of every size."""
    broadcast.CACHE.clear()
    ours = _sent(broadcast.shared_producer, scene_messages, max_window=max_window)[0]
    theirs = _sent(broadcast.ORIGINAL, scene_messages, max_window=max_window)[0]
    assert len(ours) == len(theirs) == -(-len(scene_messages) // max_window)
    assert [_decoded(x) for x in ours] == [_decoded(x) for x in theirs]


def test_pages_that_keep_up_share_one_serialisation(scene_messages) -> None:
    """Ten pages, the same windows: each window serialised once, and every page sent it."""
    broadcast.CACHE.clear()
    sent = _sent(broadcast.shared_producer, scene_messages, pages=10, max_window=16)
    windows = len(sent[0])
    assert all([_decoded(x) for x in s] == [_decoded(x) for x in sent[0]] for s in sent)
    assert broadcast.CACHE.misses == windows and broadcast.CACHE.hits == 9 * windows


def test_a_window_of_other_messages_is_serialised_anew(scene_messages) -> None:
    """The cache is keyed by the messages themselves: a window differing by one message, or by their
    order, is serialised again; the same window is not."""
    cache = broadcast.WindowCache()
    first = cache.serialized(scene_messages[:5])
    assert cache.serialized(list(scene_messages[:5])) is first
    others = [scene_messages[:4] + scene_messages[6:7], scene_messages[1:6], scene_messages[4::-1]]
    assert all(cache.serialized(w) is not first for w in others)
    assert (cache.hits, cache.misses) == (1, 4)


def test_every_window_is_stamped_when_it_is_sent(scene_messages) -> None:
    """A window served from the cache carries the time it is sent, not the time it was serialised
    (the page paces what it is sent by these stamps)."""
    serialized = broadcast.serialize(scene_messages[:9])
    zstd = zstandard.ZstdCompressor(level=1)
    first, second = serialized.frame(zstd, 12.5), serialized.frame(zstd, 99.25)
    assert _decoded(first)[0]["messages"] == _decoded(second)[0]["messages"]

    def stamp(data: bytes) -> float:
        size, compressed = int.from_bytes(data[:8], "little"), int.from_bytes(data[8:16], "little")
        inner = zstandard.ZstdDecompressor().decompress(data[16 : 16 + compressed], size)
        return msgspec.msgpack.decode(inner)["timestampSec"]

    assert (stamp(first), stamp(second)) == (12.5, 99.25)


def test_a_pages_own_messages_are_not_shared() -> None:
    """A page's own buffer (its panel) is never served from the cache: another page's panel is not
    its panel even when built of equal messages."""
    broadcast.CACHE.clear()
    message = _messages.GuiUpdateMessage("id", {"value": 1})

    async def run() -> None:
        buffer = AsyncMessageBuffer(asyncio.get_running_loop(), persistent_messages=False)
        buffer.push(message)
        await asyncio.wait_for(broadcast.shared_producer(_Socket(buffer, 1, []), buffer, 0), timeout=5)

    asyncio.run(run())
    assert broadcast.CACHE.hits == broadcast.CACHE.misses == 0


def test_viser_is_patched_only_where_it_was_copied_from() -> None:
    """The installed viser's producer is the one copied (its source unchanged), so the App runs with
    the cache; a producer of any other source is left alone."""
    assert broadcast.copied_from(broadcast.ORIGINAL)
    assert _infra._message_producer is broadcast.shared_producer  # the App above installed it

    async def other(*args) -> None:  # a viser whose producer changed
        return None

    assert not broadcast.copied_from(other)
