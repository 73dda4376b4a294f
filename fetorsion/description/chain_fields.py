"""The tables of a chain or network file (inertias and springs given directly, a network's
stations, shafts, gears, propellers, couplings and nonlinear elements), as data: the crank's
tables a chain file shares (``[engine]``, ``[excitation]``, ``[[dampers]]`` ...) are
:mod:`fetorsion.description.fields`' own. The chain-format page is generated from them."""

from __future__ import annotations

from .defaults import DEFAULT_PARTITION, DEFAULT_WEB_METHOD
from .fields import (CRANK_SECTIONS, DAMPERS, DISTRIBUTIONS, ENGINE, EXCITATION, LIMITS, META, TANGENTIAL_HARMONICS, UNCERTAINTY, UNITS,
                     Field, Section, one_of, schema)
from .marine import CK_FACTORS, PROPELLER_DAMPING, SIGMA_B_CAP_PA
from .model import PARTITIONS, WEB_METHOD_NAMES


CHAIN = Section("chain", "A torsional chain given directly: inertias joined by springs, station 1 at the front "
                "(pulley).", (
    Field("name", "name used in tables and plots; default the file's name", "a string"),
    Field("inertias_kgm2", "the stations' inertias, kg·m²; with an engine each must already hold its cylinder's "
          "rotating mass and mean reciprocating inertia (m_rot R² + m_rec R²/2)", "at least 2, each > 0"),
    Field("stiffnesses_nm_per_rad", "the springs between consecutive stations, N·m/rad",
          "one fewer than inertias, each > 0"),
    Field("labels", "a name for each station; default `inertia 1`, `inertia 2`, ...",
          "one string per inertia"),
    Field("absolute_damping_nms_per_rad", "viscous damper from each inertia to ground, N·m·s/rad (the "
          "diagonal of C)", "one per inertia, each >= 0"),
    Field("relative_damping_nms_per_rad", "viscous damper across each spring, N·m·s/rad (tridiagonal C)",
          "one per spring, each >= 0"),
    Field("loss_factors", "hysteretic loss factor η of each spring (complex stiffness k(1 + iη), marine and "
          "diesel practice)", "one number, or one per spring; each >= 0"),
    Field("cylinder_stations", "the station (1-based, or its name in a network) that carries each cylinder's "
          "whole torque; several may share one", "one per cylinder of `[engine]`, each 1..number of inertias; "
          "needs `[engine]`"),
    Field("constant_speed", "network form: `true` for a line held at a constant speed anywhere in its "
          "`[excitation]` range (a generating set on its governor, the range its band): it runs continuously across "
          "the band, so a speed barred there (up to the rated speed, the range's top) fails the shafts' verdict; "
          "default false", "true or false"),
    Field("stations", "network form, instead of the lists above: `[[chain.stations]]` (below)",
          "at least 2 (with a crank's: any); not with the list keys"),
    Field("shafts", "network form: `[[chain.shafts]]` (below)", "the stations all joined, no gear loop; "
          "optional with a crank"),
    Field("gears", "network form: `[[chain.gears]]` (below); optional", "—"),
    Field("nonlinear", "network form: `[[chain.nonlinear]]` (below); optional", "—"),
    Field("cranks", "network form: `[[chain.cranks]]` (below), a crank description as a part of the network; "
          "optional", "at most one"),
    Field("propellers", "network form: `[[chain.propellers]]` (below); optional", "—"),
    Field("couplings", "network form: `[[chain.couplings]]` (below); optional", "—"),
), required=True)

CRANKS = Section("chain.cranks", "Network form: a crank description as one part of the network, by its lumped "
                 "model. Its stations come first (its pulley is station 1, the speed the orders refer to), named "
                 "`<name>.<label>` with the partition's labels (17 DOF: `J1`, `W1`, `P1`, …; "
                 "docs/networks-and-transients.md), and `<name>.pulley` / `<name>.flywheel` name its first and last "
                 "station; shafts, gears and nonlinear elements join them to the other stations. Without an "
                 "`[engine]` of the chain file's own, the crank's `[engine]` and `[excitation]` drive its pins "
                 "(spread over the stations as its lumped model spreads them).", (
    Field("name", "the crank's name, the prefix of its stations' names; default `crank`", "no `.`, not `ground`"),
    Field("file", "the crank description (.toml), relative to this chain file's folder", "an existing crank "
          "description (not a chain file), valid by its own rules, without `[[dampers]]`"),
    Field("dof", f"its lumped partition, or `condensed`: the condensed FE crank in its bearings (the engine model of "
          f"`fetorsion run`; the forced response and `fetorsion run` of the network solve it, its other stations "
          f"are the {DEFAULT_PARTITION}-DOF partition's names and only its pulley and flywheel may be joined); "
          f"default {DEFAULT_PARTITION}", one_of(PARTITIONS) + " or `condensed`"),
    Field("stiffness", f"its web-stiffness method; default `{DEFAULT_WEB_METHOD}`", one_of(WEB_METHOD_NAMES)),
), array=True)

STATIONS = Section("chain.stations", "Network form: the stations, by name (docs/networks-and-transients.md).", (
    Field("name", "the station's name, used by shafts, gears and `cylinder_stations`", "unique; not `ground`"),
    Field("inertia_kgm2", "its inertia, kg·m²; 0 for a gear whose inertia the gear it meshes with carries",
          ">= 0; > 0 somewhere in every group of stations joined by gears"),
    Field("damping_nms_per_rad", "a viscous damper to ground, N·m·s/rad; default 0", ">= 0"),
), array=True)
SHAFTS = Section("chain.shafts", "Network form: springs between two stations, or a station and `ground`.", (
    Field("between", "the two stations it joins (`ground` for a spring to ground)", "two different names"),
    Field("stiffness_nm_per_rad", "N·m/rad", "> 0"),
    Field("damping_nms_per_rad", "viscous damper across it, N·m·s/rad; default 0", ">= 0"),
    Field("loss_factor", "hysteretic loss factor η; default 0", ">= 0"),
    Field("diameter_m", "the shaft section's outer diameter, m, where IACS UR M68's stress limits are to judge "
          "it (docs/propulsion-tvc.md)", "> 0; with `tensile_strength_pa` and `feature`"),
    Field("bore_m", "its bore, m; default 0", ">= 0, < `diameter_m`"),
    Field("tensile_strength_pa", "the specified minimum tensile strength σ_B of its material, Pa (the rule caps it: "
          "carbon steel 760 N/mm², alloy 800)", "> 0; with `diameter_m`"),
    Field("feature", "its design feature, which sets the rule's factor C_K",
          one_of(tuple(CK_FACTORS)) + "; with `diameter_m`"),
    Field("material", "`carbon` (carbon and carbon-manganese steel) or `alloy`: which cap σ_B takes; default carbon",
          one_of(tuple(SIGMA_B_CAP_PA))),
), array=True)
PROPELLERS = Section("chain.propellers", "Network form: a propeller at a station. The station's `inertia_kgm2` is "
                     "its dry inertia; the network takes it times (1 + `entrained_water_share`) and adds its damping "
                     "to ground, linearised at `damping_speed_rpm` (docs/propulsion-tvc.md).", (
    Field("station", "the station it sits at", "a station of the network (not a crank's), inertia > 0"),
    Field("blades", "number of blades z: it excites orders z, 2z, …", "integer >= 2"),
    Field("entrained_water_share", "the water turning with it, as a share of its dry inertia (its maker's figure "
          "or a regression such as Parsons 1983's)", ">= 0, required: no default is assumed"),
    Field("rated_torque_nm", "its mean torque at the rated speed, N·m", "> 0"),
    Field("rated_speed_rpm", "the rated (maximum continuous) shaft speed, rpm", "> 0"),
    Field("torque_exponent", "n of the law Q = Q_r (n/n_r)^n; default 2 (the propeller law)", "> 0"),
    Field("damping_model", "the damping model: `propeller_law`, c = n Q/ω (Archer's, Frahm's and Schwanecke's are "
          "not offered: no published worked value was found to test them); default propeller_law",
          one_of(tuple(PROPELLER_DAMPING))),
    Field("damping_speed_rpm", "the speed at which the damping is linearised, rpm: the response takes this one "
          "constant damping at every speed (a published case's stated damping); without it the forced response "
          "takes the law's damping at each speed of its sweep, and the modes' damping and the time domain "
          "the rated speed's", "> 0"),
    Field("blade_order_shares", "the blade-order torque amplitudes as shares of the mean torque (orders z, 2z, …)",
          "a list, each >= 0; optional"),
    Field("passage_rate_rpm_per_s", "the rate the engine's speed (station 1's) passes a barred range at in the "
          "time-domain check against τ_T, rpm/s (the engine's acceleration); default 10 rpm/s, ASSUMED",
          "> 0"),
    Field("name", "label; default the station's name", "a string"),
    Field("source", "where the numbers come from", "a string"),
), array=True)
COUPLINGS = Section("chain.couplings", "Network form: a flexible coupling from its maker's data sheet, between two "
                    "stations. It joins them as a spring of the sheet's dynamic stiffness with the loss factor "
                    "η = ψ/2π, both at `operating_temperature_c` (linear between the sheet's two temperatures, the "
                    "nearer one held outside them).", (
    Field("between", "the two stations it joins", "two different stations"),
    Field("stiffness_nm_per_rad", "dynamic torsional stiffness C_Tdyn at the sheet's nominal temperature, N·m/rad",
          "> 0"),
    Field("relative_damping", "relative damping ψ at the nominal temperature (energy dissipated a cycle over the "
          "elastic energy at its amplitude)", ">= 0"),
    Field("temperature_c", "the sheet's nominal temperature, °C", "a finite number"),
    Field("warm_stiffness_nm_per_rad", "C_Tdyn at `warm_temperature_c`, N·m/rad; optional",
          "> 0; with the other two warm fields"),
    Field("warm_relative_damping", "ψ at `warm_temperature_c`", ">= 0; with the other two warm fields"),
    Field("warm_temperature_c", "the sheet's warm temperature, °C", "> `temperature_c`"),
    Field("operating_temperature_c", "the temperature the network takes the coupling at, °C; default "
          "`temperature_c`", "a finite number"),
    Field("permissible_vibratory_torque_nm", "the sheet's permissible vibratory torque amplitude, N·m; optional",
          ">= 0"),
    Field("permissible_power_w", "the sheet's permissible heat (power loss) P_KV, W; optional", ">= 0"),
    Field("ambient_c", "the ambient temperature at which P_KV holds, °C", "a finite number; needs "
          "`permissible_power_w`"),
    Field("max_temperature_c", "the rubber's permissible continuous temperature, °C, which P_KV reaches from "
          "`ambient_c` (the heat balance, docs/propulsion-tvc.md); default `warm_temperature_c`",
          "> `ambient_c`; needs `permissible_power_w`"),
    Field("maximum_torque_nm", "the sheet's maximum torque T_Kmax for transient events (a start, a stop, a "
          "resonance passed), N·m: the time-domain passages judge the coupling's largest torque against it; optional",
          ">= 0"),
    Field("stiffness_tolerance", "the sheet's tolerance of the dynamic stiffness as a share (0.15: ±15 %); the "
          "TVC then adds the configurations with the stiffness at both ends; optional", ">= 0 and < 1"),
    Field("name", "label; default `coupling`", "a string"),
    Field("source", "the data sheet", "a string"),
), array=True)
START = Section("start", "A network file's engine start: the time-domain run from the speed the engine fires "
                "steadily at up to the lowest speed of `[excitation]`'s range, every shaft section's stress "
                "against UR M68's τ_T (the passage of the resonances below the range, a generator set's start; "
                "docs/propulsion-tvc.md). Needs `[engine]` and an `[excitation]` whose load is a mean indicated "
                "pressure.", (
    Field("from_rpm", "the speed the run starts at (station 1's), rpm: the speed the engine fires steadily at "
          "after its starter", "> 0, < the lowest speed of `[excitation]` speed_range_rpm"),
    Field("rate_rpm_per_s", "the start's acceleration, rpm/s of station 1; a slower start is the more severe",
          "> 0"),
    Field("imep_pa", "the mean indicated pressure of every cylinder during the start, Pa: its friction and the "
          "torque that accelerates the line (no external load)", "> 0"),
    Field("source", "where the numbers come from", "a string"),
))
STOP = Section("stop", "A network file's engine stop: the fuel cut, every cylinder motored, the line coasting "
               "down in the time domain, every shaft section's stress against UR M68's τ_T (τ_C above λ 0.8), as "
               "the start (docs/propulsion-tvc.md). Needs `[engine]` and an `[excitation]` by the synthetic cycle "
               "or a harmonic table with a column at p_mi 0.", (
    Field("from_rpm", "the speed the fuel is cut at (station 1's), rpm; default the top of `[excitation]` "
          "speed_range_rpm", "> `to_rpm`"),
    Field("to_rpm", "the speed the run ends at, rpm", "> 0"),
    Field("rate_rpm_per_s", "the coast-down's deceleration, rpm/s of station 1 (the friction torque over the "
          "line's inertia); a slower stop is the more severe", "> 0"),
    Field("source", "where the numbers come from", "a string"),
))
GEARS = Section("chain.gears", "Network form: rigid gear meshes; a branch is solved with the gear constraint "
                "(K_r = TᵀKT) at the reference speed of the first station.", (
    Field("between", "the driving and the driven station", "two different stations"),
    Field("ratio", "speed of the second station over the first", "> 0"),
), array=True)

NONLINEAR = Section("chain.nonlinear", "Network form: a nonlinear element between two stations (or a station and "
                    "`ground`): a multi-stage clutch damper or a dual-mass flywheel's arc springs. Its elastic torque "
                    "is piecewise linear and odd in the twist x (first station's angle less the second's), with "
                    "Coulomb friction in parallel that sticks through a stiff spring (an elastic-perfectly-plastic "
                    "element, docs/networks-and-transients.md). The time domain integrates it as it is; modes, "
                    "Campbell and the forced response take the stage's stiffness at `preload_nm`.", (
    Field("name", "the element's name (its section label)", "a string"),
    Field("between", "the two stations it joins (`ground` for one end to ground)", "two different names"),
    Field("stiffnesses_nm_per_rad", "the stages' stiffnesses, from the first (small twists) outwards, N·m/rad",
          "a list, each > 0"),
    Field("stage_angles_deg", "the twist at which each stage after the first begins, deg",
          "one fewer than the stiffnesses, each > 0, ascending"),
    Field("friction_torque_nm", "the Coulomb friction torque (the hysteresis loop's half height), N·m; default 0",
          ">= 0"),
    Field("stick_stiffness_nm_per_rad", "the stiffness through which the friction sticks, N·m/rad; default "
          "20 × the stiffest stage", "> the stiffest stage"),
    Field("preload_nm", "the mean torque the element carries (the drive torque through a clutch), N·m; default 0",
          "a finite number"),
    Field("coast_stiffnesses_nm_per_rad", "the coast side's stages (negative twist), from the first outwards, "
          "N·m/rad; default: the drive side's mirrored", "a list, each > 0"),
    Field("coast_stage_angles_deg", "the coast side's stage starts (as magnitudes), deg",
          "one fewer than the coast stiffnesses, each > 0, ascending"),
    Field("slip_torque_nm", "a clutch's capacity: the plates slip while the total torque (preload plus the "
          "vibratory part) would exceed it, N·m; default 0: it never slips (time domain only)",
          "> |preload_nm|"),
    Field("source", "where the numbers come from", "a string"),
), array=True)


#: The tables of a chain file.
CHAIN_SECTIONS = (META, UNITS, CHAIN, CRANKS, STATIONS, SHAFTS, PROPELLERS, COUPLINGS, GEARS, NONLINEAR, ENGINE,
                  EXCITATION, START, STOP, TANGENTIAL_HARMONICS, DAMPERS, LIMITS, UNCERTAINTY, DISTRIBUTIONS)

CHAIN_SCHEMA = schema(CHAIN_SECTIONS)


def is_count(path: str) -> bool:
    """Whether a field path (``engine.cylinders``, ``webs.*.thickness``) names a field whose rule is
    an integer (a count): such a field cannot take the values between its range's bounds, so it
    is no ``[uncertainty]`` input and no ``[design]`` variable."""
    parts = path.split(".")
    for section in (*CRANK_SECTIONS, *CHAIN_SECTIONS):
        if section.name == parts[0] or section.name == ".".join(parts[:2]):
            if any(f.key == parts[-1] and f.rule.startswith("integer") for f in section.fields):
                return True
    return False
