"""A time-domain run that the machine cannot hold is refused before it allocates, naming the
option to change and the value that fits (issue 55)."""

from __future__ import annotations

import math
import tracemalloc

import pytest

import fetorsion
from conftest import GEOMETRY
from fetorsion.cli.commands import main
from fetorsion.errors import ParameterError
from fetorsion.response.time_budget import check_run_fits, sample_bytes

GIB = 2**30


def test_a_run_up_that_does_not_fit_names_the_rate_and_the_smallest_that_fits():
    """1000-6000 rpm at 0.01 rpm/s, 1 degree a step: 5e5 s of run, h = 1°/(6000 rpm) = 2.78e-5 s,
    1.8e10 samples. With 1 GiB available the smallest rate fits 0.8 GiB: by hand below."""
    duration = (6000.0 - 1000.0) / 0.01  # s
    h = math.radians(1.0) / (6000 * math.pi / 30)
    samples = int(duration / h) + 1
    each = 8 * (17 + 16 + 16)
    with pytest.raises(ParameterError) as err:
        check_run_fits(duration, math.radians(1.0), 6000.0, 17, 16, (1000.0, 6000.0), available=GIB)
    assert err.value.parameter == "rate_rpm_per_s"
    smallest = 0.01 * samples * each / (0.8 * GIB)
    assert f"smallest rate that fits at this step is {smallest:.3g} rpm/s" in str(err.value)
    # at that rate it fits (to the rounding of the sample count)
    fits = check_run_fits(5000.0 / (1.001 * smallest), math.radians(1.0), 6000.0, 17, 16, (1000.0, 6000.0),
                          available=GIB)
    assert fits * each <= 0.8 * GIB


def test_a_steady_run_that_does_not_fit_names_the_step():
    with pytest.raises(ParameterError) as err:
        check_run_fits(2.0, math.radians(1e-6), 3000.0, 17, 16, None, available=GIB)
    assert err.value.parameter == "step_rad" and "smallest step that fits" in str(err.value)


@pytest.mark.slow  # two runs of 0.7 and 1.4 M samples: 14 s
def test_the_rule_bounds_the_memory_a_run_takes():
    """The per-sample rule against tracemalloc's peak of a run of about 1.4 M samples on the
    Peugeot's 17-DOF chain: the growth from 0.72 M to 1.44 M samples (the fixed part cancels)
    is within the rule's bytes a sample, and not below half of it (a rule too loose would refuse
    runs that fit)."""
    crank = fetorsion.load(GEOMETRY / "peugeot_glx_engine.toml")
    peaks, counts = [], []
    for step_deg in (0.025, 0.0125):
        tracemalloc.start()
        res = fetorsion.run_transient(crank, run=(1000.0, 3000.0), rate_rpm_per_s=2000.0,
                                      step_rad=math.radians(step_deg))
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
        counts.append(res.time_s.size)
    per_sample = (peaks[1] - peaks[0]) / (counts[1] - counts[0])
    rule = sample_bytes(res.angle_rad.shape[0], res.section_torque_nm.shape[0])
    assert 0.5 * rule <= per_sample <= rule, (per_sample, rule)


def test_the_command_refuses_before_any_work(capsys):
    """The issue's two commands: one line naming the option, no traceback."""
    src = str(GEOMETRY / "peugeot_glx_engine.toml")
    for argv, option in ((["--run-up", "1000", "6000", "--rate", "0.01"], "--rate 0.01"),
                         (["--rpm", "3000", "--source", "lumped17", "--step-deg", "1e-6"], "--step-deg")):
        assert main(["transient", src, *argv]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"fetorsion: error: {option}") and "fits" in err and "Traceback" not in err


def test_a_steady_state_space_run_names_the_cycles_that_fit():
    from fetorsion.response.time_budget import check_cycles_fit

    with pytest.raises(ParameterError) as err:
        check_cycles_fit(5_000_000, 500, 10_000, available=GIB)  # 20 GB of states
    # 0.8 GiB / (5e6 x 4000 B) of 10 000 cycles
    assert err.value.parameter == "cycles" and f"at most {int(10_000 * 0.8 * GIB / 2e10)} cycles fit" in str(err.value)
    check_cycles_fit(50_000, 500, 100, available=GIB)  # 0.2 GB: fits, says nothing
