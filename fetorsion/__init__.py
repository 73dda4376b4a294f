"""fetorsion: torsional vibration analysis of engine crankshafts.

>>> import fetorsion
>>> crank = fetorsion.load("geometry/peugeot_glx.toml")
>>> res = fetorsion.lumped(crank, dof=17)
>>> res.frequencies_hz.shape[0] == res.dof - 1
True
"""

from .description.files import load
from .description.model import Crank
from .description.chain_model import Chain, Network
from .description.defaults import DEFAULT_MESH_SIZE, DEFAULT_MODES
from .errors import DescriptionError, FetorsionError

#: Names imported on first use (PEP 562): the excitation stage pulls in scipy.integrate
#: (0.3 s), which the FE modal path and the Gmsh child process (which imports this package
#: too) never need; without the laziness every ``import fetorsion.x`` paid it.
_LAZY = {
    "run_campbell": "excitation.campbell",
    "PARTITIONS": "lumped_model.lumped", "LumpedResult": "lumped_model.lumped", "lumped": "lumped_model.lumped",
    "run_response": "response.forced", "run_transient": "response.transient",
    "run_sensitivity": "studies.sensitivity", "with_values": "description.edit",
    "run_crank_study": "studies.study",
    "run_stress": "design.stress", "run_damper": "design.dampers", "run_verdict": "design.verdict",
    "run_condensed": "fe.condensed", "run_coupled_response": "response.coupled",
    "run_crank_verdict": "design.crank_verdict", "run_fatigue": "design.fatigue",
    "run_comparison": "studies.comparison", "run_calibration": "studies.calibration_fit",
    "run_torsiograph": "measured.torsiograph", "run_modal_fit": "measured.modal", "run": "app.run",
    "load_results": "report.load",
}


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def run_modal(crank, mesh_size: float = DEFAULT_MESH_SIZE, modes: int = DEFAULT_MODES, **kwargs):
    """3D FE free-free modes of a crank (lazy import: gmsh and scikit-fem load on first use).

    Parameters
    ----------
    crank : Crank
        The description.
    mesh_size : float
        Global element size, m (finer at fillets and drillings).
    modes : int
        Number of elastic modes.
    **kwargs
        To :func:`fetorsion.fe.crankfe.run_modal` (purpose, fillet size, solver, support).

    Returns
    -------
    CrankModal
        A :class:`fetorsion.fe.modal.ModalResult` (frequencies in Hz, labelled mode shapes) that
        also holds the crank and its mesh.

    Examples
    --------
    >>> import fetorsion
    >>> modal = fetorsion.run_modal(fetorsion.load("geometry/peugeot_glx.toml"), mesh_size=0.02)  # doctest: +SKIP
    >>> modal.first_torsional()  # Hz, free-free; measured 905.9 Hz  # doctest: +SKIP
    """
    from .fe.crankfe import run_modal as _run

    return _run(crank, mesh_size, modes, **kwargs)


__all__ = ["Chain", "Crank", "DescriptionError", "FetorsionError", "LumpedResult", "Network", "PARTITIONS", "load", "load_results",
           "lumped", "run", "run_calibration", "run_campbell", "run_comparison", "run_condensed", "run_coupled_response",
           "run_crank_study", "run_crank_verdict", "run_damper", "run_fatigue", "run_modal", "run_modal_fit",
           "run_response", "run_sensitivity", "run_stress", "run_torsiograph", "run_transient", "run_verdict",
           "with_values"]
__version__ = "0.1.0"
