"""Issue 42: universal files as modal-test packages export them — written here by pyuff itself,
not by fetorsion — read by what their records' data types say, whatever the labels' spelling."""

from __future__ import annotations

import numpy as np
import pytest

from fetorsion.errors import FetorsionError
from fetorsion.measured import read_uff58

HZ = np.linspace(100.0, 900.0, 161)
H = 1e-6 / (1 - (HZ / 500.0) ** 2 + 0.02j * HZ / 500.0)  # rad/N m: a receptance with a mode at 500 Hz


def export(path, ordinate_label="rad/Nm", denominator_label="N m", abscissa_label="Hz", ordinate_type=8,
           denominator_type=13, directions=(4, 4)):
    """An FRF as a test system writes it through pyuff: record 9 displacement (8) at a rotational
    direction (4), record 10 force (13), the labels as given."""
    import pyuff

    dset = pyuff.prepare_58(
        func_type=4, rsp_node=1, rsp_dir=directions[0], ref_node=1, ref_dir=directions[1], id1="hammer",
        abscissa_spec_data_type=18, abscissa_axis_units_lab=abscissa_label,
        ordinate_spec_data_type=ordinate_type, ordinate_axis_units_lab=ordinate_label,
        orddenom_spec_data_type=denominator_type, orddenom_axis_units_lab=denominator_label,
        data=H, x=HZ, abscissa_spacing=0, binary=0)
    pyuff.UFF(str(path)).write_sets([dset], mode="add")
    return path


@pytest.mark.parametrize("ordinate, denominator, scale", [
    ("rad/Nm", "N m", 1.0),  # the ratio in the response's label, the excitation's own label too
    ("rad/N-m", "NONE", 1.0),
    ("rad/(N*m)", "NONE", 1.0),
    ("deg/Nm", "NONE", np.pi / 180),  # a label names the scale: degrees per N m
    ("NONE", "NONE", 1.0),  # no labels: the data types say angle per torque, in SI
])
def test_common_label_spellings_and_none_labels_are_read(tmp_path, ordinate, denominator, scale):
    """Every spelling reads the same receptance (to the ASCII file's 12-13 digits), in rad/N m."""
    f, = read_uff58(export(tmp_path / "h.uff", ordinate, denominator,
                           abscissa_label="NONE" if ordinate == "NONE" else "Hz"))
    assert (f.unit, f.reference_unit) == ("rad", "N m")
    np.testing.assert_allclose(f.abscissa, HZ, rtol=1e-6)  # record 7/abscissa: 6 digits in ASCII
    np.testing.assert_allclose(f.ordinate, scale * H, rtol=1e-10)


@pytest.mark.parametrize("kwargs, scale, note", [
    (dict(ordinate_label="rad/s"), 1.0, "record 9 field 1 says data type 8 (displacement), but its unit label "
                                        "(field 6) 'rad/s' is a unit of angular velocity: read as angle, in rad"),
    (dict(ordinate_label="NONE", denominator_label="m/s^2"), 1.0,
     "record 10 field 1 says data type 13 (force), but its unit label (field 6) 'm/s^2' is a unit of acceleration"),
    (dict(ordinate_label="rad/Nm", denominator_label="N"), 1.0, "names the excitation in 'Nm', but record 10's "
                                                                "label (field 6) says 'N'"),
    (dict(ordinate_label="radians"), 1.0, "'radians' is not a unit fetorsion knows: read in rad, the SI unit of its "
                                          "data type 8 (displacement)"),
])
def test_the_data_type_decides_and_a_contradicting_label_is_noted(tmp_path, kwargs, scale, note):
    """Issue 54: a record's data type (field 1) decides what its values are; a label of another
    quantity, or one that cannot be read, is noted naming the record and the field, and the FRF
    is read in its data type's SI unit (the receptance as written, rad/N m)."""
    f, = read_uff58(export(tmp_path / "h.uff", **kwargs))
    assert (f.unit, f.reference_unit) == ("rad", "N m")
    np.testing.assert_allclose(f.ordinate, scale * H, rtol=1e-10)
    assert any(note in n for n in f.notes), f.notes


def test_a_record_without_a_quantity_or_a_readable_label_is_refused(tmp_path):
    with pytest.raises(FetorsionError, match=r"no unit label and record 9 says no quantity"):
        read_uff58(export(tmp_path / "h.uff", ordinate_label="NONE", ordinate_type=0))
    with pytest.raises(FetorsionError, match=r"'radians' is not a unit fetorsion knows, and record 9 field 1 says "
                                             r"no quantity"):
        read_uff58(export(tmp_path / "g.uff", ordinate_label="radians", ordinate_type=0))


def test_a_mobility_typed_receptance_is_read_as_its_type_says_unless_told(tmp_path):
    """The issue's file: record 9 says velocity (11), its label 'rad/Nm'. The data type decides
    (a mobility, in rad/s per N m) and the contradiction is noted; ``frf_type='receptance'``
    reads it as the receptance it is, noting the data type it overrides."""
    path = export(tmp_path / "h.uff", ordinate_label="rad/Nm", ordinate_type=11)
    f, = read_uff58(path)
    assert (f.unit, f.reference_unit) == ("rad/s", "N m")
    assert any("record 9 field 1 says data type 11 (velocity), but its unit label (field 6) 'rad/Nm' (its response "
               "'rad') is a unit of angle" in n for n in f.notes), f.notes
    g, = read_uff58(path, frf_type="receptance")
    assert g.unit == "rad"
    np.testing.assert_allclose(g.ordinate, H, rtol=1e-10)
    assert any("read as a receptance, as stated" in n for n in g.notes), g.notes
    assert not any("is a unit of angle" in n for n in g.notes)  # the label agrees with what it is now read as
    with pytest.raises(FetorsionError, match="frf_type 'rate'"):
        read_uff58(path, frf_type="rate")


def test_a_stated_unit_reads_an_unlabelled_untyped_record(tmp_path):
    """Record 9 with neither a label nor a data type: the user's unit (``--frf-unit``) is used."""
    f, = read_uff58(export(tmp_path / "h.uff", "NONE", "NONE", ordinate_type=0),
                    units={"ordinate": "mrad", "reference": "N m"})
    np.testing.assert_allclose(f.ordinate, 1e-3 * H, rtol=1e-10)


def test_the_command_line_names_its_own_option_for_an_unreadable_label(tmp_path, capsys):
    """Through `compare`, the way out names the option (--frf-unit), not a Python argument."""
    from conftest import GEOMETRY
    from fetorsion.cli import main

    path = export(tmp_path / "h.uff", "radians", ordinate_type=0)
    assert main(["compare", str(GEOMETRY / "renault21.toml"), str(path), "--band", "400", "600",
                 "--source", "lumped17"]) == 2
    err = capsys.readouterr().err
    assert "state the unit (--frf-unit" in err and "units=" not in err
    assert main(["compare", str(GEOMETRY / "renault21.toml"), str(path), "--band", "400", "600",
                 "--source", "lumped17", "--frf-unit", "rad/N m", "--json", str(tmp_path / "c.json")]) == 0
    assert "frequencies" in (tmp_path / "c.json").read_text()  # read, in the unit stated


def test_a_written_universal_file_has_the_users_umask(tmp_path):
    """Issue 42: files written by fetorsion get the mode a plain open() gives (0644 under umask
    022), not a temporary file's private 0600."""
    import os

    from fetorsion.measured import MeasuredFunction, write_uff58

    old = os.umask(0o022)
    try:
        path = write_uff58(tmp_path / "m.uff", [MeasuredFunction("frf", HZ, "frequency", H, "rad", (1, 4), (1, 4),
                                                                 "N m")])
    finally:
        os.umask(old)
    assert path.stat().st_mode & 0o777 == 0o644
