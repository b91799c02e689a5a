"""The package layout: no import circles, and imports run one way, geometry <- fem <- ltca <- tools.

Every .py file under geometry/, fem/ and ltca/ is parsed with ``ast``, under its import name: the folders
geometry/ and fem/ are the packages ``ltca.geometry`` and ``ltca.fem``. Every import counts (module level,
inside functions, under ``TYPE_CHECKING``), relative imports resolved. ``from p import name`` is an edge
to the module ``p.name`` when that is one of ours, else to ``p``. A failure prints the circle it found.
"""
from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("geometry", "fem", "ltca")                # installed (folders of the repository)
TOOLS = "tools"                                       # maintainer tooling in the repository, not installed
#: folder of the repository -> its import name
IMPORT_NAME = {"geometry": "ltca.geometry", "fem": "ltca.fem", "ltca": "ltca", TOOLS: TOOLS}
#: layers, lowest first: a module may import only modules of its own or a lower layer
LAYERS = ("ltca.geometry", "ltca.fem", "ltca", TOOLS)


def _rank(mod: str) -> int:
    """The layer of a module: the longest layer name it is or lies inside."""
    return max((len(layer), i) for i, layer in enumerate(LAYERS) if mod == layer or mod.startswith(layer + "."))[1]


def _modules(root: Path = ROOT, packages: tuple[str, ...] = PACKAGES) -> dict[str, tuple[Path, bool]]:
    """Module name -> (file, is a package's __init__)."""
    out = {}
    for pkg in packages:
        for path in sorted((root / pkg).rglob("*.py")):
            parts = path.relative_to(root).with_suffix("").parts
            parts = tuple(IMPORT_NAME[parts[0]].split(".")) + parts[1:]
            is_pkg = parts[-1] == "__init__"
            out[".".join(parts[:-1] if is_pkg else parts)] = (path, is_pkg)
    return out


def _resolve(name: str, modules) -> str | None:
    """The longest prefix of dotted ``name`` that is one of our modules."""
    parts = name.split(".")
    for n in range(len(parts), 0, -1):
        cand = ".".join(parts[:n])
        if cand in modules:
            return cand
    return None


@functools.cache                                  # parsed once per session; the tests only read it
def import_graph(root: Path = ROOT, packages: tuple[str, ...] = PACKAGES) -> dict[str, dict[str, int]]:
    """Module -> {imported module of ours: line of the first such import} over ``packages``."""
    modules = _modules(root, packages)
    graph: dict[str, dict[str, int]] = {}
    for mod, (path, is_pkg) in modules.items():
        edges: dict[str, int] = {}
        package = mod if is_pkg else mod.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            targets = []
            if isinstance(node, ast.Import):
                targets = [_resolve(a.name, modules) for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")
                    base = base[:len(base) - (node.level - 1)]
                    src = ".".join(base + ([node.module] if node.module else []))
                else:
                    src = node.module or ""
                for a in node.names:
                    sub = f"{src}.{a.name}"
                    targets.append(sub if sub in modules else _resolve(src, modules))
            for t in targets:
                if t is not None and t != mod:
                    edges.setdefault(t, node.lineno)
        graph[mod] = edges
    return graph


def find_cycles(graph: dict[str, set | dict]) -> list[list[str]]:
    """One circle per strongly connected component of more than one node (Tarjan), as [a, b, ..., a]."""
    index, low, stack, on, sccs = {}, {}, [], set(), []
    counter = [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                sccs.append(set(comp))

    for v in sorted(graph):
        if v not in index:
            strong(v)
    cycles = []
    for comp in sccs:                                   # a shortest circle through the component's first node
        start = min(comp)
        prev, frontier, cycle = {start: None}, [start], None
        while cycle is None:
            nxt = []
            for v in frontier:
                if start in graph.get(v, ()):
                    path = [v]
                    while prev[path[-1]] is not None:
                        path.append(prev[path[-1]])
                    cycle = path[::-1] + [start]
                    break
                for w in sorted(graph.get(v, ())):
                    if w in comp and w not in prev:
                        prev[w] = v
                        nxt.append(w)
            frontier = nxt
        cycles.append(cycle)
    return cycles


def _group(mod: str, pkg: str) -> str:
    """The node of a module of ``pkg`` in the subpackage graph: ``ltca.cylindrical.run`` -> ``ltca.cylindrical``."""
    return ".".join(mod.split(".")[:pkg.count(".") + 2])


def _inside(mod: str, pkg: str) -> bool:
    return mod.startswith(pkg + ".")


def _show(cycles: list[list[str]]) -> str:
    return "\n".join("  " + " -> ".join(c) for c in cycles)


def _explain(cycles: list[list[str]], graph) -> str:
    """Each circle, and every module on some circle with it (its strongly connected component)."""
    out = []
    for c in cycles:
        comp = sorted(m for m in _reachable(graph, c[0]) if c[0] in _reachable(graph, m))
        out.append("  " + " -> ".join(c) + (f"   (circle of {', '.join(comp)})" if len(comp) > len(c) - 1 else ""))
    return "\n".join(out)


def _reachable(graph, start: str) -> set:
    seen, todo = {start}, [start]
    while todo:
        for w in graph.get(todo.pop(), ()):
            if w not in seen:
                seen.add(w)
                todo.append(w)
    return seen


def subpackage_graph(graph: dict[str, dict[str, int]], pkg: str) -> dict[str, set]:
    """The subpackages and top-level modules of ``pkg`` as nodes, an edge where any of their modules imports."""
    groups: dict[str, set] = {}
    for mod, edges in graph.items():
        if not _inside(mod, pkg):
            continue
        a = _group(mod, pkg)
        groups.setdefault(a, set()).update(_group(t, pkg) for t in edges if _inside(t, pkg) and _group(t, pkg) != a)
    return groups


def against_the_direction(graph: dict[str, dict[str, int]]) -> list[str]:
    return [f"  {mod} (line {line}) imports {t}" for mod, edges in sorted(graph.items())
            for t, line in sorted(edges.items()) if _rank(t) > _rank(mod)]


def test_the_scan_sees_every_kind_of_import(tmp_path):
    """On a small tree: relative imports, imports in functions and under TYPE_CHECKING all make edges."""
    files = {
        "geometry/__init__.py": "",
        "geometry/a.py": "def f():\n    from ltca.fem import b\n",
        "fem/__init__.py": "",
        "fem/b.py": "import ltca.x.c\n",
        "ltca/__init__.py": "",
        "ltca/top.py": "from .x import c\n",
        "ltca/x/__init__.py": "",
        "ltca/x/c.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .d import D\n",
        "ltca/x/d.py": "def g():\n    from ..top import h\n",
    }
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    graph = import_graph(tmp_path)
    assert set(graph["ltca.x.c"]) == {"ltca.x.d"} and set(graph["ltca.x.d"]) == {"ltca.top"}
    assert find_cycles(graph) == [["ltca.top", "ltca.x.c", "ltca.x.d", "ltca.top"]]
    assert find_cycles(subpackage_graph(graph, "ltca")) == [["ltca.top", "ltca.x", "ltca.top"]]
    assert against_the_direction(graph) == ["  ltca.fem.b (line 1) imports ltca.x.c",
                                            "  ltca.geometry.a (line 2) imports ltca.fem.b"]


def test_the_scan_sees_the_packages():
    graph = import_graph()
    assert len(graph) > 50 and sum(len(e) for e in graph.values()) > 100


def test_no_import_cycle_among_modules():
    graph = import_graph()
    cycles = find_cycles(graph)
    print(_explain(cycles, graph))
    assert not cycles, "import circles among modules:\n" + _explain(cycles, graph)


def test_no_import_cycle_among_subpackages():
    """ltca's (and fem's) subpackages and top-level modules as nodes: no circle between them either."""
    graph = import_graph()
    for pkg in ("ltca", "ltca.fem"):
        cycles = find_cycles(subpackage_graph(graph, pkg))
        print(pkg, _show(cycles))
        assert not cycles, f"import circles among the subpackages of {pkg}:\n" + _show(cycles)


def test_imports_run_geometry_fem_ltca():
    bad = against_the_direction(import_graph())
    assert not bad, "imports against geometry <- fem <- ltca:\n" + "\n".join(bad)


def test_the_layers_are_imported_under_one_namespace():
    """No module imports the folders by their folder names (``geometry``, ``fem``): that would load a second copy
    of a module beside ``ltca.geometry`` / ``ltca.fem``, and clash with other distributions of those names."""
    bad = []
    for mod, (path, _) in _modules(packages=PACKAGES + (TOOLS,)).items():
        for node in ast.walk(ast.parse(path.read_text())):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else []
            bad += [f"  {mod} (line {node.lineno}) imports {n}" for n in names if n.split(".")[0] in ("geometry", "fem")]
    assert not bad, "imports by folder name, not ltca.geometry / ltca.fem:\n" + "\n".join(bad)


def test_every_package_says_what_it_holds():
    """Every package's __init__.py has a docstring (what it holds, what it may import)."""
    missing = [m for m, (path, is_pkg) in _modules().items()
               if is_pkg and not ast.get_docstring(ast.parse(path.read_text()))]
    assert not missing, f"packages without a docstring: {missing}"


#: the command layer: the only modules that print (the console of a command); everything else is library
COMMAND_MODULES = {
    "ltca.cli", "ltca.console", "ltca.driver", "ltca.cylindrical.run", "ltca.bevel.run", "ltca.planetary.run",
    "ltca.drivetrain.budget", "ltca.drivetrain.chain", "ltca.design.driver",
    "ltca.design.bevel_torque", "ltca.study.runner", "ltca.rexs.cli",
}


def _calls(path: Path, name: str, attr: str | None = None) -> list[int]:
    """Lines of calls to ``name(...)`` (or ``name.attr(...)``) in a module."""
    out = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Call):
            f = node.func
            if attr is None and isinstance(f, ast.Name) and f.id == name:
                out.append(node.lineno)
            elif attr is not None and isinstance(f, ast.Attribute) and f.attr == attr and \
                    isinstance(f.value, ast.Name) and f.value.id == name:
                out.append(node.lineno)
    return out


def test_library_modules_neither_print_nor_pick_a_backend():
    """Only the command layer prints; only the command line picks a matplotlib backend."""
    printing, backend = [], []
    for mod, (path, _) in _modules().items():
        if mod.startswith("ltca.verify"):
            continue
        if mod not in COMMAND_MODULES and _calls(path, "print"):
            printing.append(f"{mod}: lines {_calls(path, 'print')}")
        if mod != "ltca.cli" and _calls(path, "matplotlib", "use"):
            backend.append(mod)
    assert not printing, "print() in library modules:\n" + "\n".join(printing)
    assert not backend, f"matplotlib.use() outside ltca.cli: {backend}"


def test_the_tooling_imports_the_package_never_the_reverse():
    """tools/ (not installed) may import geometry, fem and ltca; no installed module imports tools, and the tooling
    makes no import circle."""
    graph = import_graph(packages=PACKAGES + (TOOLS,))
    assert any(m.startswith(TOOLS + ".") for m in graph), "the scan must see tools/"
    bad = against_the_direction(graph)
    assert not bad, "imports against geometry <- fem <- ltca <- tools:\n" + "\n".join(bad)
    cycles = find_cycles(graph)
    assert not cycles, "import circles:\n" + _show(cycles)


def test_the_tooling_is_not_installed():
    """The package discovery (setup.py: geometry*, fem*, ltca* and the data folders) does not pick up tools/ (it
    stays in the repository)."""
    text = (ROOT / "setup.py").read_text()
    include = re.search(r"find_packages\(include=\[(.*?)\]\)", text).group(1)
    patterns = [x.strip().strip('"') for x in include.split(",")]
    assert patterns and not any(pattern.split("*")[0].split(".")[0] == TOOLS for pattern in patterns)


def test_only_the_command_line_and_the_case_layer_import_the_study_package():
    """The study runs analyses, never the other way: only the command line, the case layer (a study is a case
    kind) and the key reference know it."""
    graph = import_graph()
    users = {m for m, edges in graph.items() for t in edges if t.startswith("ltca.study") and
             not m.startswith("ltca.study")}
    assert users == {"ltca.cli", "ltca.cases", "ltca.keys"}


def test_tests_share_code_through_fixtures_only():
    """No test module imports another test module or ``conftest``: shared code lives in ``tests/fixtures``."""
    bad = []
    for path in sorted((ROOT / "tests").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module or ""] if isinstance(node, ast.ImportFrom) else []
            bad += [f"{path.relative_to(ROOT)}:{node.lineno} imports {n}" for n in names
                    if n.split(".")[-1].startswith("test_") or n.split(".")[0] in ("conftest", "tests")]
    assert not bad, "\n".join(bad)
