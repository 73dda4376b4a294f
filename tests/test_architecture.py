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
                               "studies", "design", "report", "app", "mechanics", "cli", "measured"])
    for name in packages:  # each stage says what it owns and hands on
        doc = ast.get_docstring(ast.parse((PACKAGE / name / "__init__.py").read_text()))
        assert doc and len(doc) > 80, name


# ---------------------------------------------------------------------------
# Defaults in one home, no dead public code, no CLI flag below the CLI


def literal_defaults(sources=None):
    """(parameter or option name, value) -> places, for every numeric literal default: function
    parameters, argparse options' ``default=`` and module-level constants. 0, 1, 2 and -1 are not counted (neutral
    values, not choices someone could change in one place and forget in another)."""
    found: dict[tuple, list[str]] = {}

    def note(name, node, where):
        if (isinstance(node, ast.Constant) and isinstance(node.value, (int, float))
                and not isinstance(node.value, bool) and node.value not in (0, 1, 2, -1)):
            found.setdefault((name, node.value), []).append(where)

    if sources is None:
        sources = {name: path.read_text() for name, path in modules().items()}
    for name, text in sources.items():
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                a = node.args
                positional = a.posonlyargs + a.args
                pairs = list(zip(positional[len(positional) - len(a.defaults):], a.defaults))
                pairs += [(k, d) for k, d in zip(a.kwonlyargs, a.kw_defaults) if d is not None]
                for arg, default in pairs:
                    note(arg.arg, default, f"{name}.{node.name}")
            elif isinstance(node, ast.Module):  # module-level constants: NAME = literal
                for stmt in node.body:
                    if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name):
                        note(stmt.targets[0].id, stmt.value, f"{name}.{stmt.targets[0].id}")
            elif isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "add_argument":
                flags = [c.value for c in node.args if isinstance(c, ast.Constant)]
                for kw in node.keywords:
                    if kw.arg == "default" and flags:
                        note(flags[0].lstrip("-").replace("-", "_"), kw.value, f"{name} {flags[0]}")
    return found


def test_literal_defaults_finder_finds_a_repeat():
    found = literal_defaults({"a": "def f(x, mu=0.25, n=1):\n    pass\n",
                              "b": "def g(*, mu=0.25):\n    pass\np.add_argument('--mu', default=0.25)\n",
                              "c": "mu = 0.25\n"})
    assert found == {("mu", 0.25): ["a.f", "b.g", "b --mu", "c.mu"]}


def test_no_default_literal_is_written_twice():
    repeated = {k: v for k, v in literal_defaults().items() if len(v) > 1}
    assert not repeated, "name one constant for each: " + "; ".join(f"{k}: {v}" for k, v in repeated.items())


#: Public names that nothing in the package uses but that are kept as API, each with why: a
#: reader of what a command writes, and the independent checks the validation rests on.
API_ONLY = {
    "load_condensed": "reads the .npz that 'fetorsion condense --npz' writes",
    "run_fillet_scf": "the SCF mesh-convergence study (benchmarks/bench_fillet_scf.py, docs/fillet-stress.md)",
    "stepped_shaft_scf": "the SCF method on Peterson's stepped shaft: the validation of fillet_scfs",
    "peterson_stepped_bending": "Peterson's bending fit: the published check of the bending SCF (tests/test_scf.py)",
    "step_fillet_length": "Nestorides' fillet length: the check of the FE throw stiffness",
    "chart_point": "one point of the computed web chart (scripts/web_chart.py builds the chart from it)",
    "render_gif": "an animated mode shape for slides, beside the report's still images",
    "peak_amplification": "a damped chain's peak amplification: the check of the optimiser on Den Hartog's system",
    # the rotating-frame terms of the condensed crank (fe/rotating.py), tested on a spinning shaft
    # and on point-mass bodies; wired into run_condensed and the coupled response next
    "rotating_frame_matrices": "Coriolis and spin-softening matrices on the Craig–Bampton basis",
    "attachment_rotating_matrices": "the attachments' rotating-frame terms on the masters",
    "rotating_modes": "natural frequencies in the rotating frame",
    "rotating_harmonic": "harmonic response in the rotating frame",
    "prestress": "the centrifugal prestress at the quadrature points, for geometric_stiffness",
    "geometric_stiffness": "the stress stiffening that goes with spin softening",
}


def public_definitions():
    """(name, module) of every public module-level function, class and constant."""
    for name, path in modules().items():
        for node in ast.parse(path.read_text()).body:
            targets = [node.name] if isinstance(node, (ast.FunctionDef, ast.ClassDef)) else \
                [t.id for t in getattr(node, "targets", []) if isinstance(t, ast.Name)]
            yield from ((t, name) for t in targets if not t.startswith("_"))


def test_every_public_name_is_used():
    import re

    from collections import Counter

    # a name (an identifier) occurs as \bname\b exactly where it is one whole \w+ word: count the
    # words once instead of searching the package once per name
    package = Counter(w for p in modules().values() for w in re.findall(r"\w+", p.read_text()))
    outside = Counter(w for folder in ("benchmarks", "scripts", "examples") for p in (ROOT / folder).rglob("*.py")
                      for w in re.findall(r"\w+", p.read_text()))
    unused = []
    for name, module in public_definitions():
        uses = package[name] - 1  # less its definition
        if uses == 0 and not outside[name] and name not in API_ONLY:
            unused.append(f"{module}.{name}")
    assert not unused, f"defined but used nowhere (remove, or say why in API_ONLY): {unused}"
    assert all(any(n == name for n, _ in public_definitions()) for name in API_ONLY), "stale API_ONLY entry"


def flags_in_code(text: str) -> list[str]:
    """Command-line flags (``--name``) in the string literals of a module, docstrings aside."""
    import re

    tree = ast.parse(text)
    docs = {id(n.body[0].value) for n in ast.walk(tree)
            if isinstance(n, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
            and n.body and isinstance(n.body[0], ast.Expr) and isinstance(n.body[0].value, ast.Constant)}
    return [m for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)
            and id(n) not in docs for m in re.findall(r"(?<![\w-])--[a-z][a-z-]*", n.value)]


def test_flag_finder_skips_docstrings():
    text = '"""Use --mesh-size."""\ndef f(x):\n    """--dof"""\n    raise E(f"--type {x}: bad")\n'
    assert flags_in_code(text) == ["--type"]


def test_no_module_below_the_command_line_names_a_flag():
    # Compute code names its parameters (errors.ParameterError); cli/ translates them to options.
    offenders = {name: flags for name, path in modules().items()
                 if not name.startswith("fetorsion.cli") and (flags := flags_in_code(path.read_text()))}
    assert not offenders, offenders


def test_sources_are_cited_by_bibliography_key():
    # "[Key]" in the package resolves in docs/references.md; a project-internal pointer ("seed 003",
    # "issue 14") means nothing to an outside reader and is not used.
    import re

    defined = set(re.findall(r"\*\*\[(\w+)\]\*\*", (ROOT / "docs" / "references.md").read_text()))
    cited, internal = set(), []
    for name, path in modules().items():
        text = path.read_text()
        # after a space or "(": not list[Part] or x[None]; three letters at least: not "[Hz]"
        cited |= set(re.findall(r"(?<=[\s(])\[([A-Z][a-z]{2,})\]", text))
        internal += [f"{name}: {m}" for m in re.findall(r"\bseeds? 0\d\d|\bissue[ -]\d+", text, flags=re.I)]
    assert defined >= {"Seyedalian", "Kazemi", "Ismailov", "Asgari", "Wang"}
    assert cited <= defined, cited - defined
    assert not internal, internal


def test_the_runs_hand_offs_name_their_types():
    """Issue 41 (in part): no outcome field of a run is typed ``object``, the steps read their
    options from a RunOptions, not a dict, and run() returns its RunOutcome."""
    outcomes = ast.parse((ROOT / "fetorsion/report/outcomes.py").read_text())
    untyped = [f"{c.name}.{a.target.id}" for c in outcomes.body if isinstance(c, ast.ClassDef)
               for a in c.body if isinstance(a, ast.AnnAssign) and ast.unparse(a.annotation) == "object"]
    assert not untyped, untyped
    run = ast.parse((ROOT / "fetorsion/app/run.py").read_text())
    context = next(c for c in run.body if isinstance(c, ast.ClassDef) and c.name == "RunContext")
    fields = {a.target.id: ast.unparse(a.annotation) for a in context.body if isinstance(a, ast.AnnAssign)}
    assert fields["options"] == "RunOptions"
    entry = next(f for f in run.body if isinstance(f, ast.FunctionDef) and f.name == "run")
    assert ast.unparse(entry.returns) == "RunOutcome"


def stage_order() -> list[str]:
    """The stage order, as docs/architecture.md writes it (its ``Stages:`` line)."""
    line = next(x for x in (ROOT / "docs/architecture.md").read_text().splitlines() if x.startswith("Stages:"))
    return [s.strip() for s in line.split(":", 1)[1].split(",")]


def test_no_stage_imports_a_later_one():
    """Issue 41: every subpackage is in the written stage order, and no module imports a module
    of a later stage (lazy imports included: a lazy import back up is still one)."""
    order = stage_order()
    packages = sorted(p.name for p in PACKAGE.iterdir() if (p / "__init__.py").exists())
    assert sorted(order) == packages, set(order) ^ set(packages)
    rank = {s: k for k, s in enumerate(order)}
    known = modules()
    back = []
    for name, path in known.items():
        here = name.split(".")[1] if name.count(".") >= 1 else None
        for target, _ in imports(name, path, known):
            there = target.split(".")[1] if target.count(".") >= 1 else None
            if here in rank and there in rank and rank[there] > rank[here]:
                back.append(f"{name} imports {target}")
    assert not back, back


#: The parsed TOML document, as the user wrote it: the description stage's own input (the
#: ``data`` the readers take, the ``raw`` and free ``[notes]`` tables the model keeps for
#: variants and the report), not a record one stage hands another.
TOML_DOCUMENT = {("fetorsion.description.crank", "parse_crank", "data"),
                 ("fetorsion.description.files", "parse_description", "data"),
                 ("fetorsion.description.reader", "resolve_field", "data"),
                 ("fetorsion.mechanics.input", "is_crank_description", "data"),
                 ("fetorsion.mechanics.input", "parse_mechanics", "data"),
                 ("fetorsion.description.model", "Crank", "raw"), ("fetorsion.description.chain_model", "Chain", "raw"),
                 ("fetorsion.description.chain_model", "Network", "raw"), ("fetorsion.description.model", "Crank", "notes")}


def untyped_names(annotation: str) -> list[str]:
    """``dict``, ``object`` or ``Any`` written bare anywhere in an annotation (``dict[str, float]``
    names its keys and values; ``list[dict]`` and ``dict | None`` do not)."""
    tree = ast.parse(annotation, mode="eval")
    subscripted = {id(n.value) for n in ast.walk(tree) if isinstance(n, ast.Subscript)}
    return [n.id for n in ast.walk(tree) if isinstance(n, ast.Name) and n.id in ("dict", "object", "Any")
            and id(n) not in subscripted]


def test_untyped_annotation_finder():
    assert untyped_names("dict") == ["dict"] and untyped_names("list[dict]") == ["dict"]
    assert untyped_names("SCFSet | dict | None") == ["dict"] and untyped_names("object") == ["object"]
    assert untyped_names("dict[str, float]") == [] and untyped_names("dict[str, tuple[float, float]] | None") == []


def test_no_untyped_hand_off_crosses_a_stage():
    """Issue 41: every function parameter and public class field that a module of another stage
    imports is typed (issue 56: annotated at all): no bare ``dict``, ``object`` or ``Any`` (a record is a dataclass; a mapping
    says its keys and values), the TOML document as read aside (:data:`TOML_DOCUMENT`)."""
    order, known = stage_order(), modules()

    def stage(name):
        return name.split(".")[1] if name.count(".") >= 1 else None

    crossing = {(target, n) for name, path in known.items() for target, names in imports(name, path, known)
                if stage(target) != stage(name) and stage(target) in order and stage(name) in order
                for n in names or ()}
    assert len(crossing) > 200  # the walk sees the run's hand-offs (about 400)
    bad = []
    for target, n in sorted(crossing):
        node = next((x for x in ast.parse(known[target].read_text()).body if getattr(x, "name", None) == n), None)
        typed = []
        if isinstance(node, ast.FunctionDef):
            args = node.args.posonlyargs + node.args.args + node.args.kwonlyargs
            bad += [f"{target}.{n}: {a.arg}: no annotation" for a in args if a.annotation is None]
            typed = [(a.arg, a.annotation) for a in args if a.annotation is not None]
        elif isinstance(node, ast.ClassDef):
            typed = [(a.target.id, a.annotation) for a in node.body
                     if isinstance(a, ast.AnnAssign) and not a.target.id.startswith("_")]
        bad += [f"{target}.{n}: {arg}: {ast.unparse(ann)}" for arg, ann in typed
                if untyped_names(ast.unparse(ann)) and (target, n, arg) not in TOML_DOCUMENT]
    assert not bad, bad


def test_no_stage_reads_or_edits_the_parsed_document():
    """Issue 56: the description is edited as data (``fetorsion.description.edit``: a new, checked
    description with named fields changed; the values a path names; the document it was read
    from); no module outside ``description/`` touches a description's ``raw`` document."""
    offences = []
    for name, path in modules().items():
        if name.startswith("fetorsion.description"):
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Attribute) and node.attr == "raw":
                offences.append(f"{name}:{node.lineno}")
    assert not offences, offences


# ---------------------------------------------------------------------------
# Sizes a reader can hold (issue 56)

#: Lines of a module at most (all its lines: code, docstrings, comments).
MODULE_LINES = 600
#: Lines of a function at most, its docstring not counted (numpydoc docstrings are the
#: documentation and should not be cut short to fit).
FUNCTION_LINES = 60
#: Lines of a command-line module at most: it parses and prints, the stages compute.
CLI_MODULE_LINES = 300
#: Functions that are data tables (one entry a line), exempt from FUNCTION_LINES: none today.
DATA_TABLES: frozenset[str] = frozenset()


def function_lines(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Lines of ``node`` from its ``def`` to its last line, less its docstring's."""
    n = node.end_lineno - node.lineno + 1
    first = node.body[0] if node.body else None
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
        n -= first.end_lineno - first.lineno + 1
    return n


def oversized(sources: dict[str, str]) -> list[str]:
    """Every module over its limit and every function over FUNCTION_LINES, as sentences."""
    found = []
    for name, text in sorted(sources.items()):
        limit = CLI_MODULE_LINES if name.startswith("fetorsion.cli.") else MODULE_LINES
        lines = text.count("\n")
        if lines > limit:
            found.append(f"{name}: {lines} lines (at most {limit})")
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and f"{name}.{node.name}" not in DATA_TABLES:
                n = function_lines(node)
                if n > FUNCTION_LINES:
                    found.append(f"{name}.{node.name}: {n} lines without its docstring (at most {FUNCTION_LINES})")
    return found


def test_the_size_finder_counts_code_not_docstrings():
    body = "\n".join(f"    x{k} = {k}" for k in range(FUNCTION_LINES - 1))
    doc = '    """' + "\n".join(["a docstring"] * 40) + '"""\n'
    assert oversized({"fetorsion.x": f"def f():\n{doc}{body}\n"}) == []  # the def and 59 lines: at the limit
    found = oversized({"fetorsion.x": f"def f():\n{doc}{body}\n    return 0\n"})
    assert found == [f"fetorsion.x.f: {FUNCTION_LINES + 1} lines without its docstring (at most {FUNCTION_LINES})"]
    assert oversized({"fetorsion.cli.x": "\n" * (CLI_MODULE_LINES + 1)}) == [
        f"fetorsion.cli.x: {CLI_MODULE_LINES + 1} lines (at most {CLI_MODULE_LINES})"]


def test_no_module_or_function_is_longer_than_a_reader_can_hold():
    found = oversized({name: path.read_text() for name, path in modules().items()})
    assert not found, "\n".join(found)


def test_every_fetorsion_import_of_the_scripts_examples_and_tests_resolves():
    """A module moved inside the package leaves no script, benchmark, example or test importing it
    from where it was (``scripts/`` and ``benchmarks/`` run outside the suite, so nothing else would
    notice): every ``from fetorsion... import name``, lazy ones included, names a module that exists
    and a name it defines."""
    import importlib

    broken = []
    for folder in ("scripts", "benchmarks", "examples", "tests", "docs/_ext"):
        for path in (ROOT / folder).rglob("*.py"):
            for node in ast.walk(ast.parse(path.read_text())):
                if isinstance(node, ast.ImportFrom) and not node.level and (node.module or "").startswith("fetorsion"):
                    try:
                        module = importlib.import_module(node.module)
                    except ImportError as e:
                        broken.append(f"{path.relative_to(ROOT)}:{node.lineno}: {e}")
                        continue
                    broken += [f"{path.relative_to(ROOT)}:{node.lineno}: {node.module} has no {a.name}"
                               for a in node.names if a.name != "*" and not hasattr(module, a.name)
                               and importlib.util.find_spec(f"{node.module}.{a.name}") is None]
    assert not broken, "\n".join(broken)


def test_every_public_function_and_class_shows_an_example():
    """Issue 56, examples first: every function and class ``fetorsion`` exports has a ``>>>``
    example in its docstring (run as a doctest by the default suite; the FE ones are marked to
    skip, their lines still the way to call them). Constants (``PARTITIONS``) hold no docstring."""
    import inspect

    import fetorsion

    exported = [(n, getattr(fetorsion, n)) for n in fetorsion.__all__]
    without = [n for n, o in exported if (inspect.isfunction(o) or inspect.isclass(o))
               and ">>>" not in (inspect.getdoc(o) or "")]
    assert not without, without
