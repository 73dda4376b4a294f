"""Reading description files: a TOML reader that never raises on the user's content, and
:class:`Table`, typed access to one table that records every problem (field, value, rule)
instead of stopping at the first. Used by the crank and chain descriptions and by the
mechanics input file.
"""

from __future__ import annotations

import functools
import math
import re
import tomllib
from pathlib import Path

from ..errors import DescriptionError, Problem
from .units import LENGTH_UNITS


class Table:
    """Typed access to one TOML table that records problems instead of raising."""

    def __init__(self, data, path: str, problems: list[Problem], scale: float = 1.0, absent: bool = False,
                 schema: dict | None = None):
        self.path = path
        # The declared fields (fetorsion.description.fields): table name -> keys, None for free keys.
        self.schema = schema
        self.problems = problems
        self.scale = scale
        # A required table that is missing is reported once, not once more for each field.
        self.absent = absent or not isinstance(data, dict)
        if not isinstance(data, dict):
            problems.append(Problem(path, data, "must be a table"))
            data = {}
        self.data = data
        self.used: set[str] = set()

    def _name(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    def get(self, key: str, default=None):
        """The raw value of ``key`` (``default`` when absent), marked as read."""
        return self._get(key, default)

    def raw(self, key):
        """The raw value of a required ``key``; None (and the problem recorded) when missing."""
        value = self._get(key, _REQUIRED)
        return None if value is _MISSING else value

    def choice(self, key, values, default):
        """One of ``values`` (ints or strings, compared exactly, bools never match)."""
        raw = self._get(key, default)
        if isinstance(raw, bool) or raw not in values or type(raw) not in {type(v) for v in values}:
            self.problems.append(Problem(self._name(key), raw, f"must be one of {', '.join(map(str, values))}"))
            return default
        return raw

    def _get(self, key: str, default):
        self.used.add(key)
        if key not in self.data:
            if default is _REQUIRED and not self.absent:
                self.problems.append(Problem(self._name(key), None, "is required"))
            return _MISSING if default is _REQUIRED else default
        return self.data[key]

    def number(self, key, default=None, *, length=False,
               positive=False, nonnegative=False, below=None, above=None):
        """A real number (required when ``default`` is None); ``length=True`` converts
        from the file's length unit to m."""
        raw = self._get(key, _REQUIRED if default is None else default)
        if raw is _MISSING:
            return math.nan
        if isinstance(raw, bool) or not isinstance(raw, (int, float)) or not math.isfinite(raw):
            self.problems.append(Problem(self._name(key), raw, "must be a finite number"))
            return math.nan
        value = float(raw)
        if ((not positive or value > 0) and (not nonnegative or value >= 0) and (below is None or value < below)
                and (above is None or value > above)):  # the common case, without building the messages
            return value * self.scale if length else value
        broken = [rule for rule, ok in (("must be > 0", not positive or value > 0),
                                        ("must be >= 0", not nonnegative or value >= 0),
                                        (f"must be < {below}", below is None or value < below),
                                        (f"must be > {above}", above is None or value > above)) if not ok]
        self.problems += [Problem(self._name(key), raw, rule) for rule in broken]
        if broken:  # NaN: no rule relating this field to others can fire on a value already refused
            return math.nan
        return value * self.scale if length else value

    def integer(self, key, *, minimum=1):
        raw = self._get(key, _REQUIRED)
        if raw is _MISSING:
            return 0
        if isinstance(raw, bool) or not isinstance(raw, int) or raw < minimum:
            self.problems.append(Problem(self._name(key), raw, f"must be an integer >= {minimum}"))
            return 0
        return raw

    def text(self, key, default="", choices=None):
        raw = self._get(key, default)
        if raw is _MISSING:
            return ""
        if not isinstance(raw, str):
            self.problems.append(Problem(self._name(key), raw, "must be a string"))
            return ""
        if choices is not None and raw not in choices:
            self.problems.append(Problem(self._name(key), raw, f"must be one of {', '.join(choices)}"))
        return raw

    def flag(self, key, default=False):
        raw = self._get(key, default)
        if not isinstance(raw, bool):
            self.problems.append(Problem(self._name(key), raw, "must be true or false"))
            return False
        return raw

    def numbers(self, key, *, required=True):
        raw = self._get(key, _REQUIRED if required else [])
        if raw is _MISSING:
            return ()
        if not isinstance(raw, list) or not all(finite_number(v) for v in raw):
            self.problems.append(Problem(self._name(key), raw, "must be a list of finite numbers"))
            return ()
        return tuple(float(v) for v in raw)

    def tables(self, key, *, required=True):
        raw = self._get(key, _REQUIRED if required else [])
        if raw is _MISSING:
            return []
        if not isinstance(raw, list) or not all(isinstance(t, dict) for t in raw):
            self.problems.append(Problem(self._name(key), raw, "must be an array of tables ([[...]])"))
            return []
        return [Table(t, f"{self._name(key)}.{i + 1}", self.problems, self.scale, schema=self.schema)
                for i, t in enumerate(raw)]

    def table(self, key, *, required=True):
        raw = self._get(key, _REQUIRED if required else {})
        return Table({} if raw is _MISSING else raw, self._name(key), self.problems, self.scale,
                     absent=raw is _MISSING or self.absent, schema=self.schema)

    def finish(self):
        """Report keys the reader never asked for: they are typos or unsupported.

        With a ``schema``, a key the reader asked for that the schema does not declare is a bug
        of the reader, not of the file: it raises, so that the documented fields (generated from
        the schema) always cover what the reader accepts.
        """
        if self.schema is not None:
            table = _schema_table(self.path)
            declared = self.schema.get(table, frozenset())
            undeclared = set() if declared is None else self.used - declared
            if undeclared or table not in self.schema:
                raise RuntimeError(f"the reader reads [{table}] {sorted(undeclared)}, which "
                                   "fetorsion/description/fields.py does not declare")
        for key in self.data:
            if key not in self.used:
                self.problems.append(Problem(self._name(key), self.data[key], "is not a known field here"))


_REQUIRED = object()
_MISSING = object()


@functools.lru_cache(maxsize=1024)
def _schema_table(path: str) -> str:
    """The schema's name of the table at ``path``: ``webs.3`` -> ``webs`` (asked once per table
    of every study sample's description)."""
    return re.sub(r"\.\d+", "", path)


def finite_number(v) -> bool:
    """A real number (not a bool), neither NaN nor infinite."""
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


MAX_DESCRIPTION_BYTES = 16 * 2**20  # a description is a few kB; anything this big is not one


def read_toml(path: str | Path) -> dict:
    """Read a TOML file defensively: a missing, unreadable, oversized, binary or non-TOML
    file gives a :class:`DescriptionError` naming it, never a traceback."""
    path = Path(path)

    def fail(rule):
        raise DescriptionError(str(path), [Problem("file", str(path), rule)])

    if not path.exists():
        fail("does not exist")
    if path.is_dir():
        fail("is a folder; give a .toml description file")
    if not path.is_file():
        fail("is not a regular file")
    if path.stat().st_size > MAX_DESCRIPTION_BYTES:
        fail(f"is larger than {MAX_DESCRIPTION_BYTES >> 20} MiB; a description is a small TOML text file")
    try:
        raw = path.read_bytes()
    except OSError as exc:
        fail(f"could not be read ({exc.strerror or exc})")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        fail(f"is not UTF-8 text (byte {exc.start}); a description is a TOML text file")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        fail(f"is not valid TOML ({exc})")


def read_length_unit(root: Table, source: str) -> str:
    """Read ``[units] length`` and set the table's length scale; without a known unit no
    length can be checked, so that problem is raised at once."""
    units = root.table("units")
    unit = units.text("length", choices=tuple(LENGTH_UNITS))
    units.finish()
    if unit not in LENGTH_UNITS:
        raise DescriptionError(source, root.problems)
    root.scale = LENGTH_UNITS[unit]
    return unit


def resolve_field(data: dict, path: str) -> list[tuple[str, object]]:
    """The (concrete path, value) pairs a dotted field path names in a raw description.

    Indices are 1-based; ``*`` stands for every entry of a list of tables.
    """
    found = [("", data)]
    for key in path.split("."):
        nxt = []
        for where, node in found:
            if isinstance(node, list) and key == "*":
                nxt += [(f"{where}.{i + 1}", v) for i, v in enumerate(node)]
            elif isinstance(node, list) and key.isdigit() and 1 <= int(key) <= len(node):
                nxt.append((f"{where}.{key}", node[int(key) - 1]))
            elif isinstance(node, dict) and key in node:
                nxt.append((f"{where}.{key}", node[key]))
        found = nxt
    return [(where.lstrip("."), v) for where, v in found]


def field_keys(parent, key: str) -> list:
    """The keys of ``parent`` a path's last part names: a table's key (set even where the table
    lacks it), or a list's 1-based index (``*``: every index), as
    :func:`~fetorsion.description.reader.resolve_field` reads them."""
    if isinstance(parent, list):
        if key == "*":
            return list(range(len(parent)))
        return [int(key) - 1] if key.isdigit() and 1 <= int(key) <= len(parent) else []
    return [key]
