"""The import rule of ARCHITECTURE.md, checked on the source (not on what happens to be loaded).

Every module of ``flumekit`` is parsed with :mod:`ast`; every import, at module level or inside
a function, is resolved to the ``flumekit`` module it names. A module may import from its own
layer or an earlier one, never from a later one, and never a private (``_name``) name of another
module: neither ``from flumekit.a import _x`` nor ``import flumekit.a as m; m._x``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "flumekit"

#: layers in import order; a module may import from its own layer and the ones before it
LAYERS: tuple[tuple[str, ...], ...] = (
    ("errors", "conventions", "units", "schema", "campaign", "signal", "scaling", "lazy",
     "docstrings"),
    ("io",),
    ("qc",),
    ("waves", "hydro", "performance"),
    ("flap", "ballscrew", "uvp"),
    ("synth", "uncertainty"),
    ("figures", "plot", "report"),
    ("pipeline",),
    ("stages",),
    ("bench", "cli"),
)
LAYER_OF = {part: i for i, parts in enumerate(LAYERS) for part in parts}
#: imports that the layers would allow but the architecture does not: readers know file formats,
#: not campaign configuration (the caller passes what a reader needs)
FORBIDDEN = {"flumekit.io": ("flumekit.campaign",)}
#: the package root (``flumekit/__init__.py``) is the public facade over every layer: nothing
#: inside the package may import a name from it except the version string
FACADE = len(LAYERS)
ROOT_CONSTANTS = {"__version__"}


def module_name(path: Path, package: Path = PACKAGE) -> str:
    """Dotted module name of a source file under ``package``."""
    parts = list(path.relative_to(package.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def all_modules(package: Path = PACKAGE) -> dict[str, Path]:
    """Every module of the package: dotted name -> source path."""
    return {module_name(p, package): p for p in sorted(package.rglob("*.py"))}


def layer(module: str) -> int:
    """Layer index of a ``flumekit`` module (the facade for the package root)."""
    parts = module.split(".")
    if len(parts) == 1:
        return FACADE
    if parts[1] not in LAYER_OF:
        raise KeyError(
            f"module {module} is in no layer: add flumekit.{parts[1]} to LAYERS in "
            "tests/test_layering.py and to ARCHITECTURE.md"
        )
    return LAYER_OF[parts[1]]


def _is_private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _owner(module: str) -> str:
    """The module that owns a private name defined in ``module`` (a private module belongs to
    its parent package)."""
    parts = module.split(".")
    while len(parts) > 1 and _is_private(parts[-1]):
        parts.pop()
    return ".".join(parts)


def _resolve(node: ast.ImportFrom, module: str, is_package: bool) -> str:
    """Absolute module name of a (possibly relative) ``from ... import``."""
    if not node.level:
        return node.module or ""
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def violations(source: str, module: str, modules: set[str], is_package: bool = False) -> list[str]:
    """Every breach of the import rule in one module's source, as readable messages.

    Parameters
    ----------
    source : the module's source text
    module : its dotted name (``flumekit.flap.analysis``)
    modules : dotted names of every module of the package (to tell a submodule from a name)
    is_package : whether the source is a package ``__init__``
    """
    tree = ast.parse(source)
    own = layer(module)
    out: list[str] = []
    module_aliases: dict[str, str] = {}  # local name -> flumekit module it is bound to

    def check(line: int, target: str, name: str | None, shown: str) -> None:
        if target != "flumekit" and not target.startswith("flumekit."):
            return
        if target == "flumekit" and name is not None and name not in modules_under_root:
            # a name defined in (or re-exported by) the package root
            lay = 0 if name in ROOT_CONSTANTS else FACADE
        else:
            lay = layer(target)
        if lay > own:
            later = "the package root" if lay == FACADE else "/".join(LAYERS[lay])
            out.append(f"{module}:{line}: `{shown}` imports from a later layer ({later})")
        for package, names in FORBIDDEN.items():
            if (module + ".").startswith(package + ".") and any(
                    (target + ".").startswith(n + ".") for n in names):
                out.append(f"{module}:{line}: `{shown}`: {package} may not import {target}")
        private_module = any(_is_private(p) for p in target.split(".")) and not (
            module + ".").startswith(_owner(target) + ".")
        if private_module or (name is not None and _is_private(name)
                              and _owner(target) != _owner(module)):
            out.append(f"{module}:{line}: `{shown}` imports a private name of another module")

    modules_under_root = {m.split(".")[1] for m in modules if m.count(".") >= 1}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                shown = f"import {a.name}" + (f" as {a.asname}" if a.asname else "")
                check(node.lineno, a.name, None, shown)
                if a.name.startswith("flumekit"):
                    module_aliases[a.asname or a.name] = a.name
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(node, module, is_package)
            for a in node.names:
                shown = f"from {'.' * node.level}{node.module or ''} import {a.name}"
                full = f"{target}.{a.name}"
                if full in modules:  # `from pkg import submodule`
                    check(node.lineno, full, None, shown)
                    module_aliases[a.asname or a.name] = full
                else:
                    check(node.lineno, target, a.name, shown)
    # private attributes reached through a module bound by an import: `m._name`
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                and node.value.id in module_aliases and _is_private(node.attr)):
            target = module_aliases[node.value.id]
            if _owner(target) != _owner(module):
                out.append(f"{module}:{node.lineno}: `{node.value.id}.{node.attr}` uses a "
                           f"private name of {target}")
    return out


def test_every_module_has_a_layer():
    for name in all_modules():
        layer(name)  # raises naming the module


def test_imports_follow_the_layers():
    modules = all_modules()
    names = set(modules)
    found: list[str] = []
    for name, path in modules.items():
        found += violations(path.read_text(encoding="utf-8"), name, names,
                            is_package=path.name == "__init__.py")
    assert not found, "import rule broken (see ARCHITECTURE.md):\n" + "\n".join(found)


NAMES = {"flumekit", "flumekit.errors", "flumekit.signal", "flumekit.io", "flumekit.io.mfprof",
         "flumekit.flap", "flumekit.flap.friction", "flumekit.flap.simulator", "flumekit.stages",
         "flumekit.stages.runs", "flumekit.waves", "flumekit.waves.theory", "flumekit.io._private"}


@pytest.mark.parametrize("source, module, expected", [
    # a later layer, at module level and inside a function, absolute and relative
    ("from flumekit.stages.runs import write_run", "flumekit.flap.friction",
     "flumekit.flap.friction:1: `from flumekit.stages.runs import write_run` imports from a "
     "later layer (stages)"),
    ("def f():\n    import flumekit.flap.simulator as s", "flumekit.io.mfprof",
     "flumekit.io.mfprof:2: `import flumekit.flap.simulator as s` imports from a later layer "
     "(flap/ballscrew/uvp)"),
    ("from ..flap import friction", "flumekit.waves.theory",
     "flumekit.waves.theory:1: `from ..flap import friction` imports from a later layer "
     "(flap/ballscrew/uvp)"),
    # a re-exported name from the package root
    ("from flumekit import InputError", "flumekit.signal",
     "flumekit.signal:1: `from flumekit import InputError` imports from a later layer "
     "(the package root)"),
    # private names across modules: imported, or reached through a module alias
    ("from flumekit.flap.friction import _step", "flumekit.flap.simulator",
     "flumekit.flap.simulator:1: `from flumekit.flap.friction import _step` imports a private "
     "name of another module"),
    ("from flumekit.flap import friction as fr\nfr._step(1)", "flumekit.flap.simulator",
     "flumekit.flap.simulator:2: `fr._step` uses a private name of flumekit.flap.friction"),
    ("from flumekit.io._private import x", "flumekit.waves.theory",
     "flumekit.waves.theory:1: `from flumekit.io._private import x` imports a private name of "
     "another module"),
    # allowed by the layers, not by the architecture
    ("from flumekit.campaign import UVP", "flumekit.io.mfprof",
     "flumekit.io.mfprof:1: `from flumekit.campaign import UVP`: flumekit.io may not import "
     "flumekit.campaign"),
])
def test_violations_are_named(source, module, expected):
    assert violations(source, module, NAMES) == [expected]


@pytest.mark.parametrize("source, module", [
    ("from flumekit.errors import InputError", "flumekit.io.mfprof"),  # an earlier layer
    ("from flumekit.hydro import x", "flumekit.waves.theory"),  # the same layer
    ("from flumekit import __version__", "flumekit.signal"),
    ("from flumekit import signal as sig", "flumekit.flap.friction"),
    ("from flumekit.io._private import x", "flumekit.io.mfprof"),  # inside its package
    ("from flumekit.flap.friction import _step\n_step(1)", "flumekit.flap.friction"),
    ("from . import friction\nfriction.__name__", "flumekit.flap.simulator"),
    ("import numpy as np\nnp._x", "flumekit.flap.simulator"),  # not ours
])
def test_allowed_imports_pass(source, module):
    assert violations(source, module, NAMES) == []


def imported_modules(source: str, module: str, modules: set[str],
                     is_package: bool = False) -> dict[str, int]:
    """The ``flumekit`` modules one module's source imports, at module level or inside a
    function: module name -> first line. ``from pkg import sub`` names the submodule ``sub``;
    ``from pkg import name`` names ``pkg``."""
    out: dict[str, int] = {}

    def add(target: str, line: int) -> None:
        if (target == "flumekit" or target.startswith("flumekit.")) and target != module:
            out.setdefault(target, line)

    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            for a in node.names:
                add(a.name, node.lineno)
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(node, module, is_package)
            for a in node.names:
                full = f"{target}.{a.name}"
                add(full if full in modules else target, node.lineno)
    return out


def import_cycles(graph: dict[str, dict[str, int]]) -> list[list[str]]:
    """One cycle (a list of modules, the first repeated at the end) in every strongly connected
    component of more than one module of the import ``graph`` (Tarjan 1972, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[list[str]] = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph.get(root, ()))))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            for child in children:
                if child not in graph:
                    continue
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    comp = []
                    while True:
                        m = stack.pop()
                        on_stack.discard(m)
                        comp.append(m)
                        if m == node:
                            break
                    if len(comp) > 1:
                        components.append(sorted(comp))
    cycles = []
    for comp in components:
        members, start = set(comp), comp[0]
        # shortest path back to the start within the component (breadth first)
        previous = {start: None}
        queue, end = [start], None
        while queue and end is None:
            node = queue.pop(0)
            for child in sorted(graph[node]):
                if child == start:
                    end = node
                    break
                if child in members and child not in previous:
                    previous[child] = node
                    queue.append(child)
        path = [start]
        while end is not None:
            path.insert(1, end)
            end = previous[end]
        cycles.append(path[:1] + path[2:] + [start] if len(path) > 1 else path)
    return cycles


def _cycle_text(cycle: list[str], graph: dict[str, dict[str, int]]) -> str:
    return " -> ".join(f"{a} (line {graph[a][b]})" for a, b in zip(cycle, cycle[1:])) + \
        f" -> {cycle[-1]}"


def test_no_import_cycles():
    modules = all_modules()
    names = set(modules)
    graph = {name: imported_modules(path.read_text(encoding="utf-8"), name, names,
                                    is_package=path.name == "__init__.py")
             for name, path in modules.items()}
    cycles = import_cycles(graph)
    assert not cycles, "import cycles between flumekit modules (move the shared names to a " \
        "module both sides can import):\n" + "\n".join(_cycle_text(c, graph) for c in cycles)


def test_cycles_are_named():
    names = {"flumekit.a", "flumekit.b", "flumekit.c", "flumekit.d"}
    sources = {"flumekit.a": "from flumekit.b import x",
               "flumekit.b": "def f():\n    from flumekit import c",
               "flumekit.c": "import flumekit.a\nfrom flumekit.d import y",
               "flumekit.d": "import numpy"}
    graph = {m: imported_modules(s, m, names) for m, s in sources.items()}
    cycles = import_cycles(graph)
    assert cycles == [["flumekit.a", "flumekit.b", "flumekit.c", "flumekit.a"]]
    assert _cycle_text(cycles[0], graph) == ("flumekit.a (line 1) -> flumekit.b (line 2) -> "
                                             "flumekit.c (line 1) -> flumekit.a")
    del graph["flumekit.c"]["flumekit.a"]
    assert import_cycles(graph) == []


def test_stage_modules_stay_small():
    """A stage only wires (reads, calls one domain function, writes): a stage module past
    150 lines holds domain code that belongs in its package."""
    long = {p.name: n for p in sorted((PACKAGE / "stages").glob("*.py"))
            if (n := len(p.read_text().splitlines())) > 150}
    assert long == {}, long
