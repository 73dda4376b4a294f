"""The figure of a forced response (:class:`fetorsion.response.forced.ResponseResult`): the pulley's
angle and twist and the most loaded section's torque against speed, a compared curve beside them."""

from __future__ import annotations

import numpy as np


def plot_response(result, ax):
    """Pulley angle and twist, and the most loaded section's torque (or the compared one), against
    speed. Returns the Axes of the angles.

    Parameters
    ----------
    result : ResponseResult
        The response.
    ax : matplotlib Axes or None
        Where the angles are drawn (then without the torque); None: a new figure with both panels.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        fig = plt.figure(figsize=(9, 7))
        a1, a2 = fig.subplots(2, 1, sharex=True)
    else:
        fig, a1, a2 = ax.figure, ax, None
    a1.plot(result.rpm, result.pulley_angle_deg, label="pulley angle (absolute)")
    a1.plot(result.rpm, result.pulley_twist_deg, label="pulley twist against flywheel end")
    a1.set_ylabel("vibratory angle [deg]")
    a1.legend(fontsize=8)
    a1.set_title(f"{result.name}\nforced response, {result.damping_text().replace('zeta', 'ζ')}", fontsize=10, wrap=True)
    c = result.compare
    if c and c["quantity"] == "pulley_angle_deg":
        a1.plot(c["rpm"], np.asarray(c["value"]) * c["to_si"], "k--", label=f"{c['name']} (compared)")
        a1.legend(fontsize=8)
    if a2 is None:
        a1.set_xlabel("engine speed [rpm]")
        return a1
    worst = np.argmax(result.section_torque_nm.max(axis=0))
    if c and c["quantity"] == "section_torque_nm":
        worst = c["section"]
        a2.plot(c["rpm"], np.asarray(c["value"]) * c["to_si"], "k--", label=f"{c['name']} (compared)")
    a2.plot(result.rpm, result.section_torque_nm[:, worst], color="C3",
            label=f"section {result.section_labels[worst]}: amplitude (½ peak-to-peak)")
    if result.section_torque_peak_nm is not None:
        a2.plot(result.rpm, result.section_torque_peak_nm[:, worst], color="C3", ls=":",
                label="largest |torque| over the cycle (orders summed with phases)")
    a2.set_ylabel("vibratory torque [N m]")
    a2.set_xlabel("engine speed [rpm]")
    a2.legend(fontsize=8)
    fig.tight_layout()
    return a1


def compare_lines(c: dict | None) -> list[str]:
    """Table lines of a comparison (none without one)."""
    if not c:
        return []
    unit = "N m" if c["quantity"] == "section_torque_nm" else "deg"
    return [f"  compared with {c['name']} ({c['where']}):",
            f"    curve peak {c['curve_peak']:.4g} {unit} at {c['curve_peak_rpm']:.0f} rpm; model peak "
            f"{c['model_peak']:.4g} {unit} at {c['model_peak_rpm']:.0f} rpm: {c['peak_difference_percent']:+.1f} % "
            f"and {c['model_peak_rpm'] - c['curve_peak_rpm']:+.0f} rpm; model at the curve's peak speed "
            f"{c['model_at_curve_peak_rpm']:.4g} {unit}"]
