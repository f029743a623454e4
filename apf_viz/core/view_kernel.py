"""A robot's view built in one compiled pass (numba), where numba is installed.

The same "nearest robot per primitive direction" as :func:`apf_viz.core.grid.nearest_per_direction`
(paper §2, *Visibility*), but as one loop over the k robots instead of a dozen numpy calls: each offset's
lattice distance g = gcd(|dx|, |dy|) and primitive direction (dx/g, dy/g), the nearest robot of each
direction kept in a table indexed by the direction (a crowd, every offset at most :data:`DIRECT_SPAN`)
or in an open-addressing hash table (robots spread wider), then the visible robots in index order and in
the view's order (dx, then dy in the observer's frame). In a crowd of 1,000 robots a build costs about
21 µs (28 with the hash table, numpy's 95), and the crowd's traveller builds one at each of its steps
(docs/PERFORMANCE.md).

numba is optional (``pip install apf-viz[fast]``): without it, or with ``APF_VIZ_KERNELS=0`` in the
environment, :func:`compiled` returns None and :class:`~apf_viz.core.visibility.Views` builds with numpy,
the reference the kernel is tested against (``tests/test_view_kernel.py``). numba is imported on the
first view of a run of at least :data:`KERNEL_MIN_ROBOTS` robots, so a small run never pays for it; the
compiled code is cached on disk (``cache=True``), so only the first process on a machine compiles.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable
from types import ModuleType

import numpy as np

from apf_viz.core.grid import PACKED_SPAN_LIMIT

KERNEL_MIN_ROBOTS = 48
"""Below this many robots a numpy build costs little, and importing numba (a fifth of a second) more."""

KERNEL_SPAN_LIMIT = PACKED_SPAN_LIMIT
"""The kernel is used while every offset is below this in both coordinates: then the view's sort key
dx·(2·span + 1) + dy and the hash of a direction are exact in int64 (|key| < 2^42). Beyond it (robots
spread far apart, which walks serve) the numpy build, exact for every offset int64 holds, is used."""

_EMPTY = np.iinfo(np.int64).min
_COUNTING_SPAN = 1 << 14  # the view is ordered by counting sorts below this span, else by a sort
REDUCED_SPAN = 1024
"""Offsets with |dx|, |dy| below this have g, |dx|/g and |dy|/g in one table (:func:`reduced_table`):
a look-up instead of a Euclid loop and two divisions, a tenth of the cost of a crowd's view."""
DIRECT_SPAN = 255
"""Where the caller's bound on every offset (the robots' extent) is at most this (a crowd), the nearest
robot per direction is kept in a table indexed by the direction itself, at most (2·255 + 1)² entries: no
hashing, no probing, no pass over a hash table; beyond it, the hash table."""
_BITS = 10  # REDUCED_SPAN = 2^10: g, |dx|/g and |dy|/g each fit in 10 bits of a table entry
_KEY_OFFSET = 1 << 21  # a primitive direction (ux, uy), |ux|, |uy| < 2^20, packed as one key
_KEY_WIDTH = 1 << 22

# (positions, observer, flip, light codes, reach, *new_tables(k))
#   → (ids, sx, sy, dx, ly, code, lights present)
Built = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, "int | np.integer"]
Kernel = Callable[..., Built]


@functools.cache
def reduced_table() -> np.ndarray:
    """For 0 ≤ a, b < REDUCED_SPAN: g = gcd(a, b) | (a/g) << 10 | (b/g) << 20, as uint32 (4 MiB, made
    once); the entry of (0, 0) is 0 (only the observer stands there)."""
    axis = np.arange(REDUCED_SPAN, dtype=np.int64)
    g = np.gcd.outer(axis, axis)
    g[0, 0] = 1
    entry = g | (axis[:, None] // g) << _BITS | (axis[None, :] // g) << (2 * _BITS)
    entry[0, 0] = 0
    table: np.ndarray = entry.astype(np.uint32)
    return table


def table_size(k: int) -> int:
    """The open-addressing table for k robots: a power of two, at most a quarter full."""
    size = 16
    while size < 4 * k:
        size *= 2
    return size


def new_tables(k: int) -> tuple[np.ndarray, ...]:
    """A caller's own arguments for the kernel after its first five: the reduced table (shared), the
    hash table's work arrays (overwritten by every call), and the direction table's: its entries, each
    valid only for the call its stamp names (so it is never cleared), each robot's entry, and the count
    of calls."""
    n = table_size(k)
    hashed = tuple(np.empty(n, dtype=np.int64) for _ in range(3))
    side = 2 * DIRECT_SPAN + 1
    direct = (
        np.zeros(side * side, dtype=np.int64),  # stamp: untouched pages cost nothing until used
        np.empty(side * side, dtype=np.int32),  # g of the nearest robot seen so far
        np.empty(side * side, dtype=np.int32),  # that robot
        np.empty(k, dtype=np.int64),  # each robot's direction entry (−1: the observer)
        np.zeros(1, dtype=np.int64),  # calls so far
    )
    return (reduced_table(), *hashed, *direct)


def compiled() -> Kernel | None:
    """The compiled view build, or None when numba is missing or ``APF_VIZ_KERNELS=0``."""
    if os.environ.get("APF_VIZ_KERNELS", "1") == "0":
        return None
    try:
        import numba
    except ImportError:
        return None
    return _compile(numba)


@functools.cache
def _compile(numba: ModuleType) -> Kernel:
    # build_view calls its helpers as globals: compiled code must find the compiled ones there.
    global _counting_pass, _order_by_offset, _nearest_by_table, _nearest_by_hash, _in_view_order
    counting, order, by_table, by_hash, view_order = (
        getattr(f, "py_func", f)
        for f in (_counting_pass, _order_by_offset, _nearest_by_table, _nearest_by_hash, _in_view_order)
    )
    try:
        jit = numba.njit(cache=True, nogil=True)
        compiled_counting = jit(counting)
    except RuntimeError:  # numba has nowhere to write its cache (a read-only install, no writable home)
        jit = numba.njit(nogil=True)
        compiled_counting = jit(counting)
    _counting_pass = compiled_counting
    _order_by_offset = jit(order)
    _nearest_by_table = jit(by_table)
    _nearest_by_hash = jit(by_hash)
    _in_view_order = jit(view_order)  # after _order_by_offset: it calls the compiled one
    kernel: Kernel = jit(build_view)
    return kernel


def build_view(
    P: np.ndarray,
    r: int,
    flip: int,
    code_of: np.ndarray,
    reach: int,
    reduced: np.ndarray,
    hk: np.ndarray,
    hv: np.ndarray,
    hg: np.ndarray,
    stamp: np.ndarray,
    best_g: np.ndarray,
    best_j: np.ndarray,
    entry: np.ndarray,
    calls: np.ndarray,
) -> Built:
    """Robot r's view (numba compiles this; plain Python runs it too, slowly: the tests do).

    Args:
        P: shape (k, 2) int64, distinct points, every offset below :data:`KERNEL_SPAN_LIMIT`.
        r: the observer. flip: 1 if its local +y is the global +y, else −1.
        code_of: each robot's light code (uint8).
        reach: a bound on |dx| and |dy| of every offset (the caller keeps one: the robots' extent).
        reduced, hk, hv, hg, stamp, best_g, best_j, entry, calls: :func:`new_tables`.

    Returns:
        ids (visible robots, increasing), sx, sy (their global offsets, in ids' order), the view
        sorted by (dx, dy) in r's frame: dx, ly (its local y) and code, and the codes present as a bit
        each (−1 if some code is too large for the bits: then unknown).
    """
    k = P.shape[0]
    x0 = P[r, 0]
    y0 = P[r, 1]
    if reach <= DIRECT_SPAN:
        calls[0] += 1
        visible = _nearest_by_table(P, r, reduced, stamp, best_g, best_j, entry, calls[0], reach)
    else:
        visible = _nearest_by_hash(P, r, reduced, hk, hv, hg)
    n = 0
    for j in range(k):
        if visible[j]:
            n += 1
    ids = np.empty(n, dtype=np.int64)
    sx = np.empty(n, dtype=np.int64)
    sy = np.empty(n, dtype=np.int64)
    span = 1
    i = 0
    for j in range(k):
        if visible[j]:
            ids[i] = j
            sx[i] = P[j, 0] - x0
            sy[i] = P[j, 1] - y0
            span = max(span, abs(sx[i]) + 1, abs(sy[i]) + 1)
            i += 1
    dx_sorted, ly_sorted, code, present = _in_view_order(ids, sx, sy * flip, code_of, span)
    return ids, sx, sy, dx_sorted, ly_sorted, code, present


def _in_view_order(
    ids: np.ndarray, sx: np.ndarray, ly: np.ndarray, code_of: np.ndarray, span: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int | np.integer]:
    """The visible robots sorted by (dx, ly) in the observer's frame: dx, ly, light code, and the codes
    present as a bit each (−1 past 62 codes). ``span`` bounds |dx| and |ly|."""
    n = ids.shape[0]
    if span <= _COUNTING_SPAN:
        by_offset = _order_by_offset(sx, ly, span)
    else:
        by_offset = np.argsort(sx * (2 * span + 1) + ly)  # distinct points: distinct keys
    dx_sorted = np.empty(n, dtype=np.int64)
    ly_sorted = np.empty(n, dtype=np.int64)
    code = np.empty(n, dtype=np.uint8)
    present: int | np.integer = 0  # one bit per palette code, or -1 past 62 codes
    for i in range(n):
        o = by_offset[i]
        dx_sorted[i] = sx[o]
        ly_sorted[i] = ly[o]
        c = code_of[ids[o]]
        code[i] = c
        present = present | (np.int64(1) << np.int64(c)) if c < 62 and present >= 0 else -1
    return dx_sorted, ly_sorted, code, present


def _nearest_by_table(
    P: np.ndarray,
    r: int,
    reduced: np.ndarray,
    stamp: np.ndarray,
    best_g: np.ndarray,
    best_j: np.ndarray,
    entry: np.ndarray,
    call: int,
    reach: int,
) -> np.ndarray:
    """Which robots r sees, every offset at most ``reach`` ≤ :data:`DIRECT_SPAN` (< REDUCED_SPAN): the
    nearest robot of each primitive direction kept in the entry (ux + reach, uy + reach) of a table
    (2·reach + 1) wide; an entry counts only if its stamp is this call's."""
    k = P.shape[0]
    low = (1 << _BITS) - 1
    width = 2 * reach + 1
    x0 = P[r, 0]
    y0 = P[r, 1]
    for j in range(k):
        if j == r:
            entry[j] = -1
            continue
        dx = P[j, 0] - x0
        dy = P[j, 1] - y0
        e = np.int64(reduced[abs(dx), abs(dy)])
        g = e & low
        ux = (e >> _BITS) & low
        uy = e >> (2 * _BITS)
        if dx < 0:
            ux = -ux
        if dy < 0:
            uy = -uy
        s = (ux + reach) * width + uy + reach
        entry[j] = s
        if stamp[s] != call or g < best_g[s]:  # the first along this line of sight, or nearer
            stamp[s] = call
            best_g[s] = g
            best_j[s] = j
    visible = np.zeros(k, dtype=np.bool_)
    for j in range(k):
        s = entry[j]
        if s >= 0 and best_j[s] == j:
            visible[j] = True
    return visible


def _nearest_by_hash(
    P: np.ndarray, r: int, reduced: np.ndarray, hk: np.ndarray, hv: np.ndarray, hg: np.ndarray
) -> np.ndarray:
    """Which robots r sees, for any offsets: the nearest robot of each primitive direction kept in an
    open-addressing table keyed by the direction."""
    k = P.shape[0]
    mask = hk.shape[0] - 1
    span_r = reduced.shape[0]
    low = (1 << _BITS) - 1
    x0 = P[r, 0]
    y0 = P[r, 1]
    for s in range(hk.shape[0]):
        hk[s] = _EMPTY
    for j in range(k):
        if j == r:
            continue
        dx = P[j, 0] - x0
        dy = P[j, 1] - y0
        a = abs(dx)
        b = abs(dy)
        if a < span_r and b < span_r:
            e = np.int64(reduced[a, b])
            g = e & low
            ua = (e >> _BITS) & low
            ub = e >> (2 * _BITS)
        else:
            while b:
                a, b = b, a % b
            g = a
            ua = abs(dx) // g
            ub = abs(dy) // g
        # The primitive direction (±ua, ±ub) as one key; the robot nearest along it is the one seen.
        ux = ua if dx >= 0 else -ua
        uy = ub if dy >= 0 else -ub
        key = (ux + _KEY_OFFSET) * _KEY_WIDTH + uy + _KEY_OFFSET
        h = (ux * 40503 + uy * 2654435761) & mask  # exact (|ux|, |uy| < 2^20); the probe decides
        while True:
            held = hk[h]
            if held == _EMPTY:
                hk[h] = key
                hv[h] = j
                hg[h] = g
                break
            if held == key:
                if g < hg[h]:  # nearer along the same line of sight: it hides the other
                    hv[h] = j
                    hg[h] = g
                break
            h = (h + 1) & mask
    visible = np.zeros(k, dtype=np.bool_)
    for s in range(hk.shape[0]):
        if hk[s] != _EMPTY:
            visible[hv[s]] = True
    return visible


def _order_by_offset(sx: np.ndarray, ly: np.ndarray, span: int) -> np.ndarray:
    """The permutation sorting the points by (sx, ly), every |coordinate| < span: two stable counting
    sorts, by ly then by sx (linear; compiled sorts of hundreds of keys cost more)."""
    return _counting_pass(sx, _counting_pass(ly, np.arange(sx.shape[0]), span), span)


def _counting_pass(keys: np.ndarray, order: np.ndarray, span: int) -> np.ndarray:
    """``order`` stably re-sorted by ``keys[order[t]]`` (every |key| < span)."""
    n = order.shape[0]
    width = 2 * span + 1
    count = np.zeros(width + 1, dtype=np.int64)
    for t in range(n):
        count[keys[order[t]] + span + 1] += 1
    for v in range(width):
        count[v + 1] += count[v]
    out = np.empty(n, dtype=np.int64)
    for t in range(n):
        i = order[t]
        v = keys[i] + span
        out[count[v]] = i
        count[v] += 1
    return out
