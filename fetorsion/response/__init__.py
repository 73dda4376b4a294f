"""Stage 5, response: the forced torsional response of a chain over the speed range
(:mod:`.forced`, dampers included as the model has them), its synthesis over orders into
periodic signals and their extremes (:mod:`.synthesis`), and the condensed FE crank's coupled
torsion-bending response in its bearings (:mod:`.coupled`).

Takes a crank with ``[excitation]`` and a lumped model; hands a
:class:`~fetorsion.response.forced.ResponseResult` to the design stage and the report.
"""
