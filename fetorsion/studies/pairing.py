"""Measured natural frequencies paired with a model's: the nearest model mode to each, and the
MAC of the fitted shapes against the paired model shapes at the measured stations."""

from __future__ import annotations

import numpy as np

from ..errors import FetorsionError


def pair_frequencies(measured_hz, model_hz, model_kinds=None) -> tuple[np.ndarray, list]:
    """The nearest model frequency (and its kind) to each measured one."""
    j = nearest_modes(measured_hz, model_hz)
    kinds = list(model_kinds) if model_kinds is not None else ["torsional"] * len(model_hz)
    return np.asarray(model_hz, float)[j], [kinds[i] for i in j]


def nearest_modes(measured_hz, model_hz) -> np.ndarray:
    """Index of the nearest model frequency to each measured one."""
    measured_hz, model_hz = np.asarray(measured_hz, float), np.asarray(model_hz, float)
    if model_hz.size == 0:
        raise FetorsionError("compare: the model has no elastic mode to pair the measured frequencies with")
    return np.argmin(np.abs(model_hz[None, :] - measured_hz[:, None]), axis=1)


def paired_mac(estimate, model_shapes: np.ndarray, paired: np.ndarray) -> tuple[np.ndarray | None, str]:
    """MAC of each fitted shape of ``estimate`` with its paired model shape, at the measured stations.

    A measured response node n is the model's station n (1-based, the chain's order from the
    pulley end), as the model's own receptances are written (:func:`fetorsion.studies.comparison.model_predictions`).

    Parameters
    ----------
    estimate : ModalEstimate
        Fitted modes, ``shapes`` (stations, modes) at ``stations`` ((node, direction), ...).
    model_shapes : ndarray, shape (modes, model stations)
        The model's mode shapes, row j that of model mode j.
    paired : ndarray of int
        The model mode paired with each fitted mode.

    Returns
    -------
    mac : ndarray (fitted modes,) or None
        None when fewer than two stations were measured (a MAC of one component is 1 whatever
        the shapes) or a node is not a model station.
    note : str
        Why there is no MAC, else empty.
    """
    from ..measured.modal import mac

    nodes = [int(n) for n, _ in estimate.stations]
    if len(set(nodes)) < 2:
        return None, "shapes measured at fewer than two stations"
    stations = model_shapes.shape[1]
    outside = [n for n in nodes if not 1 <= n <= stations]
    if outside:
        return None, f"measured node {outside[0]} is not one of the model's stations 1-{stations}"
    model = model_shapes[np.ix_(paired, np.asarray(nodes) - 1)].T  # (measured stations, fitted modes)
    return np.array([mac(estimate.shapes[:, i], model[:, i]) for i in range(len(paired))]), ""
