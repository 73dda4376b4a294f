"""A new user's crank through the FE steps: what :func:`try_crank` gives for one description,
the sweep over plausible cranks (:mod:`fetorsion.description.samples`,
``benchmarks/bench_plausible_sweep.py``, docs/plausible-cranks.md) built on it."""

from __future__ import annotations


def try_crank(raw: dict, source: str, mesh_size: float | None = None) -> dict:
    """What a new user gets from ``raw``: read (every check), the lumped chain with the throws'
    static FE for its webs (the ``fe`` web method), the whole crank's free-free FE modes, at the
    default mesh size.

    Returns a row: ``status`` ``"ok"``, ``"refused"`` (the reader or a check before any FE work
    said why, in ``message``) or ``"failed"`` (an error after FE work began, in ``step`` and
    ``message``), with the seconds and first torsional frequencies of the steps that ran.
    """
    import time

    from ..errors import DescriptionError, FetorsionError
    from ..fe.crankfe import run_modal
    from ..io import available_memory
    from ..solid.mesh import estimate_mesh
    from ..lumped_model.lumped import lumped
    from ..description.crank import parse_crank
    from ..description.defaults import DEFAULT_MESH_SIZE

    size = DEFAULT_MESH_SIZE if mesh_size is None else mesh_size
    row = {"name": source, "cylinders": raw["engine"]["cylinders"], "stroke_mm": raw["engine"]["stroke"],
           "fillets": "fillets" in raw, "drillings": "oil_holes" in raw,
           "counterweights": "counterweight_radius" in raw["webs"][0], "hollow_pins": "bore" in raw["pins"][0]}
    try:
        crank = parse_crank(raw, source=source)
    except DescriptionError as exc:
        return {**row, "status": "refused", "step": "read", "message": str(exc)}
    est = estimate_mesh(crank, size)
    if est.mesh_bytes + est.modal_bytes > available_memory():  # what `fetorsion modal` refuses before meshing
        return {**row, "status": "refused", "step": "memory",
                "message": f"the modal job would need {(est.mesh_bytes + est.modal_bytes) / 2**30:.1f} GiB"}

    def modal():
        res = run_modal(crank, size)
        # the first mode with 10 % torsion: a bare crank's first torsion mode is coupled with its
        # bending (28 % torsion on a flat four), and it is the one the lumped chain models
        torsional = res.of_kind("torsional")
        return {"f1_hz": res.first_carrying_torsion(),
                "first_torsional_hz": float(torsional[0]) if len(torsional) else None, "dofs": int(res.dofs)}

    for step, call in (("lumped, fe webs", lambda: {"f1_hz": float(lumped(crank, stiffness="fe").frequencies_hz[0])}),
                       ("modal", modal)):
        t0 = time.perf_counter()
        try:
            row[step] = {**call(), "seconds": time.perf_counter() - t0}
        except FetorsionError as exc:
            return {**row, "status": "failed", "step": step, "message": str(exc)}
    return {**row, "status": "ok"}
