"""The ready-made patterns and starts (``demo_patterns/`` at the top of the repository).

A wheel or a non-editable install ships them inside the package, as ``apf_viz/demo_patterns`` (the
mapping is in pyproject.toml); a source checkout or an editable install reads the top-level folder, the
one source of both."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

from pydantic import BaseModel, ConfigDict, model_validator

from apf_viz.core.files import read_text
from apf_viz.core.formats import MAX_INPUT_BYTES
from apf_viz.core.grid import as_point

_PACKAGE = Path(__file__).resolve().parent


def packaged_dir(name: str) -> Path:
    """A top-level folder of the checkout that ships inside the package (demo_patterns, docs): the
    installed copy, or the checkout's own."""
    shipped = _PACKAGE / name
    return shipped if shipped.is_dir() else _PACKAGE.parent / name


def demo_dir() -> Path:
    """The folder of demo patterns (its ``starts/`` holds the demo starts)."""
    return packaged_dir("demo_patterns")


NOT_PATTERNS = ("scenarios.json", "figures.json")  # lists of demo_patterns/, not patterns


def demo_files(sub: str = "", suffix: str = ".json") -> dict[str, Path]:
    """The demo files of ``demo_patterns/`` (or of its sub-folder ``sub``), by name without the suffix.
    The scenario and figure lists are not patterns."""
    folder = demo_dir() / sub if sub else demo_dir()
    return {p.stem: p for p in sorted(folder.glob(f"*{suffix}")) if p.name not in NOT_PATTERNS}


class Scenario(BaseModel):
    """A ready lesson: a start with a pattern of its size, or a recorded trace, and what it shows.

    Files are named, never given as paths: a name resolves only through :func:`demo_files`."""

    model_config = ConfigDict(extra="forbid", frozen=True)
    name: str
    shows: str
    robots: str | None = None  # demo_patterns/starts/<robots>.json
    pattern: str | None = None  # demo_patterns/<pattern>.json
    trace: str | None = None  # demo_patterns/traces/<trace>.jsonl (<trace> may be lights/<name>)
    algorithm: str = "apf-opaque-grid"  # for a start and pattern (a trace names its own)
    # Rule ids its run fires under the visualiser's default adversary (ASYNC, seed 1): what its text
    # promises, checked by tests/test_session.py.
    fires: tuple[str, ...] = ()

    @model_validator(mode="after")
    def _one_source(self) -> Scenario:
        if (self.trace is None) == (self.robots is None or self.pattern is None):
            raise ValueError(f"scenario {self.name!r}: give robots and pattern, or a trace")
        return self

    def files(self) -> dict[str, Path]:
        """The scenario's files by role: robots and pattern, or trace."""
        if self.trace is not None:
            # "lights/NAME": a trace of a sub-folder (the light-budget lab's counterexamples)
            sub, _, name = self.trace.rpartition("/")
            return {"trace": demo_files(f"traces/{sub}" if sub else "traces", ".jsonl")[name]}
        assert self.robots is not None and self.pattern is not None
        return {"robots": demo_files("starts")[self.robots], "pattern": demo_files()[self.pattern]}


class _Scenarios(BaseModel):
    model_config = ConfigDict(extra="forbid")
    scenarios: list[Scenario]


@cache
def scenarios() -> dict[str, Scenario]:
    """The ready scenarios of ``demo_patterns/scenarios.json``, by name, in the file's order."""
    parsed = _Scenarios.model_validate_json(read_text(demo_dir() / "scenarios.json", MAX_INPUT_BYTES))
    return {s.name: s for s in parsed.scenarios}


def pattern_of_size(k: int) -> tuple[str, list[tuple[int, int]]] | None:
    """The first demo pattern (by name) with ``k`` points, if there is one."""
    for name, path in demo_files().items():
        points = json.loads(read_text(path, MAX_INPUT_BYTES)).get("points", [])
        if len(points) == k:
            return name, [as_point(p) for p in points]
    return None


DEMO_DIR = demo_dir()
DEMO_START = DEMO_DIR / "starts" / "demo-10.json"
DEMO_PATTERN = DEMO_DIR / "heart.json"


SHIPPED_KINDS = {"robots": ("starts", ".json"), "pattern": ("", ".json"), "trace": ("traces", ".jsonl")}
"""Where each kind of input ships (a sub-folder of demo_patterns/, the suffix): names a user may give."""


def shipped_file(name: str, kind: str) -> Path | None:
    """The packaged file a bare name stands for (``sym-call-7`` as robots, ``cup-7`` as a pattern,
    ``literal-collision-4`` as a trace), or None."""
    sub, suffix = SHIPPED_KINDS[kind]
    return demo_files(sub, suffix).get(name)


def find_scenario(name: str) -> str:
    """A Demo scenario's title from its title, or from a word of it that names one scenario only
    (``heart``, ``lockstep``); a one-line error naming the choices otherwise."""
    titles = list(scenarios())
    if name in titles:
        return name
    word = name.strip().lower()
    found = [t for t in titles if word and word in t.lower().replace("_", " ").split()]
    if len(found) == 1:
        return found[0]
    said = "names several" if found else "names none"
    raise ValueError(f"--demo {name!r} {said} of the scenarios: {'; '.join(titles)}")
