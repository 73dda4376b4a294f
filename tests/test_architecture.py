"""The package layout reads as the pipeline: no import cycles between modules, and no
``_private`` name used outside the module that defines it (issue 12)."""

from __future__ import annotations

import ast
from pathlib import Path

from conftest import ROOT

PACKAGE = ROOT / "fetorsion"
TOP_LEVEL_LIMIT = 5  # modules directly in fetorsion/ besides __init__: a handful


def module_name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def modules() -> dict[str, Path]:
    return {module_name(p): p for p in PACKAGE.rglob("*.py")}


def resolve(importer: str, is_package: bool, level: int, target: str | None) -> str:
    base = importer.split(".")
    base = base if is_package else base[:-1]
    if level:
        base = base[: len(base) - (level - 1)]
        return ".".join(base + ([target] if target else []))
    return target or ""


def imports(name: str, path: Path, known: dict[str, Path]):
    """(imported module, imported names) pairs of every import statement, lazy ones included."""
    tree = ast.parse(path.read_text())
    is_package = path.name == "__init__.py"
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("fetorsion"):
                    yield alias.name, []
        elif isinstance(node, ast.ImportFrom):
            target = resolve(name, is_package, node.level, node.module)
            if not target.startswith("fetorsion"):
                continue
            names = [a.name for a in node.names]
            submodules = [f"{target}.{n}" for n in names if f"{target}.{n}" in known]
            for sub in submodules:
                yield sub, []
            yield target, [n for n in names if f"{target}.{n}" not in known]


def graph():
    known = modules()
    return {name: {t for t, _ in imports(name, path, known) if t in known and t != name}
            for name, path in known.items()}


def find_cycles(nodes: dict[str, set[str]]) -> list[list[str]]:
    """Every cycle a depth-first walk meets, each as a path that returns to its start."""
    state, stack, cycles = {}, [], []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(nodes.get(n, ())):
            if state.get(m) == 1:
                cycles.append(stack[stack.index(m):] + [m])
            elif m not in state:
                visit(m)
        stack.pop()
        state[n] = 2

    for n in sorted(nodes):
        if n not in state:
            visit(n)
    return cycles


def test_cycle_finder_finds_a_cycle():
    assert find_cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c", "a"]]
    assert find_cycles({"a": {"b"}, "b": set(), "c": {"a", "b"}}) == []


def test_no_import_cycle():
    g = graph()
    assert g["fetorsion.excitation.campbell"] >= {"fetorsion.lumped_model.lumped", "fetorsion.modes"}
    # A package's __init__ only re-exports its own modules: it is left out as a target, so that
    # 'a.x imports b.y' is not read as 'a.x imports b, which imports every b.*'.
    nodes = {n: {t for t in deps if not (PACKAGE / Path(*t.split(".")[1:]) / "__init__.py").exists()}
             for n, deps in g.items()}
    cycles = find_cycles(nodes)
    assert not cycles, "import cycles: " + "; ".join(" -> ".join(c) for c in cycles)


def test_no_private_name_imported_across_modules():
    known = modules()
    offences = [f"{name} imports {target}.{n}" for name, path in known.items()
                for target, names in imports(name, path, known) for n in names
                if n.startswith("_") and not n.startswith("__")]
    assert not offences, offences


def test_the_package_is_subpackages_and_a_handful_of_modules():
    top = sorted(p.stem for p in PACKAGE.glob("*.py") if p.name != "__init__.py")
    assert len(top) <= TOP_LEVEL_LIMIT, top
    packages = sorted(p.name for p in PACKAGE.iterdir() if (p / "__init__.py").exists())
    assert packages == sorted(["description", "solid", "fe", "webs", "lumped_model", "excitation", "response",
                               "studies", "report", "mechanics", "cli"])
    for name in packages:  # each stage says what it owns and hands on
        doc = ast.get_docstring(ast.parse((PACKAGE / name / "__init__.py").read_text()))
        assert doc and len(doc) > 80, name
