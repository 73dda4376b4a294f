"""The models a study runs: a crank variant in, named outputs out.

Each model is a small frozen, picklable object (it travels to the cluster's workers once per
study) called with one sample, ``{field path: value}`` in file units, and returning a dict
of outputs. Its ``key`` names what it computes, the description included, so that the sample
store never mixes results of different models or cranks.
"""

from __future__ import annotations

import hashlib
import json
import math
import pickle
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

from ..description.defaults import CHECK_MESH_SIZE, DEFAULT_WEB_METHOD
from ..description.model import Crank
from ..errors import FetorsionError, ParameterError
from ..lumped_model.lumped import PARTITIONS, lumped
from ..description.edit import document, with_values

#: What each kind of model gives (Hz; ``severity``: the largest Campbell severity in the
#: operating range, degrees of vibratory angle at the pulley).
LUMPED_OUTPUTS = ("f1", "f2", "f3", "severity")
FE_OUTPUTS = ("f1", "f2")
MODEL_CHOICES = tuple(f"lumped{d}" for d in PARTITIONS) + ("fe",)
#: What the coarse FE variant leaves out (``with_values(..., details=False)``): inputs under
#: these paths cannot be sampled by it.
FE_LEFT_OUT = ("fillets", "oil_holes")
#: Elastic modes the FE model computes: enough to find two torsional among the bending ones.
FE_MODES = 12


def description_hash(crank: Crank) -> str:
    """Hash of what a variant is built from: the file's data (without its ranges) and the
    parsed excitation (a pressure CSV's content lives there, not in the file's data)."""
    raw = document(crank, without=("uncertainty", "distributions"))
    h = hashlib.sha256(json.dumps(raw, sort_keys=True, default=str).encode())
    h.update(pickle.dumps(crank.excitation))
    return h.hexdigest()[:24]


def _check_outputs(outputs, allowed, what) -> tuple[str, ...]:
    bad = [o for o in outputs if o not in allowed]
    if bad or not outputs:
        raise ParameterError("outputs", f"{bad[0] if bad else ''}: the {what} model gives {', '.join(allowed)}")
    return tuple(outputs)


@dataclass(frozen=True)
class LumpedModel:
    """f1, f2, f3 (Hz) of a lumped partition of the crank variant; ``severity`` from its
    Campbell diagram when asked (needs ``[excitation]``)."""

    crank: Crank
    dof: int = 17
    stiffness: str = DEFAULT_WEB_METHOD
    outputs: tuple[str, ...] = ("f1",)
    details: bool = True

    def __post_init__(self):
        _check_outputs(self.outputs, LUMPED_OUTPUTS, f"lumped{self.dof}")
        if "severity" in self.outputs and self.crank.excitation is None:
            raise ParameterError("outputs", f"severity: {self.crank.source} has no [excitation] table")

    expensive = False

    @property
    def label(self) -> str:
        return f"lumped {self.dof} DOF, {self.stiffness}" + ("" if self.details else ", no fillets/drillings")

    @cached_property  # every stored sample names its model: one hash of the description, not one each
    def key(self) -> str:
        return (f"lumped{self.dof}/{self.stiffness}/details={self.details}/{','.join(sorted(self.outputs))}/"
                f"{description_hash(self.crank)}")

    def __call__(self, values: dict) -> dict:
        variant = with_values(self.crank, values, details=self.details)
        res = lumped(variant, self.dof, self.stiffness)
        f = res.frequencies_hz
        out = {f"f{j + 1}": float(f[j]) if j < len(f) else math.nan for j in range(3)}
        if "severity" in self.outputs:
            from ..excitation.campbell import run_campbell

            camp = run_campbell(variant, res.torsional_modes())
            out["severity"] = max((c.severity for c in camp.crossings if c.in_range), default=0.0)
        return {k: out[k] for k in self.outputs}


@dataclass(frozen=True)
class FEModel:
    """First (and second) torsional frequency (Hz) of the 3D FE model of the crank variant,
    without fillets and drillings at a coarse mesh by default: the sensitivity FE checks'
    variant, a few seconds a run."""

    crank: Crank
    mesh_size: float = CHECK_MESH_SIZE
    outputs: tuple[str, ...] = ("f1",)
    details: bool = False

    def __post_init__(self):
        _check_outputs(self.outputs, FE_OUTPUTS, "fe")

    expensive = True

    @property
    def label(self) -> str:
        return f"FE {self.mesh_size * 1e3:g} mm" + ("" if self.details else ", no fillets/drillings")

    @cached_property  # every stored sample names its model: one hash of the description, not one each
    def key(self) -> str:
        return (f"fe/{self.mesh_size!r}/details={self.details}/modes={FE_MODES}/{','.join(sorted(self.outputs))}/"
                f"{description_hash(self.crank)}")

    def __call__(self, values: dict) -> dict:
        from ..fe.crankfe import run_modal

        res = run_modal(with_values(self.crank, values, details=self.details), self.mesh_size, modes=FE_MODES)
        tors = res.of_kind("torsional")
        if len(tors) == 0:
            raise FetorsionError(f"no torsional mode among the first {FE_MODES} elastic modes")
        out = {"f1": float(tors[0]), "f2": float(tors[1]) if len(tors) > 1 else math.nan}
        return {k: out[k] for k in self.outputs}


def make_model(crank: Crank, model: str, outputs: Sequence[str] = ("f1",), stiffness: str = DEFAULT_WEB_METHOD,
               mesh_size: float = CHECK_MESH_SIZE, details: bool | None = None):
    """``lumpedN`` or ``fe`` as a model object (``details``: None keeps each model's default)."""
    if model == "fe":
        return FEModel(crank, mesh_size, tuple(outputs), False if details is None else details)
    if model.removeprefix("lumped").isdigit() and int(model.removeprefix("lumped")) in PARTITIONS:
        return LumpedModel(crank, int(model.removeprefix("lumped")), stiffness, tuple(outputs),
                           True if details is None else details)
    raise ParameterError("model", f"{model}: choose from {', '.join(MODEL_CHOICES)}")
