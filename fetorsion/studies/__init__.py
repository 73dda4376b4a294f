"""Studies: many runs of the stages below, varying the description's inputs: one-at-a-time
sensitivity and the f1 band (:mod:`.sensitivity`). Later: Monte Carlo and Sobol' studies on
Dask.
"""
