"""Stage 2, the solid: the analytic web outline, the Gmsh (OpenCASCADE) crank solid and its
curved second-order tet mesh, with the mesh file formats.

Takes a :class:`~fetorsion.description.model.Crank`; hands a
:class:`~fetorsion.solid.mesh.CrankMesh` (numpy arrays, SI) to the FE stage. Gmsh runs in a
child process (:mod:`.isolate`) so that its aborts become ordinary errors.
"""
