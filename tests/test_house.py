"""The house a maintainer extends: every package ships, each extension point has one registry, rooms
of one job (no module over 500 lines of code, no function over 60), and no two modules import each other."""

from __future__ import annotations

import ast
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest

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


def _modules() -> dict[str, Path]:
    found = {}
    for p in PACKAGE.rglob("*.py"):
        if "__pycache__" in p.parts:
            continue
        parts = list(p.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        found[".".join(parts)] = p
    return found


def _imports(path: Path, modules: dict[str, Path]) -> set[str]:
    """Every apf_viz module ``path`` imports, at any depth: in functions and under TYPE_CHECKING too (an
    import made late or for annotations only is still a dependency a reader must follow)."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("apf_viz"):
            for alias in node.names:
                full = f"{node.module}.{alias.name}"
                out.add(full if full in modules else node.module)
        elif isinstance(node, ast.Import):
            out.update(a.name for a in node.names if a.name.startswith("apf_viz"))
    return {m for m in out if m in modules}


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan, iteratively)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    found = []
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on.add(root)
        while work:
            v, children = work[-1]
            w = next(children, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    component.append(w)
                    if w == v:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return found


def _defines(path: Path) -> bool:
    """Whether a module defines a function or class of its own (a package's ``__init__`` that does is a
    module like any other, not a list of its submodules)."""
    tree = ast.parse(path.read_text())
    return any(isinstance(n, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef) for n in tree.body)


def test_no_two_modules_import_each_other():
    """Not even for annotations: a circle means neither module can be read, or moved, alone. A package's
    ``__init__`` importing its own submodules is how a package lists them, not a circle, unless it also
    defines things of its own (then its submodules importing it, and it them, is a circle)."""
    modules = _modules()
    graph = {
        m: {
            d
            for d in _imports(p, modules)
            if d != m and not (d.startswith(m + ".") and not (p.name == "__init__.py" and _defines(p)))
        }
        for m, p in modules.items()
    }
    assert _cycles(graph) == [], _cycles(graph)
    graph["apf_viz.core.history"].add("apf_viz.core.engine")  # the test can see a circle
    (circle,) = _cycles(graph)
    assert {"apf_viz.core.engine", "apf_viz.core.history"} <= set(circle)


def test_the_view_model_reads_the_run_through_a_protocol_and_imports_nothing_stateful():
    """workbench/view_model turns state into what is drawn: it imports the core and plain data, never a
    controller, the session, the lecturer, the scene, a panel or viser."""
    modules = _modules()
    rooms = (
        "workbench.session",
        "workbench.run_controller",
        "ui.app",
        "ui.panels",
        "ui.scene",
        "workbench.lecturer",
        "ui.recorder",
        "workbench.verifier",
    )
    stateful = tuple(f"apf_viz.{m}" for m in rooms)
    assert all(any(name.startswith(m) for name in modules) for m in stateful)  # each still exists
    for name, path in modules.items():
        if name.startswith("apf_viz.workbench.view_model"):
            bad = [m for m in _imports(path, modules) if m.startswith(stateful)]
            assert bad == [], (name, bad)
            assert "import viser" not in path.read_text() and "from viser" not in path.read_text()


def code_lines(text: str) -> set[int]:
    """The numbers of the lines that hold code: not blank, not only a comment, not a docstring (a
    module's, class's or function's first string), so that explanation never counts against a cap."""
    import io
    import tokenize

    skip = {
        tokenize.COMMENT,
        tokenize.NL,
        tokenize.NEWLINE,
        tokenize.INDENT,
        tokenize.DEDENT,
        tokenize.ENDMARKER,
    }
    lines: set[int] = set()
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type not in skip:
            lines.update(range(tok.start[0], tok.end[0] + 1))
    for node in ast.walk(ast.parse(text)):
        body = getattr(node, "body", None)
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef) and body:
            first = body[0]
            if (
                isinstance(first, ast.Expr)
                and isinstance(first.value, ast.Constant)
                and isinstance(first.value.value, str)
            ):
                lines.difference_update(range(first.lineno, (first.end_lineno or first.lineno) + 1))
    return lines


def test_code_lines_count_code_only():
    text = (
        '"""A module.\n\nIts words."""\n\n# why\nx = 1\n\n\n'
        'def f():\n    """Doc."""\n    return (\n        x\n    )\n'
    )
    assert sorted(code_lines(text)) == [6, 9, 11, 12, 13]


def test_rooms_of_one_job_no_module_over_500_lines_no_function_over_60():
    """A module a maintainer can read whole, a function that does one thing: at most 500 and 60 lines of
    code (docstrings and comments do not count: explanation is never what makes a room too big)."""
    long_modules, long_functions = [], []
    for name, path in _modules().items():
        text = path.read_text()
        code = code_lines(text)
        if len(code) > 500:
            long_modules.append(name)
        for node in ast.walk(ast.parse(text)):
            is_function = isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
            if is_function and len(code & set(range(node.lineno, (node.end_lineno or 0) + 1))) > 60:
                long_functions.append(f"{name}.{node.name}")
    assert long_modules == [] and long_functions == []


DOCUMENTED = ("core", "workbench", "api")
"""The packages whose every public function and class says what it does: the engine, the rooms of the
workbench and the library's API."""
Definition = ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef


def _public_definitions(body: list[ast.stmt], prefix: str = "") -> list[tuple[str, Definition]]:
    """Every function and class of a module's (or class's) body whose name is public, with the classes'
    own, recursively; a function nested in a function's body is its caller's detail, and is left out."""
    found: list[tuple[str, Definition]] = []
    for node in body:
        if isinstance(node, Definition):
            if not node.name.startswith("_"):
                found.append((prefix + node.name, node))
            if isinstance(node, ast.ClassDef):
                found += _public_definitions(node.body, f"{prefix}{node.name}.")
    return found


def test_every_public_function_and_class_of_the_core_workbench_and_api_has_a_docstring():
    """A maintainer reads what a function does before how it does it: a sentence or two on each (an
    overload, a property and a protocol's member too)."""
    seen, missing = 0, []
    for path in sorted(_modules().values()):
        if path.relative_to(PACKAGE).parts[0] not in DOCUMENTED:
            continue
        for qualname, node in _public_definitions(ast.parse(path.read_text()).body):
            seen += 1
            if ast.get_docstring(node) is None:
                missing.append(f"{path.relative_to(ROOT)}:{node.lineno} {qualname}")
    assert seen > 500, seen  # the walk reached the packages
    assert missing == [], "no docstring:\n" + "\n".join(missing)


def test_viser_is_entered_by_one_door():
    """Every name viser does not publish (``viser._…``, ``viser.infra``, a handle's ``_impl`` or
    ``_marks``, the server's ``_websock_server``, the producer, its client's Mantine class names) is used
    in ui/viser_compat.py only, where each has a contract test and a fallback
    (tests/test_viser_compat.py; the player's time field: tests/test_lecture_projector.py)."""
    import re

    inside = re.compile(
        r"from viser\.(?:_|infra)|import viser\.(?:_|infra)|(?<!self)\._impl\b|(?<!self)\._marks\b"
        r"|_websock_server|_live_connections|_message_producer\b|_append_aligned_buffers|\.mantine-"
    )
    package = Path(__file__).resolve().parent.parent / "apf_viz"
    found = []
    for path in sorted(package.rglob("*.py")):
        if path.name == "viser_compat.py":
            continue
        code = [line.split("#")[0] for line in path.read_text().splitlines()]
        text = "\n".join(code)
        text = re.sub(r'"""[\s\S]*?"""', "", text)  # docstrings may name what they explain
        found += [f"{path.relative_to(package)}: {m.group(0)}" for m in inside.finditer(text)]
    assert found == []


BLOCK_VISER = """
import sys
class Block:
    def find_spec(self, name, path=None, target=None):
        if name == "viser" or name.startswith("viser."):
            raise ImportError("viser is not importable here")
sys.meta_path.insert(0, Block())
from apf_viz.cli import main
import importlib, pkgutil, apf_viz.workbench, apf_viz.figure
for package in (apf_viz.workbench, apf_viz.figure):
    for module in pkgutil.walk_packages(package.__path__, package.__name__ + "."):
        importlib.import_module(module.name)
assert main(["lecture", "check", "what-a-robot-cannot-see"]) == 0
assert main(["figure", "--figure", "call1", "--format", "tikz", "--out", sys.argv[1]]) == 0
assert "viser" not in sys.modules
"""


def test_the_workbench_lecture_check_and_figures_run_with_viser_unimportable(tmp_path):
    """The workbench (every module of apf_viz/workbench: sessions, the view model, the lecturer, the
    studio...) and what is built on it (every module of figure/, lecture check) know no viser: they
    import and run where it cannot be imported."""
    import subprocess
    import sys

    done = subprocess.run(
        [sys.executable, "-c", BLOCK_VISER, str(tmp_path / "f.tex")],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=Path(__file__).resolve().parent.parent,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert (tmp_path / "f.tex").read_text().startswith(r"\begin{tikzpicture}")


LAYERS = {
    # a package: the packages it must never import (at any depth: in functions and for annotations too)
    "apf_viz.core": ("apf_viz.workbench", "apf_viz.ui", "apf_viz.figure", "apf_viz.cli"),
    "apf_viz.workbench": ("apf_viz.ui", "apf_viz.cli"),
    "apf_viz.figure": ("apf_viz.ui", "apf_viz.cli"),
    "apf_viz.ui": ("apf_viz.cli",),
}


def test_the_layers_import_downwards_only():
    """The core knows no workbench, the workbench and the figures know no viser adapter (``ui/``), and
    nothing below the command line imports it: ``ui/`` is handed a session, not an argparse Namespace."""
    modules = _modules()
    assert all(any(m.startswith(layer) for m in modules) for layer in LAYERS)
    wrong = []
    for name, path in modules.items():
        for layer, below in LAYERS.items():
            if name == layer or name.startswith(layer + "."):
                wrong += [f"{name} -> {d}" for d in _imports(path, modules) if d.startswith(below)]
    assert wrong == []


def test_no_module_outside_the_scene_reads_a_renderers_insides():
    """A renderer's nodes and helpers are the scene's own: others ask its public methods (``nodes``,
    ``words``, ``visible_height``), so that a layer can change how it keeps them."""
    import re

    private = re.compile(r"\b(?:renderer|selection|canvas|base)\._[a-z]\w*")
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if "scene" in path.relative_to(PACKAGE).parts:
            continue
        found += [f"{path.relative_to(PACKAGE)}: {m.group(0)}" for m in private.finditer(path.read_text())]
    assert found == []


def test_no_class_declares_its_hosts_members_again():
    """A class that needs another's members holds it (a part: the engine's Events and Walker, the
    watches' QuietSteps) or subclasses where they are declared (SessionCore, EngineCore, Canvas); none
    re-declares them for the type checker (an ``if TYPE_CHECKING:`` inside a class body)."""
    found = []
    for name, path in _modules().items():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ClassDef):
                found += [
                    f"{name}.{node.name}"
                    for stmt in node.body
                    if isinstance(stmt, ast.If) and "TYPE_CHECKING" in ast.unparse(stmt.test)
                ]
    assert found == []


def test_a_test_that_starts_chromium_without_the_browser_mark_is_refused_at_collection():
    """``--quick`` leaves out the marked tests only; conftest refuses an unmarked test asking for the
    browser (its rule, on stand-in tests: one marked, one not, one that needs no browser)."""
    from types import SimpleNamespace

    from tests.conftest import unmarked_browser_tests

    def item(nodeid: str, fixtures: tuple[str, ...], marked: bool):
        return SimpleNamespace(
            nodeid=nodeid, fixturenames=fixtures, get_closest_marker=lambda name: object() if marked else None
        )

    items = [item("a", ("browser", "tmp_path"), True), item("b", ("browser",), False), item("c", (), False)]
    assert unmarked_browser_tests(items) == ["b"]


IMPORT_SHARDS = 4  # the modules split four ways: one interpreter each, run side by side by the workers


@pytest.mark.slow
@pytest.mark.parametrize("shard", range(IMPORT_SHARDS))
def test_every_module_imports_on_its_own(shard):
    """A run-time import circle (a module importing, at its top, one that imports it back while it is
    half made) shows only when that module is imported first. In a fresh interpreter, each module of
    the package (every fourth, from ``shard``: the whole took 20 s alone, the suite's slowest test but
    one) is imported with every apf_viz module forgotten before it: as if it were the first (the
    third-party libraries stay loaded; a circle through them is not ours). ``__main__`` modules run."""
    script = textwrap.dedent(
        """
        import importlib, pkgutil, sys
        import apf_viz
        names = sorted(m.name for m in pkgutil.walk_packages(apf_viz.__path__, "apf_viz.")
                       if not m.name.endswith("__main__"))[SHARD::SHARDS]
        failed = []
        for name in names:
            for loaded in [n for n in sys.modules if n == "apf_viz" or n.startswith("apf_viz.")]:
                del sys.modules[loaded]
            try:
                importlib.import_module(name)
            except Exception as e:
                failed.append(f"{name}: {type(e).__name__}: {e}")
        print(len(names))
        print("\\n".join(failed))
        """
    )
    script = script.replace("SHARD::SHARDS", f"{shard}::{IMPORT_SHARDS}")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    count, *failed = done.stdout.strip().splitlines()
    assert int(count) > 150 // IMPORT_SHARDS and not failed, failed


def _assigned_names(tree: ast.Module) -> set[str]:
    targets = [t for n in tree.body if isinstance(n, ast.Assign) for t in n.targets]
    targets += [n.target for n in tree.body if isinstance(n, ast.AnnAssign)]
    return {t.id for t in targets if isinstance(t, ast.Name)}


def _exported(tree: ast.Module) -> list[str]:
    """The names a module's ``__all__`` lists (a literal list)."""
    for n in tree.body:
        target = (
            n.targets[0] if isinstance(n, ast.Assign) else n.target if isinstance(n, ast.AnnAssign) else None
        )
        if isinstance(target, ast.Name) and target.id == "__all__" and n.value is not None:
            return list(ast.literal_eval(n.value))
    return []


def test_every_package_says_what_it_exports():
    """``__all__`` in every package's ``__init__.py`` (an empty one where the modules are the interface)."""
    inits = sorted(PACKAGE.rglob("__init__.py"))
    missing = [
        str(i.relative_to(ROOT)) for i in inits if "__all__" not in _assigned_names(ast.parse(i.read_text()))
    ]
    assert len(inits) > 10 and not missing, missing
    for init in inits:  # and says every name it re-exports (``from m import a as a``)
        tree = ast.parse(init.read_text())
        again = {
            a.name for n in tree.body if isinstance(n, ast.ImportFrom) for a in n.names if a.asname == a.name
        }
        listed = set(_exported(tree))
        assert again <= listed, (str(init.relative_to(ROOT)), sorted(again - listed))


IMPORT_NAME = {"pillow": "PIL", "pytest-xdist": "xdist"}


def _third_party(path: Path) -> set[str]:
    """The top-level names of every module ``path`` imports (at any depth of its code)."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            out.add(node.module.split(".")[0])
        elif isinstance(node, ast.Import):
            out.update(a.name.split(".")[0] for a in node.names)
    return out


def test_the_lowest_versions_run_tests_that_reach_every_dependency():
    """scripts/test_lowest.sh runs a list of test files, not the whole quick suite: each dependency of
    scripts/lowest.txt is imported by one of them or by a module of ours one of them imports (pytest and
    its plugin run them). A dependency dropped from that reach would be installed at its lowest version
    and never used there."""
    import re

    script = (ROOT / "scripts" / "test_lowest.sh").read_text()
    listed = [ROOT / name for name in re.search(r"LOWEST_TESTS=\((.*?)\)", script, re.S).group(1).split()]
    assert all(p.is_file() for p in listed), [p.name for p in listed if not p.is_file()]
    modules = _modules()
    reached = set().union(*(_third_party(p) for p in listed))
    for test in listed:
        reached |= set().union(*(_third_party(modules[m]) for m in _imports(test, modules)))
    wanted = {
        IMPORT_NAME.get(name, name)
        for line in (ROOT / "scripts" / "lowest.txt").read_text().splitlines()
        if line and not line.startswith("#")
        for name in [re.sub(r"\[.*\]", "", line.split("==")[0])]
        if name not in ("pytest", "pytest-xdist")
    }
    assert wanted - reached == set()
