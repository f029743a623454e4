"""``apf-viz docs``: the manual, as it ships (a wheel holds docs/ too: the help texts name its pages)."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.core.formats import InputError
from apf_viz.demos import packaged_dir

NAME = "docs"
HELP = "the manual: list its pages, or print one (apf-viz docs guide | less)"


def docs_dir() -> Path:
    """The manual's folder: shipped inside the package, or a checkout's docs/."""
    return packaged_dir("docs")


def pages() -> dict[str, Path]:
    """The manual's pages by name, lower case (guide, cli, lectures, …)."""
    return {p.stem.lower(): p for p in sorted(docs_dir().glob("*.md"))}


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("page", nargs="?", help="a page's name: guide, cli, lectures, … (none: the list)")


def run(args: argparse.Namespace) -> int:
    found = pages()
    if args.page is None:
        for name, path in found.items():
            title = path.read_text(encoding="utf-8").splitlines()[0].lstrip("# ")
            print(f"{name:14} {title}")
        print(f"(in {docs_dir()})")
        return 0
    page = found.get(args.page.lower().removesuffix(".md"))
    if page is None:
        raise InputError(f"no page {args.page!r} in the manual; pages: {', '.join(found)}")
    print(page.read_text(encoding="utf-8"), end="")
    return 0
