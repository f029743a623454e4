"""Edit: draw the pattern or place the robots with the studio's tools (workbench/studio.py); switching back to
Run checks the drafts and restarts. A box is dragged on the canvas (viser's rectangle select, this
browser's own; Shift erases) while the Box or Select tool is chosen in an edit mode; the cell tool and
the eraser paint along a drag (ui/scene/paint_surface.py)."""

from __future__ import annotations

import html

from apf_viz.ui.panels.context import PanelContext, put, tell
from apf_viz.ui.scene.camera import covered_cells
from apf_viz.ui.scene.paint_surface import PaintSurface
from apf_viz.workbench.selection import SELECTION_COMMANDS
from apf_viz.workbench.studio import (
    FIT_PATTERN,
    FIT_ROBOTS,
    MIRRORS,
    NUDGES,
    PAINTING,
    TOOL_KEYS,
    TOOLS,
    TRANSFORMS,
)
from apf_viz.workbench.view_model import SessionView

MODES = {"Run": "run", "Edit pattern": "edit-pattern", "Edit robots": "edit-robots"}
MODE_LABELS = {v: k for k, v in MODES.items()}
KEYS_LINE = (
    "<small>Keys: "
    + " · ".join(f"{key} {tool}" for tool, key in TOOL_KEYS.items())
    + " · Ctrl+Z undo · Ctrl+Shift+Z redo · F frame</small>"
)

# While this page draws, E picks the eraser and must not also lift viser's camera (its W A S D Q E keys).
# Viser's shortcuts listen on <html>, its camera on the document above it: a listener on <html> that
# stops E there lets the shortcut through and keeps the camera still. One listener a page; the flag is
# set by :meth:`EditFolder.refresh` (an image that fails to load runs its onerror).
E_KEEPS_THE_CAMERA = (
    '<img alt="" src="data:,drawing" style="display:none" onerror="'
    "if(!window.apfDrawKeys){window.apfDrawKeys=1;document.documentElement.addEventListener('keydown',"
    "function(e){if(window.apfDrawing&&e.code==='KeyE'){e.stopPropagation();}});}"
    '">'
)
DRAWING_FLAG = '<img alt="" src="data:,drawing-{on}" style="display:none" onerror="window.apfDrawing={on}">'


def tool_hint(tool: str) -> str:
    key = TOOL_KEYS.get(tool)
    return f"{TOOLS[tool]} (key {key})" if key else TOOLS[tool]


class EditFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        s = ctx.session
        with ctx.driving(gui.add_folder("Edit", expand_by_default=False)):
            self.mode = gui.add_dropdown("Mode", tuple(MODES), initial_value="Run")
            self.mode.on_update(self._on_mode)
            self.counts = gui.add_markdown("")
            self.tool = gui.add_dropdown("Tool", tuple(TOOLS), initial_value="cell", hint=tool_hint("cell"))
            self.tool.on_update(ctx.from_browser(lambda e: self._on_tool(), "Tool"))
            self.size = gui.add_number(
                "Size", initial_value=4, min=1, max=200, step=1, hint="radius, length, steps"
            )
            self.size.on_update(ctx.from_browser(lambda e: s.set_tool_size(self.size.value), "Size"))
            self.text = gui.add_text(
                "Text", initial_value="APF", hint="letters A–Z, digits, spaces (3×5 font)"
            )
            self.text.on_update(ctx.from_browser(self._on_text, "Text"))
            self.tool_hint = gui.add_markdown("")
            gui.add_markdown(KEYS_LINE)
            gui.add_html(E_KEEPS_THE_CAMERA)
            self._drawing_flag = gui.add_html(DRAWING_FLAG.format(on=0))
            self._drawing = False
            self.said = gui.add_markdown("")  # what the last edit did (Studio.said): not over the run
            self.mirror = gui.add_dropdown(
                "Mirror", tuple(MIRRORS), initial_value="off", hint="copy every cell drawn across the middle"
            )
            self.mirror.on_update(
                ctx.from_browser(self._quietly(lambda e: s.set_mirror(self.mirror.value)), "Mirror")
            )
            selection = gui.add_button_group("Selection", SELECTION_COMMANDS)
            selection.on_click(
                ctx.guard(self._quietly(lambda e: s.selection_command(e.target.value)), "Selection")
            )
            transforms = gui.add_button_group("Transform", TRANSFORMS[:4])
            transforms.on_click(ctx.guard(self._quietly(self._on_transform), "Edit"))
            nudge = gui.add_button_group("Move all", tuple(NUDGES))
            nudge.on_click(ctx.guard(self._quietly(lambda e: s.transform(e.target.value)), "Edit"))
            history = gui.add_button_group("History ", ("Undo", "Redo"))
            history.on_click(ctx.guard(self._quietly(lambda e: s.transform(e.target.value)), "Edit"))
            fit = gui.add_button_group("Fit to k", (FIT_PATTERN, FIT_ROBOTS))
            fit.on_click(ctx.guard(self._quietly(lambda e: s.transform(e.target.value)), "Edit"))
            self.fit_preview = gui.add_markdown("")
            gui.add_button("Clear pattern").on_click(ctx.guard(lambda e: s.clear_pattern()))
            self.save_as = gui.add_text("Save as", initial_value="", hint="a name for the pattern drawn")
            gui.add_button("Save pattern", hint="into the pattern library (serve --library DIR)").on_click(
                ctx.guard(lambda e: s.save_pattern(self.save_as.value), "Library")
            )
            self.saved = gui.add_dropdown(
                "Saved", ("—", *s.saved), initial_value="—", hint="load a saved pattern"
            )
            self.saved.on_update(ctx.from_browser(self._on_saved, "Library"))
        self._commands(gui, ctx)
        self._boxing = False
        self._surface = PaintSurface(ctx.client, self._stroke) if ctx.client is not None else None

    def _commands(self, gui, ctx: PanelContext) -> None:
        """The studio's keys (viser's commands, listed by Ctrl+K too): a tool each, Undo and Redo."""
        s = ctx.session
        for tool, key in TOOL_KEYS.items():
            command = gui.add_command(f"Tool: {tool}", description=TOOLS[tool], hotkey=key)
            command.on_trigger(ctx.guard(lambda e, tool=tool: self._key_tool(tool), "Tool"))
        for label, key, modifier in (("Undo", "Z", "cmd/ctrl"), ("Redo", "Z", "cmd/ctrl+shift")):
            command = gui.add_command(
                label, description=f"{label} the last edit", hotkey=key, modifier=modifier
            )
            command.on_trigger(ctx.guard(self._quietly(lambda e, label=label: s.transform(label)), "Edit"))

    def _quietly(self, fn):
        """An edit's words go to the line under the tool (this browser's), not to a notification: the
        drawing itself shows what changed. A refusal still raises, and is notified."""

        def said(event) -> None:
            words = fn(event)
            if isinstance(words, str):
                self.ctx.session.screen.studio.said = words

        return said

    def _on_text(self, event) -> None:
        """A refused text leaves the field as the studio holds it: what is drawn next is what it says."""
        s = self.ctx.session
        try:
            s.set_tool_text(self.text.value)
        except ValueError:
            self.text.value = s.screen.studio.text
            raise

    def _on_transform(self, event) -> str:
        # The camera stays where the person put it, even when the drawing grows out of view: F frames it.
        return self.ctx.session.transform(event.target.value)

    def _stroke(self, client, phase: str, screen: tuple[float, float] | None) -> None:
        """A drag on the paint surface: the cell under the pointer painted (or erased) along the way."""
        point = self.ctx.point_at(client, screen) if screen is not None else None
        cell = (round(point[0]), round(point[1])) if point is not None else None
        session = self.ctx.session
        if not self.ctx.drives():
            return
        try:
            session.stroke(phase, cell)
        except ValueError as err:
            tell(client, "Refused", str(err), error=True)
        self.ctx.changed()

    def _on_saved(self, event) -> str | None:
        name = self.saved.value
        return self.ctx.session.load_saved_pattern(name) if name != "—" else None

    def _key_tool(self, tool: str) -> str | None:
        """A tool's key: in an Edit mode, that tool (the dropdown shows it at the next refresh)."""
        s = self.ctx.session
        if s.mode == "run":
            return None  # the key is a tool's only while drawing
        s.set_tool(tool)
        self.ctx.changed()
        return None

    def _on_tool(self) -> None:
        self.ctx.session.set_tool(self.tool.value)
        self.tool.hint = tool_hint(self.tool.value)
        self.ctx.release_focus()  # a key typed next is a shortcut, not a search in the dropdown

    def _on_mode(self, event) -> None:
        if event.client is None:
            return
        s = self.ctx.session
        if not self.ctx.may(event):
            return
        mode = MODES.get(self.mode.value)
        problem = s.set_mode(mode) if mode is not None else f"no mode {self.mode.value!r}"  # type: ignore[arg-type]
        if problem:  # refused: the drafts stay, and the browser that asked is told why
            self.mode.value = MODE_LABELS[s.mode]
            tell(event.client, "Still editing", problem, error=True)
        else:  # the keys act on the run again (Space plays, F frames), not on the dropdown
            self.ctx.release_focus()
        self.ctx.changed()

    def _box(self, event, erase: bool) -> None:
        """A box dragged on this browser's canvas: from the cell pressed in to the cell released in, both
        included (as a pixel editor's rectangle), then filled, erased or selected."""
        a, b = (self.ctx.point_at(event.client, corner) for corner in (event.screen_min, event.screen_max))
        if a is None or b is None:
            tell(event.client, "Box", "drag the box over the grid", error=True)
            return
        first, last = covered_cells(a, b)
        self.ctx.guard(self._quietly(lambda e: self.ctx.session.draw_box(first, last, erase)), "Box")(event)

    def _boxes(self, wanted: bool) -> None:
        """Rectangle select on this browser's canvas only while it draws boxes (a plain drag is the
        camera's otherwise)."""
        client = self.ctx.client
        if client is None or wanted == self._boxing:
            return
        scene = client.scene  # type: ignore[attr-defined]
        if wanted:
            scene.on_rect_select()(lambda e: self._box(e, erase=False))
            scene.on_rect_select(modifier="shift")(lambda e: self._box(e, erase=True))
        else:
            scene.remove_rect_select_callback("all")
        self._boxing = wanted

    def refresh(self, view: SessionView) -> None:
        put(self.counts, content=view.counts)
        if self.mode.value != MODE_LABELS[view.mode]:
            self.mode.value = MODE_LABELS[view.mode]
        studio = self.ctx.session.screen.studio
        if self.tool.value != studio.tool:
            self.tool.value = studio.tool
            self.tool.hint = tool_hint(studio.tool)
        drawing = view.mode != "run"
        if drawing != self._drawing:
            self._drawing = drawing
            put(self._drawing_flag, content=DRAWING_FLAG.format(on=int(drawing)))
        hint = tool_hint(studio.tool)
        if view.anchor is not None:  # the first of two clicks is in: say what the second does
            second = "where it goes" if studio.tool == "move" else "the second"
            hint = f"**first click at {view.anchor}**: now click {second} ({hint})"
        put(self.tool_hint, content=f"<small>{hint}</small>")
        self._boxes(view.mode != "run" and studio.tool in ("box", "select"))
        if self._surface is not None:
            self._surface.show(view.mode != "run" and studio.tool in PAINTING)
        if self.mirror.value != studio.mirror:
            self.mirror.value = studio.mirror
        put(self.fit_preview, content=f"<small>{view.fit_preview}</small>" if view.fit_preview else "")
        words = studio.said if view.mode != "run" else ""
        put(self.said, content=f"<small>↳ {html.escape(words)}</small>" if words else "")
        options = ("—", *self.ctx.session.saved)
        if tuple(self.saved.options) != options:
            self.saved.options = options
