"""A variant of a crank description: the same file with some fields set to other values."""

from __future__ import annotations

from ..description.reader import field_keys
from ..description.files import parse_description
from ..description.model import Crank


def with_values(crank: Crank, changes: dict[str, float], details: bool = True) -> Crank:
    """A copy of ``crank`` with each field path (file units, ``*`` allowed) set to a value.

    The variant is a new design, so the original's ``[uncertainty]`` ranges (and their
    ``[distributions]``) and its ``[design]`` space are dropped; so is a ``[solid]`` CAD file when
    anything changes (the variant's solid is built from its dimensions).
    ``details=False`` also drops fillets and oil holes: a cheap variant for coarse FE
    checks, where those details would dominate the element count.

    Parameters
    ----------
    crank : Crank
        The description to vary.
    changes : dict of str to float
        Field path (``"webs.*.thickness"``, 1-based indices, ``*`` = every entry) to its new
        value, in the file's units (lengths in ``[units] length``).
    details : bool
        Keep the fillets and oil holes.

    Returns
    -------
    Crank
        The variant, checked by every rule of the description.
    """
    raw = dict(crank.raw)
    for key in ("uncertainty", "distributions", "design"):
        raw.pop(key, None)
    if changes or not details:  # the CAD solid has the given dimensions: a variant is built from its own
        raw.pop("solid", None)
    if not details:
        for key in ("fillets", "oil_holes"):
            raw.pop(key, None)
    for path, value in changes.items():
        parent_path, _, key = path.rpartition(".")
        for parent in _copied_along(raw, parent_path):
            for k in field_keys(parent, key):
                parent[k] = value
    return parse_description(raw, source=crank.source)


def _copied_along(tree: dict, path: str) -> list[dict]:
    """The tables ``path`` names in ``tree`` (as :func:`resolve_field`), each made a fresh copy
    in a fresh copy of every table and array above it, so that setting their keys leaves the
    original description as it was. Everything off the path stays shared: parsing never writes
    to the tree, and a full copy of it (the pressure table's arrays) was a sixth of a study
    sample's time."""
    found = [tree]
    for key in path.split(".") if path else ():
        nxt = []
        for node in found:
            if isinstance(node, list):
                picks = range(len(node)) if key == "*" else (
                    [int(key) - 1] if key.isdigit() and 1 <= int(key) <= len(node) else [])
            else:
                picks = [key] if isinstance(node, dict) and key in node else []
            for k in picks:
                child = node[k]
                if isinstance(child, (dict, list)):
                    node[k] = child = type(child)(child)  # a fresh container in the (fresh) parent
                nxt.append(child)
        found = nxt
    return found
