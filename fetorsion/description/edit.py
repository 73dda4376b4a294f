"""The description edited as data: a new, checked description with named fields changed
(:func:`with_values`), the values a field path names (:func:`field_values`) and the document a
description was read from (:func:`document`), so that no stage reads or edits the parsed TOML
itself.

Examples
--------
>>> import fetorsion
>>> from fetorsion.description.edit import field_values, with_values
>>> crank = fetorsion.load("geometry/renault21.toml")
>>> field_values(crank, "webs.3.thickness")
[('webs.3.thickness', 22.0)]
>>> field_values(with_values(crank, {"webs.3.thickness": 24.0}), "webs.3.thickness")
[('webs.3.thickness', 24.0)]
"""

from __future__ import annotations

from collections.abc import Collection
from typing import TYPE_CHECKING

from ..errors import DescriptionError, FetorsionError, Problem
from .files import parse_description
from .model import Crank
from .reader import field_keys, resolve_field

if TYPE_CHECKING:
    from .chain_model import Chain, Network


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
        The variant, checked by every rule of the description; a path that names no field (an
        index out of range, a table the description lacks) is refused by name.

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/peugeot_glx.toml")
    >>> thicker = fetorsion.with_values(crank, {"webs.*.thickness": 25.0})  # mm: the file's unit
    >>> [round(w.thickness, 4) for w in thicker.webs][:2], crank.webs[0].thickness
    ([0.025, 0.025], 0.023)
    >>> fetorsion.with_values(crank, {"webs.0.thickness": 25.0})
    Traceback (most recent call last):
    ...
    fetorsion.errors.DescriptionError: geometry/peugeot_glx.toml: 1 problem(s) in the description
      - webs.0.thickness = 25.0: names no table of this description (indices are 1-based and within the table's count; `*` is every entry)
    """
    raw = dict(crank.raw)
    for key in ("uncertainty", "distributions", "design"):
        raw.pop(key, None)
    if changes or not details:  # the CAD solid has the given dimensions: a variant is built from its own
        raw.pop("solid", None)
    if not details:
        for key in ("fillets", "oil_holes"):
            raw.pop(key, None)
    nowhere = []
    for path, value in changes.items():
        parent_path, _, key = path.rpartition(".")
        parents = _copied_along(raw, parent_path)
        if not parents and (details or path.split(".")[0] not in ("fillets", "oil_holes")):
            nowhere.append(Problem(path, value, "names no table of this description (indices are 1-based and "
                                   "within the table's count; `*` is every entry)"))
        for parent in parents:
            for k in field_keys(parent, key):
                parent[k] = value
    if nowhere:  # else the change would be lost without a word (webs.0 or webs.9 of eight webs)
        raise DescriptionError(crank.source, nowhere)
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


def field_values(description: Crank | Chain | Network, path: str) -> list[tuple[str, object]]:
    """(concrete path, value) of every field ``path`` names in ``description`` (a crank, chain or
    network), in file units: ``"webs.*.thickness"`` gives one pair per web, 1-based."""
    return resolve_field(description.raw, path)


def document(description: Crank | Chain | Network, without: Collection[str] = ()) -> dict:
    """The document ``description`` was read from (file units), its top-level tables named in
    ``without`` left out: what a store keys on or a result records. A shallow copy: read it, do
    not edit it (:func:`with_values` makes an edited description)."""
    return {k: v for k, v in description.raw.items() if k not in without}


# ---------------------------------------------------------------------------
# The description's text edited in place, every change commented (a calibrated or designed file)


def _toml_float(x: float) -> str:
    text = repr(float(x))
    return text if any(c in text for c in ".eE") or text in ("inf", "nan") else text + ".0"


def _table_path(header: str, counts: dict) -> str:
    """The concrete path of a table header line (``[[webs]]`` -> ``webs.3`` for the third)."""
    if header.startswith("[["):
        name = header[2:header.index("]]")].strip()
        counts[name] = counts.get(name, 0) + 1
        return f"{name}.{counts[name]}"
    return header[1:header.index("]")].strip()


def edit_toml_values(text: str, changes: dict[str, float], note: str) -> str:
    """``text`` (a TOML description) with each concrete field (``webs.3.thickness``) set to its
    value, line by line, each changed line commented with its old value and ``note``.

    Only plain ``key = value`` lines under ``[table]`` / ``[[array]]`` headers are edited; a field
    the file does not spell that way is refused (one message naming it)."""
    import tomllib

    lines = text.splitlines(keepends=True)
    counts: dict = {}
    table = ""
    found = set()
    # a list's entries (``chain.inertias_kgm2.3``): the list's line is edited, entry by entry
    entries: dict[str, dict[int, float]] = {}
    for p, v in changes.items():
        head, _, last = p.rpartition(".")
        if last.isdigit():
            entries.setdefault(head, {})[int(last) - 1] = v
    for k, line in enumerate(lines):
        stripped = line.strip()
        if stripped.startswith("["):
            table = _table_path(stripped, counts)
            continue
        if "=" not in stripped or stripped.startswith("#"):
            continue
        key, _, rest = stripped.partition("=")
        key = key.strip().strip('"')
        path = f"{table}.{key}" if table else key
        if path not in changes and path not in entries:
            continue
        old, _, comment = rest.partition("#")
        eol = "\n" if line.endswith("\n") else ""
        indent = line[: len(line) - len(line.lstrip())]
        was = f"; before: {comment.strip()}" if comment.strip() else ""
        if path in entries:
            try:
                values = tomllib.loads(f"v = {old.strip()}")["v"]
            except tomllib.TOMLDecodeError:
                continue  # a list over several lines: refused below by name
            for i, v in entries[path].items():
                values[i] = v
                found.add(f"{path}.{i + 1}")
            new = "[" + ", ".join(_toml_float(v) if i in entries[path] else repr(v) for i, v in enumerate(values)) + "]"
        else:
            new = _toml_float(changes[path])
            found.add(path)
        lines[k] = f"{indent}{key} = {new}  # was {old.strip()}: {note}{was}{eol}"
    missing = [p for p in changes if p not in found]
    if missing:
        raise FetorsionError(f"{missing[0]} is not a plain 'key = value' line of the description; the changed "
                             "file cannot be written by editing it")
    return "".join(lines)
