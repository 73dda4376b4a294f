"""fetorsion: torsional vibration analysis of engine crankshafts.

>>> import fetorsion
>>> crank = fetorsion.load("geometry/peugeot_glx.toml")
>>> res = fetorsion.lumped(crank, dof=17)
>>> res.frequencies_hz.shape[0] == res.dof - 1
True
"""

from .crank import Chain, Crank, load
from .errors import DescriptionError, FetorsionError
from .lumped import PARTITIONS, LumpedResult, lumped

__all__ = ["Chain", "Crank", "DescriptionError", "FetorsionError", "LumpedResult", "PARTITIONS", "load", "lumped"]
__version__ = "0.1.0"
