"""Stage 3a, finite elements: tet mesh arrays, P2 elasticity assembly, the sparse
shift-invert eigen-solver, rigid attachments and ties, the modal analysis, mode labels and
the crank's FE job (:mod:`.crankfe`).

Takes a :class:`~fetorsion.solid.mesh.CrankMesh`; hands a
:class:`~fetorsion.fe.modal.ModalResult` and :class:`~fetorsion.modes.TorsionalModes` to
the excitation stage. Bearings and the condensed crank: :mod:`.couplings` (distributing
couplings), :mod:`.substructure` (Craig–Bampton from one factorisation, the full model in
supports), :mod:`.condensed` (the crank's masters, attachments and bearings on them, ``.npz``).
"""
