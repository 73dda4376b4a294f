"""A run's costliest sections kept between runs: the FE step's free-free modes with their pictures,
and a crank's fatigue verdict: a second run of the same crank does not compute them again.

Each section is kept as its ``results.json`` entry (the JSON a report folder holds, which
:mod:`fetorsion.report.load` reads back into the typed outcome, figure for figure the same: issue
56's round trip) and the files it drew that cannot be drawn from that entry (the FE mode pictures
and the report page's 3D view: the mesh and the mode shapes are not kept). The key is a SHA-256
of everything the section reads:

* ``fe``: the condensed crank's key (:func:`fetorsion.fe.store.condensed_key`: the description's
  FE tables, a CAD solid's content, the mesh size, the section cuts, the code) and the number
  of modes;
* ``fatigue``: the whole description as read, its parsed excitation (a pressure CSV's content
  lives there), a CAD solid's content, the options the verdict reads, and the code with its
  shipped tables (:func:`fetorsion.io.code_hash`).

A section found here is marked in ``results.json`` (``from_store``) and in the report's timings,
so a reader knows which numbers this run computed. Files live in ``runs/`` of the store's folder,
one ``.npz`` per section, written atomically, the least recently used removed once the folder
passes its share of the store's bound (:func:`fetorsion.fe.store.trim`); an unreadable file of
ours is removed and the section computed again. ``fetorsion store --clear`` empties it.
"""

from __future__ import annotations

import hashlib
import json
import os
import pickle
from pathlib import Path

import numpy as np

from ..description.edit import document
from ..io import atomic_output, code_hash, default_store

FOLDER = "runs"
#: Layout of a kept section's file (changes with this module's format).
FORMAT = 1
#: RunOptions fields a crank's fatigue verdict reads (the others: output, workers, reporting).
FATIGUE_OPTIONS = ("mesh_size", "modes", "inertia_ratio", "fatigue_method", "fe_path")


def folder(store=None) -> Path:
    """Where the sections are kept: ``runs/`` in the store's folder."""
    return Path(store if store is not None else default_store()) / FOLDER


def _digest(payload: dict) -> str:
    return hashlib.sha256(json.dumps({**payload, "format": FORMAT}, sort_keys=True, default=repr).encode()).hexdigest()


def fe_key(crank, mesh_size: float, cuts, modes: int) -> str:
    """The key of the FE step's modes and pictures of ``crank`` (module docstring)."""
    from ..fe.store import condensed_key

    return _digest({"section": "fe", "condensed": condensed_key(crank, mesh_size, cuts), "modes": int(modes)})


def fatigue_key(crank, options) -> str:
    """The key of ``crank``'s fatigue verdict under the run's ``options`` (module docstring)."""
    solid = getattr(crank, "solid_step", None)
    return _digest({"section": "fatigue", "description": document(crank),
                    "excitation": hashlib.sha256(pickle.dumps(crank.excitation)).hexdigest(),
                    "solid": None if solid is None else hashlib.sha256(Path(solid).read_bytes()).hexdigest(),
                    "options": {name: getattr(options, name) for name in FATIGUE_OPTIONS}, "code": code_hash()})


def stored(key: str, store=None) -> tuple[dict, dict[str, bytes]] | None:
    """(the section's results.json entry, {file name: bytes}) kept under ``key``, or None."""
    path = folder(store) / f"{key}.npz"
    if not path.is_file():
        return None
    try:
        with np.load(path) as d:
            entry = json.loads(str(d["entry"]))
            files = {str(name): d[f"file_{i}"].tobytes() for i, name in enumerate(json.loads(str(d["names"])))}
    except Exception:  # noqa: BLE001 - any unreadable file of ours is computed again, never trusted
        path.unlink(missing_ok=True)
        return None
    os.utime(path)  # least recently used goes first
    return entry, files


def remember(key: str, entry: dict, files: dict[str, bytes] | None = None, store=None) -> None:
    """Keep ``entry`` (JSON-able: a results.json entry) and ``files`` under ``key``; then trim the
    folder. A store that cannot be written is only a lost speed-up."""
    from ..fe.store import trim

    files = files or {}
    path = folder(store) / f"{key}.npz"
    arrays = {"entry": np.array(json.dumps(entry)), "names": np.array(json.dumps(list(files)))}
    arrays.update({f"file_{i}": np.frombuffer(data, dtype=np.uint8) for i, data in enumerate(files.values())})
    try:
        with atomic_output(path) as tmp:
            with open(tmp, "wb") as fh:
                np.savez(fh, **arrays)
        trim(path.parent, keep=path)
    except OSError:
        pass
