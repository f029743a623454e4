"""Run: the Demo scenarios, stepping and playing, the timeline, a followed trace, the outcome and the
story of the last events."""

from __future__ import annotations

import html
import time

from apf_viz.demos import scenarios
from apf_viz.lecture import lectures
from apf_viz.ui import viser_compat
from apf_viz.ui.panels.context import PanelContext, put, tell
from apf_viz.ui.panels.shortcuts import NOTE_TITLES
from apf_viz.workbench.run_controller import MAX_SPEED, slider_speed
from apf_viz.workbench.view_model import SessionView
from apf_viz.workbench.view_model.legend import symbol_html
from apf_viz.workbench.view_model.story import MAX_TRAIL

# Escape gives the keyboard back to the run from any field of the panel (viser ignores its hotkeys while
# a field has focus): one listener a page, installed by an image that fails to load.
ESCAPE_RELEASES = (
    '<img alt="" src="data:,escape" style="display:none" onerror="'
    "if(!window.apfEscape){window.apfEscape=1;document.addEventListener('keydown',function(e){"
    "if(e.key==='Escape'&&document.activeElement&&document.activeElement!==document.body)"
    "{document.activeElement.blur();}},true);}"
    '">'
)

# A focused slider (the Timeline, Speed) takes the arrow keys for itself: the page's camera listens to
# them on the document, after the slider has moved, and would turn the view too. Stopped at the body, on
# their way up from a slider, they never reach it. One listener a page, installed as above.
SLIDER_KEYS_STAY = (
    '<img alt="" src="data:,slider" style="display:none" onerror="'
    "if(!window.apfSliderKeys){window.apfSliderKeys=1;document.body.addEventListener('keydown',function(e){"
    "var t=e.target;if(t&&t.getAttribute&&t.getAttribute('role')==='slider'){e.stopPropagation();}});}"
    '">'
)

# A choice made in any dropdown (Scheduler, Algorithm, Demo pattern, Figure, …) gives the keyboard back to
# the run: the dropdown would keep the focus, so Enter would do nothing and M would type into it. One
# listener a page, installed as above; it acts once the dropdown has taken the option.
DROPDOWNS_RELEASE = (
    '<img alt="" src="data:,dropdowns" style="display:none" onerror="'
    "if(!window.apfDropdowns){window.apfDropdowns=1;document.addEventListener('click',function(e){"
    "var o=e.target&&e.target.closest&&e.target.closest('[role=option]');if(!o){return;}"
    "setTimeout(function(){var a=document.activeElement;"
    "if(a&&a!==document.body&&a.blur){a.blur();}},50);},true);}"
    '">'
)

RELEASE_FOCUS = (
    '<img alt="" src="data:,{n}" style="display:none" '
    'onerror="document.activeElement && document.activeElement.blur && document.activeElement.blur()">'
)


KEYS_DRIVING = (
    "<small>Keys: Enter step · Backspace back · Space play/pause · PgDn/PgUp next/previous "
    "stage · M next move · F frame the run · P presentation mode · J the class address (Ctrl+K lists "
    "them). In a focused field "
    "or slider, keys act on it alone; Esc gives them back</small>"
)
KEYS_FOLLOWING = (
    "<small>Keys: F frame the run · P presentation mode (the presenter's keys drive the run)</small>"
)

JUMPS = ("Next move", "Next stage", "Frame run")  # the Go to buttons; Frame run last: every page has it
LAST_EVENT_REFRESH_S = 0.125
"""While playing, the last event's line changes at most this often: every event of a run played at up to
8 steps a second, and no markdown re-rendered in every frame of a fast one (nobody reads 30 lines a
second; the page draws fewer frames for each)."""


class RunFolder:
    """What a lecture needs on the panel's first screen: the Demo, Step / Back / Play / Reset, the jumps,
    the outcome, the event number and the last event in full (the History folder has the rest)."""

    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        with gui.add_folder("Run"):
            self.role = gui.add_markdown("")
            self._own_run_controls(gui)
            self.class_drives = gui.add_checkbox(
                "Class may drive",
                initial_value=False,
                visible=False,
                hint="let the class pages step, play and change the shared run (untick to take it back)",
            )
            self.class_drives.on_update(ctx.from_browser(self._on_class_drives))
            self.demo = ctx.driving(
                gui.add_dropdown("Demo", ("—", *scenarios()), initial_value="—"), shared=True
            )
            self.demo.on_update(ctx.from_browser(self._on_demo))
            self.demo_note = gui.add_markdown("")
            # After a Demo is picked, the keyboard belongs to the lecture again: viser ignores hotkeys while
            # a field has focus, and the dropdown keeps it. A constant handler in this browser's own panel
            # gives the focus up (an image that fails to load runs its onerror); a new count re-runs it.
            gui.add_html(ESCAPE_RELEASES)
            gui.add_html(DROPDOWNS_RELEASE)
            gui.add_html(SLIDER_KEYS_STAY)
            gui.add_html(viser_compat.NOTICES_BESIDE_THE_RUN)  # notifications never cover the run
            self._release = gui.add_html("")
            self._releases = 0
            ctx.release_focus = self.release_focus  # for the other folders' fields (Edit's Mode)
            self.lecture = ctx.driving(gui.add_dropdown(
                "Lecture", ("—", *lectures()), initial_value="—",
                hint="a guided lecture: PageDown / Next stop runs to each stop and shows its words",
            ), shared=True)  # fmt: skip
            self.lecture.on_update(ctx.from_browser(self._on_lecture, "Lecture"))
            self.words = gui.add_markdown("")
            self.stops = gui.add_button_group("Stops", ("Previous stop", "Next stop"), visible=False)
            self.stops.on_click(ctx.guard(self._on_stop, "Lecture"))
            self.controls = ctx.driving(gui.add_button_group("Controls", ("Step", "Back", "Play", "Reset")))
            self.controls.on_click(ctx.guard(self._on_control))
            # A page that may not drive keeps Frame run (its own camera) and not the jumps of the run.
            self.jumps = gui.add_button_group("Go to", JUMPS)
            self.jumps.on_click(self._on_jump)
            self.keys = gui.add_markdown(KEYS_DRIVING)
            gui.add_button(
                "Presentation mode", hint="collapse this panel; a large caption on the canvas (P)"
            ).on_click(ctx.guard(lambda e: ctx.toggle_presentation(e), mine=True))
            self._trace_controls(gui)
            self.banner = gui.add_markdown("")
            self.fatal = gui.add_button(
                "Go to the fatal decision",
                visible=False,
                hint="the step at which the colliding robot computed its move",
            )
            self.fatal.on_click(ctx.guard(self._to_fatal))
            self.event = gui.add_number("Event", initial_value=0, disabled=True)
            self.last_event = gui.add_markdown("")
            self._last_event_at = -LAST_EVENT_REFRESH_S  # when the line last changed while playing

    def _trace_controls(self, gui) -> None:
        s = self.ctx.session
        self.trace = gui.add_markdown("")
        self.branch = gui.add_button("Branch here", visible=False, hint="leave the trace: the scheduler runs")
        self.branch.on_click(self.ctx.guard(lambda e: s.branch_here()))
        self.aside = gui.add_markdown("")
        self.restore = gui.add_button(
            "Return to set-aside branch",
            visible=False,
            hint="enter the newest branch kept, and follow it (History lists them all)",
        )
        self.restore.on_click(self.ctx.guard(lambda e: s.return_to_set_aside()))

    def _on_class_drives(self, event) -> None:
        self.ctx.classroom.set_class_may_drive(self.class_drives.value, self.ctx.browser)
        # The keys drive the run again: a checkbox left with the focus took Space for itself (and gave
        # the class the run by a press meant for Play).
        self.release_focus()

    def _to_fatal(self, event) -> None:
        step = self.ctx.view().fatal[1]
        if step is not None:
            self.ctx.session.seek(step)

    def _on_demo(self, event) -> None:
        """A ready scenario; what it shows stays under the dropdown, for the room to read. Picking one
        leaves a lecture being followed."""
        if self.demo.value != "—":
            if self.ctx.session.lecturer is not None:
                self.ctx.session.start_lecture(None)
            self.ctx.session.load_scenario(self.demo.value)
            self.release_focus()

    def _on_lecture(self, event) -> str | None:
        """A shipped lecture from the list (never a path), from its first stop, in presentation mode (its
        words large on the canvas); "—" leaves it."""
        name, s = self.lecture.value, self.ctx.session
        if name == "—":
            lecture = None
        elif name in lectures():
            lecture = lectures()[name]
        elif s.lecturer is not None and s.lecturer.lecture.title == name:  # a lecture from a file: again
            lecture = s.lecturer.lecture
        else:
            return "that lecture is no longer loaded"
        said = s.start_lecture(lecture)
        self.release_focus()
        if name != "—" and not self.ctx.presenting():  # the words large on the canvas; P brings the panel
            self.ctx.toggle_presentation(event)
        return said if "not reached" in said or name == "—" else None  # else the caption says it

    def _on_stop(self, event) -> str:
        s = self.ctx.session
        return s.next_stop() if event.target.value == "Next stop" else s.previous_stop()

    def release_focus(self) -> None:
        """Take the keyboard focus off the panel's fields in this browser, so that its keys drive the run."""
        self._releases += 1
        put(self._release, content=RELEASE_FOCUS.format(n=self._releases))

    def _on_control(self, event) -> None:
        value, s = event.target.value, self.ctx.session
        if value == "Step":
            self.ctx.step(event)
        elif value == "Back":
            s.back()
        elif value in ("Play", "Pause"):
            said = s.toggle_play()
            if said:
                tell(event.client, "Play", said)
        elif value == "Reset":
            s.reset()
        self.ctx.changed()

    def _on_jump(self, event) -> None:
        """Next move / Next stage run the scheduler until something happens (the result goes to the
        browser that asked); Frame run points that browser's camera at the whole run."""
        value, client = event.target.value, event.client
        if value == "Frame run":
            if client is not None:
                self.ctx.frame(client)
            return
        if not self.ctx.may(event):
            return
        result = self.ctx.session.run_until("move" if value == "Next move" else "stage")
        tell(client, NOTE_TITLES[value], result)
        self.ctx.changed()

    def refresh(self, view: SessionView) -> None:
        put(self.controls, options=("Step", "Back", "Pause" if view.playing else "Play", "Reset"))
        put(self.event, value=view.event)
        last = f"**Last event:** {view.last_events[0]}" if view.last_events else "**Last event:** —"
        if view.note_here:  # the schedule's author speaks: their words, escaped, never markup
            last += f"  \n<b>Note:</b> <i>{html.escape(view.note_here)}</i>"
        now = time.monotonic()
        if self.last_event.content != last and (
            not view.playing or now - self._last_event_at >= LAST_EVENT_REFRESH_S
        ):
            put(self.last_event, content=last)
            self._last_event_at = now
        note = f"<small>{symbol_html(view.scenario_note)}</small>" if view.scenario_note else ""
        if self.demo_note.content != note:
            self.demo_note.content = note
        if not view.scenario_note and self.demo.value != "—":
            self.demo.value = "—"  # another run replaced the scenario
        put(self.banner, content=view.banner)
        self._refresh_role()
        self._refresh_lecture(view)
        drives = self.ctx.drives()
        put(self.jumps, options=JUMPS if drives else JUMPS[-1:])
        fatal = view.fatal[1] is not None and drives
        if self.fatal.visible != fatal:
            self.fatal.visible = fatal
        self._refresh_trace(view)

    def _own_run_controls(self, gui) -> None:
        """Try it yourself (a class page) and Back to the lecture (a page trying its own run)."""
        ctx = self.ctx
        self.alone = gui.add_button(
            "Try it yourself",
            visible=False,
            hint="a run of this page's own, from the lecture's run as it is now: the projector is untouched",
        )
        self.alone.on_click(ctx.guard(lambda e: ctx.try_alone(), "Try it yourself", mine=True))
        self.back = gui.add_button("Back to the lecture", visible=False, hint="drop this page's own run")
        self.back.on_click(ctx.guard(lambda e: ctx.back_to_lecture(), "Back to the lecture", mine=True))

    def _refresh_role(self) -> None:
        """What this page is: presenting (with the class's permission to drive), or following."""
        room, browser = self.ctx.classroom, self.ctx.browser
        own = self.ctx.in_own_run()
        presenter = room.role(browser) == "presenter" and not own
        laptop = self.ctx.laptop()
        seat = f" · **laptop {laptop}**" if laptop is not None else ""
        if own:
            said = f"**Your own run**{seat} · the projector is untouched"
        elif presenter:
            said = "**Presenting**" + (" · the class may drive" if room.class_may_drive else "")
        else:
            said = f"**Following the lecture**{seat}" + (
                " · the presenter lets the class drive" if room.class_may_drive else " · the presenter drives"
            )
        if self.role.content != said:
            self.role.content = said
        keys = KEYS_DRIVING if room.may_drive(browser) else KEYS_FOLLOWING
        if self.keys.content != keys:
            self.keys.content = keys
        if self.class_drives.visible != presenter:
            self.class_drives.visible = presenter
        trying = not own and room.role(browser) == "class"
        if self.alone.visible != trying:
            self.alone.visible = trying
        if self.back.visible != own:
            self.back.visible = own
        if self.class_drives.value != room.class_may_drive:
            self.class_drives.value = room.class_may_drive

    def _refresh_lecture(self, view: SessionView) -> None:
        words = ""
        if view.lecture is not None:
            where, title, say = view.lecture
            words = f"<small>{where}</small>  \n**{symbol_html(title)}**  \n{symbol_html(say)}"
        if self.words.content != words:
            self.words.content = words
        stops = view.lecture is not None and self.ctx.drives()  # a class page's keys do not turn them
        if self.stops.visible != stops:
            self.stops.visible = stops
        title = view.lecture_title or "—"
        if title != "—" and title not in self.lecture.options:  # a lecture from a file (serve --lecture)
            self.lecture.options = ("—", *lectures(), title)
        if self.lecture.value != title:  # the lecture followed, or "—" once it is left
            self.lecture.value = title

    def _refresh_trace(self, view: SessionView) -> None:
        drives = self.ctx.drives()  # a page that follows sees the trace's line, not its controls
        following = view.trace_position is not None and drives
        if self.branch.visible != following:
            self.branch.visible = following
        put(self.trace, content=view.trace_line)
        restore = bool(view.branches) and drives
        if self.restore.visible != restore:
            self.restore.visible = restore
        put(self.aside, content=view.aside_line)


class HistoryFolder:
    """The run's history: the events before the last, speed, the timeline, the counts."""

    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        s = ctx.session
        with gui.add_folder("History"):
            self.log = gui.add_markdown("")
            self.speed = ctx.driving(
                gui.add_slider(
                    "Speed", min=1, max=int(MAX_SPEED), step=1, initial_value=10, hint="steps per second"
                )
            )
            self._speed_shown = float(self.speed.value)  # what this page's slider showed before a change
            self.speed.on_update(ctx.from_browser(self._on_speed))
            self.timeline = ctx.driving(gui.add_slider(
                "Timeline", min=0, max=1, step=1, initial_value=0,
                hint="scrub the history; stepping from the past branches",
            ))  # fmt: skip
            self.timeline.on_update(ctx.from_browser(lambda e: s.seek(self.timeline.value)))
            cycle = ctx.driving(gui.add_button(
                "Rewind the last cycle", hint="back before the last actor's Look: its whole Look-Compute-Move"
            ))  # fmt: skip
            cycle.on_click(ctx.guard(lambda e: s.back_cycle(), "Rewind the last cycle"))
            self.branches = ctx.driving(gui.add_dropdown(
                "Branches", ("—",), initial_value="—", visible=False,
                hint="every line of steps a step from the past left: where it left, how it ends",
            ))  # fmt: skip
            self.enter = ctx.driving(gui.add_button(
                "Enter branch", visible=False, hint="replay the chosen branch, follow it; this line is kept"
            ))  # fmt: skip
            self.enter.on_click(ctx.guard(self._enter, "Branches"))
            self.stats = gui.add_markdown("")
            self.numbers = ctx.driving(
                gui.add_checkbox("Numbers", initial_value=True, hint="each robot's number beside it")
            )
            self.numbers.on_update(ctx.from_browser(lambda e: s.set_numbers(bool(self.numbers.value))))
            self.trails = ctx.driving(gui.add_slider(
                "Trails", min=0, max=MAX_TRAIL, step=1, initial_value=0,
                hint="draw each robot's last N moves (0: none)",
            ))  # fmt: skip
            self.trails.on_update(ctx.from_browser(lambda e: s.set_trails(self.trails.value)))

    def _on_speed(self, event) -> None:
        """An arrow key climbs SPEED_LADDER (1, 2, 5, 10, … 5000), a drag or a typed value is taken as
        it is; the slider then shows the speed the run took."""
        s = self.ctx.session
        s.set_speed(slider_speed(self._speed_shown, float(self.speed.value)))
        self._show_speed(s.speed)

    def _show_speed(self, speed: float) -> None:
        self._speed_shown = speed
        put(self.speed, value=int(speed))

    def _enter(self, event) -> str:
        chosen = self.branches.value
        if not chosen.startswith("#"):
            return "choose a branch in the Branches list"
        number = int(chosen[1:].split(":")[0])
        self.ctx.session.return_to_set_aside(number)
        return f"entered branch #{number}: Step follows it"

    def _refresh_branches(self, view: SessionView) -> None:
        options = view.branches[::-1] or ("—",)  # newest first
        if tuple(self.branches.options) != options:
            self.branches.options = options
            self.branches.value = options[0]
        shown = bool(view.branches)
        if self.branches.visible != shown:
            self.branches.visible = shown
            self.enter.visible = shown

    def refresh(self, view: SessionView) -> None:
        self._refresh_branches(view)
        if self.ctx.session.speed != self._speed_shown:  # another page (or a lecture) set it
            self._show_speed(self.ctx.session.speed)
        put(self.timeline, max=max(1, view.history_length))
        put(self.timeline, value=view.steps)
        log = "  \n".join(f"<small>{e}</small>" for e in view.last_events[1:6])
        if self.log.content != log:
            self.log.content = log
        put(self.stats, content=view.stats)
        if self.numbers.value != view.numbers:
            self.numbers.value = view.numbers
        if self.trails.value != view.trail_setting:
            self.trails.value = view.trail_setting
        viser_compat.set_slider_marks(self.timeline, view.timeline_marks)  # viser has no public setter
