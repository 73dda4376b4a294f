"""The results protocol: what every result a run writes can do, and the one typed reader that
gives a result back from its ``to_dict()``.

A result is a dataclass with ``to_dict()`` (JSON-ready, SI units in its key names),
``from_dict(d)`` (the result back), ``table()`` (plain text) and ``plot(ax=None)`` (returns
the Axes). Most results need no reading code of their own: :func:`from_fields` reads a dict
into any dataclass by its fields' annotations (arrays back from lists, nested results,
tuples, ``dict[str, X]``, ``X | None``), told only where a key differs from its field's name.

>>> from dataclasses import dataclass
>>> import numpy as np
>>> @dataclass
... class Peak:
...     rpm: np.ndarray
...     label: str
...     width: tuple[float, float] | None = None
>>> p = from_fields(Peak, {"rpm": [1000, 2000], "label": "P1", "width": [1.5, 2.0]})
>>> p.rpm.dtype, p.width
(dtype('float64'), (1.5, 2.0))
"""

from __future__ import annotations

import dataclasses
import sys
import types
import typing
from collections.abc import Mapping
from typing import Protocol, runtime_checkable

import numpy as np


#: What a result's ``to_dict()`` returns and its ``from_dict`` reads: JSON's object, its values
#: plain numbers, strings, booleans, None, lists and such objects (SI units in the key names).
JSONObject = dict[str, typing.Any]


@runtime_checkable
class Result(Protocol):
    """What every result of a run has: its figures as JSON, the result back from them, a table
    and a plot."""

    def to_dict(self) -> JSONObject:
        """Every figure as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "Result":
        """The result back from its :meth:`to_dict`."""

    def table(self) -> str:
        """The result as plain text."""

    def plot(self, ax=None):
        """Draw the result on ``ax`` (a new figure when None); return the Axes."""


def jsonable(x):
    """``x`` with every numpy array and scalar as plain lists and numbers, every key a string
    (what :func:`json.dumps` takes)."""
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return jsonable(x.tolist())
    if isinstance(x, np.generic):
        return x.item()
    return x


def field_types(cls: type) -> dict[str, object]:
    """Each dataclass field's annotation of ``cls``, evaluated where it can be (a name imported
    only for type checking reads as ``None``: its value is passed on as it is)."""
    hints = {}
    for klass in reversed(cls.__mro__):
        module = vars(sys.modules.get(klass.__module__, types.ModuleType("x")))
        for name, ann in getattr(klass, "__annotations__", {}).items():
            try:
                hints[name] = eval(ann, module) if isinstance(ann, str) else ann  # noqa: S307 (annotations)
            except Exception:  # a TYPE_CHECKING name, or a newer syntax than the interpreter's
                hints[name] = None
    return {f.name: hints.get(f.name) for f in dataclasses.fields(cls)}


def _array(value) -> np.ndarray:
    """A list as an array: floats where it holds numbers (None read as NaN), else as it is."""
    try:
        return np.array(value, dtype=float)
    except (TypeError, ValueError):
        return np.array(value, dtype=object if not isinstance(value, list) or not value else None)


def convert(value, kind):
    """``value`` read from JSON as the annotation ``kind`` says (None: as it is)."""
    if kind is None or value is None and kind is not float:
        return value
    origin, args = typing.get_origin(kind), typing.get_args(kind)
    if origin in (typing.Union, types.UnionType):
        if value is None:
            return None
        for arg in (a for a in args if a is not type(None)):
            try:
                return convert(value, arg)
            except (TypeError, ValueError, KeyError):
                continue
        return value
    if kind is np.ndarray:
        return _array(value)
    if kind is float:  # JSON keeps an int an int (a count annotated loosely stays a count)
        return float("nan") if value is None else value if isinstance(value, int) else float(value)
    if origin is tuple:
        items = args[:1] * len(value) if len(args) == 2 and args[1] is Ellipsis else args or (None,) * len(value)
        return tuple(convert(v, a) for v, a in zip(value, items))
    if origin is list:
        return [convert(v, args[0] if args else None) for v in value]
    if origin in (dict, Mapping):
        return {k: convert(v, args[1] if args else None) for k, v in value.items()}
    if isinstance(kind, type) and dataclasses.is_dataclass(kind) and isinstance(value, Mapping):
        return kind.from_dict(value) if hasattr(kind, "from_dict") else from_fields(kind, value)
    return value


def from_fields(cls: type, d: Mapping[str, object], keys: Mapping[str, str] | None = None,
                **given: object) -> object:
    """A dataclass ``cls`` read from the dict ``d`` by its fields' annotations.

    Parameters
    ----------
    cls : dataclass type
        The result.
    d : mapping
        Its ``to_dict()``: every field under its own name, unless ``keys`` names another; a field
        whose key is missing takes its default.
    keys : mapping of str to str, optional
        Field name -> the key its value is stored under, where they differ.
    **given
        Fields given as they are (read by the caller: a key of another shape, or not stored).

    Returns
    -------
    cls
        The result.
    """
    keys = keys or {}
    values = dict(given)
    for name, kind in field_types(cls).items():
        key = keys.get(name, name)
        if name not in values and key in d:
            values[name] = convert(d[key], kind)
    init = {f.name for f in dataclasses.fields(cls) if f.init}
    return cls(**{k: v for k, v in values.items() if k in init})
