"""Measured data in: universal-file functions, order cuts, a torsiograph and a modal fit, each
checked on made-up data whose answer is known from how it was made."""

from __future__ import annotations

import os

import numpy as np
import pytest

from fetorsion.errors import FetorsionError
from fetorsion.measured import MeasuredFunction, read_order_cut_csv, read_uff58, write_uff58

# ---------------------------------------------------------------------------
# UFF dataset 58


def frf_and_orders(seed=1):
    """An FRF (complex, against Hz), an order cut (real, against rpm) and an order spectrum
    (complex, against order), on abscissae that 6 significant digits hold exactly (the ASCII
    58's abscissa format), so that both formats can be held to the same tolerance."""
    rng = np.random.default_rng(seed)
    f = np.arange(1, 801) * 0.625  # Hz
    wn, zeta = 2 * np.pi * 180.0, 0.02
    w = 2 * np.pi * f
    frf = MeasuredFunction("frf", f, "frequency", 1 / (0.05 * (wn**2 - w**2 + 2j * zeta * wn * w)), "rad",
                           response=(3, 4), reference=(1, 4), reference_unit="N m", label="flywheel / pulley")
    rpm = np.arange(800.0, 6001.0, 25.0)
    cut = MeasuredFunction("order function", rpm, "speed", rng.uniform(1e-4, 3e-3, len(rpm)), "rad",
                           response=(1, 4), order=2.5, label="pulley order 2.5")
    orders = np.arange(1, 25) * 0.5
    spectrum = MeasuredFunction("spectrum", orders, "order",
                                rng.normal(size=len(orders)) + 1j * rng.normal(size=len(orders)), "rad/s^2",
                                response=(1, 4), rpm=3200.0)
    return [frf, cut, spectrum]


@pytest.mark.parametrize("binary", [True, False], ids=["58b", "ascii"])
def test_uff58_round_trip_is_within_1e9(tmp_path, binary):
    # 1e-9 is reachable in both formats: 58b stores IEEE doubles (pyuff packs the abscissa and
    # the ordinate with struct 'd'), so its round trip is exact; ASCII 58 writes ordinates as
    # E20.12 (pyuff: %20.11e, 12 significant digits, relative error <= 5e-12) and abscissae as
    # E13.5, which the grids above hold exactly.
    written = frf_and_orders()
    path = write_uff58(tmp_path / "m.uff", written, binary=binary)
    read = read_uff58(path)
    assert [r.kind for r in read] == ["frf", "order function", "spectrum"]
    for a, b in zip(written, read):
        assert np.max(np.abs(b.abscissa - a.abscissa) / np.abs(a.abscissa)) <= 1e-9
        assert np.max(np.abs(b.ordinate - a.ordinate)) <= 1e-9 * np.max(np.abs(a.ordinate))
        assert np.iscomplexobj(b.ordinate) == np.iscomplexobj(a.ordinate)
        assert (b.unit, b.reference_unit, b.response, b.reference, b.label, b.order, b.rpm) == \
               (a.unit, a.reference_unit, a.response, a.reference, a.label, a.order, a.rpm)
    assert os.listdir(tmp_path) == ["m.uff"]


def test_uff58_writes_the_standard_function_types(tmp_path):
    # A spectrum is type 12 and an order function 27 in record 6, which other programs read.
    path = write_uff58(tmp_path / "m.uff", frf_and_orders(), binary=False)
    lines = path.read_text().splitlines()
    record6 = [lines[i + 6] for i, line in enumerate(lines) if line.startswith("    58")]
    assert [int(r[:5]) for r in record6] == [4, 27, 12]


def relabel(path, old: str, new: str, count=1):
    """The file with the first ``count`` unit labels ``old`` replaced (same field width)."""
    text = path.read_bytes()
    old_b, new_b = f" {old:<20s}".encode(), f" {new:<20s}".encode()
    assert text.count(old_b) >= count
    path.write_bytes(text.replace(old_b, new_b, count))


def test_uff58_units_come_from_the_file_or_the_caller(tmp_path):
    frf = frf_and_orders()[0]
    path = write_uff58(tmp_path / "m.uff", [frf])
    relabel(path, "rad", "mrad")  # a file in milliradians per N m: read in rad per N m
    assert np.allclose(read_uff58(path)[0].ordinate, 1e-3 * frf.ordinate, rtol=1e-15)
    relabel(path, "mrad", "NONE")
    with pytest.raises(FetorsionError, match="ordinate has no unit label; state its unit"):
        read_uff58(path)
    assert np.allclose(read_uff58(path, units={"ordinate": "deg"})[0].ordinate, frf.ordinate * np.pi / 180)
    with pytest.raises(FetorsionError, match="'N m', but 'N' was stated"):
        read_uff58(path, units={"ordinate": "rad", "reference": "N"})
    relabel(path, "NONE", "m/s^2")  # an acceleration where record 9 says displacement
    with pytest.raises(FetorsionError, match="is a unit of acceleration, not of angle or length"):
        read_uff58(path)


def test_uff58_write_leaves_nothing_after_an_error(tmp_path, monkeypatch):
    import pyuff

    good = frf_and_orders()
    (tmp_path / "m.uff").write_bytes(b"the user's earlier file")
    bad = MeasuredFunction("frf", good[0].abscissa, "frequency", good[0].ordinate, "rad", (1, 4))
    with pytest.raises(FetorsionError, match="function 2.*needs a reference"):
        write_uff58(tmp_path / "m.uff", [good[0], bad])
    calls = []

    def fail_second(self, dsets, mode="add", force_double=True):  # a failure midway through writing
        calls.append(1)
        if len(calls) == 2:
            raise OSError("disk full")
        return original(self, dsets, mode, force_double)

    original = pyuff.UFF.write_sets
    monkeypatch.setattr(pyuff.UFF, "write_sets", fail_second)
    with pytest.raises(OSError, match="disk full"):
        write_uff58(tmp_path / "m.uff", good)
    assert os.listdir(tmp_path) == ["m.uff"]
    assert (tmp_path / "m.uff").read_bytes() == b"the user's earlier file"


# ---------------------------------------------------------------------------
# Order cuts from CSV


def test_order_cut_csv_in_si_with_its_phase(tmp_path):
    path = tmp_path / "cut.csv"
    path.write_text("# name = pulley, 2nd order\n# unit = mrad\n# order = 2\n"
                    "1000, 0.5, 10\n2000, 1.5, -80\n3000, 0.75, -170\n")
    cut = read_order_cut_csv(path)
    assert (cut.kind, cut.abscissa_quantity, cut.unit, cut.order, cut.label) == \
           ("order function", "speed", "rad", 2.0, "pulley, 2nd order")
    assert np.allclose(cut.ordinate, 1e-3 * np.array([0.5, 1.5, 0.75]) * np.exp(1j * np.radians([10, -80, -170])),
                       rtol=1e-14)
    path.write_text("1000, 0.5\n2000, 1.5\n3000, 0.75\n")  # no unit in the file: the caller's
    assert np.allclose(read_order_cut_csv(path, unit="deg").ordinate, np.radians([0.5, 1.5, 0.75]), rtol=1e-14)
    with pytest.raises(FetorsionError, match="cut.csv: the amplitude has no unit"):
        read_order_cut_csv(path)
