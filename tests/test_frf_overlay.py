"""Issue 54: a modal test's universal file, as a test system writes it through pyuff, set beside
the model with no option: the band is the file's, the units are its records' data types, the
measured FRFs are drawn over the model's and the stabilisation diagram is drawn."""

from __future__ import annotations

import json

import numpy as np
import pytest
import scipy.linalg

from fetorsion.cli import main

#: The chain of docs/chain-format.md: pulley, two throws, flywheel (kg m², N m/rad)
INERTIAS = [0.01, 0.02, 0.02, 0.3]
STIFFNESSES = [4.0e5, 5.0e5, 4.5e5]
ZETA = 0.02  # the description's default modal damping ratio, which the model's FRFs carry
HZ = np.arange(1, 3001) * 0.5  # 0.5 to 1500 Hz, as the issue's file (0 Hz left out: a free body's receptance is infinite there)


def chain_file(tmp_path):
    path = tmp_path / "chain4.toml"
    path.write_text(f'[chain]\nname = "four inertias"\ninertias_kgm2 = {INERTIAS}\n'
                    f'stiffnesses_nm_per_rad = {STIFFNESSES}\nlabels = ["pulley", "throw 1", "throw 2", "flywheel"]\n')
    return path


def modal_receptances():
    """The chain's receptances (rad/N m) to a torque at the pulley, by the modal sum over every mode,
    the rigid rotation included (−1/(ω² ΣJ)), each elastic mode damped with ζ: (4, frequencies),
    and the elastic natural frequencies."""
    J, k = np.array(INERTIAS), np.array(STIFFNESSES)
    K = np.diag(np.r_[k, 0.0] + np.r_[0.0, k]) - np.diag(k, 1) - np.diag(k, -1)
    lam, phi = scipy.linalg.eigh(K, np.diag(J))
    wn = np.sqrt(np.clip(lam, 0.0, None))
    wn[0] = 0.0
    w = 2 * np.pi * HZ
    H = sum(np.outer(phi[:, r] * phi[0, r], 1 / (wn[r] ** 2 - w**2 + 2j * ZETA * wn[r] * w)) for r in range(4))
    return H, wn[1:] / (2 * np.pi)


def write_with_pyuff(path, H, ordinate_type=8, label="rad/Nm"):
    """One dataset 58 per station as a test system writes it: the ratio in record 9's label, record
    10 unlabelled, the abscissa evenly spaced in record 7."""
    import pyuff

    sets = [pyuff.prepare_58(func_type=4, rsp_node=n + 1, rsp_dir=4, ref_node=1, ref_dir=4, id1=f"hammer {n + 1}/1",
                             abscissa_spec_data_type=18, abscissa_axis_units_lab="Hz",
                             ordinate_spec_data_type=ordinate_type, ordinate_axis_units_lab=label,
                             orddenom_spec_data_type=13, orddenom_axis_units_lab="NONE",
                             data=H[n], x=HZ, abscissa_spacing=0, binary=0) for n in range(len(H))]
    pyuff.UFF(str(path)).write_sets(sets, mode="add")
    return path


@pytest.fixture(scope="module")
def compared(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("overlay")
    H, exact = modal_receptances()
    uff = write_with_pyuff(tmp / "chain_frf.uff", H)
    argv = ["compare", str(chain_file(tmp)), str(uff), "--json", str(tmp / "c.json"), "--plot", str(tmp / "c.png")]
    assert main(argv) == 0  # no --band, no unit, no type: the file says them
    return json.loads((tmp / "c.json").read_text())["frequencies"][0], exact, tmp, H


def test_the_issues_file_reads_with_no_option_and_gives_the_three_frequencies(compared):
    """The modal fit's own bound (0.1 %, tests/test_measured.py) on the chain's three elastic modes."""
    freq, exact, _, _ = compared
    assert len(freq["measured_hz"]) == 3
    assert np.max(np.abs(np.array(freq["measured_hz"]) / exact - 1)) < 1e-3
    assert np.max(np.abs(np.array(freq["model_hz"]) / exact - 1)) < 1e-9  # the chain's own eigenvalues
    assert freq["frf_overlays"] == ["1:4", "2:4", "3:4", "4:4"] and freq["overlay_note"] == ""


def test_the_stabilisation_diagram_holds_each_mode_as_stable_poles(compared):
    """Every chosen mode is a column of stable poles over most model orders (the rule's
    RECURRENCE), within the chart's stability tolerance of the exact frequency; the chart spans
    the file's band."""
    from fetorsion.measured.modal import FREQUENCY_STABLE, RECURRENCE

    freq, exact, _, _ = compared
    chart = freq["stabilisation"]
    f, orders, stable = np.array(chart["frequencies_hz"]), np.array(chart["orders"]), np.array(chart["stable"])
    assert chart["band_hz"] == [0.5, 1500.0]
    for fn in exact:
        near = stable & (np.abs(f / fn - 1) < 2 * FREQUENCY_STABLE)
        assert len(set(orders[near])) >= RECURRENCE * orders.max(), fn


def test_the_overlays_are_the_models_frfs_at_the_measured_stations(compared):
    """The model's FRF drawn over the measured one is the direct solve of the same chain with the same
    modal damping: equal to the modal sum the file was written from, to the ASCII file's 12 digits
    and the solve's round-off (rtol 1e-6 where |H| is not near an antiresonance's zero)."""
    import fetorsion
    from fetorsion.measured import read_uff58
    from fetorsion.studies.modelfrf import frf_overlays

    _, _, tmp, H = compared
    frfs = read_uff58(tmp / "chain_frf.uff")
    overlays, note = frf_overlays(fetorsion.load(tmp / "chain4.toml"), frfs)
    assert note == "" and [o.station for o in overlays] == ["1:4", "2:4", "3:4", "4:4"]
    for o, h in zip(overlays, H):
        np.testing.assert_allclose(o.measured, h, rtol=1e-10)
        big = np.abs(h) > 1e-3 * np.abs(h).max()
        np.testing.assert_allclose(o.model[big], h[big], rtol=1e-6)


def test_a_mobility_is_set_beside_the_models_mobility(tmp_path):
    """A file of mobilities (record 9: velocity, rad/s per N m): the model's receptance times iω."""
    import fetorsion
    from fetorsion.measured import read_uff58
    from fetorsion.studies.modelfrf import frf_overlays

    H, _ = modal_receptances()
    Y = H * 2j * np.pi * HZ
    frfs = read_uff58(write_with_pyuff(tmp_path / "y.uff", Y, ordinate_type=11, label="rad/s/Nm"))
    overlays, _ = frf_overlays(fetorsion.load(chain_file(tmp_path)), frfs)
    assert overlays[0].form == "mobility" and overlays[0].unit == "rad/s"
    big = np.abs(Y[0]) > 1e-3 * np.abs(Y[0]).max()
    np.testing.assert_allclose(overlays[0].model[big], Y[0][big], rtol=1e-6)


def test_the_figure_has_an_overlay_per_station_and_the_diagram(compared):
    """The written figure: magnitude and phase panels per station, the stabilisation diagram, the
    frequencies; every title inside the canvas."""
    from fetorsion.studies.comparison import ComparisonResult

    _, _, tmp, _ = compared
    png = tmp / "c.png"
    assert png.stat().st_size > 30_000
    import fetorsion
    from fetorsion.measured import read_measured
    from fetorsion.studies.comparison import run_comparison

    crank = fetorsion.load(tmp / "chain4.toml")
    res = run_comparison(crank, read_measured([str(tmp / "chain_frf.uff")]))
    assert isinstance(res, ComparisonResult)
    fig = res.plot()
    titles = [ax.get_title() for ax in fig.axes]
    assert sum(t.startswith("FRF at") and t.endswith("magnitude") for t in titles) == 4
    assert sum(t.startswith("FRF at") and t.endswith("phase") for t in titles) == 4
    assert any(t.startswith("stabilisation diagram: 3 mode(s)") for t in titles)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    canvas = fig.bbox
    for ax in fig.axes:
        box = ax.title.get_window_extent(renderer)
        if ax.get_title():
            assert canvas.x0 - 1 <= box.x0 and box.x1 <= canvas.x1 + 1, ax.get_title()
