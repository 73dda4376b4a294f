"""Universal File Format dataset 58 (function at nodal DOF): FRFs, spectra and order functions
as test systems export them, read and written with pyuff [Pyuff] against the dataset's
specification [Uff58].

What the file says is checked before it is used: the function type (record 6), the abscissa's
specific data type (record 8: frequency, rpm or order) and the units of records 8 to 10. A
record's specific data type (with the response or reference direction: 1-3 translation, 4-6
rotation) decides what its values are — displacement at a rotational direction is an angle, in
the file's units, SI [Uff58] — and its free-text unit label only repeats it, in whatever
spelling the test system uses (``rad/Nm``, ``rad/N-m``, ``rad/(N*m)``, ``deg/Nm``, ``NONE``;
an FRF's ordinate label often names the whole ratio). So a record whose label is empty or
``NONE`` is read in the SI unit of its data type, and a label that names a unit of the data
type's quantity gives the scale (``deg``, ``mrad``). A label of another quantity, or one
fetorsion cannot read, does not decide: the record is read in its data type's SI unit and the
function carries a note naming the record and the fields (``frf_type=``, the command line's
``--frf-type``, says what an FRF's response is where the data type is wrong). A record without
a usable data type (0, general) needs a readable label or a stated unit. Values are converted to
SI on reading (abscissae: Hz, rpm or order).

pyuff 2.5.8 writes function types 0, 1, 2, 3, 4, 6 and 9 only; a spectrum (type 12) and an
order function (type 27) are written as type 0 and their record 6 set afterwards, so that
other programs read them as what they are. The order of an order cut (abscissa rpm), or the
speed of an order spectrum (abscissa order), is the record's z-axis value (record 7 field 6,
with record 11's data type 20 or 19), which pyuff reads and writes with 6 significant digits.
"""

from __future__ import annotations

import re
import tempfile
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import FetorsionError
from .units import SI_UNITS as UNITS_SI
from .units import UNITS, normalise, unit

#: record 6 field 1: the function types read, and what each is called here
FUNCTION_TYPES = {4: "frf", 12: "spectrum", 27: "order function"}
KIND_TYPES = {kind: code for code, kind in FUNCTION_TYPES.items()}
GENERAL = 0  # record 6's 'general or unknown': an order function when its abscissa is rpm or order
#: record 8 field 1 of the abscissa -> the quantity (the units module's name)
ABSCISSA_TYPES = {18: "frequency", 19: "speed", 20: "order"}
ABSCISSA_CODES = {q: code for code, q in ABSCISSA_TYPES.items()}
ABSCISSA_UNITS = {"frequency": "Hz", "speed": "rpm", "order": "-"}
#: a quantity -> the data type records 9 and 10 are written with
ORDINATE_CODES = {"angle": 8, "length": 8, "angular velocity": 11, "velocity": 11, "angular acceleration": 12,
                  "acceleration": 12, "torque": 13, "force": 13, "pressure": 15}
NONE = "NONE"  # the UFF's word for an unused text field
DELIMITER = re.compile(rb"    -1(?=\r|\n| {74}|$)")  # the lines that open and close each dataset
ID_WIDTH = 80  # characters of an ID line


@dataclass(frozen=True, eq=False)
class MeasuredFunction:
    """One measured function, in SI.

    Attributes
    ----------
    kind : str
        ``'frf'``, ``'spectrum'`` or ``'order function'``.
    abscissa : ndarray
        Ascending abscissa: frequency [Hz], speed [rpm] or order [-], by ``abscissa_quantity``.
    abscissa_quantity : str
        ``'frequency'``, ``'speed'`` or ``'order'``.
    ordinate : ndarray
        Real or complex values, in ``unit`` (per ``reference_unit`` for an FRF).
    unit : str
        The SI unit of the ordinate (the response, for an FRF): ``'rad'``, ``'m/s^2'``, ...
    response : tuple of int
        (node, direction) of the response; UFF directions: 1-3 translation, 4-6 rotation.
    reference : tuple of int, optional
        (node, direction) of the excitation of an FRF.
    reference_unit : str, optional
        The SI unit of an FRF's excitation (``'N m'``, ``'N'``).
    label : str
        A description (the UFF's ID line 1).
    order : float, optional
        The engine order of an order function against speed (an order cut).
    rpm : float, optional
        The speed [rpm] of an order function against order (an order spectrum).
    notes : tuple of str
        What reading found questionable and how it was read (a unit label that contradicts its
        record's data type, or that fetorsion cannot read).
    """

    kind: str
    abscissa: np.ndarray
    abscissa_quantity: str
    ordinate: np.ndarray
    unit: str
    response: tuple[int, int]
    reference: tuple[int, int] | None = None
    reference_unit: str | None = None
    label: str = ""
    order: float | None = None
    rpm: float | None = None
    notes: tuple[str, ...] = ()

    @property
    def abscissa_unit(self) -> str:
        """The abscissa's unit: ``'Hz'``, ``'rpm'`` or ``'-'`` (order)."""
        return ABSCISSA_UNITS[self.abscissa_quantity]


# ---------------------------------------------------------------------------
# Reading


def _label(text) -> str | None:
    text = str(text).strip()
    return None if not text or text.upper() == NONE else text


#: The UFF record that carries each of a function's units, for messages
RECORDS = {"abscissa": 8, "ordinate": 9, "reference": 10}
#: record 9/10 data types, by name, for messages
TYPE_NAMES = {8: "displacement", 11: "velocity", 12: "acceleration", 9: "force", 13: "force",
              15: "pressure", 18: "frequency", 19: "rpm", 20: "order"}
#: data type -> (the quantity at a translational direction, at a rotational one)
TYPED_QUANTITIES = {8: ("length", "angle"), 11: ("velocity", "angular velocity"),
                    12: ("acceleration", "angular acceleration"), 9: ("force", "torque"), 13: ("force", "torque"),
                    15: ("pressure", "pressure"), 18: ("frequency",) * 2, 19: ("speed",) * 2, 20: ("order",) * 2}
#: records 9 and 10's data types -> the quantities its unit may be of, rotational first (the other
#: types are not checked)
ORDINATE_TYPES = {code: tuple(dict.fromkeys(pair[::-1])) for code, pair in TYPED_QUANTITIES.items()
                  if code not in ABSCISSA_TYPES}
#: the quantities an FRF's excitation may be (the denominator of a ratio label)
EXCITATIONS = ("torque", "force")


def typed_quantity(code: int, direction: int | None) -> str | None:
    """The quantity a record's specific data type says, at a response or reference direction
    (4-6 rotation, else translation); None for a type that does not say (0 general, 1 unknown)."""
    pair = TYPED_QUANTITIES.get(code)
    if pair is None:
        return None
    return pair[1] if direction in (4, 5, 6) else pair[0]


def split_ratio(text: str) -> tuple[str, str] | None:
    """An FRF label naming the whole ratio, ``rad/Nm``, ``rad/(N*m)``, ``deg/N-m``, as (response
    unit, excitation unit) when its right side is a torque or force unit; else None."""
    if "/" not in text:
        return None
    top, _, bottom = text.rpartition("/")
    found = UNITS.get(normalise(bottom.strip().strip("()")))
    if found is None or found.quantity not in EXCITATIONS or not top.strip():
        return None
    return top.strip(), bottom.strip().strip("()")


class UnstatedUnit(FetorsionError):
    """A record whose unit the file does not say in a way fetorsion can read: the caller must
    state it (``units=``; the command line's ``--frf-unit`` or ``--unit``)."""

    def __init__(self, text: str, record: str):
        self.text, self.record = text, record
        super().__init__(self.stating(f"units={{'{record}': ...}}"))

    def stating(self, how: str) -> str:
        """The message, naming ``how`` the unit is stated."""
        return self.text.replace("{how}", how)


def _same(a: str, b: str) -> bool | None:
    """Whether two unit texts name one unit (None: one of them is not known)."""
    x, y = UNITS.get(normalise(a)), UNITS.get(normalise(b))
    return None if x is None or y is None else (x.quantity, x.factor) == (y.quantity, y.factor)


def _units_of(dset, where: str, units: dict, record: str, key: str, allowed, code: int,
              direction: int | None, notes: list, label: str | None = None):
    """The Unit of one record (see the module docstring). The data type decides the quantity;
    the label gives the scale where it names a unit of that quantity; a label of another
    quantity, or one fetorsion cannot read, is noted in ``notes`` (naming the record and its
    fields) and the record read in its data type's SI unit. A unit the caller states must agree
    with a readable label."""
    number = RECORDS[record]
    labelled = label if label is not None else _label(dset.get(f"{key}_axis_units_lab", ""))
    stated = units.get(record)
    typed = typed_quantity(code, direction)
    if typed is not None:  # at its direction the data type says one quantity
        allowed = (typed,)
    kind = f"data type {code} ({TYPE_NAMES[code]})" if code in TYPE_NAMES else f"data type {code}"
    given = unit(stated, f"{where}: stated {record} unit", allowed) if stated is not None else None
    found = UNITS.get(normalise(labelled)) if labelled is not None else None
    if labelled is not None and found is None and given is None and typed is None:
        raise UnstatedUnit(f"{where}: the {record}'s unit label (record {number} field 6) {labelled!r} is not a "
                           f"unit fetorsion knows, and record {number} field 1 says no quantity ({kind}): state the "
                           "unit ({how}) to read it", record)
    if found is not None and given is not None and (found.quantity, found.factor) != (given.quantity, given.factor):
        raise FetorsionError(f"{where}: the file's {record} unit is {labelled!r}, but {stated!r} was stated")
    if given is not None:
        return given
    if found is not None and (allowed is None or found.quantity in allowed):
        return found
    if typed is None:
        raise UnstatedUnit(f"{where}: the {record} has no unit label and record {number} says no quantity "
                           f"({kind}); state its unit ({{how}})", record)
    si = UNITS_SI[typed]
    raw = _label(dset.get(f"{key}_axis_units_lab", ""))
    shown = repr(labelled) if raw in (None, labelled) else f"{raw!r} (its response {labelled!r})"
    if found is not None:
        notes.append(f"{where}: record {number} field 1 says {kind}, but its unit label (field 6) {shown} "
                     f"is a unit of {found.quantity}: read as {typed}, in {si} (the data type decides{OVERRIDE})")
    elif labelled is not None:
        notes.append(f"{where}: record {number}'s unit label (field 6) {shown} is not a unit fetorsion "
                     f"knows: read in {si}, the SI unit of its {kind} (state the FRF unit if it is another scale)")
    return unit(si, where)


#: How a reader overrides the data type of an FRF's response (said where a label contradicts it)
OVERRIDE = "; stating the FRFs' type (receptance, mobility, accelerance) overrides it"
#: An FRF's form -> the data type of its response (record 9 field 1)
FRF_TYPES = {"receptance": 8, "mobility": 11, "accelerance": 12}


def _function(dset, where: str, units: dict, frf_type: str | None = None) -> MeasuredFunction:
    code = int(dset["func_type"])
    abscissa_code = int(dset["abscissa_spec_data_type"])
    quantity = ABSCISSA_TYPES.get(abscissa_code)
    kind = FUNCTION_TYPES.get(code)
    if code == GENERAL and quantity in ("speed", "order"):
        kind = "order function"
    if kind is None:
        raise FetorsionError(f"{where}: function type {code} is not read; fetorsion reads FRFs (4), "
                             "spectra (12) and order functions (27)")
    if quantity is None:
        raise FetorsionError(f"{where}: abscissa data type {abscissa_code} (record 8) is not frequency (18), "
                             "rpm (19) or order (20)")
    if kind == "order function" and quantity == "frequency":
        raise FetorsionError(f"{where}: an order function needs an abscissa of rpm (19) or order (20), not frequency")
    x, y = np.asarray(dset["x"], dtype=float), np.asarray(dset["data"])
    n = int(dset["num_pts"])
    if len(y) != n or len(x) != n:
        raise FetorsionError(f"{where}: is truncated: record 7 says {n} values, the data holds {len(y)}")
    if n < 2 or not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise FetorsionError(f"{where}: needs >= 2 finite values")
    if np.any(np.diff(x) <= 0):
        raise FetorsionError(f"{where}: the abscissa is not ascending")
    notes: list[str] = []
    xu = _units_of(dset, where, units, "abscissa", "abscissa", (quantity,), abscissa_code, None, notes)
    ordinate_code = int(dset["ordinate_spec_data_type"])
    if kind == "frf" and frf_type is not None:
        if ordinate_code not in (0, 1, FRF_TYPES[frf_type]):
            notes.append(f"{where}: record 9 field 1 says data type {ordinate_code} "
                         f"({TYPE_NAMES.get(ordinate_code, 'other')}); read as a {frf_type}, as stated")
        ordinate_code = FRF_TYPES[frf_type]
    response_dir, reference_dir = int(dset["rsp_dir"]), int(dset["ref_dir"])
    ordinate_label = _label(dset.get("ordinate_axis_units_lab", ""))
    ratio = split_ratio(ordinate_label) if kind == "frf" and ordinate_label is not None else None
    yu = _units_of(dset, where, units, "ordinate", "ordinate", ORDINATE_TYPES.get(ordinate_code), ordinate_code,
                   response_dir, notes, None if ratio is None else ratio[0])
    reference = ru = None
    scale = yu.factor
    if kind == "frf":
        denominator_code = int(dset["orddenom_spec_data_type"])
        own = _label(dset.get("orddenom_axis_units_lab", ""))
        if ratio is not None and own is not None and _same(own, ratio[1]) is False:
            notes.append(f"{where}: the ordinate's label {ordinate_label!r} names the excitation in {ratio[1]!r}, "
                         f"but record 10's label (field 6) says {own!r}: record 10's is read")
        ru = _units_of(dset, where, units, "reference", "orddenom", ORDINATE_TYPES.get(denominator_code),
                       denominator_code, reference_dir, notes, own if own is not None else (ratio and ratio[1]))
        scale /= ru.factor
        reference = (int(dset["ref_node"]), reference_dir)
    z_code, z = int(dset.get("z_axis_spec_data_type", 0)), float(dset.get("z_axis_value", 0.0))
    return MeasuredFunction(
        kind=kind, abscissa=x * xu.factor, abscissa_quantity=quantity, ordinate=y * scale, unit=yu.si,
        response=(int(dset["rsp_node"]), int(dset["rsp_dir"])), reference=reference,
        reference_unit=ru.si if ru else None, label=_label(dset.get("id1", "")) or "",
        order=z if quantity == "speed" and z_code == ABSCISSA_CODES["order"] else None,
        rpm=z if quantity == "order" and z_code == ABSCISSA_CODES["speed"] else None, notes=tuple(notes))


def read_uff58(path, units: dict[str, str] | None = None, frf_type: str | None = None) -> list[MeasuredFunction]:
    """The dataset-58 functions of a universal file, in SI, or one message naming the file.

    Parameters
    ----------
    path : str or Path
        A ``.uff``/``.unv`` file (ASCII 58 or binary 58b). Other datasets in it (151 header,
        164 units, 55 modes) are passed over; a file with no dataset 58 is refused.
    units : dict[str, str], optional
        Units for records without a unit label: keys ``'abscissa'``, ``'ordinate'`` and
        ``'reference'`` (an FRF's excitation), values such as ``'Hz'``, ``'rad'``, ``'N m'``.
        A record with a label keeps it; a stated unit that disagrees with it is refused.
    frf_type : {'receptance', 'mobility', 'accelerance'}, optional
        What every FRF's response is (displacement, velocity or acceleration per load), over
        record 9's data type; a record whose data type says otherwise gets a note.

    Returns
    -------
    list of MeasuredFunction
        In file order.
    """
    import pyuff

    path, units = Path(path), dict(units or {})
    if not path.is_file():
        raise FetorsionError(f"{path}: is not a file")
    if frf_type is not None and frf_type not in FRF_TYPES:
        raise FetorsionError(f"frf_type {frf_type!r}: choose one of {', '.join(FRF_TYPES)}")
    unknown = set(units) - {"abscissa", "ordinate", "reference"}
    if unknown:
        raise FetorsionError(f"{path}: units has keys {sorted(unknown)}; use 'abscissa', 'ordinate', 'reference'")
    delimiters = len(DELIMITER.findall(path.read_bytes()))
    if delimiters == 0:
        raise FetorsionError(f"{path}: is not a universal file (no '    -1' dataset delimiter)")
    if delimiters % 2:
        raise FetorsionError(f"{path}: is truncated: its last dataset has no closing '    -1' line")
    try:
        uff = pyuff.UFF(str(path))
        types = [int(t) for t in uff.get_set_types()]
        found = [i for i, t in enumerate(types) if t == 58]
        if not found:
            raise FetorsionError(f"{path}: holds dataset(s) {', '.join(map(str, sorted(set(types))))} "
                                 "but no dataset 58 (function at nodal DOF)")
        sets = [uff.read_sets(i) for i in found]
    except FetorsionError:
        raise
    except Exception as exc:  # pyuff raises bare Exceptions on a malformed record
        raise FetorsionError(f"{path}: is not a readable dataset 58 ({exc})") from None
    return [_function(d, f"{path} (dataset {i + 1})", units, frf_type) for i, d in zip(found, sets)]


# ---------------------------------------------------------------------------
# Writing


def _check(f: MeasuredFunction, where: str) -> None:
    if f.kind not in KIND_TYPES:
        raise FetorsionError(f"{where}: kind {f.kind!r}; choose one of {', '.join(KIND_TYPES)}")
    if f.abscissa_quantity not in ABSCISSA_CODES:
        raise FetorsionError(f"{where}: abscissa_quantity {f.abscissa_quantity!r}; choose one of "
                             f"{', '.join(ABSCISSA_CODES)}")
    x, y = np.asarray(f.abscissa), np.asarray(f.ordinate)
    if x.ndim != 1 or x.shape != y.shape or len(x) < 2:
        raise FetorsionError(f"{where}: abscissa and ordinate need the same length, >= 2")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))) or np.any(np.diff(x) <= 0):
        raise FetorsionError(f"{where}: needs finite values and an ascending abscissa")
    unit(f.unit, f"{where}: unit")
    if f.kind == "frf" and (f.reference is None or f.reference_unit is None):
        raise FetorsionError(f"{where}: an FRF needs a reference (node, direction) and a reference_unit")


def _record(f: MeasuredFunction, binary: bool) -> dict:
    yu = unit(f.unit, "unit")
    written = KIND_TYPES[f.kind] if KIND_TYPES[f.kind] == KIND_TYPES["frf"] else GENERAL
    reference = f.reference or (0, 0)
    z_code, z = 0, 0.0
    if f.order is not None and f.abscissa_quantity == "speed":
        z_code, z = ABSCISSA_CODES["order"], float(f.order)
    elif f.rpm is not None and f.abscissa_quantity == "order":
        z_code, z = ABSCISSA_CODES["speed"], float(f.rpm)
    dset = {
        "type": 58, "binary": int(binary), "func_type": written, "id1": (" ".join(f.label.split()) or NONE)[:ID_WIDTH],
        "rsp_node": int(f.response[0]), "rsp_dir": int(f.response[1]),
        "ref_node": int(reference[0]), "ref_dir": int(reference[1]),
        # uneven spacing: the abscissa goes into the data (doubles in 58b), not into record 7's
        # minimum and increment, which are written with 6 significant digits
        "abscissa_spacing": 0, "x": np.asarray(f.abscissa, dtype=float),
        "data": np.asarray(f.ordinate) if np.iscomplexobj(f.ordinate) else np.asarray(f.ordinate, dtype=float),
        "abscissa_spec_data_type": ABSCISSA_CODES[f.abscissa_quantity],
        "abscissa_axis_lab": f.abscissa_quantity, "abscissa_axis_units_lab": f.abscissa_unit,
        "ordinate_spec_data_type": ORDINATE_CODES.get(yu.quantity, 1),
        "ordinate_axis_lab": yu.quantity, "ordinate_axis_units_lab": yu.si,
        "orddenom_spec_data_type": 0,  # records 10 and 11 unused: data type 0 [Uff58]
        "z_axis_spec_data_type": z_code, "z_axis_value": z,
    }
    if f.kind == "frf":
        ru = unit(f.reference_unit, "reference_unit")
        dset.update({"orddenom_spec_data_type": ORDINATE_CODES.get(ru.quantity, 1),
                     "orddenom_axis_lab": ru.quantity, "orddenom_axis_units_lab": ru.si})
    return dset


def _set_function_type(block: bytes, code: int) -> bytes:
    """``block`` (one dataset as pyuff wrote it) with record 6's function type set to ``code``."""
    lines = block.split(b"\n", 8)  # the delimiter, the id line and five ID lines come first
    record6 = lines[7]
    if int(record6[:5]) != GENERAL:
        raise RuntimeError(f"unexpected record 6 from pyuff: {record6!r}")
    lines[7] = b"%5i" % code + record6[5:]
    return b"\n".join(lines)


def write_uff58(path: str | Path, functions: Iterable[MeasuredFunction], binary: bool = True) -> Path:
    """Write measured functions to a universal file as dataset 58 (58b when ``binary``).

    The file is written beside its destination under a temporary name and renamed over it, so
    a reader never sees half a file and an error leaves nothing behind.

    Parameters
    ----------
    path : str or Path
        The destination.
    functions : list of MeasuredFunction
        What to write, in SI (the units written are the SI ones).
    binary : bool
        58b (doubles, abscissa included: a round trip is exact) if True; ASCII 58 if False
        (ordinates with 12 significant digits, abscissae with 6, by the dataset's formats).

    Returns
    -------
    Path
        ``path``.
    """
    import pyuff

    path, functions = Path(path), list(functions)
    if not functions:
        raise FetorsionError(f"{path}: nothing to write")
    for i, f in enumerate(functions):
        _check(f, f"{path} (function {i + 1})")
    if not path.parent.is_dir():
        raise FetorsionError(f"{path}: the folder {path.parent} does not exist")
    blocks = []
    with tempfile.TemporaryDirectory(prefix="fetorsion-uff-") as scratch:
        for i, f in enumerate(functions):
            piece = Path(scratch) / f"{i}.uff"
            # 'add' to a new file: pyuff 2.5.8's 'overwrite' reopens the file for the binary data
            # of a 58b and so truncates the header it has just written
            pyuff.UFF(str(piece)).write_sets([_record(f, binary)], mode="add")
            block = piece.read_bytes()
            code = KIND_TYPES[f.kind]
            blocks.append(block if code == KIND_TYPES["frf"] else _set_function_type(block, code))
    from ..io import atomic_output

    with atomic_output(path) as temporary:  # with the user's umask, as a plain open() would
        temporary.write_bytes(b"".join(blocks))
    return path
