"""Every default that more than one stage uses, in one place (SI units)."""

DEFAULT_WEB_METHOD = "carter"
# FE mesh: global element size; fillets and drillings get finer (fetorsion.solid.mesh).
DEFAULT_MESH_SIZE = 0.010  # m
# Coarse FE checks (sensitivity of f1 on the crank without fillets and drillings).
CHECK_MESH_SIZE = 0.025  # m
DEFAULT_MODES = 20  # elastic FE modes
DEFAULT_PARTITION = 17  # lumped DOF for Campbell and forced response
#: The fast model's name wherever a model is chosen (``--source``, ``--model``): the 17-DOF
#: lumped chain of the default partition.
LUMPED17 = f"lumped{DEFAULT_PARTITION}"
# Modal damping ratio when the description's [excitation] gives none: a design-rule value for
# an undamped steel crank.
DEFAULT_DAMPING_RATIO = 0.02
# The band of the crank's modal damping ratio when the description states none: dynamic
# magnifiers Q = 1/(2ζ) of 30 to 60 for an undamped crank system, as engine practice states it
# (no published table of them was read: a description should give its own band and source).
# The fatigue verdict is given at its low end (the worst case) as well.
DEFAULT_DAMPING_BAND = (1.0 / 120.0, 1.0 / 60.0)
DEFAULT_DAMPING_BAND_SOURCE = "default: dynamic magnifier Q = 30-60 of an undamped crank (stated engine practice; no published table read)"
# The forced response and the verdict reach past the rated (top) speed to overspeed, as crank
# fatigue checks do (a governor's or a driver's overrun): this multiple of the top speed.
DEFAULT_OVERSPEED = 1.1
DEFAULT_SPEED_STEPS = 300  # speeds across the operating range in the forced response
# A damper's ring inertia over the equivalent inertia of the mode it damps (Den Hartog's μ): a
# common pulley-damper size.
DEFAULT_INERTIA_RATIO = 0.25
DEFAULT_TORSIONAL_MODES = 3  # torsional modes labelled, tabulated and in the Campbell diagram
# Runs of a study by method (Sobol': base samples, N·(inputs + 2) runs; Morris: trajectories;
# grid: levels per input): a 5-95 % band, indices with confidence intervals of a few hundredths.
DEFAULT_STUDY_SAMPLES = {"sobol": 512, "morris": 20, "montecarlo": 2000, "grid": 5}

#: Working cycles a steady time-domain run keeps after its transients have settled.
DEFAULT_TRANSIENT_CYCLES = 8
#: Teeth of the simulated toothed wheel whose edges the time domain's order tracking reads.
DEFAULT_TEETH = 120
#: Crank angle per time step at a time-domain run's top speed, degrees.
DEFAULT_STEP_DEG = 0.5
# A nonlinear element's friction (Coulomb) sticks through a spring this many times the stiffest of
# its stages (an elastic-perfectly-plastic, Jenkins, element): stiff enough that the loop is the
# Coulomb parallelogram within 1/STICK_FACTOR of its width at twists of a stage's size.
DEFAULT_STICK_FACTOR = 20.0
# The nonlinear time domain's integrators, the default first: the compiled Dormand-Prince kernel
# (response/compiled.py, friction as exact Jenkins elements), then scipy solve_ivp's (friction by
# Bouc-Wen's rate law; LSODA switches between Adams and BDF by itself), kept as the cross-check.
NONLINEAR_METHODS = ("compiled", "LSODA", "Radau", "BDF")
#: The run-up of ``fetorsion run``'s time-domain section, rpm/s: the rate of the issue's benchmark. Slow
#: for the crank's own modes (their passage parameter α/Γ² = q (dΩ/dt) / (ζω)² is ~0.1–0.2 at 500 Hz and
#: ζ = 0.02), fast for a driveline's (the report states α/Γ² of each crossing it compares), and a whole run
#: stays a few seconds of computation (a slower rate costs proportionally more steps).
DEFAULT_RUNUP_RATE = 1000.0
