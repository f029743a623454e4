"""The house a maintainer extends: every package ships, each extension point has one registry, rooms
of one job (no module over 500 lines, no function over 60), and no two modules import each other."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "apf_viz"


def test_every_package_of_the_source_is_listed_for_the_wheel():
    """pyproject.toml lists packages by hand (the demo patterns ship from outside apf_viz/): a package
    left off that list is missing from every wheel, and only a wheel's install would show it."""
    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    found = {
        ".".join(p.parent.relative_to(ROOT).parts)
        for p in PACKAGE.rglob("__init__.py")
        if "__pycache__" not in p.parts
    }
    assert found - listed == set()


def test_the_licence_is_stated_and_shipped():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]
    assert (ROOT / "LICENSE").read_text().startswith("MIT License")
