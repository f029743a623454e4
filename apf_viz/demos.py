"""The ready-made patterns and starts (``demo_patterns/`` at the top of the repository).

A wheel or a non-editable install ships them inside the package, as ``apf_viz/demo_patterns`` (the
mapping is in pyproject.toml); a source checkout or an editable install reads the top-level folder, the
one source of both."""

from __future__ import annotations

from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent


def demo_dir() -> Path:
    """The folder of demo patterns (its ``starts/`` holds the demo starts)."""
    shipped = _PACKAGE / "demo_patterns"
    return shipped if shipped.is_dir() else _PACKAGE.parent / "demo_patterns"


def demo_files(sub: str = "") -> dict[str, Path]:
    """The demo files of ``demo_patterns/`` (or of its sub-folder ``sub``), by name without ``.json``."""
    folder = demo_dir() / sub if sub else demo_dir()
    return {p.stem: p for p in sorted(folder.glob("*.json"))}


DEMO_DIR = demo_dir()
DEMO_START = DEMO_DIR / "starts" / "demo-10.json"
DEMO_PATTERN = DEMO_DIR / "heart.json"
