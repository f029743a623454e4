"""The room's answers to a lecture stop's question: one answer a page (changed at will until the
reveal), how many answered, their anonymous spread, and the reveal. A page is known by a key of its
own (ui/answer_key.py: the same key after a reload), never by a name; nothing here says which page gave
which answer. Pure: no viser."""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass

from apf_viz.core.formats import InputError
from apf_viz.core.grid import COORD_LIMIT
from apf_viz.lecture import QUESTION_OUTCOMES
from apf_viz.workbench.question import Answer, cell_choice, choice_words

MAX_ANSWERS = 2_000
"""Pages answering one question, at most (a class is tens; a page's key is its own, so a browser that
sends new keys cannot grow the poll past this)."""
_CELL = re.compile(r"\s*\(?\s*([−-]?\d{1,13})\s*,\s*([−-]?\d{1,13})\s*\)?\s*")


@dataclass(frozen=True)
class Bar:
    """One choice of the spread: how many gave it, and whether the run made it (after the reveal)."""

    choice: str
    words: str
    count: int
    right: bool


@dataclass(frozen=True)
class PollView:
    """What the screen says of a question, the same on every page: the question, how many answered, and
    (on the presenter's caption only, once asked for or revealed) the spread; after the reveal, the run's
    answer and how many gave it."""

    question: str
    kind: str
    count: int
    bars: tuple[Bar, ...] = ()  # the spread, when shown
    answer: str = ""  # the run's answer in words, once revealed
    right: int = 0  # how many gave it, once revealed
    present: int = 0  # seats in the room or that answered (0: not known, as on an exported page)


class Poll:
    """One question's answers."""

    def __init__(self, answer: Answer, robots: int, lights: tuple[str, ...]) -> None:
        self.answer = answer
        self.kind = answer.question.kind
        self.choices: tuple[str, ...] | None = {
            "robot": tuple(str(i) for i in range(robots)),
            "light": lights,
            "outcome": QUESTION_OUTCOMES,
            "cell": None,  # any cell of the grid
        }[self.kind]
        self._given: dict[str, str] = {}
        self.revealed = False
        self.spread_shown = False

    @property
    def question(self) -> str:
        """The question in words, as every page shows it."""
        return self.answer.question.words()

    def give(self, who: str | None, choice: str) -> str:
        """Page ``who`` answers ``choice`` (its earlier answer replaced); what its page is told. A page
        with no seat (None: the server has not issued it one yet) cannot answer."""
        if who is None:
            raise InputError("this page has no seat yet: reload it, then answer")
        if self.revealed:
            raise InputError("the answer is out: this question takes no more answers")
        choice = self.read(choice)
        if who not in self._given and len(self._given) >= MAX_ANSWERS:
            raise InputError(f"{MAX_ANSWERS} pages have answered, the most a question takes")
        self._given[who] = choice
        return f"your answer: {choice_words(self.kind, choice)} (you may change it until the reveal)"

    def read(self, choice: str) -> str:
        """A choice as a page sent it, in the poll's own spelling; refused in one line if it is none."""
        choice = str(choice).strip()
        if self.choices is not None:
            if choice not in self.choices:
                raise InputError(f"{choice[:40]!r} is not an answer to “{self.question}”")
            return choice
        m = _CELL.fullmatch(choice)
        if m is None:
            raise InputError(f"{choice[:40]!r}: answer with a cell, as x, y (e.g. 2, -1)")
        x, y = (int(v.replace("−", "-")) for v in m.groups())
        if abs(x) > COORD_LIMIT or abs(y) > COORD_LIMIT:
            raise InputError(f"({x}, {y}): a cell's |x| and |y| are at most {COORD_LIMIT:,}")
        return cell_choice(x, y)

    def given(self, who: str | None) -> str | None:
        """``who``'s answer (its page shows it; no other page is shown it)."""
        return self._given.get(who) if who is not None else None

    def told(self, who: str | None) -> str:
        """What ``who``'s own page says of its answer: the answer held (a reload keeps it), and after the
        reveal whether it was the run's ("" before an answer)."""
        mine = self.given(who)
        said = choice_words(self.kind, mine) if mine is not None else None
        if self.revealed:
            if said is None:
                return "you did not answer"
            return f"you answered {said}: {'right' if mine in self.answer.right else 'not this time'}"
        return f"your answer: {said}" if said is not None else ""

    @property
    def count(self) -> int:
        """How many pages have answered."""
        return len(self._given)

    @property
    def right_count(self) -> int:
        """How many pages gave one of the run's right choices."""
        return sum(1 for c in self._given.values() if c in self.answer.right)

    def spread(self) -> list[Bar]:
        """The answers given, a bar per choice (every offered choice, a cell only once given; after the
        reveal the run's answer too, even if nobody gave it), most given first for cells."""
        counts = Counter(self._given.values())
        shown = list(self.choices) if self.choices is not None else sorted(counts, key=lambda c: -counts[c])
        if self.revealed:
            shown += sorted(c for c in self.answer.right if c not in shown)
        return [
            Bar(c, choice_words(self.kind, c), counts[c], self.revealed and c in self.answer.right)
            for c in shown
        ]

    def view(self, here: frozenset[str] = frozenset()) -> PollView:
        """What the screen says of it; ``here``: the seats connected now (a seat that answered and left
        still counts among those asked)."""
        shown = self.spread_shown or self.revealed
        return PollView(
            self.question,
            self.kind,
            self.count,
            tuple(self.spread()) if shown else (),
            self.answer.words() if self.revealed else "",
            self.right_count if self.revealed else 0,
            len(here | self._given.keys()) if here else 0,
        )
