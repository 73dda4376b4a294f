"""How many samples a time-domain run takes and whether the machine holds them, known before the
run starts (``--step-deg 1e-6`` and ``--run-up 1000 6000 --rate 0.01`` tried to allocate
94 and 268 GiB and ended in tracebacks).

A run of duration D at a constant step h = Δθ / ω_top (:func:`fetorsion.response.transient.run_transient`)
holds N = D / h + 1 samples; a run-up from A to B at rate r lasts D = |B − A| / r, a steady run its
settling time plus ``cycles`` working cycles. Every sample carries the coordinates' angles, the
sections' torques, the load on each coordinate and a few scalars (time, speed, crank angle, tooth
edges), so its memory grows as N (c + s + 16) doubles for c coordinates and s sections: measured
with tracemalloc at 1.4 M samples, 321 bytes a sample on the Peugeot's 17-DOF chain (17
coordinates, 16 sections: this rule gives 392) and 161 on the dual-mass flywheel network (3, 2:
this rule 168).
"""

from __future__ import annotations

import math

from ..errors import ParameterError
from ..io import available_memory

#: Doubles a sample holds besides one per coordinate and one per section (time, speed, crank
#: angle, tooth edges, the load's interpolation): the measurement in the module docstring.
SCALARS_PER_SAMPLE = 16
#: The share of the machine's available memory a run may plan to fill: the rest is the
#: interpreter's, the model's and the figures'.
MEMORY_SHARE = 0.8


def sample_bytes(coordinates: int, sections: int) -> int:
    """Bytes one time sample of a run holds (module docstring)."""
    return 8 * (coordinates + sections + SCALARS_PER_SAMPLE)


def check_run_fits(duration_s: float, step_rad: float, top_rpm: float, coordinates: int, sections: int,
                   run: tuple[float, float] | None, available: int | None = None) -> int:
    """The run's sample count, or a :class:`ParameterError` naming what to change when its samples
    would not fit in :data:`MEMORY_SHARE` of the available memory: the rate of a run (the
    smallest that fits), else the step (the smallest that fits).

    Parameters
    ----------
    duration_s : float
        The run's duration, s (a run (A, B) at rate r: |B − A| / r; steady: its settling and cycles).
    step_rad : float
        Crank angle per step at the top speed, rad.
    top_rpm : float
        The run's top speed, rpm.
    coordinates, sections : int
        The model's coordinates and section torques.
    run : (float, float) or None
        A run's speeds (A, B), rpm; None for steady running.
    available : int, optional
        Available memory, bytes (default: the machine's now).
    """
    h = step_rad / (top_rpm * math.pi / 30)
    samples = int(duration_s / h) + 1
    each = sample_bytes(coordinates, sections)
    room, need = _room(samples, each, available)
    if samples * each <= room:
        return samples
    fit = room / each  # samples that fit
    if run is not None:
        rate = abs(run[1] - run[0]) / duration_s
        raise ParameterError("rate_rpm_per_s", f"{rate:g}: the run would hold {need}; the smallest rate that fits "
                             f"at this step is {rate * samples / fit:.3g} rpm/s")
    smallest = step_rad * samples / fit
    raise ParameterError("step_rad", f"{step_rad:.3g} rad ({math.degrees(step_rad):.3g}°): the run would hold {need}; "
                         f"the smallest step that fits is {smallest:.3g} rad ({math.degrees(smallest):.3g}°)")


def check_cycles_fit(samples: int, values_per_sample: int, cycles: int, available: int | None = None) -> None:
    """Refuse (:class:`ParameterError` on ``cycles``, with the most that fit) a steady run of
    ``cycles`` working cycles whose ``samples`` of ``values_per_sample`` doubles each would not fit
    in :data:`MEMORY_SHARE` of the available memory (the condensed crank's state-space run)."""
    each = 8 * values_per_sample
    room, need = _room(samples, each, available)
    if samples * each > room:
        raise ParameterError("cycles", f"{cycles}: the run would hold {need}; at most "
                             f"{int(cycles * room / (samples * each))} cycles fit")


def _room(samples: int, each: int, available: int | None) -> tuple[float, str]:
    """(bytes a run may plan to fill, what ``samples`` of ``each`` bytes would hold against it, in words)."""
    room = MEMORY_SHARE * (available_memory() if available is None else available)
    return room, f"{samples:.3g} samples of {each} bytes ({samples * each / 2**30:.3g} GiB) where {room / 2**30:.3g} GiB is free"

