"""The house rules of docs/ and the README, checked on the source tree itself.

Each rule is read from the code with :mod:`ast` (never by importing it), so a
rule that stops holding fails here with the file and line that break it.
"""
from __future__ import annotations

import ast
import re
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SOURCE_DIRS = ("ccopt", "formulations")
MAX_MODULE_LINES = 600
MAX_FUNCTION_LINES = 80
# A float literal this small inside code is a tolerance and must have a name
# (tolerances.py, or a module constant with a one-line reason).
TOLERANCE_LITERAL = 1e-5
DECISIONS = ("ccopt/compensate/decisions.py", "ccopt/verify/decisions.py")


def _sources() -> list[Path]:
    return sorted(p for d in SOURCE_DIRS for p in (ROOT / d).rglob("*.py"))


def _module_name(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[0] == "formulations":
        parts[0] = "ccopt_formulations"
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _tree(path: Path) -> ast.Module:
    return ast.parse(path.read_text(), filename=str(path))


def _imported(path: Path, node: ast.AST) -> list[str]:
    """Absolute names an import statement brings in (modules and module.attr)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    assert isinstance(node, ast.ImportFrom)
    if node.level:
        base = _module_name(path).split(".")
        if path.name != "__init__.py":
            base = base[:-1]
        base = base[: len(base) - node.level + 1]
        module = ".".join(base + ([node.module] if node.module else []))
    else:
        module = node.module or ""
    return [module] + [f"{module}.{a.name}" for a in node.names]


def _import_graph() -> dict[str, set[str]]:
    modules = {_module_name(p): p for p in _sources()}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        deps: set[str] = set()
        for node in ast.walk(_tree(path)):
            if not isinstance(node, (ast.Import, ast.ImportFrom)):
                continue
            names = _imported(path, node)
            if isinstance(node, ast.ImportFrom) and any(n in modules for n in names[1:]):
                # ``from pkg import submodule``: the submodule is what is used
                names = [n for n in names[1:] if n in modules]
            for target in names:
                while target and target not in modules:
                    target = target.rpartition(".")[0]
                if target and target != name:
                    deps.add(target)
        graph[name] = deps
    return graph


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one node (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def _package(module: str) -> str:
    parts = module.split(".")
    return ".".join(parts[:2]) if parts[0] == "ccopt" else parts[0]


def test_no_import_cycle_between_modules():
    assert _cycles(_import_graph()) == []


def test_no_import_cycle_between_packages():
    """Subpackages form layers: the package ``ccopt`` itself (the public API
    that imports them all) is the only one above them."""
    graph = _import_graph()
    packages: dict[str, set[str]] = {}
    for module, deps in graph.items():
        here = _package(module)
        packages.setdefault(here, set()).update(
            _package(d) for d in deps if _package(d) != here)
    below_root = {p: d - {"ccopt"} for p, d in packages.items() if p != "ccopt"}
    assert _cycles(below_root) == []
    assert not [p for p, d in packages.items() if p != "ccopt" and "ccopt" in d and
                p.startswith("ccopt.")], "a subpackage imports the package root"


def test_ccopt_never_imports_formulations():
    bad = [m for m, deps in _import_graph().items()
           if m.startswith("ccopt.") or m == "ccopt"
           for d in deps if d.startswith("ccopt_formulations")]
    assert bad == []


def test_module_and_function_lengths():
    long_modules, long_functions = [], []
    for path in _sources():
        rel = path.relative_to(ROOT)
        n = len(path.read_text().splitlines())
        if n > MAX_MODULE_LINES:
            long_modules.append(f"{rel}: {n} lines")
        for node in ast.walk(_tree(path)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                length = node.end_lineno - node.lineno + 1
                if length > MAX_FUNCTION_LINES:
                    long_functions.append(f"{rel}:{node.lineno}: {node.name} {length} lines")
    assert long_modules == [] and long_functions == []


def test_tolerances_have_names():
    """No small float literal inside code: module-level assignments name them."""
    unnamed = []
    for path in _sources():
        if path.name == "tolerances.py":
            continue
        tree = _tree(path)
        named = {id(sub) for node in tree.body if isinstance(node, (ast.Assign, ast.AnnAssign))
                 for sub in ast.walk(node)}
        for node in ast.walk(tree):
            if (isinstance(node, ast.Constant) and isinstance(node.value, float)
                    and 0 < abs(node.value) <= TOLERANCE_LITERAL and id(node) not in named):
                unnamed.append(f"{path.relative_to(ROOT)}:{node.lineno}: {node.value!r}")
    assert unnamed == []


def _function_level_imports(path: Path) -> list[tuple[int, list[str]]]:
    found = []
    for fn in ast.walk(_tree(path)):
        if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for node in ast.walk(fn):
                if isinstance(node, (ast.Import, ast.ImportFrom)):
                    found.append((node.lineno, _imported(path, node)))
    return found


def test_imports_inside_functions_only_for_heavy_optional_libraries():
    """An import inside a function is allowed only for a third-party library
    (never ccopt's own modules), with a comment on that line or the line above
    saying why it is deferred."""
    bad = []
    for path in _sources():
        lines = path.read_text().splitlines()
        for lineno, names in _function_level_imports(path):
            rel = f"{path.relative_to(ROOT)}:{lineno}"
            if any(n.split(".")[0] in ("ccopt", "ccopt_formulations") for n in names):
                bad.append(f"{rel}: imports ccopt's own {names[0]} inside a function")
            elif "#" not in lines[lineno - 1] and not lines[lineno - 2].strip().startswith("#"):
                bad.append(f"{rel}: deferred import of {names[0]} without a comment saying why")
    assert bad == []


@pytest.mark.parametrize("decisions", DECISIONS)
def test_every_decision_is_read_where_its_rule_is_applied(decisions):
    """Changing a decision is changing decisions.py: so every flag in it must
    be read by the code that applies the rule."""
    path = ROOT / decisions
    names = [t.id for node in _tree(path).body if isinstance(node, (ast.Assign, ast.AnnAssign))
             for t in (node.targets if isinstance(node, ast.Assign) else [node.target])
             if isinstance(t, ast.Name) and t.id.isupper()]
    assert names, f"no decisions found in {decisions}"
    others = [p for p in _sources() if p != path]
    used = set()
    for p in others:
        for node in ast.walk(_tree(p)):
            if isinstance(node, ast.Attribute) and node.attr in names:
                used.add(node.attr)
            elif isinstance(node, ast.Name) and node.id in names:
                used.add(node.id)
    assert sorted(set(names) - used) == []


def test_every_package_folder_is_in_the_wheel():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    listed = set(project["tool"]["setuptools"]["packages"])
    folders = {_module_name(p.parent / "__init__.py")
               for p in (ROOT / "ccopt").rglob("*.py") if "__pycache__" not in p.parts}
    assert folders - listed == set()
    assert project["tool"]["setuptools"]["package-dir"]["ccopt.bundled_cases"] == "cases"


def test_nothing_cites_a_path_outside_the_repository():
    pattern = re.compile(r"\.\./shared|shared/(spec|conformance|DESIGN)")
    texts = [p for p in ROOT.rglob("*") if p.is_file() and p.suffix in
             (".py", ".md", ".toml", ".ipynb", ".txt", ".cfg", "")
             and not {".git", ".venv", "__pycache__", "build"} & set(p.parts)]
    bad = [f"{p.relative_to(ROOT)}:{i}" for p in texts
           for i, line in enumerate(p.read_text(errors="replace").splitlines(), 1)
           if pattern.search(line)]
    assert bad == []
