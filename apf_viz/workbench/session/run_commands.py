"""Commands on the run: building it anew, stepping, playing, going back, the adversary."""

from __future__ import annotations

import time
from typing import Literal

from apf_viz.core.schedulers import BY_HAND
from apf_viz.workbench.screen_state import BrowserState
from apf_viz.workbench.session.core import SCHEDULER_LABELS, SessionCore
from apf_viz.workbench.view_model import stage_of


class RunCommands(SessionCore):
    """Commands on the run: building it anew, stepping, playing, going back, the adversary."""

    def reset(self) -> None:
        """Back to the start of the current run (same start, pattern, flips, algorithm)."""
        with self.lock:
            self.run.reset()
            self._clear_selections()

    def set_algorithm(self, name: str) -> None:
        """The same start and pattern under another algorithm: the run restarts."""
        with self.lock:
            self.run.set_algorithm(name)
            self._clear_selections()

    def set_all_activations(self, keep: bool) -> None:
        """Keep every no-op activation (teaching what the adversary can do) or skip them (the default);
        the run restarts."""
        with self.lock:
            self.run.set_skip_noops(not keep)
            self._clear_selections()

    def set_light_semantics(self, semantics: str) -> None:
        """Restart the run under ``compute`` or ``lc-atomic`` light semantics (every page's selection
        cleared)."""
        with self.lock:
            self.run.set_light_semantics(semantics)
            self._clear_selections()

    # ------------------------------------------------------------------ stepping
    def step(self, state: BrowserState | None = None) -> bool:
        """One step chosen by the scheduler (in Manual: the robot selected in ``state``, a page's; the
        presenter's for None). False if nothing ran."""
        with self.lock:
            if self.mode != "run":
                return False
            if self.engine.finished:  # Compare: the run beside it may go on alone
                twin = self.screen.twin
                return twin is not None and twin.step_alone(self.engine, self.run.config)
            if self.scheduler_name in BY_HAND and not self.run.following:
                selected = (state or self.presenter).selected
                if selected is None:
                    return False
                self.run.step_robot(selected)
                return True
            return self.run.step()

    def why_not_step(self) -> str:
        """Why Step ran nothing, for the person who pressed it."""
        if self.mode != "run":
            return self._why_editing("Step")
        if self.engine.finished:
            said = f"the run is over ({self.engine.outcome}): Back, the timeline or Reset go on from earlier"
            twin = self.screen.twin.engine if self.screen.twin is not None else None
            if twin is not None:  # Compare: the run beside it went on alone, to its own end
                said += f"; the run beside it is over too, at event {twin.state.events} ({twin.outcome})"
                if not twin.finished:  # Manual: no scheduler to go on with
                    said = f"the run is over ({self.engine.outcome}); in Manual the run beside it stays"
            return said
        if self.run.following:  # at the end of the recorded steps, the run not over
            return (
                f"{self.run.following_what} ends here (its recorded steps are done): Branch here lets "
                "the scheduler go on from this event"
            )
        if self.scheduler_name in BY_HAND:
            return "Manual: click a robot to run its next phase"
        return "nothing could run"

    def play_steps(self, allowance: int = 1) -> int:
        """Up to ``allowance`` steps of Play (the render thread's); stops playing when nothing ran.
        Returns the steps taken (0: none)."""
        with self.lock:
            if self.mode != "run":
                self.run.pause()
                return 0
            if self.engine.finished and self.run.playing:  # Compare: the run beside it plays on alone
                taken = 0
                while taken < allowance and self.step():
                    taken += 1
                if not taken:
                    self.run.pause()
                return taken
            return self.run.play_steps(allowance)

    def run_until(self, what: Literal["move", "stage"], limit: int = 1_000_000, seconds: float = 3.0) -> str:
        """Step until some robot moves, or the stage changes; stops early on an outcome, in Manual, or
        after ``limit`` steps. Returns what happened, for a notification."""
        with self.lock:
            if self.mode != "run":  # e.g. the Unsolvable box demo opens in Edit robots
                return self._why_editing("Next move / Next stage")
            if self.scheduler_name in BY_HAND and not self.run.following:
                return "Next move / Next stage need a scheduler other than Manual"
            self.run.pause()
            e = self.engine
            wanted = "move" if what == "move" else "new stage"
            moves, stage = e.state.moves, stage_of(self.run, self.screen)
            version = e.state.version
            deadline = time.monotonic() + seconds  # the lock is held: keep every browser responsive
            for taken in range(1, limit + 1):
                if not self.run.step():
                    return f"the run is over ({e.outcome})" if e.finished else "nothing could run"
                if e.finished:
                    return f"{e.outcome} after {_steps(taken)}"
                if what == "move" and e.state.moves > moves:
                    return f"a robot moved after {_steps(taken)}"
                if what == "stage" and e.state.version != version:  # stages change with lights or moves
                    version = e.state.version
                    now = stage_of(self.run, self.screen)
                    if now != stage:
                        return f"{now} after {_steps(taken)}"
                if time.monotonic() > deadline:
                    return f"still no {wanted} after {_steps(taken)}: press again"
            return f"no {wanted} within {limit:,} steps"

    def back(self) -> None:
        """Stop playing and take back the last step."""
        self.run.back()

    def seek(self, step: float) -> None:
        """Stop playing and go to that step of the history (any number is clamped; NaN refused)."""
        self.run.seek(step)

    def seek_event(self, event: int) -> None:
        """Go to the step that ends with event number ``event`` (Compare's Go to divergence)."""
        with self.lock:
            done = 0
            history = self.engine.history
            for i, effects in enumerate(history.effects(0, history.length)):
                done += len(effects)
                if done >= event:
                    self.run.seek(i + 1)
                    return
            self.run.seek(self.engine.history.length)

    def back_to_stage(self, seconds: float = 3.0) -> str:
        """Back to where the previous stage began (PageUp: Next stage's stops, in reverse). Returns what
        happened, for a notification."""
        with self.lock:
            self.run.pause()
            e = self.engine
            deadline = time.monotonic() + seconds  # the lock is held: keep every browser responsive
            if e.step_index == 0:
                return "at the start of the run"
            stage = stage_of(self.run, self.screen)
            while e.step_index > 0 and stage_of(self.run, self.screen) == stage:
                e.seek(e.step_index - 1)  # into the previous stage (or to the start)
                if time.monotonic() > deadline:
                    return f"still in {stage} at step {e.step_index}: press again"
            previous = stage_of(self.run, self.screen)
            while e.step_index > 0:
                e.seek(e.step_index - 1)
                if stage_of(self.run, self.screen) != previous:
                    e.seek(e.step_index + 1)  # its first step
                    break
                if time.monotonic() > deadline:
                    break
            return f"{previous} from step {e.step_index}"

    def set_scheduler(self, label_or_name: str) -> None:
        """The adversary for the steps to come, by its label in the dropdown or its registry name."""
        self.run.set_scheduler(SCHEDULER_LABELS.get(label_or_name, label_or_name))

    def set_seed(self, seed: float) -> None:
        """The seed for the steps to come (a whole number in 0 .. 2^63 − 1)."""
        self.run.set_seed(seed)

    def set_speed(self, speed: float) -> None:
        """Steps per second while playing (clamped)."""
        self.run.set_speed(speed)

    def toggle_play(self) -> str | None:
        """Play or pause; in an edit mode nothing plays, and why is returned (for the browser that
        asked): the drafts' problem if they have one, else the way back to Run."""
        with self.lock:
            if self.mode != "run":
                return self._why_editing("Play")
            twin = self.screen.twin  # Compare: a run beside an ended one may play on alone
            self.run.toggle_play(twin is not None and twin.goes_on_alone(self.engine, self.run.config))
            return None

    def _why_editing(self, control: str) -> str:
        problem = self.editor.problem()
        if problem:  # e.g. the Unsolvable box demo: Run would refuse the drafts as they are
            return f"{control} runs in Run mode, and these drafts cannot start a run: {problem}"
        return f"{control} runs in Run mode: switch Mode back to Run"

    def pause(self) -> None:
        """Stop playing."""
        self.run.pause()


def _steps(n: int) -> str:
    return "1 step" if n == 1 else f"{n:,} steps"
