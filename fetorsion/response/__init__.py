"""Stage 5, response: the forced torsional response over the speed range (:mod:`.forced`).
Later: dampers, synthesis over orders, vibratory stress and limits.

Takes a crank with ``[excitation]`` and a lumped model; hands a
:class:`~fetorsion.response.forced.ResponseResult` to the report.
"""
