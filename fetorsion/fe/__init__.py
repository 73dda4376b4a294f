"""Stage 3a, finite elements: tet mesh arrays, P2 elasticity assembly, the sparse
shift-invert eigen-solver, rigid attachments and ties, the modal analysis, mode labels and
the crank's FE job (:mod:`.crankfe`).

Takes a :class:`~fetorsion.solid.mesh.CrankMesh`; hands a
:class:`~fetorsion.fe.modal.ModalResult` and :class:`~fetorsion.modes.TorsionalModes` to
the excitation stage. Later: bearings and the condensed (reduced) crank.
"""
