"""Web stiffness: the section formulas of eq. (4), (5), (7), the classical web formulas
(Carter, Ker Wilson, a beam bound), the FE throw stiffness with its cache and the computed
BICERA-style chart, all behind one registry of web methods (:mod:`.methods`).

Takes a :class:`~fetorsion.description.model.Crank`; hands equivalent lengths (m) to the
lumped stage. Uses the solid and FE stages for its FE methods.
"""
