"""fetorsion: torsional vibration analysis of engine crankshafts.

>>> import fetorsion
>>> crank = fetorsion.load("geometry/peugeot_glx.toml")
>>> res = fetorsion.lumped(crank, dof=17)
>>> res.frequencies_hz.shape[0] == res.dof - 1
True
"""

from .campbell import run_campbell
from .crank import Chain, Crank, load
from .errors import DescriptionError, FetorsionError
from .lumped import PARTITIONS, LumpedResult, lumped
from .response import run_response
from .sensitivity import run_sensitivity, with_values


def run_modal(crank, mesh_size: float = 0.010, modes: int = 20, **kwargs):
    """3D FE free-free modes of a crank (lazy import: gmsh and scikit-fem load on first use).

    See :func:`fetorsion.crankfe.run_modal`; returns a :class:`fetorsion.crankfe.CrankModal`
    whose ``.result`` is a :class:`fetorsion.modal.ModalResult`.
    """
    from .crankfe import run_modal as _run

    return _run(crank, mesh_size, modes, **kwargs)


__all__ = ["Chain", "Crank", "DescriptionError", "FetorsionError", "LumpedResult", "PARTITIONS", "load", "lumped",
           "run_campbell", "run_modal", "run_response", "run_sensitivity", "with_values"]
__version__ = "0.1.0"
