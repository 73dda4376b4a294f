"""Errors raised for user mistakes, so the CLI can print them without a traceback."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Problem:
    """One violated rule: which field, what it held, and the rule it breaks."""

    field: str
    value: object
    rule: str

    def __str__(self) -> str:
        return f"{self.field} = {self.value!r}: {self.rule}"


class FetorsionError(Exception):
    """A mistake in what the user asked for (input file, option); never a bug.

    Examples
    --------
    >>> import fetorsion
    >>> try:
    ...     fetorsion.load("geometry/no_such_crank.toml")
    ... except fetorsion.FetorsionError as e:  # the CLI prints it without a traceback
    ...     print(type(e).__name__)
    DescriptionError
    """


class GeometryError(FetorsionError):
    """The description is valid field by field but does not make one sound solid, or a CAD solid
    (``[solid] step``) is not one closed solid of the described crank (:mod:`fetorsion.solid`)."""


class ParameterError(FetorsionError):
    """A bad argument of a fetorsion function, named by its parameter (``kind 'x': choose ...``).

    The command line prints it with the option that set the parameter instead
    (``--type 'x': choose ...``), so the stages below it never name a command-line flag.
    """

    def __init__(self, parameter: str, message: str):
        self.parameter, self.message = parameter, message
        super().__init__(self.named(parameter))

    def named(self, name: str) -> str:
        """The message with ``name`` (an option, an environment variable) for the parameter."""
        return f"{name} {self.message}"


class DescriptionError(FetorsionError, ValueError):
    """A crank or chain description breaks one or more rules.

    Every problem is collected before raising, so the user fixes them in one go.

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/peugeot_glx.toml")
    >>> try:
    ...     fetorsion.with_values(crank, {"webs.*.thickness": -1.0, "journals.1.diameter": 0.0})
    ... except fetorsion.DescriptionError as e:  # every broken rule at once, each by its field
    ...     print(len(e.problems), e.problems[0])
    9 journals.1.diameter = 0.0: must be > 0
    """

    def __init__(self, source: str, problems: list[Problem]):
        self.source = source
        self.problems = list(problems)
        lines = [f"{source}: {len(self.problems)} problem(s) in the description"]
        lines += [f"  - {p}" for p in self.problems]
        super().__init__("\n".join(lines))
