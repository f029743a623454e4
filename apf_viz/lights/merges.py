"""The merges the lab tries (two lights of an algorithm shown as one), and the starts it explores."""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass

from apf_viz.algorithms.merged_lights import MARKER, merged_name
from apf_viz.core.formats import InputError
from apf_viz.core.schedulers import ordered

COLUMNS = (
    "algorithm", "merge", "shown", "hidden", "ks", "verdict", "stage", "violation", "k", "start", "y_up",
    "events", "starts", "states", "random_runs", "random_failed", "seconds", "trace", "error",
    "exercised", "random_exercised",
)  # fmt: skip
# exercised: explorer views (each once per start) in which the base algorithm set the hidden light;
# random_exercised: the same in the random runs (decisions asked, each distinct view once per run).
KEY = ("algorithm", "merge", "ks")
RANDOM_KS = (6, 7, 8, 9, 10, 11, 12)
# Numbered runs keep their scheduler: the order the lab was first run in, then any added since.
RANDOM_SCHEDULERS = ordered(("fsync", "ssync", "async", "stale-first", "round-robin"))
RANDOM_SYMMETRIC_KS = tuple(range(8, 21))
DEMO_SCALES = (1, 2, 3)
MAX_STATES = 2_000_000  # per start: a k = 5 start with every flip takes about 200,000 with the reduction


@dataclass(frozen=True)
class Merge:
    """One variant of the lab: ``hidden`` is shown as ``shown``."""

    algorithm: str
    shown: str
    hidden: str

    @property
    def name(self) -> str:
        return f"{self.shown}={self.hidden}"

    @property
    def variant(self) -> str:
        return merged_name(self.algorithm, [(self.shown, self.hidden)])

    @classmethod
    def of(cls, row: dict) -> Merge:
        return cls(row["algorithm"], row["shown"], row["hidden"])


def ks_label(ks: Sequence[int]) -> str:
    """The table's ``ks`` column: the explorer's robot counts, as "1,2,3"."""
    return ",".join(map(str, ks))


def merges(algorithm: str, only: str | None = None) -> list[Merge]:
    """Every ordered pair of the algorithm's lights, or the pairs ``only`` names ("a=b,c=d")."""
    from apf_viz.algorithms import get_algorithm

    try:
        lights = get_algorithm(algorithm).lights
    except ValueError as e:
        raise InputError(f"--algorithm: {e}") from None
    if MARKER in algorithm:
        raise InputError(
            f"--algorithm {algorithm}: the lab merges lights itself; name the algorithm unmerged"
        )
    every = [Merge(algorithm, a, b) for a in lights for b in lights if a != b]
    if only is None:
        return every
    chosen = []
    for part in only.split(","):
        a, eq, b = part.strip().partition("=")
        m = Merge(algorithm, a.strip(), b.strip())
        if not eq or m not in every:
            raise InputError(
                f"--merges {part.strip()!r}: not a=b with two different lights of {algorithm} "
                f"({', '.join(lights)})"
            )
        chosen.append(m)
    return chosen


def parse_ks(text: str) -> tuple[int, ...]:
    """The robot counts the explorer covers: 1–3 (every start of the box) and 4–5 (the stated starts)."""
    from apf_viz.sweeps import parse_range

    ks = tuple(sorted(set(parse_range(text, "--ks"))))
    if not ks or ks[0] < 1 or ks[-1] > 5:
        raise InputError(
            f"--ks {text!r}: the explorer covers k = 1 to 5 (1–3: every start of a 4×4 box; 4–5: "
            "the stated starts)"
        )
    return ks


def starts_for(ks: Sequence[int]) -> list[tuple[str, list]]:
    """(name, start) in the order the explorer takes them: fewest robots first, so the first
    counterexample found is a small one; for each k the symmetric starts with robots on the axis first
    (where leader election is hardest), each start once."""
    from apf_viz.core.pattern_match import normalise
    from apf_viz.explore.small_starts import STATED_STARTS, axis_symmetric_box_starts, solvable_box_starts

    out: list[tuple[str, list]] = []
    seen: set[tuple] = set()

    def add(name: str, start: list) -> None:
        key = tuple(normalise(start))
        if key not in seen:
            seen.add(key)
            out.append((name, start))

    for k in ks:
        for start in axis_symmetric_box_starts(k, 5) if k >= 2 else []:
            add(json.dumps(start), start)
        if k <= 3:
            for start in solvable_box_starts(k, 4, mirrored=True):
                add(json.dumps(start), start)
        else:
            for name, start in STATED_STARTS.items():
                if len(start) == k:
                    add(name, start)
    return out


def explore_every_flip(algorithm, start: list):
    """The explorer on one start towards a row of its robots, under every assignment of flips (ASYNC, the
    reduction): what stage 0 asks of the base algorithm and stage 1 of each merge."""
    from apf_viz.explore.check import all_flips, check
    from apf_viz.explore.small_starts import line_pattern

    k = len(start)
    return check(algorithm, start, line_pattern(k), all_flips(k), "async", MAX_STATES, False)
