"""
A six-cylinder diesel from its chain
====================================

A six-cylinder diesel from the literature, from its chain: natural frequencies, the major-order
resonance and the vibratory torque beside the publication's curves.

The engine is the MWM six-cylinder diesel of Mendes, Meirelles & Zampieri (2008),
doi:10.1243/14644193JMBD126; chain, engine data and damping as openTorsion's ICE example
transcribes them (examples/mendes2008/, every number's source in its comments); the cylinder
pressure is fetorsion's synthetic cycle scaled to the published curve's 15.2 MPa peak. The
published values are the peaks of the article's Fig. 31 and 32 as openTorsion digitised them
(the digitised curves themselves are not copied into this project). No input is adjusted to
match: the differences printed are what they are (docs/chain-files.md discusses them).

Usage: python examples/mendes2008_six_cylinder.py [OUT.png]
"""

import sys
from pathlib import Path

import numpy as np

import fetorsion
from fetorsion.excitation.campbell import run_campbell
from fetorsion.response.forced import run_response

# Peaks of the article's vibratory-torque curves (N m, rpm), read from openTorsion's digitisation
# (opentorsion/examples/torsional_vibration_data_fig31.csv / fig32.csv, commit d5b91d89).
PUBLISHED = {31: ("cylinder 6 - flywheel", 9477.0, 2149.0), 32: ("pulley - gear train", 841.0, 2148.0)}

# The repository's root, so that the script runs from any folder (the documentation builds the
# gallery from inside examples/).
ROOT = Path(fetorsion.__file__).resolve().parents[1]

chain = fetorsion.load(ROOT / "examples/mendes2008/mwm6_chain.toml")
modes = fetorsion.lumped(chain)
print(modes.table())

camp = run_campbell(chain)
major = max((c for c in camp.crossings if c.in_range and c.mode == 1), key=lambda c: c.severity)
print(f"major-order resonance: order {major.order:g} x mode 1 ({major.frequency_hz:.1f} Hz) at {major.rpm:.0f} rpm")

rpm = np.arange(1000.0, 2550.0 + 1e-9, 5.0)  # finer than the 25 rpm steps of openTorsion's example
res = run_response(chain, rpm=rpm)
worst = int(np.argmax(res.section_torque_nm.max(axis=0)))
i = int(np.argmax(res.section_torque_nm[:, worst]))
print(f"most loaded section: {res.labels[worst]}-{res.labels[worst + 1]}, "
      f"{res.section_torque_nm[i, worst]:.0f} N m at {rpm[i]:.0f} rpm")

for fig, section in ((31, len(res.labels) - 2), (32, 0)):  # cyl 6-flywheel; pulley-gear train
    where, peak, peak_rpm = PUBLISHED[fig]
    j = int(np.argmax(res.section_torque_nm[:, section]))
    model, model_rpm = res.section_torque_nm[j, section], rpm[j]
    print(f"Fig. {fig} ({where}): published peak {peak:.0f} N m at {peak_rpm:.0f} rpm; fetorsion {model:.0f} N m "
          f"at {model_rpm:.0f} rpm ({100 * (model / peak - 1):+.1f} %, {model_rpm - peak_rpm:+.0f} rpm)")

# The vibratory torque of every section against speed, with the published peaks marked.
ax = res.plot()
for fig, section in ((31, len(res.labels) - 2), (32, 0)):
    where, peak, peak_rpm = PUBLISHED[fig]
    ax.plot(peak_rpm, peak, "kx", ms=9)
    ax.annotate(f"Fig. {fig}", (peak_rpm, peak), textcoords="offset points", xytext=(6, 4))
if len(sys.argv) > 1:
    ax.figure.savefig(sys.argv[1], dpi=120)
    print(f"picture -> {sys.argv[1]}")
