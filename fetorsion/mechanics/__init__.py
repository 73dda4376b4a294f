"""Crank-train mechanics of the other source papers, beside the torsion pipeline: balancing
(:mod:`.balance`), flywheel sizing (:mod:`.flywheel`), planetary cranks (:mod:`.planetary`),
their small input file (:mod:`.input`) and their reports (:mod:`.reports`).
"""
