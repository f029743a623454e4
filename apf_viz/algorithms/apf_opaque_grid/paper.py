"""The paper's three algorithms as it writes them, line by line (``pseudocode.json``, transcribed from the
paper's LaTeX by ``scripts/make_pseudocode.py``), with each resolution's line inserted or rewritten in
place, and which line each rule id acts on: what the screen's Paper panel shows (core/portrayal.py).

Line numbers count as the paper's algorithm2e (``linesnumbered,vlined``) prints them: every ``if``,
``else if``, ``else`` and statement is a line, procedure headers and ``end`` are not; Algorithm 3 numbers
on through LineMove and TargetMove. docs/ALGORITHM.md, "The paper on screen"."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

from apf_viz.algorithms.apf_opaque_grid.resolutions import RESOLUTIONS, Resolution, Resolutions
from apf_viz.core.portrayal import CodeBlock, CodeLine, Pseudocode

SOURCE = Path(__file__).with_name("pseudocode.json")


@cache
def _source() -> dict:
    return json.loads(SOURCE.read_text(encoding="utf-8"))


@cache
def pseudocode(resolutions: Resolutions) -> Pseudocode:
    """The paper with the lines of ``resolutions`` in place (the literal paper: only those it needs)."""
    data = _source()
    changes: dict[tuple[str, int], list[dict]] = {}
    for change in data["resolution_lines"]:
        if Resolution(change["resolution"]) in resolutions:
            at = change.get("after", change.get("replaces"))
            changes.setdefault((change["algorithm"], at), []).append(change)
    blocks = []
    for algorithm in data["algorithms"]:
        lines: list[CodeLine] = []
        seen: dict[str, int] = {}
        for procedure in algorithm["procedures"]:
            lines.append(CodeLine(f"{algorithm['id']}:{procedure['title']}", "", 0, procedure["title"]))
            for line in procedure["lines"]:
                here = changes.get((algorithm["id"], line["n"]), [])
                replaced = any("replaces" in c for c in here)
                key = f"{algorithm['id']}.{line['n']}"
                lines.append(
                    CodeLine(key, str(line["n"]), line["depth"] + 1, line["text"], replaced=replaced)
                )
                for c in here:
                    base = f"{c['resolution']}@{key}"
                    seen[base] = seen.get(base, 0) + 1
                    name = base if seen[base] == 1 else f"{base}:{seen[base]}"
                    why = RESOLUTIONS[Resolution(c["resolution"])]
                    lines.append(CodeLine(name, "", c["depth"] + 1, c["text"], c["resolution"], why))
        blocks.append(CodeBlock(algorithm["title"], tuple(lines)))
    rules = {rule: tuple(keys) for rule, keys in {**data["rules"], **data["context"]}.items()}
    return Pseudocode(tuple(blocks), rules, dict(data["outside"]), dict(data["unreached"]))


def citation(paper: Pseudocode, rule_id: str) -> str | None:
    """How a rule's text cites the paper: "lines 3–5" from the innermost condition it acts under (or
    the condition it stops at) to its last action; None for a rule with no line of the paper's own."""
    keys = [k for k in paper.lines_of(rule_id) if "@" not in k]
    if not keys:
        return None
    numbers = sorted(int(k.split(".")[1]) for k in keys)
    first, last = numbers[0], numbers[-1]
    found = paper.line(keys[0])
    assert found is not None
    block, i = found
    text = block.lines[i].text
    enclosing = paper.enclosing(keys[0])
    if not (text.endswith(" then") or text == "else") and enclosing:
        first = int(enclosing[0].split(".")[1])
    return f"line {first}" if first == last else f"lines {first}–{last}"
