"""The condensed cranks already built, kept between commands: a content-addressed cache.

A condensed crank (:func:`fetorsion.fe.condensed.run_condensed`: mesh, assembly, factorisation,
Craig–Bampton) costs 25–45 s on the Renault 21 (2 cores) and a second or two to use, so every
command that answers for the crank in its bearings (``run``, ``campbell``, ``response``,
``damper``, ``transient``) takes it from here after the first has built it. The key is a SHA-256
of what the condensation reads:

* the description's parsed tables less those no FE stage reads (:data:`NOT_READ_BY_FE`: the
  excitation, dampers, limits, uncertainty ranges and notes; a test holds ``fe`` and ``solid`` to
  that), so a new damping ratio reuses the crank and a new web width rebuilds it;
* the mesh size and the section cuts' centres (exact floats);
* the file layout and fetorsion's own source (:func:`fetorsion.io.code_hash`): other code never
  serves its numbers.

Each crank is one ``.npz`` (:func:`~fetorsion.fe.condensed.save_condensed`, without the mesh's
shape basis: about 1 MB) in ``condensed/`` under the store's folder
(:func:`fetorsion.io.default_store`), written atomically; the least recently used go first once
the folder passes a quarter of the store's bound (:func:`fetorsion.io.store_max_bytes`), and
``fetorsion store`` lists and clears them. A file that cannot be read (a crash of other code,
a disk error) is removed and the crank built again.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..description.edit import document
from ..io import code_hash, default_store, store_max_bytes
from .condensed import NPZ_FORMAT, CondensedCrank, load_condensed, run_condensed, save_condensed

if TYPE_CHECKING:
    from collections.abc import Callable
    from ..description.model import Crank

#: Description tables that no FE stage reads: left out of the key.
NOT_READ_BY_FE = ("meta", "excitation", "dampers", "limits", "uncertainty")
FOLDER = "condensed"
#: The condensed cranks' share of the store's bound.
BOUND_SHARE = 0.25


def condensed_key(crank: Crank, mesh_size: float, cuts: np.ndarray | None = None) -> str:
    """The cache key of ``crank`` condensed at ``mesh_size`` (m) with section cuts at ``cuts``
    ((k, 3) m or None): module docstring."""
    exact = lambda a: [float(v).hex() for v in np.asarray(a, float).ravel()]  # noqa: E731
    solid = getattr(crank, "solid_step", None)  # a CAD solid: its content, not its name, is the geometry
    text = json.dumps({"description": document(crank, without=NOT_READ_BY_FE),
                       "solid": None if solid is None else hashlib.sha256(Path(solid).read_bytes()).hexdigest(),
                       "mesh_size": exact([mesh_size]), "cuts": None if cuts is None else exact(cuts),
                       "layout": NPZ_FORMAT, "code": code_hash()}, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()


def condensed_folder(store=None) -> Path:
    """Where the condensed cranks are kept: ``condensed/`` in the store's folder."""
    return Path(store if store is not None else default_store()) / FOLDER


def _files(folder: Path) -> list[Path]:
    """The cranks kept: only names this module writes (a key and ``.npz``), never a temporary
    being written or a file of someone else's."""
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.glob("*.npz") if len(p.stem) == 64 and all(c in "0123456789abcdef" for c in p.stem))


def stored_condensed(crank: Crank, mesh_size: float, cuts: np.ndarray | None = None,
                     store: str | Path | None = None) -> CondensedCrank | None:
    """The cached condensed crank, or None; its ``crank`` is the one given (the tables the key
    leaves out are the caller's)."""
    path = condensed_folder(store) / f"{condensed_key(crank, mesh_size, cuts)}.npz"
    if not path.is_file():
        return None
    try:
        cc = load_condensed(path, crank)
    except Exception as exc:  # noqa: BLE001 - any unreadable file of ours is rebuilt, never trusted
        print(f"[fetorsion] removed an unreadable condensed crank {path.name} ({exc})", file=sys.stderr, flush=True)
        path.unlink(missing_ok=True)
        return None
    os.utime(path)  # least recently used goes first
    return cc


def remember_condensed(cc: CondensedCrank, mesh_size: float, cuts: np.ndarray | None = None,
                       store: str | Path | None = None) -> Path:
    """Keep ``cc`` (built at ``mesh_size`` with ``cuts``) for the next command; then trim."""
    folder = condensed_folder(store)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{condensed_key(cc.crank, mesh_size, cuts)}.npz"
    save_condensed(cc, path, shapes=False)
    trim(folder, keep=path)
    return path


def trim(folder: Path, max_bytes: int | None = None, keep: Path | None = None) -> int:
    """Remove the least recently used cranks until the folder holds at most ``max_bytes``
    (default :data:`BOUND_SHARE` of the store's bound); ``keep`` stays. Returns the count removed."""
    bound = int(BOUND_SHARE * store_max_bytes()) if max_bytes is None else int(max_bytes)
    files = sorted(_files(folder), key=lambda p: p.stat().st_mtime)
    total, removed = sum(p.stat().st_size for p in files), 0
    for p in files:
        if total <= bound:
            break
        if keep is not None and p == keep:
            continue
        total -= p.stat().st_size
        p.unlink(missing_ok=True)
        removed += 1
    return removed


def condensed_store_info(store: str | Path | None = None, name: str = FOLDER) -> dict:
    """``folder``, ``cranks`` (count), ``bytes`` and ``max_bytes`` of the condensed cranks kept (or,
    ``name``, of another folder of the store kept the same way: the stress-recovery fields')."""
    folder = Path(store if store is not None else default_store()) / name
    files = _files(folder)
    return {"folder": str(folder), "cranks": len(files), "bytes": sum(p.stat().st_size for p in files),
            "max_bytes": int(BOUND_SHARE * store_max_bytes())}


def clear_condensed(store: str | Path | None = None, name: str = FOLDER) -> int:
    """Remove every condensed crank kept (only the ``.npz`` files fetorsion wrote there; ``name``:
    another folder of the store kept the same way); the count."""
    files = _files(Path(store if store is not None else default_store()) / name)
    for p in files:
        p.unlink(missing_ok=True)
    return len(files)


def condensed_crank(crank: Crank, mesh_size: float, cuts: np.ndarray | None = None, store: str | Path | None = None,
                    progress: Callable[[str], None] | None = None,
                    stage: Callable[[str], None] | None = None) -> tuple[CondensedCrank, bool]:
    """(the condensed crank, whether it came from the cache): from the cache, else built
    (:func:`~fetorsion.fe.condensed.run_condensed`, saying so through ``progress``) and kept."""
    cc = stored_condensed(crank, mesh_size, cuts, store)
    if cc is not None:
        return cc, True
    if progress is not None:
        progress(f"building the condensed crank ({mesh_size * 1e3:g} mm mesh: mesh, assembly, condensation; "
                 "kept for the next command) ...")
    cc = run_condensed(crank, mesh_size, cuts=cuts, stage=stage)
    remember_condensed(cc, mesh_size, cuts, store)
    return cc, False
