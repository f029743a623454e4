"""Time travel's tree: every line of steps a step from the past left behind, kept, named by where it
left and how it ends, and re-enterable. Nothing here steps an engine: the run's controller
(workbench/run_controller.py) replays what :meth:`Branches.path_to` gives when a branch is entered.

A branch is a tail of steps hanging off another line at an absolute step number: off the run's own
line (the recorded history, ``parent`` None), or off another kept branch. So a branch's whole line
is its parent's line up to ``at`` and then its own steps, and no step is stored twice. When the run's
line is cut at step q (a different step taken there), its tail becomes a branch, and every branch that
hung off the run's line after q now hangs off that tail: what it branched from is still kept."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from apf_viz.core.engine import Engine
from apf_viz.core.formats import InputError
from apf_viz.core.history import StepRecord

KEPT = 50
"""Branches kept at most (the oldest goes first): each holds its steps."""


@dataclass(eq=False)
class Branch:
    """A line of steps that left its parent's line (the run's own: None) at absolute step ``at``."""

    number: int
    parent: Branch | None
    at: int
    records: tuple[StepRecord, ...]
    ends: str

    @property
    def label(self) -> str:
        """How the Branches list names it: its number, where it left, its length and its end."""
        of = f" of #{self.parent.number}" if self.parent is not None else ""
        return f"#{self.number}: left at step {self.at}{of}, {len(self.records)} step(s), {self.ends}"


def ending(engine: Engine) -> str:
    """How the line the engine stands at the end of ends: its outcome and its event, or where it stops."""
    outcome = engine.state.outcome
    event = engine.state.events
    if outcome is None:
        return f"stopped at event {event}"
    return f"{outcome.upper()} at event {event}"


class Branches:
    """The lines left behind, oldest first; entering one makes it the run's line (the line left is kept)."""

    def __init__(self) -> None:
        self._kept: list[Branch] = []
        # A line keeps its number whichever line is the run's: the run's own is #1 until a step from the
        # past sets its future aside (that future is #1 then, the run's new line the next number), and a
        # line entered gives its number back to the run's line (the line left keeps its own).
        self.line = 1
        self._numbered = 1
        self.forgotten = 0  # branches dropped past :data:`KEPT`

    def __len__(self) -> int:
        return len(self._kept)

    def __iter__(self) -> Iterator[Branch]:
        return iter(self._kept)

    def keep(self, at: int, records: list[StepRecord], ends: str) -> Branch | None:
        """The run's line was cut at step ``at``: its tail ``records`` becomes a branch, and the branches
        that hung off the run's line after ``at`` hang off that tail now."""
        if not records:
            return None
        tail = Branch(self.line, None, at, tuple(records), ends)
        self._numbered += 1
        self.line = self._numbered
        for b in self._kept:
            if b.parent is None and b.at > at:
                b.parent = tail
        self._kept.append(tail)
        while len(self._kept) > KEPT:
            self._forget(self._kept[0])
        return tail

    def _forget(self, gone: Branch) -> None:
        """Drop a branch; its children keep their lines (its steps up to theirs are copied into them)."""
        self._kept.remove(gone)
        self.forgotten += 1
        for b in self._kept:
            if b.parent is gone:
                b.records = gone.records[: b.at - gone.at] + b.records
                b.parent, b.at = gone.parent, gone.at

    def find(self, number: int | None = None) -> Branch:
        """The branch of that number (the newest by default)."""
        if not self._kept:
            raise InputError("no branch was set aside")
        if number is None:
            return self._kept[-1]
        for b in self._kept:
            if b.number == number:
                return b
        raise InputError(f"no branch #{number}; branches: {', '.join(f'#{b.number}' for b in self._kept)}")

    @staticmethod
    def chain(branch: Branch) -> list[Branch]:
        """The branch and its ancestors up to the one off the run's line, that one first."""
        chain = [branch]
        while chain[-1].parent is not None:
            chain.append(chain[-1].parent)
        return chain[::-1]

    def path_to(self, number: int | None = None) -> tuple[int, list[StepRecord]]:
        """Where the branch's line leaves the run's line, and its steps from there to its end."""
        chain = self.chain(self.find(number))
        steps: list[StepRecord] = []
        for branch, child in zip(chain, [*chain[1:], None], strict=True):
            upto = len(branch.records) if child is None else child.at - branch.at
            steps.extend(branch.records[:upto])
        return chain[0].at, steps

    def entered(self, number: int | None = None) -> Branch:
        """The branch's line is now the run's (replayed by the caller after :meth:`path_to`): it leaves
        the list, and what of its ancestors is now the run's line is trimmed off them."""
        branch = self.find(number)
        chain = self.chain(branch)
        for node, child in zip(chain, [*chain[1:], None], strict=True):
            cut = child.at if child is not None else node.at + len(node.records)
            for b in self._kept:  # what hung off the part now on the run's line hangs off the run's line
                if b.parent is node and b.at <= cut:
                    b.parent = None
            if child is None:
                self._kept.remove(node)
            else:
                node.records, node.parent, node.at = node.records[cut - node.at :], None, cut
                if not node.records:
                    self._kept.remove(node)
        self.line = branch.number  # the run's line is that line now, by its own number
        return branch

    def labels(self) -> tuple[str, ...]:
        """Every kept branch's :attr:`Branch.label`, oldest first (the Branches list)."""
        return tuple(b.label for b in self._kept)
