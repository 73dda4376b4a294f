"""A propulsion line's components as a class society's torsional vibration calculation (TVC) states
them: a shaft section's design feature (the rule's factor C_K), the propeller (inertia with its
entrained water, damping by a named model, blade-order excitation) and a flexible coupling from
its maker's data sheet. Pure data and arithmetic in SI, read by :mod:`.network` and used by the
later stages (:mod:`fetorsion.design.shaft_limits`); docs/propulsion-tvc.md has the equations.

The factor C_K of IACS UR M68 [IACSM68], by the shaft's feature. The rule's own text was not
read; the symbols, the size factor C_D = 0.35 + 0.93 d^-0.2 and the first three rows of the
table (integral flange and straight sections 1.0, shrink-fit coupling 1.0, keyway with tapered
connection 0.6) were read in Lloyd's Register's naval rules, which carry the same limits
[LRNavalTV] (Vol 2, Pt 5, Ch 1, §3.1, Table 1.3.1). The other rows are the rule's values as
they are commonly restated, not confirmed from a readable text here.
"""

from __future__ import annotations

#: C_K of each shaft feature (a name a network file's ``[[chain.shafts]]`` may give as
#: ``feature``): intermediate shafts, thrust shafts outside the engine, propeller shafts.
CK_FACTORS: dict[str, float] = {
    "integral_flange": 1.0,        # intermediate shaft, integral coupling flange, straight sections [LRNavalTV]
    "shrink_fit": 1.0,             # intermediate shaft, shrink-fit coupling [LRNavalTV]
    "keyway_tapered": 0.60,        # intermediate shaft, keyway, tapered connection [LRNavalTV]
    "keyway_cylindrical": 0.45,    # intermediate shaft, keyway, cylindrical connection (unconfirmed)
    "radial_hole": 0.50,           # intermediate shaft, radial hole (unconfirmed)
    "longitudinal_slot": 0.30,     # intermediate shaft, longitudinal slot (unconfirmed)
    "thrust_collar": 0.85,         # thrust shaft, both sides of the thrust collar (unconfirmed)
    "thrust_roller_bearing": 0.85,  # thrust shaft, in way of a roller thrust bearing (unconfirmed)
    "propeller_keyless": 0.55,     # propeller shaft, flange-mounted or keyless taper-fitted propeller (unconfirmed)
    "propeller_keyed": 0.55,       # propeller shaft, key-fitted propeller (unconfirmed)
    "propeller_forward": 0.80,     # propeller shaft, aft-most bearing's forward end to the forward stern-tube seal
}
