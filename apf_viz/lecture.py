"""A guided lecture: an ordered list of stops, each naming a Demo scenario (or going on with the run),
a condition to run to, what to select and compare, and the words to say. A pydantic model read from JSON
(shipped examples in ``demo_patterns/lectures/``, user files uploadable); a stop names scenarios and
algorithms only through the built-in lists, never a path or code.
:class:`~apf_viz.workbench.lecturer.Lecturer` walks a session through it."""

from __future__ import annotations

import re
from collections.abc import Iterable
from functools import cache
from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from apf_viz.core.files import read_text
from apf_viz.core.formats import MAX_INPUT_BYTES, InputError, parse_json_model
from apf_viz.demos import demo_dir, demo_files, scenarios

MAX_LECTURE_BYTES = 1_000_000
MAX_EVENT = 10_000_000  # a stop runs at most this far (a lecture is checked the evening before)
# A stop's words are read from the back of a room at 20 px beside its picture: more than this does not fit
# the caption, and is more than a room reads while looking at the robots. Split a longer stop in two.
MAX_SAY_WORDS = 45

Outcome = Literal["formed", "collision", "stuck", "limit", "end"]  # "end": the run can go no further
State = Literal["running", "formed", "collision", "stuck", "limit"]  # a run's state when a stop is reached

# Presentation mode collapses the whole panel: words that send the room to a panel or folder name
# something the projector does not show.
_PANEL_WORDS = re.compile(r"\b(?:(?:the )?\w+ (?:panel|folder)|the panel)\b", re.I)


_OPENS = {"\u202a": "\u202c", "\u202b": "\u202c", "\u202d": "\u202c", "\u202e": "\u202c",
          "\u2066": "\u2069", "\u2067": "\u2069", "\u2068": "\u2069"}  # fmt: skip
_CLOSES = {"\u202c", "\u2069"}
_RTL = re.compile("[\u0590-\u08ff\ufb1d-\ufdff\ufe70-\ufeff]")


def isolated(text: str) -> str:
    """An author's text that cannot reorder the page's words around it: every direction control it opens
    (an embedding, override or isolate) closed at its end, and the whole set apart as an isolate (FSI …
    PDI) when it holds right-to-left letters or such controls. Left-to-right text is returned as it is."""
    if not _RTL.search(text) and not any(c in _OPENS or c in _CLOSES for c in text):
        return text
    pending: list[str] = []
    for c in text:
        if c in _OPENS:
            pending.append(_OPENS[c])
        elif c in _CLOSES and pending and pending[-1] == c:
            pending.pop()
    return "\u2068" + text + "".join(reversed(pending)) + "\u2069"


# Every model here is strict: a lecture's author writes 0 for a number; "0", true or 0.0 is a mistake
# said in one line, never read as 0 (tests/test_lecture.py).
class Until(BaseModel):
    """What a stop runs to: exactly one of an event number, a stage (words of the algorithm's stage
    name), the first time a rule id fires (``A1.off.terminal``; a part of a composite id counts) or an
    outcome."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)
    event: int | None = Field(default=None, ge=0, le=MAX_EVENT)
    stage: str | None = Field(default=None, min_length=1, max_length=200)
    rule: str | None = Field(default=None, min_length=1, max_length=120)
    outcome: Outcome | None = None

    @model_validator(mode="after")
    def _exactly_one(self) -> Until:
        given = [k for k in ("event", "stage", "rule", "outcome") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of event, stage, rule, outcome")
        return self

    def describe(self) -> str:
        if self.event is not None:
            return f"event {self.event}"
        if self.stage is not None:
            return f"the stage “{self.stage}”"
        if self.rule is not None:
            return f"rule {self.rule} fires"
        return f"the outcome {self.outcome}"


class Expect(BaseModel):
    """What a stop claims is true when it is reached; ``apf-viz lecture check`` holds every claim. Each
    field is optional; a field given is a claim."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)
    # light -> how many robots show it, exactly (0: none); lights not named are not claimed
    lights: dict[str, int] | None = Field(default=None, max_length=20)
    state: State | None = None  # the run's state
    compare_state: State | None = None  # the state of the run drawn beside it (a stop that compares)
    stage: str | None = Field(default=None, min_length=1, max_length=200)  # words of the stage name
    drawn: list[str] | None = Field(default=None, max_length=20)  # marks on the canvas, by label ("K")
    sees: int | None = Field(default=None, ge=0, le=100_000)  # robots the selected robot sees
    hidden: int | None = Field(default=None, ge=0, le=100_000)  # robots hidden from the selected robot
    stale: bool | None = None  # some robot holds a snapshot that shows others as they no longer are

    def count(self) -> int:
        """How many claims: each light counted, each mark, each other field given."""
        given = self.model_dump(exclude_none=True)
        return sum(len(v) if isinstance(v, dict | list) else 1 for v in given.values())

    @model_validator(mode="after")
    def _counts(self) -> Expect:
        for light, n in (self.lights or {}).items():
            if not 0 <= n <= 100_000 or len(light) > 40:
                raise ValueError(f"lights: {light[:40]!r}: a count from 0 to 100000")
        return self


# A coordinate pair in a stop's words: the screen gives coordinates on the grid (the event line) and in a
# robot's own frame (Why); words that give one say which.
_COORDINATES = re.compile(r"\(\s*[−-]?\d+\s*,\s*[−-]?\d+\s*\)")
_FRAME_NAMED = re.compile(r"\bframe\b|\bon the grid\b|\bgrid coordinates\b", re.I)
# Words that cannot be true together with a stage line: (the words' claim, the stage line's, in words).
_CONTRADICTIONS = (
    (re.compile(r"\bno leader\b|\bnot (?:yet )?elected\b", re.I), re.compile(r"leader elected|the leader\b"),
     "say no leader was elected"),
    (re.compile(r"\bnever forms?\b|\bnot formed\b", re.I), re.compile(r"^Formed"),
     "say the run does not form"),
)  # fmt: skip


def word_count(text: str) -> int:
    return len(text.split())


def frameless_coordinates(text: str) -> str | None:
    """The first coordinate pair in ``text`` when the text names no frame for it (the leader's, a
    robot's own, the grid), else None."""
    m = _COORDINATES.search(text)
    return m.group(0) if m and not _FRAME_NAMED.search(text) else None


def contradiction(text: str, stage_line: str) -> str | None:
    """How ``text`` (a stop's title and words) contradicts the caption's stage line, if it does."""
    for said, staged, what in _CONTRADICTIONS:
        if said.search(text) and staged.search(stage_line):
            return f"its words {what}, the stage line says “{stage_line}”"
    return None


def claimed_lights(text: str, lights: Iterable[str]) -> list[str]:
    """The lights ``text`` says a robot shows: "lit L", "lights L", "light L", "L robot(s)" for a light L
    of the algorithm (a word of the text that names a light in passing, "terminal1 light symmetric", is no
    claim that one shows it; "light symmetric" is)."""
    out = []
    for light in lights:
        name = re.escape(light)
        claim = rf"\b(?:lit|lights?)\s+(?:as\s+)?{name}\b|\b{name}\s+robots?\b"
        if re.search(claim, text, re.I):
            out.append(light)
    return out


def panel_words(text: str) -> str | None:
    """The panel or folder that ``text`` sends the room to (presentation mode hides every one), if any."""
    m = _PANEL_WORDS.search(text)
    return m.group(0) if m else None


QuestionKind = Literal["robot", "cell", "light", "outcome"]
# The outcomes a room may answer; "escape" (a robot walks away for ever) is offered though a run that is
# checked never ends in it: the run answers only what it shows within its cap.
QUESTION_OUTCOMES = ("formed", "collision", "stuck", "escape")
_ASKED = {
    "robot": "Which robot moves next?",
    "cell": "Where does robot {robot} move next?",
    "light": "Which light does robot {robot} turn on next?",
    "outcome": "How does this run end?",
}


class Question(BaseModel):
    """A question a stop asks the room. Its answer is never written by the author: it is what the run
    does from the stop under the lecture's scheduler and seed (workbench/question.py). ``robot``: which
    robot a ``cell`` or ``light`` question is about (and only theirs)."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)
    kind: QuestionKind
    robot: int | None = Field(default=None, ge=0, le=100_000)
    text: str | None = Field(default=None, min_length=1, max_length=160)  # else the kind's own words

    @field_validator("text")
    @classmethod
    def _set_apart(cls, text: str | None) -> str | None:
        return None if text is None else isolated(text)

    @model_validator(mode="after")
    def _robot_where_asked(self) -> Question:
        if self.kind in ("cell", "light") and self.robot is None:
            raise ValueError(f'a {self.kind} question names its robot ("robot": 3)')
        if self.kind in ("robot", "outcome") and self.robot is not None:
            raise ValueError(f"a {self.kind} question is about the whole run: give no robot")
        return self

    def words(self) -> str:
        """What the room is asked."""
        return self.text or _ASKED[self.kind].format(robot=self.robot)


class Stop(BaseModel):
    """One stop: where (a Demo scenario, else the run as the previous stop left it), until when, what
    to select or compare, and the words (a few sentences; the paper's symbols as ``L_1``, ``H_L^O``)."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)
    title: str = Field(min_length=1, max_length=120)
    say: str = Field(min_length=1, max_length=2000)
    scenario: str | None = Field(default=None, max_length=120)
    until: Until | None = None
    select: int | None = Field(default=None, ge=0, le=100_000)
    compare: str | None = Field(default=None, max_length=200)
    expect: Expect | None = None
    # The projector shows the class address and its QR code while at this stop (J does at any time).
    class_address: bool = False
    ask: Question | None = None  # a question to the room, answered by the run (docs/LECTURES.md)

    @model_validator(mode="after")
    def _known_scenario(self) -> Stop:
        if self.scenario is not None and self.scenario not in scenarios():
            raise ValueError(f"no Demo scenario called {self.scenario[:80]!r}")
        return self

    @field_validator("title", "say")
    @classmethod
    def _set_apart(cls, text: str) -> str:
        return isolated(text)

    @field_validator("say")
    @classmethod
    def _fits_the_caption(cls, say: str) -> str:
        if (n := word_count(say)) > MAX_SAY_WORDS:
            raise ValueError(f"{n} words; a stop says at most {MAX_SAY_WORDS} (split it into two stops)")
        return say


class Lecture(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)
    format: Literal["apf-viz-lecture"]
    version: Literal[1]
    title: str = Field(min_length=1, max_length=200)
    stops: list[Stop] = Field(min_length=1, max_length=200)

    @field_validator("title")
    @classmethod
    def _set_apart(cls, title: str) -> str:
        return isolated(title)

    @model_validator(mode="after")
    def _starts_somewhere(self) -> Lecture:
        if self.stops[0].scenario is None:
            raise ValueError("stops[0]: the first stop names a scenario (the lecture's start)")
        return self


def parse_lecture(text: str, where: str = "lecture") -> Lecture:
    """A lecture from JSON text; every problem one line naming the field (``stops[3].until: …``)."""
    return parse_json_model(Lecture, text, where)


def load_lecture(path: Path | str) -> Lecture:
    return parse_lecture(read_text(path, MAX_LECTURE_BYTES), str(path))


def find_lecture(name: Path | str) -> Lecture:
    """A lecture file, or a shipped lecture by its file's name (``algorithm-in-12-stops``) or its title:
    what ships with the package is reachable without knowing where it was installed."""
    path = Path(name)
    if path.exists():
        return load_lecture(path)
    shipped = demo_files("lectures")
    if str(name) in shipped:
        return load_lecture(shipped[str(name)])
    if str(name) in lectures():
        return lectures()[str(name)]
    raise InputError(f"{name}: no such file, nor a shipped lecture (shipped: {', '.join(shipped)})")


@cache
def lectures() -> dict[str, Lecture]:
    """The shipped lectures, by title, in file-name order."""
    out: dict[str, Lecture] = {}
    for path in sorted(demo_files("lectures").values()):
        lecture = load_lecture(path)
        if lecture.title in out:
            raise InputError(f"{path}: a second lecture called {lecture.title!r}")
        out[lecture.title] = lecture
    return out


class Marked(BaseModel):
    """A robot the paper's caption names (``r``, ``r₀``), and the lines it names by that robot: ``L_V``
    and ``L_H`` (the vertical and horizontal lines through it), ``L_I`` and ``R_I`` (the nearest occupied
    vertical lines to its left and right)."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)
    robot: int = Field(ge=0, le=100_000)
    name: str = Field(min_length=1, max_length=8)
    lines: tuple[Literal["L_V", "L_H", "L_I", "R_I"], ...] = ()


class Figure(BaseModel):
    """One of the paper's figures as a scenario: the Demo scenario that reproduces it, the event at which
    its picture holds, the robots' lights then (how many show each; what the caption describes) and the
    caption, in the paper's words."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)
    label: str
    caption: str
    scenario: str
    event: int = Field(ge=0, le=MAX_EVENT)
    lights: dict[str, int]
    # What the caption says of where the robots stand, by name (tests/test_lecture.py checks each).
    positions: tuple[str, ...] = ()
    marked: Marked | None = None  # the robot its caption names, marked in the exported figure

    def as_lecture(self) -> Lecture:
        """A one-stop lecture: its caption on screen as a stop's words."""
        stop = Stop(
            title=f"Figure “{self.label}”",
            say=self.caption,
            scenario=self.scenario,
            until=Until(event=self.event),
        )
        return Lecture(format="apf-viz-lecture", version=1, title="The paper's figures", stops=[stop])


class _Figures(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    note: str = ""
    figures: list[Figure]


@cache
def figures() -> dict[str, Figure]:
    """The paper's figures reproduced (``demo_patterns/figures.json``), by label, in the paper's order."""
    parsed = _Figures.model_validate_json(read_text(demo_dir() / "figures.json", MAX_INPUT_BYTES))
    return {f.label: f for f in parsed.figures}
