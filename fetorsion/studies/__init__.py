"""Studies: many runs of the stages below, varying the description's inputs.

- :mod:`.sensitivity`: one input at a time, the corner band of f1, the FE check.
- :mod:`.sampling`: the ``[uncertainty]`` inputs and their samples (SALib's Sobol' and
  Morris designs, Monte Carlo, grid).
- :mod:`.models`: the model a sample runs (lumped chain or coarse 3D FE of the variant).
- :mod:`.runner`: the runs on a Dask cluster (local by default), each result stored as it
  finishes in a bounded SQLite store, keyed by a hash of the sample.
- :mod:`.study`: ``run_study`` / ``run_crank_study``: bands, SALib's indices, the report folder.
- :mod:`.variants`: ``with_values``, a description with some fields changed.
- :mod:`.calibration`, :mod:`.calibration_fit`: ``run_calibration``, the ``[uncertainty]`` inputs
  fitted to measured natural frequencies (regularised least squares, an MCMC posterior);
  :mod:`.calibrated`: the calibrated description written as a new file.
"""
