"""Reading a description file: a crank description, a chain or a network, by what its tables are
(:func:`load`, :func:`parse_description`), and the field paths variants and bounds set."""

from __future__ import annotations

from pathlib import Path

from ..errors import DescriptionError, Problem
from .model import Crank
from .chain_model import Chain, Network
from .reader import read_toml
from .crank import extended, parse_crank
from .chain import parse_chain
from .network import parse_network


# Tables of the crank-train mechanics file (fetorsion.mechanics.input), which has no [engine].
MECHANICS_TABLES = {"slider_crank", "masses", "balance", "flywheel", "planetary"}


def load(path: str | Path) -> Crank | Chain | Network:
    """Read a crank description or a chain file (``[chain]`` table) from TOML; a chain file
    with ``[[chain.stations]]`` is a :class:`Network` (shafts and gear pairs between named stations).

    Parameters
    ----------
    path : str or Path
        The ``.toml`` file.

    Returns
    -------
    Crank or Chain
        In SI units.

    Raises
    ------
    DescriptionError
        Listing every violated rule with its field, value and rule.

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/peugeot_glx.toml")
    >>> crank.engine.cylinders
    4
    """
    path = Path(path)
    data = read_toml(path)
    if "extends" in data:
        data = extended(path, data)
    if "engine" not in data and "chain" not in data and MECHANICS_TABLES & set(data):
        raise DescriptionError(str(path), [Problem("file", str(path), (
            "is a mechanics file (for 'fetorsion kinematics | balance | flywheel'), not a crank description "
            "or chain file"))])
    return parse_description(data, str(path))


def parse_description(data: dict, source: str = "<description>") -> Crank | Chain | Network:
    """A parsed TOML mapping as the description it is: a network (``[chain]`` with stations or
    cranks), a chain (``[chain]``) or a crank description."""
    if "chain" in data:
        if isinstance(data["chain"], dict) and ("stations" in data["chain"] or "cranks" in data["chain"]):
            return parse_network(data, source=source)
        return parse_chain(data, source=source)
    return parse_crank(data, source=source)
