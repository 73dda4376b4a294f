"""The calibrated description: a new file beside the original, never over it, each changed
value edited in place and commented with its source (:class:`~.calibration.CalibrationResult`),
read back by every rule of a description before it is written."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..description.edit import edit_toml_values
from ..description.reader import resolve_field
from ..errors import FetorsionError, ParameterError
from .calibration import WRITTEN_DIGITS, CalibrationResult

if TYPE_CHECKING:
    from pathlib import Path


def calibrated_text(result: CalibrationResult, text: str) -> tuple[str, dict[str, float]]:
    """The calibrated description's text and the concrete fields it changes (file units).

    Parameters
    ----------
    result : CalibrationResult
        What to write (:meth:`~fetorsion.studies.calibration.CalibrationResult.calibrated_values`).
    text : str
        The original description's text.

    Returns
    -------
    (str, dict)
        A header comment listing every change and its source, then the original text with each
        changed line edited and commented; and every concrete field's new value.
    """
    values = result.calibrated_values()
    if not values:
        raise FetorsionError("calibrate: the calibration moves no input from its nominal value (to "
                             f"{WRITTEN_DIGITS} digits); no calibrated description to write")
    note = result.source_note()
    fields = {}
    header = [f"# Calibrated description: {note}.",
              f"# Model {result.model}; sigma {', '.join(f'{s:.3g}' for s in result.sigma_hz)} Hz; "
              "every changed value below is commented with its old value.",
              *([f"# Priors: {result.priors}."] if result.priors else []),
              "# Changed inputs (file units):"]
    by_name = {i.name: i for i in result.inputs}
    for name, x in values.items():
        inp = by_name[name]
        header.append(f"#   {name}: {inp.nominal:g} -> {x:g} ({result.change_note(name)})")
        for path, v in inp.values(x).items():
            fields[path] = float(f"{v:.{WRITTEN_DIGITS}g}")
    body = edit_toml_values(text, fields, note)
    return "\n".join(header) + "\n#\n" + body, fields


def write_calibrated(result: CalibrationResult, out: str | Path, force: bool = False):
    """Write the calibrated description as a new file beside the original, never over it.

    Parameters
    ----------
    result : CalibrationResult
        The calibration; its ``source`` is the original file.
    out : str or Path
        The new ``.toml`` file: not the original, and not an existing file unless ``force``.
    force : bool
        Replace an existing ``out`` (never the original).

    Returns
    -------
    dict
        Every concrete field changed and its value (file units), as read back from ``out``.
    """
    import tomllib
    from pathlib import Path

    from ..description.files import parse_description
    from ..io import write_text_atomic

    src, out = Path(result.source), Path(out)
    check_calibrated_path(out, src, force)
    text, fields = calibrated_text(result, src.read_text(encoding="utf-8"))
    # Read back before writing: the new description must parse, by every rule, to the values written.
    raw = tomllib.loads(text)
    parse_description(raw, source=str(out))
    back = {p: float(v) for p in fields for _, v in resolve_field(raw, p)}
    if back != fields:
        raise FetorsionError(f"calibrate: the calibrated description would read back other values: {back}")
    write_text_atomic(out, text)
    return back


def check_calibrated_path(out, source, force: bool = False) -> None:
    """Refuse ``out`` as the calibrated description's file: the original (``source``), an
    existing file (unless ``force``), a folder, or a name without ``.toml``."""
    import os
    from pathlib import Path

    out, source = Path(out), Path(source)
    if out.suffix.lower() != ".toml":
        raise ParameterError("out", f"{out}: the calibrated description is a .toml file")
    if out.is_dir():
        raise ParameterError("out", f"{out}: is a folder; give a new file name")
    if out.exists() and source.exists() and os.path.samefile(out, source):
        raise ParameterError("out", f"{out}: is the original description; the calibrated one is written as a new file")
    if out.exists() and not force:
        raise ParameterError("out", f"{out}: exists; give a new file name (or force to replace it)")
