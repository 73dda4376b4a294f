"""``fetorsion run``: every analysis of one crank into one report folder, written atomically.

The folder is built under a temporary name beside the target and renamed into place only
when every step has succeeded, so a failed run leaves nothing behind and a reader never
sees a half-written report. An existing target is replaced only when it is an earlier
report (:func:`fetorsion.io.check_report_folder`). Each step is a small function ``step(ctx) -> None`` that
writes its files and records its numbers in ``ctx.results``.
"""

from __future__ import annotations

import json
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from ..description.crank import load

from ..description.model import Chain, Crank
from ..errors import FetorsionError
from ..io import atomic_folder, check_report_folder, save_figure_atomic, write_text_atomic
from ..lumped_model.lumped import PARTITIONS, lumped
from ..description.defaults import DEFAULT_MESH_SIZE, DEFAULT_WEB_METHOD
from ..webs.methods import WEB_METHODS


@dataclass
class RunContext:
    """What the steps share: the crank, options, the working folder and the results."""

    crank: Crank
    folder: Path
    options: dict
    results: dict = field(default_factory=dict)
    report: list[str] = field(default_factory=list)
    fe: object = None  # the CrankModal once the FE step has run
    timings_s: dict = field(default_factory=dict)

    def save(self, fig, name: str) -> str:
        save_figure_atomic(fig, self.folder / name, close=True, dpi=120)
        return name


def _progress(message: str) -> None:
    print(f"[fetorsion] {message}", file=sys.stderr, flush=True)


def step_lumped(ctx: RunContext) -> None:
    """All five partitions with every web method; mode-shape plots of the 17-DOF model."""
    import matplotlib

    matplotlib.use("Agg")
    crank = ctx.crank
    table, skipped = {}, {}
    for method in WEB_METHODS:
        try:
            table[method] = [lumped(crank, d, method) for d in PARTITIONS]
        except FetorsionError as exc:  # e.g. a web outside the computed chart's range
            skipped[method] = str(exc)
    ctx.results["lumped"] = {m: [r.to_dict() for r in rs] for m, rs in table.items()}
    ctx.results["lumped_skipped"] = skipped
    main = table[DEFAULT_WEB_METHOD][PARTITIONS.index(17)]
    img = ctx.save(main.plot().figure, "lumped_modes_17dof.png")
    measured = crank.notes.get("measured_first_torsional_hz")
    paper = crank.notes.get("paper_lumped_first_torsional_hz", {})
    lines = ["## Lumped models (BICERA-style equivalent lengths)", "",
             "First torsional frequency f1 (Hz), free-free; error against the measurement where there is one.", ""]
    head = "| model | " + " | ".join(table) + (" | paper |" if paper else " |")
    lines += [head, "|" + "---|" * (len(table) + 1 + bool(paper))]
    for i, d in enumerate(PARTITIONS):
        cells = [_with_error(table[m][i].frequencies_hz[0], measured) for m in table]
        row = f"| {d} DOF | " + " | ".join(cells)
        row += f" | {paper.get(str(d), '')} |" if paper else " |"
        lines.append(row)
    if measured:
        lines += ["", f"Measured (free-free modal test): **{measured:g} Hz**."]
    lines += [f"Web method `{m}` not used: {why}" for m, why in skipped.items()]
    lines += ["", f"17-DOF mode shapes (Carter webs), unit twist at the pulley end: ![]({img})", ""]
    ctx.report += lines


def _with_error(f: float, measured) -> str:
    return f"{f:.1f}" + (f" ({100 * (f / measured - 1):+.1f} %)" if measured else "")


def step_fe(ctx: RunContext) -> None:
    """3D FE modal analysis with attachments; images of the torsional and first bending modes."""
    from ..fe.crankfe import run_modal
    from .render import render_mode

    from ..solid.mesh import mesh_crank

    size = ctx.options.get("mesh_size", DEFAULT_MESH_SIZE)
    _progress(f"  meshing the Gmsh solid ({size * 1e3:g} mm, curved P2 tetrahedra) ...")
    mesh = mesh_crank(ctx.crank, size)
    _progress(f"  {len(mesh.tets)} tetrahedra, {len(np.unique(mesh.tets))} nodes in {mesh.quality.seconds:.1f} s; "
              "assembling, factorising, eigen-solving ...")
    fe = run_modal(ctx.crank, size, modes=ctx.options.get("modes", 20), mesh=mesh)
    t = fe.result.timings_s
    _progress(f"  assembly {t.get('assembly', 0):.1f} s, factorisation {t.get('factorize', 0):.1f} s, "
              f"eigen-solve {t.get('eigensolve', 0):.1f} s; rendering mode images ...")
    ctx.fe = fe
    res, cm = fe.result, fe.mesh
    ctx.results["fe"] = {**res.to_dict(), "first_torsional_hz": res.first_torsional(), "mesh_size_m": size,
                         "min_sicn": cm.quality.min_sicn if cm.quality else None}
    picks = [j for j, k in enumerate(res.kinds) if k == "torsional"][:3]
    picks += [j for j, k in enumerate(res.kinds) if k == "bending"][:2]
    images = []
    for j in sorted(picks):
        name = f"mode_{j + 1:02d}_{res.kinds[j]}.png"
        render_mode(cm.nodes, cm.tets, res.shapes[j], ctx.folder / name,
                    title=f"mode {j + 1}: {res.frequencies_hz[j]:.1f} Hz, {res.kinds[j]}")
        images.append(name)
    measured = ctx.crank.notes.get("measured_first_torsional_hz")
    paper_fe = ctx.crank.notes.get("paper_fe_first_torsional_hz")
    f1 = res.first_torsional()
    lines = ["## 3D FE modal analysis (Gmsh + scikit-fem, curved P2 tetrahedra)", "",
             f"Mesh: {res.elements} ten-node tetrahedra, {res.nodes} nodes, {res.dofs} DOF, global size "
             f"{size * 1e3:g} mm (finer at fillets and drillings), minimum SICN "
             f"{ctx.results['fe']['min_sicn']:.3f}. Solver {res.backend}/{res.method}; "
             f"assembly {res.timings_s.get('assembly', 0):.1f} s, factorisation {res.timings_s.get('factorize', 0):.1f} s, "
             f"eigen-solve {res.timings_s.get('eigensolve', 0):.1f} s.", "",
             f"**First torsional mode: {_with_error(f1, measured)} Hz**"
             + (f" (paper's ANSYS: {paper_fe:g} Hz)" if paper_fe else "")
             + (f"; measured {measured:g} Hz." if measured else "."), "",
             "| mode | f (Hz) | kind | torsion | bending | axial |", "|---|---|---|---|---|---|"]
    lines += [f"| {j + 1} | {f:.1f} | {k} | {fr[0]:.2f} | {fr[1]:.2f} | {fr[2]:.2f} |"
              for j, (f, k, fr) in enumerate(zip(res.frequencies_hz, res.kinds, res.fractions))]
    lines += ["", "Rigid-body roots (Hz): " + ", ".join(f"{f:.1e}" for f in res.rigid_body_hz), ""]
    lines += [f"![]({img})" for img in images] + [""]
    ctx.report += lines


def step_campbell(ctx: RunContext) -> None:
    """Campbell diagram (FE torsional modes when the FE step ran) and forced response."""
    from ..excitation.campbell import run_campbell
    from ..response.forced import run_response

    if ctx.crank.excitation is None:
        ctx.report += ["## Campbell diagram", "", "Not run: the description has no `[excitation]` table.", ""]
        return
    camp = run_campbell(ctx.crank, ctx.fe.torsional_modes(3) if ctx.fe is not None else None)
    resp = run_response(ctx.crank)
    ctx.results["campbell"] = camp.to_dict()
    ctx.results["response"] = resp.to_dict()
    a = ctx.save(camp.plot().figure, "campbell.png")
    b = ctx.save(resp.plot(), "response.png")
    ctx.report += ["## Campbell diagram and forced response", "",
                   f"Crossings inside the operating range, most severe first ({camp.source}; severity = resonant "
                   f"vibratory angle at the pulley for ζ = {camp.damping_ratio:g}):", "", "```", camp.table(), "```", "",
                   f"![]({a})", "", "```", resp.summary(), "```", "", f"![]({b})", ""]


def step_sensitivity(ctx: RunContext) -> None:
    """f1 against each reconstructed input and the resulting band (needs [uncertainty])."""
    from ..studies.sensitivity import run_sensitivity

    if not ctx.crank.uncertainty:
        ctx.report += ["## Sensitivity", "", "Not run: the description has no `[uncertainty]` table.", ""]
        return
    sens = run_sensitivity(ctx.crank)
    ctx.results["sensitivity"] = sens.to_dict()
    checks = []
    if ctx.fe is not None:
        from ..studies.sensitivity import fe_check

        checks = fe_check(ctx.crank, sens)
        ctx.results["sensitivity"]["fe_check"] = checks
    img = ctx.save(sens.plot().figure, "sensitivity.png")
    verdict = ""
    if sens.measured_hz is not None:
        verdict = (f"The measured {sens.measured_hz:g} Hz is **{'inside' if sens.measured_inside else 'outside'}** "
                   f"the band {sens.band_hz[0]:.0f}–{sens.band_hz[1]:.0f} Hz.")
    ctx.report += ["## Sensitivity of f1 to the reconstructed geometry", "",
                   "Each input of the description's `[uncertainty]` table at its bounds, one at a time, then all "
                   "at the bounds that lower (raise) f1 together: the band's ends are model results.", "",
                   "```", sens.table(), "```", "", verdict, ""]
    if checks:
        ctx.report += ["FE check of the three most influential inputs (change of f1 from the low to the high bound; "
                       "FE on the crank without fillets and drillings, 25 mm mesh):", "",
                       "| input | lumped | FE |", "|---|---|---|"]
        ctx.report += [f"| {c['field']} | {c['lumped_change_percent']:+.1f} % | {c['fe_change_percent']:+.1f} % |"
                       for c in checks] + [""]
    ctx.report += [f"![]({img})", ""]


DEFAULT_STEPS: tuple[tuple[str, Callable[[RunContext], None]], ...] = (
    ("lumped models", step_lumped),
    ("mesh and FE modal analysis", step_fe),
    ("Campbell diagram and forced response", step_campbell),
    ("sensitivity of f1", step_sensitivity),
)
# ``fetorsion run --no-fe``: the same report without the mesh and the FE modal analysis.
FAST_STEPS = tuple(s for s in DEFAULT_STEPS if s[1] is not step_fe)


def run(path, out, steps=DEFAULT_STEPS, options: dict | None = None, force: bool = False) -> Path:
    """Run every step on the crank in ``path`` and write the report folder ``out``.

    Parameters
    ----------
    path : str or Path
        Crank description (.toml).
    out : str or Path
        Report folder. It may be new, empty, or an earlier fetorsion report (replaced only
        once the whole run has succeeded); anything else is refused unless ``force``.
    steps : sequence of (name, function)
        The analyses, in order.
    options : dict, optional
        Passed to the steps (mesh size and such).
    force : bool
        Replace ``out`` even when it is not an earlier report.

    Returns
    -------
    Path
        The report folder.
    """
    out = Path(out)
    check_report_folder(out, "out", force=force, inputs=[path])
    crank = load(path)  # every input rule is checked here, before any work or any file
    if isinstance(crank, Chain):
        raise FetorsionError(f"{path}: 'run' needs a crank description, not a chain file")
    with atomic_folder(out) as work:
        ctx = RunContext(crank, work, dict(options or {}))
        ctx.report += [f"# {crank.name}", "", f"Description: `{path}`", ""]
        for name, fn in steps:
            _progress(f"{name} ...")
            t0 = time.perf_counter()
            fn(ctx)
            ctx.timings_s[name] = time.perf_counter() - t0
            _progress(f"{name}: done in {ctx.timings_s[name]:.1f} s")
        ctx.results["timings_s"] = ctx.timings_s
        ctx.report += ["## Timings", "", *[f"- {k}: {v:.1f} s" for k, v in ctx.timings_s.items()], ""]
        write_text_atomic(work / "report.md", "\n".join(ctx.report))
        write_text_atomic(work / "results.json", json.dumps(_jsonable(ctx.results), indent=1) + "\n")
    return out


def _jsonable(x):
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.generic):
        return x.item()
    return x
