"""A hunt: the exhaustive check (:mod:`apf_viz.explore.explorer`) on many generated starts
(:mod:`apf_viz.explore.hunt_families`), one row per start: its family, k, D, the verdict, the states it
took, the seconds, and where a counterexample was written.

Each start is searched under ASYNC with the partial-order reduction and only the activations that can
change something (``eligible_only``: a whole cycle that changes nothing is dropped; it leads back to the
same configuration, so no collision, escape, deadlock or fair cycle is lost: docs/VERIFICATION.md). A
start whose search hits its state budget is ``budget``: nothing is proved about it, and the table says so
instead of calling it verified.
"""

from __future__ import annotations

import json
import random
import time
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from apf_viz.explore.hunt_families import FAMILIES, draw

__all__ = ["COLUMNS", "KEY", "HuntStart", "hunt_one", "hunt_starts"]

COLUMNS: tuple[str, ...] = (
    "family", "k", "seed", "algorithm", "flips", "D", "verdict", "states", "max_states", "seconds",
    "detail", "counterexample", "robots", "pattern", "y_up",
)  # fmt: skip
"""A hunt table's columns, in order."""
KEY: tuple[str, ...] = ("family", "k", "seed", "algorithm", "flips")
"""What names a row: a resumed hunt runs only the starts whose key is not in the table yet."""
INTEGERS = frozenset({"k", "seed", "D", "states", "max_states"})


@dataclass(frozen=True)
class HuntStart:
    """One start of a hunt: drawn from (family, k, seed) by :func:`~apf_viz.explore.hunt_families.draw`."""

    family: str
    k: int
    seed: int

    def name(self) -> str:
        return f"{self.family}-k{self.k}-s{self.seed}"


def hunt_starts(
    ks: Sequence[int], count: int, seed: int, families: Sequence[str] = tuple(FAMILIES)
) -> list[HuntStart]:
    """``count`` starts: the families in turn, each start's k drawn from ``ks`` (reproducibly from
    ``seed``), each start's own seed ``seed``·10⁶ + its number, so two hunts with different seeds share
    no start and a longer hunt begins with a shorter one's starts."""
    unknown = [f for f in families if f not in FAMILIES]
    if unknown:
        raise ValueError(f"unknown families {', '.join(unknown)}; known: {', '.join(FAMILIES)}")
    if not families or not ks:
        raise ValueError("a hunt needs at least one family and one k")
    out = []
    for i in range(count):
        rng = random.Random(f"hunt-start:{seed}:{i}")
        out.append(HuntStart(families[i % len(families)], rng.choice(list(ks)), seed * 1_000_000 + i))
    return out


def hunt_one(
    start: HuntStart,
    algorithm: str,
    max_states: int,
    counterexamples: str | None = None,
    flips: str = "drawn",
) -> dict:
    """Search every schedule of one start; its row (and, on a failure, its counterexample trace written
    into the folder ``counterexamples``). ``flips``: "drawn", the start's own y-axes; "all", every
    assignment of them in turn (2^k searches sharing their decisions; ``max_states`` is for all of
    them), the first failing one kept."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.budget import paper_D
    from apf_viz.explore.check import all_flips, counterexample_text
    from apf_viz.explore.explorer import Decisions, Explorer

    case = draw(start.family, start.k, start.seed)
    algo = get_algorithm(algorithm)
    t0 = time.perf_counter()
    assignments = [tuple(case.y_up)] if flips == "drawn" else all_flips(start.k)
    decisions, states = Decisions(), 0
    for y_up in assignments:
        result = Explorer(
            algo, case.robots, case.pattern, y_up, max_states=max(1, max_states - states),
            reduction=True, eligible_only=True, decisions=decisions,
        ).run()  # fmt: skip
        states += result.states
        if result.verdict != "verified":
            case = replace(case, y_up=list(y_up))
            break
    result.states = states
    seconds = time.perf_counter() - t0
    written = ""
    if result.verdict not in ("verified", "budget") and counterexamples is not None:
        from apf_viz.core.files import write_atomic

        folder = Path(counterexamples)
        folder.mkdir(parents=True, exist_ok=True)  # a worker on another machine: its own folder
        path = folder / f"{start.name()}.jsonl"
        text = counterexample_text(algo, case.robots, case.pattern, case.y_up, "async", result)
        write_atomic(path, text)
        written = str(path)
    return {
        "family": start.family,
        "k": start.k,
        "seed": start.seed,
        "algorithm": algorithm,
        "flips": flips,
        "D": paper_D(case.robots, case.pattern),
        "verdict": result.verdict,
        "states": result.states,
        "max_states": max_states,
        "seconds": round(seconds, 3),
        "detail": result.detail,
        "counterexample": written,
        "robots": json.dumps([list(p) for p in case.robots]),
        "pattern": json.dumps([list(p) for p in case.pattern]),
        "y_up": json.dumps(case.y_up),
    }
