"""fetorsion: torsional vibration analysis of engine crankshafts.

>>> import fetorsion
>>> crank = fetorsion.load("geometry/peugeot_glx.toml")
>>> res = fetorsion.lumped(crank, dof=17)
>>> res.frequencies_hz.shape[0] == res.dof - 1
True
"""

from .excitation.campbell import run_campbell
from .description.crank import load
from .description.model import Chain, Crank
from .description.defaults import DEFAULT_MESH_SIZE, DEFAULT_MODES
from .errors import DescriptionError, FetorsionError
from .lumped_model.lumped import PARTITIONS, LumpedResult, lumped
from .response.forced import run_response
from .response.stress import run_stress
from .studies.damper_tuning import run_damper
from .studies.verdict import run_verdict
from .studies.sensitivity import run_sensitivity, with_values
from .studies.study import run_crank_study


def run_modal(crank, mesh_size: float = DEFAULT_MESH_SIZE, modes: int = DEFAULT_MODES, **kwargs):
    """3D FE free-free modes of a crank (lazy import: gmsh and scikit-fem load on first use).

    See :func:`fetorsion.fe.crankfe.run_modal`; returns a :class:`fetorsion.fe.crankfe.CrankModal`
    (a :class:`fetorsion.fe.modal.ModalResult` that also holds the crank and its mesh).
    """
    from .fe.crankfe import run_modal as _run

    return _run(crank, mesh_size, modes, **kwargs)


__all__ = ["Chain", "Crank", "DescriptionError", "FetorsionError", "LumpedResult", "PARTITIONS", "load", "lumped",
           "run_campbell", "run_crank_study", "run_damper", "run_modal", "run_response", "run_sensitivity", "run_stress",
           "run_verdict", "with_values"]
__version__ = "0.1.0"
