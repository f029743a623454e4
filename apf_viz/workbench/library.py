"""The pattern library: drafts saved under a name in a folder the person chose when starting the server
(``serve --library DIR``; by default the user's data directory), listed and loaded back by name. A browser
names a pattern, never a path: a name is a short word checked against a pattern, and a file is read only
if the folder's listing holds it. Files are written atomically."""

from __future__ import annotations

import os
import re
from collections.abc import Sequence
from pathlib import Path

from apf_viz.core.files import write_atomic
from apf_viz.core.formats import InputError, load_pattern, pattern_json
from apf_viz.core.grid import Point, as_point

NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9 _-]{0,59}")


def default_folder() -> Path:
    """``$XDG_DATA_HOME/apf-viz/patterns`` (``~/.local/share`` when unset; ``%APPDATA%`` on Windows)."""
    base = (
        os.environ.get("XDG_DATA_HOME") or os.environ.get("APPDATA") or str(Path.home() / ".local" / "share")
    )
    return Path(base) / "apf-viz" / "patterns"


def _file_name(name: str) -> str:
    if not NAME.fullmatch(name):
        raise InputError(
            f"pattern name {name[:60]!r}: 1 to 60 letters, digits, spaces, '-' or '_', "
            "starting with a letter or digit"
        )
    return name.strip().replace(" ", "_") + ".json"


class PatternLibrary:
    """Saved patterns in one folder, by name."""

    def __init__(self, folder: Path | None = None) -> None:
        self.folder = folder or default_folder()
        if self.folder.exists() and not self.folder.is_dir():
            raise InputError(
                f"--library {self.folder}: is a file, not a folder (give one to keep patterns in)"
            )

    def names(self) -> list[str]:
        """The saved patterns' names (their files' names, ``_`` read as a space), sorted."""
        if not self.folder.is_dir():
            return []
        return sorted(p.stem.replace("_", " ") for p in self.folder.glob("*.json") if NAME.fullmatch(p.stem))

    def save(self, name: str, cells: Sequence[Point]) -> Path:
        """Save ``cells`` as the pattern called ``name`` (over one of that name); returns its file. An empty
        pattern is refused."""
        if not cells:
            raise InputError("an empty pattern is not saved: draw at least one cell")
        path = self.folder / _file_name(name)
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
        except (FileExistsError, NotADirectoryError):
            raise InputError(f"{self.folder}: is not a folder; the pattern is not saved") from None
        write_atomic(path, pattern_json(cells, name.strip()))
        return path

    def load(self, name: str) -> list[Point]:
        """The cells of the saved pattern called ``name`` (only a name the folder lists is read)."""
        if name not in self.names():
            raise InputError(f"no saved pattern called {name[:60]!r}")
        return [as_point(p) for p in load_pattern(self.folder / _file_name(name)).points]
