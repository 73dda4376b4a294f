"""One result protocol (issue 12): every results object has ``to_dict()`` (JSON-ready),
``table()`` (text) and ``plot(ax=None)`` returning a matplotlib Axes (the one it was given)."""

from __future__ import annotations

import json

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import fetorsion  # noqa: E402
from conftest import GEOMETRY  # noqa: E402
from fetorsion.description.model import Material  # noqa: E402
from fetorsion.excitation.kinematics import kinematics  # noqa: E402
from fetorsion.fe.modal import modal  # noqa: E402
from fetorsion.fe.tetmesh import cylinder_mesh  # noqa: E402
from fetorsion.mechanics.balance import minmax_overbalance, residual_locus  # noqa: E402
from fetorsion.mechanics.flywheel import size_flywheel  # noqa: E402
from fetorsion.mechanics.planetary import planetary  # noqa: E402
from fetorsion.studies.models import make_model  # noqa: E402
from fetorsion.studies.sampling import study_inputs  # noqa: E402
from fetorsion.studies.study import run_study  # noqa: E402
from fetorsion.design.stress import run_stress  # noqa: E402
from fetorsion.design.dampers import run_damper  # noqa: E402
from fetorsion.design.scfset import SCFSet  # noqa: E402

RENAULT = fetorsion.load(GEOMETRY / "renault21.toml")
SCF = SCFSet.of(2.0, 2.2, "given")
MWM6 = GEOMETRY.parent / "examples" / "mendes2008" / "mwm6_chain.toml"


def _verdict():
    from dataclasses import replace

    from fetorsion.description.model import Limits
    from fetorsion.design.verdict import run_verdict

    chain = replace(fetorsion.load(MWM6), limits=Limits(continuous_torque=3000.0, transient_torque=6000.0, source="t"))
    return run_verdict(chain, rpm=np.linspace(1000.0, 2600.0, 20))


def _fillet_scf():
    from fetorsion.design.scf import FilletSCFResult

    rows = json.loads((GEOMETRY.parent / "results" / "scf" / "renault21.json").read_text())["rows"]
    return FilletSCFResult("Renault 21", 0, rows)


def _results():
    yield "lumped", lambda: fetorsion.lumped(RENAULT, 17)
    yield "modal", lambda: modal(cylinder_mesh(0.2, 0.04, 0.02), Material(210e9, 0.3, 7850.0), modes=6)
    yield "campbell", lambda: fetorsion.run_campbell(RENAULT)
    yield "response", lambda: fetorsion.run_response(RENAULT, rpm=[1000.0, 2000.0, 3000.0])
    yield "sensitivity", lambda: fetorsion.run_sensitivity(RENAULT)
    yield "study", lambda: run_study(make_model(RENAULT, "lumped17"), study_inputs(RENAULT)[0], "sobol", 8,
                                     progress=False)
    yield "stress", lambda: run_stress(RENAULT, scf=SCF, rpm=[2000.0, 4000.0, 6000.0])
    yield "damper", lambda: run_damper(RENAULT, "tuned", 0.2, optimise=False, scf=SCF, rpm=[2000.0, 4000.0, 6000.0])
    yield "verdict", _verdict
    yield "fillet scf", _fillet_scf
    yield "kinematics", lambda: kinematics(np.radians(np.arange(0, 361, 30.0)), 0.04, 0.14, 300.0, name="k")
    yield "flywheel", lambda: size_flywheel(7000.0, 3000.0, 0.04, 0.27, 0.21, 0.085)
    yield "planetary", lambda: planetary("epicycloid", 0.06, 0.02, 0.2)
    yield "residual locus", lambda: residual_locus(0.5, 0.0, 0.3)
    yield "min-max", lambda: minmax_overbalance(0.3, k_step=0.05, alpha_step_deg=5.0)


CASES = list(_results())


@pytest.mark.parametrize("make", [c[1] for c in CASES], ids=[c[0] for c in CASES])
def test_every_result_has_the_protocol(make):
    res = make()
    data = res.to_dict()
    # JSON as it is: no numpy scalar or array, no NaN or infinity (json.dumps raises on any of them)
    assert isinstance(data, dict) and json.loads(json.dumps(data, allow_nan=False)).keys() == data.keys()
    text = res.table()
    assert isinstance(text, str) and any(ch.isdigit() for ch in text)
    ax = res.plot()
    assert isinstance(ax, matplotlib.axes.Axes) and ax.has_data()
    plt.close(ax.figure)
    _, given = plt.subplots()
    assert res.plot(ax=given) is given and given.has_data()
    plt.close(given.figure)
