"""Stage 6, design: what an engineer decides from the response — the vibratory stress at every
fillet with its concentration factors from fetorsion's own FE (:mod:`.stress`, :mod:`.scf`),
torsional dampers from Den Hartog's optima to a damper tuned on the whole crank
(:mod:`.dampers`), and the verdict against the description's limits (:mod:`.verdict`).

Takes a crank or chain, its response (:mod:`fetorsion.response`) and the FE stages for the
stress concentration; hands results with ``.plot()`` and ``.to_dict()`` to the report.
"""
