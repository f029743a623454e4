from __future__ import annotations

import json
from pathlib import Path

import pytest


@pytest.fixture
def write_json(tmp_path: Path):
    """Write an object (or raw text) to a file under tmp_path and return its path."""

    def _write(name: str, data) -> Path:
        p = tmp_path / name
        p.write_text(data if isinstance(data, str) else json.dumps(data))
        return p

    return _write
