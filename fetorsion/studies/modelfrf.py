"""The free-free model's FRFs beside measured ones: the chain's or the condensed crank's
(K, M, C) with the description's modal damping, its receptance between any two stations, and
each measured FRF set beside the model's at its station in its form (receptance, mobility,
accelerance), for :mod:`fetorsion.studies.comparison`'s figure and its written predictions."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..description.defaults import LUMPED17


def free_model(crank, damping_ratio: float | None = None, condensed=None):
    """The free-free model's (K, M, C) and the matrix row of each of its stations (1-based
    station n is row ``rows[n - 1]``: a chain's stations; the condensed crank's masters' θx),
    with the description's modal damping ratio on every elastic mode (and a chain file's stated
    dampers and loss factors, in a complex K)."""
    from ..description.defaults import DEFAULT_DAMPING_RATIO

    zeta = damping_ratio if damping_ratio is not None else getattr(getattr(crank, "excitation", None),
                                                                   "modal_damping_ratio", DEFAULT_DAMPING_RATIO)
    if condensed is not None:
        from ..response.coupled import supported_damping

        K, M, C, keep = supported_damping(condensed, "free", zeta)
        rows = [int(np.flatnonzero(keep == condensed.dof(lb, "rx"))[0]) for lb in condensed.labels]
        return K, M, C, rows
    from ..description.chain_model import Chain
    from ..lumped_model.lumped import chain_matrices, lumped, stated_damping
    from ..modes import modal_damping_matrix

    res = lumped(crank, 17)
    M, K = chain_matrices(res.inertias_kgm2, res.stiffnesses_nm_per_rad)
    C = modal_damping_matrix(M, K, zeta)
    if isinstance(crank, Chain):  # a chain file's own dampers and loss factors, as its forced response has them
        C_stated, H_loss = stated_damping(crank, res)
        C, K = C + C_stated, K + 1j * H_loss
    return K, M, C, list(range(len(M)))


def free_receptances(K, M, C, drive: int, read, frequency_hz) -> np.ndarray:
    """(len(read), frequencies) complex: the rows ``read`` of (K − ω²M + iωC)⁻¹ e_drive, NaN at
    0 Hz (a free body has no static receptance)."""
    w = 2 * np.pi * np.asarray(frequency_hz, float)
    w = np.where(w > 0, w, np.nan)
    f = np.zeros(len(M))
    f[drive] = 1.0
    H = np.empty((len(w), len(M)), complex)
    for a in range(0, len(w), 100):  # blocks: (100, n, n) complex stays small for a few hundred DOF
        b = slice(a, a + 100)
        Z = K[None] - w[b, None, None] ** 2 * M[None] + 1j * w[b, None, None] * C[None]
        H[b] = np.linalg.solve(np.nan_to_num(Z), np.broadcast_to(f, (Z.shape[0], len(M)))[..., None])[..., 0]
    H[~np.isfinite(w)] = np.nan
    return H[:, list(read)].T


def model_receptances(crank, frequency_hz, stations=(0, -1), damping_ratio: float | None = None,
                      condensed=None) -> np.ndarray:
    """The free-free model's receptances (rad/N·m) at the pulley and flywheel ends to a torque at
    the pulley end, with the description's modal damping ratio on every elastic mode (and a chain
    file's stated dampers and loss factors): (2, frequencies) complex. The lumped chain's
    (``stations``: 0-based chain stations), or, given ``condensed``, the condensed crank's (its
    front and rear masters' θx)."""
    K, M, C, rows = free_model(crank, damping_ratio, condensed)
    read = [rows[0], rows[-1]] if condensed is not None else [rows[s] for s in stations]
    return free_receptances(K, M, C, rows[0], read, frequency_hz)


#: An FRF's form -> the power of iω that takes a receptance to it
FORM_POWERS = {"receptance": 0, "mobility": 1, "accelerance": 2}


@dataclass
class FrfOverlay:
    """A measured FRF and the model's at the same station, to the same reference, in the same form.

    Attributes
    ----------
    station : str
        ``node:direction`` of the response (node n the model's n-th station).
    frequency_hz : ndarray
    measured, model : ndarray, complex
        In SI, ``unit`` per ``reference_unit``.
    form : str
        ``'receptance'``, ``'mobility'`` or ``'accelerance'``.
    """

    station: str
    frequency_hz: np.ndarray
    measured: np.ndarray
    model: np.ndarray
    form: str
    unit: str
    reference_unit: str

    def plot(self, magnitude_ax, phase_ax, modes_hz=()):
        """Magnitude (log) and phase against frequency, measured as dots, the model as a line."""
        for ax in (magnitude_ax, phase_ax):
            for f in modes_hz:
                ax.axvline(f, color="0.85", lw=0.8, zorder=0)
        magnitude_ax.semilogy(self.frequency_hz, np.abs(self.measured), ".", ms=2, color="C0", label="measured")
        magnitude_ax.semilogy(self.frequency_hz, np.abs(self.model), "-", lw=1.2, color="C3", label="model")
        magnitude_ax.set_ylabel(f"|{self.form}| [{self.unit}/{self.reference_unit}]", fontsize=8)
        magnitude_ax.set_title(f"FRF at {self.station}: magnitude", fontsize=9)
        magnitude_ax.legend(fontsize=7)
        phase_ax.plot(self.frequency_hz, np.degrees(np.angle(self.measured)), ".", ms=2, color="C0")
        phase_ax.plot(self.frequency_hz, np.degrees(np.angle(self.model)), "-", lw=1.2, color="C3")
        phase_ax.set_ylim(-190, 190)
        phase_ax.set_yticks([-180, -90, 0, 90, 180])
        phase_ax.set_ylabel("phase [deg]", fontsize=8)
        phase_ax.set_title(f"FRF at {self.station}: phase", fontsize=9)
        for ax in (magnitude_ax, phase_ax):
            ax.set_xlabel("frequency [Hz]", fontsize=8)


def frf_overlays(crank, frfs, source: str = LUMPED17, condensed=None) -> tuple[list, str]:
    """Each measured FRF with the free-free model's at its station (node n the model's n-th
    station, as :func:`fetorsion.studies.pairing.paired_mac` reads them) to the measured reference, in the measured form
    (the model's receptance times (iω)^p), and why any is left out."""
    from ..measured.modal import frf_matrix

    frequency, _, stations, form, _ = frf_matrix(frfs)
    K, M, C, rows = free_model(crank, condensed=condensed if source != LUMPED17 else None)
    reference = frfs[0].reference
    if not 1 <= reference[0] <= len(rows):
        return [], f"the FRFs' reference node {reference[0]} is not one of the model's {len(rows)} stations"
    nodes = [n for n, _ in stations]
    inside = [k for k, n in enumerate(nodes) if 1 <= n <= len(rows)]
    H = free_receptances(K, M, C, rows[reference[0] - 1], [rows[nodes[k] - 1] for k in inside], frequency)
    H = H * (1j * 2 * np.pi * np.asarray(frequency)) ** FORM_POWERS[form]
    out = [FrfOverlay(f"{nodes[k]}:{stations[k][1]}", np.asarray(frequency), np.asarray(frfs[k].ordinate), h,
                      form, frfs[k].unit, frfs[k].reference_unit) for k, h in zip(inside, H)]
    left = [f"{n}:{d}" for k, (n, d) in enumerate(stations) if k not in inside]
    return out, (f"no model station for {', '.join(left)}" if left else "")
