"""A battery of bad inputs and invocations, as a new user makes them (issue 11).

Each case runs the command line in a folder that holds a user's description, notes and
earlier outputs, and asserts: the exit status; that the message names the offending field
or option; that no traceback is printed; and that nothing in the folder was created,
changed or deleted (the checks come before any work, so not even a temporary sibling is
left). Warning cases (valid but implausible dimensions) run to exit 0 and name the field.
"""

from __future__ import annotations

import hashlib
import os
import sys

import pytest

from conftest import GEOMETRY
from fetorsion.cli import main as cli_main
RENAULT = (GEOMETRY / "renault21.toml").read_text()
CERTAIN = RENAULT.split("[uncertainty]")[0]  # without the ranges, which a changed nominal would leave
CHAIN = """
[chain]
name = "two discs"
inertias_kgm2 = [0.1, 0.2]
stiffnesses_nm_per_rad = [1.0e4]
"""

# A chain with an engine (issue 18): two inertias, one cylinder on the first.
ENGINE_CHAIN = CHAIN + """cylinder_stations = [1]
loss_factors = 0.05
[units]
length = "mm"
[engine]
cylinders = 1
stroke = 90.0
rod_length = 150.0
bore = 85.0
crank_angles_deg = [0.0]
firing_order = [1]
[excitation]
reciprocating_mass_kg = 0.6
speed_range_rpm = [1000.0, 5000.0]
compression_ratio = 16.0
imep_pa = 1.0e6
"""
# A geared network (issue 29): a disc, a gear pair, a load; one cylinder on the disc.
NETWORK = """
[chain]
name = "geared"
cylinder_stations = ["disc"]
[[chain.stations]]
name = "disc"
inertia_kgm2 = 0.1
[[chain.stations]]
name = "pinion"
inertia_kgm2 = 0.01
[[chain.stations]]
name = "wheel"
inertia_kgm2 = 0.05
[[chain.stations]]
name = "load"
inertia_kgm2 = 0.5
[[chain.shafts]]
between = ["disc", "pinion"]
stiffness_nm_per_rad = 1.0e4
loss_factor = 0.05
[[chain.shafts]]
between = ["wheel", "load"]
stiffness_nm_per_rad = 2.0e4
loss_factor = 0.05
[[chain.gears]]
between = ["pinion", "wheel"]
ratio = 0.5
""" + ENGINE_CHAIN.split("loss_factors = 0.05\n")[1]
# The Renault crank (crank.toml of the user's folder) as a part of a network, a load behind its flywheel.
CRANK_NETWORK = """
[chain]
name = "crank and load"
[[chain.cranks]]
name = "r21"
file = "crank.toml"
dof = 17
stiffness = "carter"
[[chain.stations]]
name = "load"
inertia_kgm2 = 0.5
[[chain.shafts]]
between = ["r21.flywheel", "load"]
stiffness_nm_per_rad = 2.0e4
"""
NL = """[[chain.nonlinear]]
name = "clutch"
between = ["load", "ground"]
stiffnesses_nm_per_rad = [520.0, 44000.0]
stage_angles_deg = [5.5]
friction_torque_nm = 10.0
"""


def with_nonlinear(old: str, new: str) -> str:
    """The network with a [[chain.nonlinear]] element, ``old`` in it replaced by ``new``."""
    return NETWORK.replace("ratio = 0.5\n", "ratio = 0.5\n" + NL.replace(old, new))


DAMPER = """
[[dampers]]
type = "rubber"
hub_inertia_kgm2 = 1.0e-3
ring_inertia_kgm2 = 3.0e-3
stiffness_nm_per_rad = 2.6e4
loss_factor = 0.2
"""
VISCOUS = """
[[dampers]]
type = "viscous"
housing_inertia_kgm2 = 1.0e-3
ring_inertia_kgm2 = 3.0e-3
damping_nms_per_rad = 5.0
"""
# The Renault crank driven by a measured pressure curve (p.csv) instead of the synthetic cycle.
MEASURED = (RENAULT.split("[excitation]")[0] + '[excitation]\nreciprocating_mass_kg = 0.65\n'
            'speed_range_rpm = [750.0, 6500.0]\npressure_csv = "p.csv"\n\n[[attachments]]'
            + RENAULT.split("[[attachments]]", 1)[1])
# The Renault crank with a [limits] table of the fatigue verdict's overrides (round numbers).
LIMITED = RENAULT.replace("[[attachments]]", """[limits]
fatigue_strength_bending_pa = 400e6
fatigue_required_safety = 1.5
source = "test"

[[attachments]]""", 1)
CURVE = "# unit = N m\n1000, 10\n2000, 30\n3000, 20\n"


def edit(old: str, new: str, text: str = RENAULT) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def csv_rows(angles, value=5.0e5) -> str:
    return "".join(f"{a:g}, {value}\n" for a in angles)


def with_csv(name: str) -> str:
    return edit("imep_pa = [", f'pressure_csv = "{name}"\nimep_pa_was = [')


# The user's folder: every case starts from these files (name -> text or bytes).
BASE = {
    "crank.toml": RENAULT,
    "notes.txt": "my notes\n",
    "chain.toml": CHAIN,
    "mech.toml": (GEOMETRY / "b112_single.toml").read_text(),
    "old.json": '{"mine": true}\n',
    "report/notes.md": "a user's folder named report\n",
}

# (id, argv with {d} for the folder, extra files, expected exit status, texts the message must hold)
CASES = [
    # extends: a variant read on top of a base description
    ("extends-missing", "lumped {d}/x.toml", {"x.toml": 'extends = "nowhere.toml"\n'}, 2, ["nowhere.toml", "does not exist"]),
    ("extends-number", "lumped {d}/x.toml", {"x.toml": 'extends = 3\n'}, 2, ["extends = 3", "file name of the crank description"]),
    ("extends-cycle", "lumped {d}/x.toml", {"x.toml": 'extends = "y.toml"\n', "y.toml": 'extends = "x.toml"\n'},
     2, ["extends", "cycle (x.toml -> y.toml -> x.toml)"]),
    ("extends-chain", "lumped {d}/x.toml", {"x.toml": 'extends = "chain.toml"\n'}, 2, ["extends", "chain files do not extend"]),
    ("extends-bad-override", "lumped {d}/x.toml", {"x.toml": 'extends = "crank.toml"\n[fillets]\npin = -1.0\n'},
     2, ["fillets.pin", "-1"]),
    # [bearings] (issue 13)
    ("bearings-negative", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]", "[bearings]\nradial_stiffness_n_per_m = -1e8\n\n[uncertainty]")},
     2, ["bearings.radial_stiffness_n_per_m", "rigid"]),
    ("bearings-count", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]", "[bearings]\nradial_stiffness_n_per_m = [1e8, 1e8]\n\n[uncertainty]")},
     2, ["bearings.radial_stiffness_n_per_m", "one per main journal (5)"]),
    ("bearings-word", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]", '[bearings]\nradial_stiffness_n_per_m = "soft"\n\n[uncertainty]')},
     2, ["bearings.radial_stiffness_n_per_m", "soft"]),
    ("bearings-wide", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]", "[bearings]\nwidth = 40.0\n\n[uncertainty]")},
     2, ["bearings.width", "journal 1's length (23)"]),
    ("bearings-no-thrust", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]", "[bearings]\naxial_stiffness_n_per_m = 1e8\n\n[uncertainty]")},
     2, ["bearings.thrust_journal", "is required"]),
    ("bearings-thrust-9", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]", "[bearings]\naxial_stiffness_n_per_m = 1e8\nthrust_journal = 9\n\n[uncertainty]")},
     2, ["bearings.thrust_journal", "1 to 5"]),
    ("bearings-typo", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]", "[bearings]\nradial_stifness = 1e8\n\n[uncertainty]")},
     2, ["bearings.radial_stifness", "not a known field"]),
    # [bearings] as an oil film
    ("bearings-film-and-stiffness", "lumped {d}/x.toml",
     {"x.toml": edit("[uncertainty]", "[bearings]\nradial_stiffness_n_per_m = 1e8\nclearance = 0.03\noil_viscosity_pa_s = 0.01\nload_n = 5000.0\n\n[uncertainty]")},
     2, ["bearings.radial_stiffness_n_per_m", "oil film"]),
    ("bearings-film-clearance-zero", "lumped {d}/x.toml",
     {"x.toml": edit("[uncertainty]", "[bearings]\nclearance = 0.0\noil_viscosity_pa_s = 0.01\nload_n = 5000.0\n\n[uncertainty]")},
     2, ["bearings.clearance", "> 0"]),
    ("bearings-film-clearance-huge", "lumped {d}/x.toml",
     {"x.toml": edit("[uncertainty]", "[bearings]\nclearance = 30.0\noil_viscosity_pa_s = 0.01\nload_n = 5000.0\n\n[uncertainty]")},
     2, ["bearings.clearance", "journal 1's radius"]),
    ("bearings-film-no-viscosity", "lumped {d}/x.toml",
     {"x.toml": edit("[uncertainty]", "[bearings]\nclearance = 0.03\nload_n = 5000.0\n\n[uncertainty]")},
     2, ["bearings.oil_viscosity_pa_s", "is required"]),
    ("bearings-film-load-count", "lumped {d}/x.toml",
     {"x.toml": edit("[uncertainty]", "[bearings]\nclearance = 0.03\noil_viscosity_pa_s = 0.01\nload_n = [5000.0, 5000.0]\n\n[uncertainty]")},
     2, ["bearings.load_n", "one per main journal (5)"]),
    ("bearings-film-speed", "lumped {d}/x.toml",
     {"x.toml": edit("[uncertainty]", "[bearings]\nclearance = 0.03\noil_viscosity_pa_s = 0.01\nload_n = 5000.0\nspeed_rpm = -100.0\n\n[uncertainty]")},
     2, ["bearings.speed_rpm", "> 0"]),
    ("condense-shapes-no-npz", "condense {d}/crank.toml --with-shapes", {}, 2, ["--with-shapes", "--npz"]),
    ("condense-npz-suffix", "condense {d}/crank.toml --npz {d}/out.txt", {}, 2, ["--npz", "out.txt", ".npz"]),
    ("modal-bearings-refine", "modal {d}/crank.toml --support bearings --refine", {}, 2, ["--support bearings", "--refine"]),
    ("support-wall", "campbell {d}/crank.toml --support wall", {}, 2, ["--support", "wall"]),
    ("response-fe", "response {d}/crank.toml --source fe", {}, 2, ["--source fe", "condensed"]),
    # --- the description file itself
    ("binary", "lumped {d}/bin.toml", {"bin.toml": bytes(range(256))}, 2, ["bin.toml", "not UTF-8"]),
    ("latin1", "lumped {d}/l1.toml", {"l1.toml": "[meta]\nname = 'Citro\xebn'\n".encode("latin-1")}, 2,
     ["l1.toml", "not UTF-8"]),
    ("folder", "lumped {d}/report", {}, 2, ["report", "is a folder"]),
    ("missing", "lumped {d}/nothere.toml", {}, 2, ["nothere.toml", "does not exist"]),
    ("device", "lumped /dev/zero", {}, 2, ["/dev/zero", "not a regular file"]),
    ("not-toml", "lumped {d}/x.toml", {"x.toml": "this is = = not toml\n"}, 2, ["x.toml", "not valid TOML"]),
    ("empty", "lumped {d}/x.toml", {"x.toml": ""}, 2, ["units"]),
    ("mechanics-as-crank", "lumped {d}/mech.toml", {}, 2, ["mech.toml", "mechanics file"]),
    ("no-material", "lumped {d}/x.toml", {"x.toml": edit("[material]", "[materials]")}, 2, ["material"]),
    ("huge", "lumped {d}/big.toml", {"big.toml": None}, 2, ["big.toml", "MiB"]),
    # --- fields
    ("firing-mixed", "lumped {d}/x.toml", {"x.toml": edit("firing_order = [1, 3, 4, 2]", 'firing_order = [1, "3", 4, 2]')},
     2, ["engine.firing_order", "permutation"]),
    # the Renault's crank angles are 0/180/180/0: 1-2-3-4 leaves cylinder 4 no TDC in the cycle
    ("firing-impossible", "lumped {d}/x.toml", {"x.toml": edit("firing_order = [1, 3, 4, 2]", "firing_order = [1, 2, 3, 4]")},
     2, ["engine.firing_order", "cannot be fired by crank_angles_deg"]),
    ("cylinders-float", "lumped {d}/x.toml", {"x.toml": edit("cylinders = 4", "cylinders = 4.0")}, 2,
     ["engine.cylinders", "integer"]),
    ("cylinders-text", "lumped {d}/x.toml", {"x.toml": edit("cylinders = 4", 'cylinders = "4"')}, 2,
     ["engine.cylinders"]),
    ("strokes-3", "lumped {d}/x.toml", {"x.toml": edit("cycle_strokes = 4", "cycle_strokes = 3")}, 2,
     ["engine.cycle_strokes", "2, 4"]),
    ("strokes-bool", "lumped {d}/x.toml", {"x.toml": edit("cycle_strokes = 4", "cycle_strokes = true")}, 2,
     ["engine.cycle_strokes"]),
    ("imep-inf", "campbell {d}/x.toml", {"x.toml": edit("imep_pa = [", "imep_pa = inf\nimep_was = [")}, 2,
     ["excitation.imep_pa", "finite"]),
    ("imep-nan-pair", "response {d}/x.toml", {"x.toml": edit("imep_pa = [", "imep_pa = [[1000.0, nan]]\nimep_was = [")},
     2, ["excitation.imep_pa", "finite"]),
    ("E-nan", "lumped {d}/x.toml", {"x.toml": edit("youngs_modulus_pa = ", "youngs_modulus_pa = nan\nE_was = ")}, 2,
     ["material.youngs_modulus_pa", "finite"]),
    ("csv-nan", "campbell {d}/x.toml", {"x.toml": with_csv("p.csv"),
                                        "p.csv": csv_rows(range(0, 720, 10)).replace("50, 500000.0", "50, nan")},
     2, ["excitation.pressure_csv", "non-finite"]),
    ("csv-quarter", "campbell {d}/x.toml", {"x.toml": with_csv("p.csv"), "p.csv": csv_rows(range(0, 91, 5))}, 2,
     ["excitation.pressure_csv", "whole cycle"]),
    ("csv-missing", "campbell {d}/x.toml", {"x.toml": with_csv("none.csv")}, 2, ["excitation.pressure_csv", "not a file"]),
    ("csv-binary", "campbell {d}/x.toml", {"x.toml": with_csv("p.csv"), "p.csv": bytes(range(256)) * 4}, 2,
     ["excitation.pressure_csv"]),
    ("csv-and-imep", "campbell {d}/x.toml",
     {"x.toml": edit("imep_pa = [", 'pressure_csv = "p.csv"\nimep_pa = ['), "p.csv": csv_rows(range(0, 720, 10))}, 2,
     ["excitation", "exactly one of"]),
    ("no-source", "campbell {d}/x.toml", {"x.toml": edit("imep_pa = [", "imep_was = [")}, 2,
     ["excitation", "exactly one of"]),
    ("overspeed-below-rated", "campbell {d}/x.toml", {"x.toml": edit("speed_range_rpm = [750.0, 6500.0]",
                                                                     "speed_range_rpm = [750.0, 6500.0]\noverspeed_factor = 0.9")},
     2, ["excitation.overspeed_factor", ">= 1"]),
    ("speeds-reversed", "campbell {d}/x.toml", {"x.toml": edit("speed_range_rpm = [750.0, 6500.0]",
                                                               "speed_range_rpm = [6500.0, 750.0]")},
     2, ["excitation.speed_range_rpm"]),
    ("unknown-key", "lumped {d}/x.toml", {"x.toml": edit("[engine]", "[engine]\ncylinder = 4")}, 2,
     ["engine.cylinder", "not a known field"]),
    ("no-units", "lumped {d}/x.toml", {"x.toml": edit('length = "mm"', "")}, 2, ["units.length"]),
    ("bad-unit", "lumped {d}/x.toml", {"x.toml": edit('length = "mm"', 'length = "parsec"')}, 2, ["units.length"]),
    ("rod-short", "lumped {d}/x.toml", {"x.toml": edit("rod_length = 149.1", "rod_length = 30.0")}, 2,
     ["engine.rod_length"]),
    ("web-thin", "lumped {d}/x.toml", {"x.toml": RENAULT.replace("thickness = ", "thickness = 1e-6 #")}, 2,
     ["fillets.journal", "thinnest web"]),
    ("relational-with-bad-field", "lumped {d}/x.toml",
     {"x.toml": edit("stroke = 83.5", "stroke = -83.5").replace("width_pin = ", "width_pin = 10.0 #", 1)}, 2,
     ["engine.stroke", "webs.1.width_pin"]),
    ("pin-outside-web", "lumped {d}/x.toml", {"x.toml": RENAULT.replace("width_pin = ", "width_pin = 10.0 #", 1)}, 2,
     ["webs.1.width_pin", "inside its web"]),
    ("uncertainty-nu", "sensitivity {d}/x.toml", {"x.toml": edit("[uncertainty]",
                                                                 '[uncertainty]\n"material.poisson_ratio" = [0.2, 0.6]')},
     2, ["uncertainty.material.poisson_ratio", "high bound", "material.poisson_ratio"]),
    ("uncertainty-cylinders", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]",
                                                                   '[uncertainty]\n"engine.cylinders" = [3.5, 4.5]')},
     2, ["uncertainty.engine.cylinders", "engine.cylinders"]),
    ("uncertainty-inf", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]", '[uncertainty]\n"engine.stroke" = [80.0, inf]')},
     2, ["uncertainty.engine.stroke", "finite"]),
    ("uncertainty-journal-outgrows-webs", "lumped {d}/x.toml",
     {"x.toml": edit('"journals.*.diameter" = [54.0, 56.0]', '"journals.*.diameter" = [54.0, 95.0]')},
     2, ["uncertainty.journals.*.diameter", "high bound", "width_journal", "more"]),
    ("uncertainty-reversed", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]",
                                                                  '[uncertainty]\n"engine.stroke" = [90.0, 80.0]')},
     2, ["uncertainty.engine.stroke", "low < high"]),
    ("uncertainty-no-field", "lumped {d}/x.toml", {"x.toml": edit("[uncertainty]",
                                                                  '[uncertainty]\n"engine.strok" = [80.0, 90.0]')},
     2, ["uncertainty.engine.strok", "does not name"]),
    ("chain-negative", "lumped {d}/c.toml", {"c.toml": CHAIN.replace("[0.1, 0.2]", "[0.1, -0.2]")}, 2,
     ["chain.inertias_kgm2[2]"]),
    ("chain-labels", "lumped {d}/c.toml", {"c.toml": CHAIN + 'labels = ["a", 3]\n'}, 2, ["chain.labels"]),
    ("chain-springs", "lumped {d}/c.toml", {"c.toml": CHAIN.replace("[1.0e4]", "[1.0e4, 2.0e4]")}, 2,
     ["chain.stiffnesses_nm_per_rad"]),
    # --- chain files with an engine (issue 18)
    ("chain-loss-count", "response {d}/c.toml", {"c.toml": ENGINE_CHAIN.replace("loss_factors = 0.05", "loss_factors = [0.1, 0.2]")},
     2, ["chain.loss_factors", "one per spring"]),
    ("chain-loss-negative", "campbell {d}/c.toml", {"c.toml": ENGINE_CHAIN.replace("loss_factors = 0.05", "loss_factors = -0.1")},
     2, ["chain.loss_factors[1]", ">= 0"]),
    ("chain-stations-no-engine", "lumped {d}/c.toml", {"c.toml": CHAIN + "cylinder_stations = [1]\n"}, 2,
     ["chain.cylinder_stations", "[engine]"]),
    ("chain-excitation-no-engine", "campbell {d}/c.toml",
     {"c.toml": ENGINE_CHAIN.split("[engine]")[0].replace("cylinder_stations = [1]\n", "")
      + "[excitation]" + ENGINE_CHAIN.split("[excitation]")[1]}, 2, ["excitation", "[engine]"]),
    ("chain-station-count", "campbell {d}/c.toml", {"c.toml": ENGINE_CHAIN.replace("[1]\nloss", "[1, 2]\nloss")}, 2,
     ["chain.cylinder_stations", "one station"]),
    ("chain-no-stations", "campbell {d}/c.toml", {"c.toml": ENGINE_CHAIN.replace("cylinder_stations = [1]\n", "")}, 2,
     ["chain.cylinder_stations", "one station"]),
    ("chain-undamped", "response {d}/c.toml",
     {"c.toml": ENGINE_CHAIN.replace("loss_factors = 0.05", "").replace("imep_pa = 1.0e6", "imep_pa = 1.0e6\nmodal_damping_ratio = 0.0")},
     2, ["excitation.modal_damping_ratio", "no absolute"]),
    ("chain-source-fe", "campbell {d}/c.toml --source fe", {"c.toml": ENGINE_CHAIN}, 2, ["--source fe", "chain file"]),
    ("chain-no-units", "campbell {d}/c.toml", {"c.toml": ENGINE_CHAIN.replace('[units]\nlength = "mm"\n', "")}, 2,
     ["units"]),
    # --- networks and the time domain (issue 29)
    ("network-gear-loop", "lumped {d}/n.toml", {"n.toml": NETWORK + '[[chain.gears]]\nbetween = ["wheel", "pinion"]\nratio = 2.0\n'},
     2, ["chain.gears", "loop"]),
    ("network-unknown-station", "lumped {d}/n.toml", {"n.toml": NETWORK.replace('["wheel", "load"]', '["wheel", "lod"]')},
     2, ["chain.shafts.2.between", "two different stations"]),
    ("network-list-form", "lumped {d}/n.toml", {"n.toml": NETWORK.replace('name = "geared"', 'name = "geared"\nlabels = ["a"]')},
     2, ["chain.labels", "per station"]),
    ("network-cylinder-name", "campbell {d}/n.toml", {"n.toml": NETWORK.replace('["disc"]', '["dsic"]')},
     2, ["chain.cylinder_stations"]),
    ("network-damper-station", "response {d}/n.toml", {"n.toml": NETWORK + DAMPER + 'at = "nowhere"\n'}, 2,
     ["dampers.1.at", "nowhere"]),
    ("network-damper-command", "damper {d}/n.toml --objective twist", {"n.toml": NETWORK}, 2,
     ["'damper' does not take a network"]),
    # issue 56: a network on the condensed crank is refused as a network, not sent to --source lumped17 (which
    # then refused it as a network)
    ("network-condensed-damper", "damper {d}/n.toml --objective twist",
     {"n.toml": CRANK_NETWORK.replace("dof = 17", 'dof = "condensed"')}, 2,
     ["'damper' does not take a network"]),
    # --- a crank description as a part of a network ([[chain.cranks]])
    ("network-crank-missing", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace('"crank.toml"', '"nowhere.toml"')},
     2, ["chain.cranks.1.file", "nowhere.toml", "no such file"]),
    ("network-crank-is-chain", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace('"crank.toml"', '"chain.toml"')},
     2, ["chain.cranks.1.file", "not a chain file"]),
    ("network-crank-invalid", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace('"crank.toml"', '"bad.toml"'),
                                                   "bad.toml": edit("density_kgm3 = 7850.0", "density_kgm3 = -1.0")},
     2, ["chain.cranks.1.file", "material.density_kgm3"]),
    ("network-crank-partition", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace("dof = 17", "dof = 18")},
     2, ["chain.cranks.1.dof", "one of 5, 6, 17, 19, 21"]),
    ("network-crank-stiffness", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace('"carter"', '"carters"')},
     2, ["chain.cranks.1.stiffness", "carter"]),
    ("network-crank-station", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace('"r21.flywheel"', '"r21.P9"')},
     2, ["chain.shafts.1.between", "'r21.P9' is not a station of the crank 'r21'", "r21.J1"]),
    ("network-crank-name", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace('name = "r21"', 'name = "r.21"')},
     2, ["chain.cranks.1.name", "without '.'"]),
    ("network-two-cranks", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK + '[[chain.cranks]]\nname = "b"\nfile = "crank.toml"\n'},
     2, ["chain.cranks", "at most one"]),
    ("network-crank-cylinders", "campbell {d}/n.toml", {"n.toml": CRANK_NETWORK.replace(
        'name = "crank and load"', 'name = "crank and load"\ncylinder_stations = ["load"]')}, 2,
     ["chain.cylinder_stations", "crank's pins carry its cylinders"]),
    ("network-crank-clash", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace('name = "load"', 'name = "r21.J1"')
                                                 .replace('"load"]', '"r21.J1"]')}, 2, ["chain.stations.1.name", "unique"]),
    ("network-crank-dampers", "lumped {d}/n.toml", {"n.toml": CRANK_NETWORK.replace('"crank.toml"', '"damped.toml"'),
                                                   "damped.toml": RENAULT + DAMPER}, 2,
     ["chain.cranks.1.file", "[[dampers]]"]),
    ("transient-no-speed", "transient {d}/c.toml", {"c.toml": ENGINE_CHAIN}, 2, ["--rpm", "--run-up"]),
    ("transient-both", "transient {d}/c.toml --rpm 2000 --run-up 1000 2000 --rate 100", {"c.toml": ENGINE_CHAIN}, 2,
     ["--run-up", "not allowed"]),
    ("transient-no-rate", "transient {d}/c.toml --run-up 1000 3000", {"c.toml": ENGINE_CHAIN}, 2, ["--rate"]),
    ("transient-rate-alone", "transient {d}/c.toml --rpm 2000 --rate 100", {"c.toml": ENGINE_CHAIN}, 2,
     ["--rate", "--run-up"]),
    ("transient-same-speeds", "transient {d}/c.toml --run-up 2000 2000 --rate 100", {"c.toml": ENGINE_CHAIN}, 2,
     ["--run-up 2000 2000", "differ"]),
    ("transient-negative-rate", "transient {d}/c.toml --run-up 1000 2000 --rate -5", {"c.toml": ENGINE_CHAIN}, 2,
     ["--rate"]),
    ("transient-zero-rpm", "transient {d}/c.toml --rpm 0", {"c.toml": ENGINE_CHAIN}, 2, ["--rpm", "> 0"]),
    ("transient-station", "transient {d}/c.toml --rpm 2000 --station 5", {"c.toml": ENGINE_CHAIN}, 2,
     ["--station 5", "1..2"]),
    ("transient-source-fe", "transient {d}/c.toml --rpm 2000 --source fe", {"c.toml": ENGINE_CHAIN}, 2,
     ["--source fe", "lumped"]),
    ("transient-rubber-variable-inertia", "transient {d}/c.toml --rpm 2000 --variable-inertia",
     {"c.toml": ENGINE_CHAIN + DAMPER.replace("stiffness_nm_per_rad = 2.6e4\nloss_factor = 0.2\n",
                                              "dynamic_table = [[100.0, 2.6e4, 0.2], [400.0, 3.0e4, 0.25]]\n")}, 2,
     ["rubber", "Maxwell", "nonlinear integrator"]),
    ("transient-no-excitation", "transient {d}/c.toml --rpm 2000", {"c.toml": CHAIN}, 2, ["[excitation]"]),
    # the condensed crank's time domain is steady running: asked for more, it says what to choose
    ("transient-condensed-run-up", "transient {d}/crank.toml --run-up 1000 2000 --rate 100 --source condensed", {}, 2,
     ["--source condensed", "--run-up", "lumpedN"]),
    ("transient-condensed-station", "transient {d}/crank.toml --rpm 2000 --source condensed --station 3", {}, 2,
     ["--station", "pulley"]),
    ("transient-chain-condensed", "transient {d}/c.toml --rpm 2000 --source condensed", {"c.toml": ENGINE_CHAIN}, 2,
     ["--source condensed", "chain file"]),
    ("transient-plot-format", "transient {d}/n.toml --rpm 2000 --plot {d}/t.txt", {"n.toml": NETWORK}, 2,
     ["--plot"]),
    # --- [[chain.nonlinear]] (clutch dampers, DMF arc springs)
    ("nonlinear-stiffness", "transient {d}/n.toml --rpm 2000", {"n.toml": with_nonlinear("520.0", "-520.0")}, 2,
     ["chain.nonlinear.1.stiffnesses_nm_per_rad", "each > 0"]),
    ("nonlinear-stage-count", "lumped {d}/n.toml", {"n.toml": with_nonlinear("[5.5]", "[5.5, 9.0]")}, 2,
     ["chain.nonlinear.1.stage_angles_deg", "one fewer"]),
    ("nonlinear-stage-order", "lumped {d}/n.toml", {"n.toml": with_nonlinear(
        "[520.0, 44000.0]\nstage_angles_deg = [5.5]", "[520.0, 9e3, 44000.0]\nstage_angles_deg = [9.0, 5.5]")}, 2,
     ["chain.nonlinear.1.stage_angles_deg", "ascending"]),
    ("nonlinear-friction", "campbell {d}/n.toml", {"n.toml": with_nonlinear("= 10.0", "= -10.0")}, 2,
     ["chain.nonlinear.1.friction_torque_nm", ">= 0"]),
    ("nonlinear-stick", "transient {d}/n.toml --rpm 2000", {"n.toml": with_nonlinear(
        "friction_torque_nm = 10.0", "friction_torque_nm = 10.0\nstick_stiffness_nm_per_rad = 1000.0")}, 2,
     ["chain.nonlinear.1.stick_stiffness_nm_per_rad", "stiffest stage"]),
    ("nonlinear-station", "response {d}/n.toml", {"n.toml": with_nonlinear('"load", "ground"', '"lod", "ground"')},
     2, ["chain.nonlinear.1.between", "two different stations"]),
    ("nonlinear-slip-below-preload", "transient {d}/n.toml --rpm 2000", {"n.toml": with_nonlinear(
        "friction_torque_nm = 10.0", "friction_torque_nm = 10.0\npreload_nm = 150.0\nslip_torque_nm = 120.0")}, 2,
     ["chain.nonlinear.1.slip_torque_nm", "mean torque", "150"]),
    ("nonlinear-slip-scipy", "transient {d}/n.toml --run 1000 1200 --rate 1000 --integrator LSODA", {"n.toml": with_nonlinear(
        "friction_torque_nm = 10.0", "friction_torque_nm = 10.0\nslip_torque_nm = 120.0")}, 2,
     ["slip_torque", "compiled", "LSODA"]),
    ("nonlinear-coast-stage-count", "lumped {d}/n.toml", {"n.toml": with_nonlinear(
        "friction_torque_nm = 10.0", "friction_torque_nm = 10.0\ncoast_stiffnesses_nm_per_rad = [573.0, 2.8e4]")}, 2,
     ["chain.nonlinear.1.coast_stage_angles_deg", "one fewer"]),
    ("nonlinear-unknown-key", "lumped {d}/n.toml", {"n.toml": with_nonlinear("friction_torque_nm", "friction_nm")},
     2, ["friction_nm"]),
    # --- [[dampers]] and [limits] (issue 14)
    ("damper-type", "response {d}/x.toml", {"x.toml": RENAULT + DAMPER.replace('"rubber"', '"hydraulic"')}, 2,
     ["dampers.1.type", "viscous, rubber, tuned"]),
    ("damper-no-ring", "campbell {d}/x.toml", {"x.toml": RENAULT + DAMPER.replace("ring_inertia_kgm2 = 3.0e-3\n", "")},
     2, ["dampers.1.ring_inertia_kgm2", "required"]),
    ("damper-ring-negative", "response {d}/x.toml", {"x.toml": RENAULT + DAMPER.replace("3.0e-3", "-3.0e-3")}, 2,
     ["dampers.1.ring_inertia_kgm2", "> 0"]),
    ("damper-at", "response {d}/x.toml", {"x.toml": RENAULT + DAMPER + 'at = "middle"\n'}, 2, ["dampers.1.at", "front, rear"]),
    ("damper-heat-rating", "response {d}/x.toml", {"x.toml": RENAULT + DAMPER + "allowed_power_w = -5.0\n"}, 2,
     ["dampers.1.allowed_power_w"]),
    ("damping-band-reversed", "response {d}/x.toml",
     {"x.toml": RENAULT.replace("[excitation]", '[excitation]\nmodal_damping_band = [0.02, 0.01]\nmodal_damping_source = "x"', 1)},
     2, ["excitation.modal_damping_band", "low <= high"]),
    ("damping-band-no-source", "response {d}/x.toml",
     {"x.toml": RENAULT.replace("[excitation]", "[excitation]\nmodal_damping_band = [0.01, 0.02]", 1)},
     2, ["excitation.modal_damping_source", "required"]),
    ("damper-eta-negative", "response {d}/x.toml", {"x.toml": RENAULT + DAMPER.replace("loss_factor = 0.2", "loss_factor = -0.2")},
     2, ["dampers.1.loss_factor", "> 0"]),
    ("damper-viscous-no-c", "response {d}/x.toml",
     {"x.toml": RENAULT + VISCOUS.replace("damping_nms_per_rad = 5.0\n", "")}, 2,
     ["dampers.1.damping_nms_per_rad", "required"]),
    ("damper-viscous-hub-key", "response {d}/x.toml",
     {"x.toml": RENAULT + VISCOUS.replace("housing_inertia_kgm2", "hub_inertia_kgm2")}, 2,
     ["dampers.1.hub_inertia_kgm2", "not a known field"]),
    ("damper-table-descending", "response {d}/x.toml",
     {"x.toml": RENAULT + DAMPER.replace("stiffness_nm_per_rad = 2.6e4\nloss_factor = 0.2\n",
                                         "dynamic_table = [[400.0, 2.6e4, 0.2], [300.0, 2.4e4, 0.2]]\n")}, 2,
     ["dampers.1.dynamic_table", "ascending"]),
    ("damper-table-and-k", "response {d}/x.toml",
     {"x.toml": RENAULT + DAMPER + "dynamic_table = [[300.0, 2.4e4, 0.2], [400.0, 2.6e4, 0.2]]\n"}, 2,
     ["dampers.1.stiffness_nm_per_rad", "not a known field"]),
    ("damper-table-no-temperature", "response {d}/x.toml",
     {"x.toml": RENAULT + DAMPER.replace("stiffness_nm_per_rad = 2.6e4\nloss_factor = 0.2\n",
                                         "dynamic_table = [[20.0, 300.0, 2.4e4, 0.2], [20.0, 400.0, 2.6e4, 0.2]]\n")}, 2,
     ["dampers.1.temperature_c", "operating"]),
    ("damper-temperature-no-column", "response {d}/x.toml",
     {"x.toml": RENAULT + DAMPER.replace("stiffness_nm_per_rad = 2.6e4\nloss_factor = 0.2\n",
                                         "temperature_c = 60.0\ndynamic_table = [[300.0, 2.4e4, 0.2], [400.0, 2.6e4, 0.2]]\n")},
     2, ["dampers.1.temperature_c", "temperature column"]),
    ("damper-table-one-row-per-temperature", "response {d}/x.toml",
     {"x.toml": RENAULT + DAMPER.replace("stiffness_nm_per_rad = 2.6e4\nloss_factor = 0.2\n",
                                         "temperature_c = 60.0\ndynamic_table = [[20.0, 300.0, 2.4e4, 0.2], "
                                         "[80.0, 400.0, 2.6e4, 0.2]]\n")}, 2, ["dampers.1.dynamic_table", ">= 2 per temperature"]),
    ("damper-heat-and-temperature", "response {d}/x.toml",
     {"x.toml": RENAULT + DAMPER.replace("stiffness_nm_per_rad = 2.6e4\nloss_factor = 0.2\n",
                                         "temperature_c = 60.0\nambient_c = 30.0\nthermal_conductance_w_per_k = 3.0\n"
                                         "dynamic_table = [[20.0, 300.0, 2.4e4, 0.2], [20.0, 400.0, 2.6e4, 0.2]]\n")}, 2,
     ["dampers.1.temperature_c", "not both"]),
    ("damper-heat-conductance-zero", "response {d}/x.toml",
     {"x.toml": RENAULT + DAMPER.replace("stiffness_nm_per_rad = 2.6e4\nloss_factor = 0.2\n",
                                         "ambient_c = 30.0\nthermal_conductance_w_per_k = 0.0\n"
                                         "dynamic_table = [[20.0, 300.0, 2.4e4, 0.2], [20.0, 400.0, 2.6e4, 0.2]]\n")}, 2,
     ["dampers.1.thermal_conductance_w_per_k", "> 0"]),
    ("damper-heat-no-column", "response {d}/x.toml",
     {"x.toml": RENAULT + DAMPER.replace("stiffness_nm_per_rad = 2.6e4\nloss_factor = 0.2\n",
                                         "ambient_c = 30.0\nthermal_conductance_w_per_k = 3.0\n"
                                         "dynamic_table = [[300.0, 2.4e4, 0.2], [400.0, 2.6e4, 0.2]]\n")}, 2,
     ["dampers.1.ambient_c", "temperature column"]),
    ("chain-damper", "response {d}/c.toml", {"c.toml": ENGINE_CHAIN + DAMPER.replace("2.6e4", "nan")}, 2,
     ["dampers.1.stiffness_nm_per_rad", "finite"]),
    ("limits-shear-refused", "run {d}/x.toml --out {d}/new --no-fe",
     {"x.toml": edit('source = "test"', 'source = "test"\ncontinuous_shear_pa = 1e8', LIMITED)},
     2, ["limits", "continuous_shear_pa", "fatigue assessment", "fatigue_strength_bending_pa"]),
    ("limits-no-source", "run {d}/x.toml --out {d}/new --no-fe", {"x.toml": edit('source = "test"', "", LIMITED)}, 2,
     ["limits.source"]),
    ("limits-method-unknown", "response {d}/x.toml",
     {"x.toml": edit('source = "test"', 'source = "test"\nfatigue_method = "shigley"', LIMITED)},
     2, ["limits.fatigue_method", "iacs-m53"]),
    ("limits-fatigue-safety-below-1", "response {d}/x.toml",
     {"x.toml": edit("fatigue_required_safety = 1.5", "fatigue_required_safety = 0.5", LIMITED)},
     2, ["limits.fatigue_required_safety", ">= 1"]),
    ("limits-fatigue-strength-negative", "response {d}/x.toml",
     {"x.toml": edit("fatigue_strength_bending_pa = 400e6", "fatigue_strength_bending_pa = -1.0", LIMITED)},
     2, ["limits.fatigue_strength_bending_pa", ">= 0"]),
    ("limits-sigma-add-negative", "lumped {d}/x.toml",
     {"x.toml": edit('source = "test"', 'source = "test"\nadditional_bending_pa = -1.0', LIMITED)},
     2, ["limits.additional_bending_pa", ">= 0"]),
    ("limits-transient-refused", "response {d}/x.toml",
     {"x.toml": edit('source = "test"', 'source = "test"\ntransient_shear_pa = 1e8', LIMITED)},
     2, ["limits", "transient_shear_pa", "fatigue_required_safety"]),
    ("chain-limits-stress", "response {d}/c.toml", {"c.toml": ENGINE_CHAIN + '[limits]\ncontinuous_shear_pa = 1e8\nsource = "x"\n'},
     2, ["limits", "chain file", "continuous_torque_nm"]),
    ("misfire-9", "response {d}/crank.toml --misfire 9", {}, 2, ["--misfire 9", "1..4"]),
    ("misfire-0", "response {d}/crank.toml --misfire 0", {}, 2, ["--misfire"]),
    ("misfire-csv", "response {d}/x.toml --misfire 1", {"x.toml": MEASURED, "p.csv": csv_rows(range(0, 720, 10))}, 2,
     ["--misfire", "pressure_csv"]),
    ("damper-mu-0", "damper {d}/crank.toml --inertia-ratio 0", {}, 2, ["--inertia-ratio", "> 0"]),
    ("damper-mu-nan", "damper {d}/crank.toml --inertia-ratio nan", {}, 2, ["--inertia-ratio", "finite"]),
    ("damper-type-option", "damper {d}/crank.toml --type hydraulic", {}, 2, ["--type", "hydraulic"]),
    ("damper-objective", "damper {d}/crank.toml --objective mass", {}, 2, ["--objective"]),
    ("damper-hub-negative", "damper {d}/crank.toml --hub-inertia -1", {}, 2, ["--hub-inertia", ">= 0"]),
    ("damper-chain-stress", "damper {d}/c.toml --objective stress", {"c.toml": ENGINE_CHAIN}, 2,
     ["--objective stress", "chain file"]),
    ("damper-chain-fatigue", "damper {d}/c.toml --objective fatigue", {"c.toml": ENGINE_CHAIN}, 2,
     ["--objective fatigue", "chain file"]),
    # a crank's default objective is the verdict's (fatigue): a sharp corner has no SCF for it
    ("damper-sharp-fatigue", "damper {d}/x.toml", {"x.toml": CERTAIN.replace("journal = 2.5", "journal = 0.0")}, 2,
     ["--objective fatigue", "fillet"]),
    ("damper-sharp-stress", "damper {d}/x.toml --objective stress",
     {"x.toml": CERTAIN.replace("journal = 2.5", "journal = 0.0")}, 2, ["--objective stress", "fillet"]),
    ("damper-json-txt", "damper {d}/crank.toml --json {d}/notes.txt", {}, 2, ["--json"]),
    ("damper-fe", "damper {d}/crank.toml --source fe", {}, 2, ["--source fe"]),
    ("run-mu-negative", "run {d}/crank.toml --out {d}/new --inertia-ratio -1", {}, 2, ["--inertia-ratio"]),
    # --- design (issue 45): every option and the [design] table refused before any work
    ("design-no-table", "design {d}/crank.toml --out {d}/new", {}, 2, ["[design] table"]),
    ("design-generations", "design {d}/d.toml --out {d}/new --generations 0",
     {"d.toml": RENAULT + '\n[design]\n"webs.*.thickness" = [20.0, 24.0]\n'}, 2, ["--generations"]),
    ("design-mesh", "design {d}/d.toml --out {d}/new --mesh-size 0.3",
     {"d.toml": RENAULT + '\n[design]\n"webs.*.thickness" = [20.0, 24.0]\n'}, 2, ["--mesh-size 0.3"]),
    ("design-ratio", "design {d}/d.toml --out {d}/new",
     {"d.toml": RENAULT + '\n[design]\ndamper = "rubber"\ndamper_inertia_ratio = [0.3, 0.1]\n'}, 2,
     ["design.damper_inertia_ratio", "0 < low < high"]),
    ("design-solid-missing", "modal {d}/s.toml", {"s.toml": RENAULT + '\n[solid]\nstep = "none.step"\n'}, 2,
     ["solid.step", "no such file"]),
    ("mesh-step-suffix", "mesh {d}/crank.toml --step {d}/out.igs", {}, 2, ["--step", ".igs"]),
    # --- --compare (issue 18)
    ("compare-missing", "response {d}/c.toml --compare {d}/none.csv", {"c.toml": ENGINE_CHAIN}, 2,
     ["--compare", "none.csv", "not a file"]),
    ("compare-no-unit", "response {d}/c.toml --compare {d}/k.csv", {"c.toml": ENGINE_CHAIN, "k.csv": "1000, 1\n2000, 2\n3000, 1\n"},
     2, ["--compare-unit"]),
    ("compare-bad-unit", "response {d}/c.toml --compare {d}/k.csv",
     {"c.toml": ENGINE_CHAIN, "k.csv": CURVE.replace("N m", "lbf ft")}, 2, ["--compare-unit", "lbf ft"]),
    ("compare-text", "response {d}/c.toml --compare {d}/k.csv", {"c.toml": ENGINE_CHAIN, "k.csv": CURVE + "x, y\n"}, 2,
     ["--compare", "k.csv", "rpm, value"]),
    ("compare-descending", "response {d}/c.toml --compare {d}/k.csv",
     {"c.toml": ENGINE_CHAIN, "k.csv": "# unit = deg\n3000, 1\n2000, 2\n1000, 1\n"}, 2, ["--compare", "ascending"]),
    ("compare-nan", "response {d}/c.toml --compare {d}/k.csv",
     {"c.toml": ENGINE_CHAIN, "k.csv": CURVE + "4000, nan\n"}, 2, ["--compare", "row 4", "non-finite"]),
    ("compare-name-alone", "response {d}/c.toml --compare-name paper", {"c.toml": ENGINE_CHAIN}, 2,
     ["--compare-name", "need --compare"]),
    ("compare-section-big", "response {d}/c.toml --compare {d}/k.csv --compare-section 5",
     {"c.toml": ENGINE_CHAIN, "k.csv": CURVE}, 2, ["--compare-section 5", "1 shaft sections"]),
    ("compare-no-overlap", "response {d}/c.toml --compare {d}/k.csv",
     {"c.toml": ENGINE_CHAIN, "k.csv": "# unit = N m\n8000, 1\n9000, 2\n9500, 1\n"}, 2, ["--compare", "overlap"]),
    ("mech-strokes", "flywheel {d}/m.toml", {"m.toml": BASE["mech.toml"].replace("[flywheel]", "[flywheel]\ncycle_strokes = 3")},
     2, ["flywheel.cycle_strokes"]),
    # --- options
    ("dof-7", "lumped {d}/crank.toml --dof 7", {}, 2, ["--dof", "not a partition"]),
    ("stiffness-x", "lumped {d}/crank.toml --stiffness foo", {}, 2, ["--stiffness"]),
    ("json-folder", "lumped {d}/crank.toml --json {d}/report", {}, 2, ["--json", "is a folder"]),
    ("json-suffix", "lumped {d}/crank.toml --json {d}/notes.txt", {}, 2, ["--json", "format"]),
    ("json-onto-input", "lumped {d}/crank.toml --json {d}/crank.toml", {}, 2, ["--json"]),
    ("json-under-file", "lumped {d}/crank.toml --json {d}/notes.txt/out.json", {}, 2, ["--json", "not a folder"]),
    ("html-suffix", "campbell {d}/crank.toml --html {d}/notes.txt", {}, 2, ["--html", ".txt"]),
    ("html-folder", "modal {d}/crank.toml --html {d}/report", {}, 2, ["--html", "is a folder"]),
    ("plot-xyz", "sensitivity {d}/crank.toml --plot {d}/out.xyz", {}, 2, ["--plot", ".xyz"]),
    ("plot-folder", "campbell {d}/crank.toml --plot {d}/report", {}, 2, ["--plot"]),
    ("speeds-order", "campbell {d}/crank.toml --speed-range 5000 1000", {}, 2, ["--speed-range", "below"]),
    ("speeds-negative", "campbell {d}/crank.toml --speed-range -1000 2000", {}, 2, ["--speed-range", "> 0"]),
    ("speeds-inf", "response {d}/crank.toml --speed-range 1000 inf", {}, 2, ["--speed-range", "finite"]),
    ("damping-2", "campbell {d}/crank.toml --damping 2", {}, 2, ["--damping", "< 1"]),
    ("damping-negative", "response {d}/crank.toml --damping -0.05", {}, 2, ["--damping", "> 0"]),
    ("damping-nan", "response {d}/crank.toml --damping nan", {}, 2, ["--damping", "finite"]),
    ("orders-zero", "campbell {d}/crank.toml --orders 0,1", {}, 2, ["--orders", "> 0"]),
    ("orders-text", "campbell {d}/crank.toml --orders a,b", {}, 2, ["--orders"]),
    ("modes-0", "campbell {d}/crank.toml --modes 0", {}, 2, ["--modes"]),
    ("fe-mesh-0", "campbell {d}/crank.toml --source fe --mesh-size 0", {}, 2, ["--mesh-size", "> 0"]),
    ("fe-mesh-tiny", "campbell {d}/crank.toml --source fe --mesh-size 0.01", {}, 2, ["--mesh-size", "GiB"]),
    ("steps-0", "response {d}/crank.toml --steps 0", {}, 2, ["--steps"]),
    ("steps-1", "response {d}/crank.toml --steps 1", {}, 2, ["--steps"]),
    ("response-fe", "response {d}/crank.toml --source fe", {}, 2, ["--source fe"]),
    ("response-chain", "response {d}/chain.toml", {}, 2, ["chain.toml", "chain file"]),
    ("campbell-no-excitation", "campbell {d}/x.toml", {"x.toml": RENAULT.split("[excitation]")[0]}, 2,
     ["x.toml", "[excitation]"]),
    ("sensitivity-no-uncertainty", "sensitivity {d}/x.toml", {"x.toml": RENAULT.split("[uncertainty]")[0]}, 2,
     ["x.toml", "[uncertainty]"]),
    ("mesh-nothing", "mesh {d}/crank.toml", {}, 2, ["-o"]),
    ("mesh-stl", "mesh {d}/crank.toml -o {d}/x.stl", {}, 2, ["-o", ".stl"]),
    ("mesh-tiny", "mesh {d}/crank.toml -o {d}/x.msh --mesh-size 0.01", {}, 2, ["--mesh-size", "GiB"]),
    ("mesh-png-jpg", "mesh {d}/crank.toml --png {d}/x.jpg", {}, 2, ["--png"]),
    ("mesh-chain", "mesh {d}/chain.toml -o {d}/x.msh", {}, 2, ["chain.toml", "chain file"]),
    ("modal-modes-0", "modal {d}/crank.toml --modes 0", {}, 2, ["--modes"]),
    ("modal-size-negative", "modal {d}/crank.toml --mesh-size -1", {}, 2, ["--mesh-size"]),
    ("modal-mesh-missing", "modal {d}/crank.toml --mesh {d}/none.msh", {}, 2, ["--mesh", "no such file"]),
    ("modal-mesh-txt", "modal {d}/crank.toml --mesh {d}/notes.txt", {}, 2, ["--mesh", ".msh"]),
    ("modal-refine-mesh", "modal {d}/crank.toml --refine --mesh {d}/notes.txt", {}, 2, ["--refine", "--mesh"]),
    ("run-user-folder", "run {d}/crank.toml --out {d}/report", {}, 2, ["--out", "not a fetorsion report", "notes.md"]),
    ("run-out-file", "run {d}/crank.toml --out {d}/notes.txt", {}, 2, ["--out", "not a folder"]),
    ("run-out-holds-input", "run {d}/crank.toml --out {d} --force", {}, 2, ["--out", "crank.toml"]),
    ("run-all-file", "run --all {d}/crank.toml", {}, 2, ["--all"]),
    ("run-tiny-mesh", "run {d}/crank.toml --out {d}/new --mesh-size 0.01", {}, 2, ["--mesh-size", "GiB"]),
    ("run-chain-fe-option", "run {d}/c.toml --out {d}/new", {"c.toml": ENGINE_CHAIN.replace("[1]\nloss", "[3]\nloss")},
     2, ["chain.cylinder_stations"]),
    ("kinematics-step-0", "kinematics {d}/mech.toml --step 0", {}, 2, ["--step", "> 0"]),
    ("kinematics-step-big", "kinematics {d}/mech.toml --step 400", {}, 2, ["--step", "<= 360"]),
    ("kinematics-rpm-0", "kinematics {d}/mech.toml --rpm 0", {}, 2, ["--rpm"]),
    ("kinematics-crank-no-rpm", "kinematics {d}/crank.toml", {}, 2, ["--rpm"]),
    ("flywheel-cs-negative", "flywheel {d}/crank.toml --rpm 2000 --speed-fluctuation -0.04", {}, 2,
     ["--speed-fluctuation"]),
    ("flywheel-cs-big", "flywheel {d}/mech.toml --speed-fluctuation 1.5", {}, 2, ["--speed-fluctuation"]),
    ("flywheel-rpm-negative", "flywheel {d}/crank.toml --rpm -1", {}, 2, ["--rpm"]),
    ("balance-crank", "balance {d}/crank.toml", {}, 2, ["mechanics file"]),
    ("balance-json-txt", "balance {d}/mech.toml --json {d}/out.txt", {}, 2, ["--json"]),
    # --- [distributions] of the [uncertainty] inputs (issue 15)
    ("dist-unknown-entry", "lumped {d}/x.toml", {"x.toml": RENAULT + '\n[distributions]\n"webs.*.width" = "normal"\n'},
     2, ["distributions.webs.*.width", "no [uncertainty] entry"]),
    ("dist-kind", "lumped {d}/x.toml", {"x.toml": RENAULT + '\n[distributions]\n"webs.*.thickness" = "gamma"\n'},
     2, ["distributions.webs.*.thickness", "triangular"]),
    ("dist-normal-no-sd", "lumped {d}/x.toml", {"x.toml": RENAULT + '\n[distributions]\nmaterial = { kind = "normal" }\n'},
     2, ["distributions.material.sd", "sd > 0"]),
    ("dist-normal-sd-negative", "lumped {d}/x.toml",
     {"x.toml": RENAULT + '\n[distributions]\nmaterial = { kind = "normal", sd = -1.0e9 }\n'}, 2,
     ["distributions.material.sd"]),
    ("dist-triangular-sd", "lumped {d}/x.toml",
     {"x.toml": RENAULT + '\n[distributions]\nmaterial = { kind = "triangular", sd = 1.0e9 }\n'}, 2,
     ["distributions.material.sd", "only a normal"]),
    ("dist-extra-key", "lumped {d}/x.toml",
     {"x.toml": RENAULT + '\n[distributions]\nmaterial = { kind = "normal", sd = 1.0e9, mean = 2.0e11 }\n'}, 2,
     ["distributions.material", "mean"]),
    ("dist-triangular-at-high", "lumped {d}/x.toml",  # the webs' nominal 22 mm made the high bound
     {"x.toml": edit('"webs.*.thickness" = [19.0, 25.0]', '"webs.*.thickness" = [19.0, 22.0]')
      + '\n[distributions]\n"webs.*.thickness" = "triangular"\n'}, 2,
     ["distributions.webs.*.thickness", "below the high bound"]),
    # --- fetorsion study (issue 15): every option refused before the cluster starts
    ("study-method", "study {d}/crank.toml --method latin", {}, 2, ["--method", "latin"]),
    ("study-samples-0", "study {d}/crank.toml --samples 0", {}, 2, ["--samples"]),
    ("study-sobol-not-pow2", "study {d}/crank.toml --method sobol --samples 100", {}, 2, ["--samples", "power of 2"]),
    ("study-grid-too-big", "study {d}/crank.toml --method grid --samples 10", {}, 2, ["--samples", "fewer inputs"]),
    ("study-output-unknown", "study {d}/crank.toml --outputs f1,f9", {}, 2, ["--outputs", "f9"]),
    ("study-output-empty", "study {d}/crank.toml --outputs f1,,f2", {}, 2, ["--outputs"]),
    ("study-fe-severity", "study {d}/crank.toml --model fe --outputs severity", {}, 2, ["--outputs", "severity"]),
    ("study-severity-no-excitation", "study {d}/x.toml --outputs severity",
     {"x.toml": RENAULT.split("[excitation]")[0] + "[uncertainty]" + RENAULT.split("[uncertainty]")[1]}, 2,
     ["--outputs severity", "[excitation]"]),
    ("study-input-unknown", "study {d}/crank.toml --inputs webs.*.thickness,bore", {}, 2, ["--inputs", "bore"]),
    ("study-fe-fillets", "study {d}/crank.toml --model fe --inputs fillets.pin", {}, 2, ["--inputs", "fillets.pin"]),
    ("study-model", "study {d}/crank.toml --model lumped7", {}, 2, ["--model"]),
    ("study-workers-0", "study {d}/crank.toml --workers 0", {}, 2, ["--workers"]),
    ("study-workers-scheduler", "study {d}/crank.toml --workers 2 --scheduler tcp://127.0.0.1:8786", {}, 2,
     ["--workers", "--scheduler"]),
    ("study-scheduler-port", "study {d}/crank.toml --scheduler tcp://host:port", {}, 2, ["--scheduler", "host:port"]),
    ("study-seed", "study {d}/crank.toml --seed -1", {}, 2, ["--seed"]),
    ("study-no-uncertainty", "study {d}/x.toml", {"x.toml": CERTAIN}, 2, ["x.toml", "[uncertainty]"]),
    ("study-chain", "study {d}/chain.toml", {}, 2, ["chain.toml", "chain file"]),
    ("study-out-user-folder", "study {d}/crank.toml --out {d}/report", {}, 2, ["--out", "not a fetorsion report"]),
    ("study-out-holds-input", "study {d}/crank.toml --out {d} --force", {}, 2, ["--out", "crank.toml"]),
    ("study-store-file", "study {d}/crank.toml --store {d}/notes.txt", {}, 2, ["--store", "not a folder"]),
    ("study-fe-tiny-mesh", "study {d}/crank.toml --model fe --mesh-size 0.01", {}, 2, ["--mesh-size", "GiB"]),
    # --- fetorsion calibrate (issue 28): every option refused by name before any model run
    ("calibrate-no-uncertainty", "calibrate {d}/x.toml --measured-hz 530", {"x.toml": CERTAIN}, 2,
     ["x.toml", "[uncertainty]"]),
    ("calibrate-input-unknown", "calibrate {d}/crank.toml --measured-hz 530 --inputs material bore", {}, 2,
     ["--inputs", "bore"]),
    ("calibrate-input-twice", "calibrate {d}/crank.toml --measured-hz 530 --inputs material material", {}, 2,
     ["--inputs", "material", "twice"]),
    ("calibrate-too-many-inputs", "calibrate {d}/crank.toml --measured-hz 530 --inputs " + " ".join(["material"] * 16),
     {}, 2, ["--inputs", "16 names", "only 15"]),
    ("calibrate-negative-hz", "calibrate {d}/crank.toml --measured-hz -530", {}, 2, ["--measured-hz", "> 0"]),
    ("calibrate-descending", "calibrate {d}/crank.toml --measured-hz 905 530", {}, 2, ["--measured-hz", "ascending"]),
    ("calibrate-too-many-modes", "calibrate {d}/crank.toml --model lumped5 --measured-hz 1 2 3 4 5", {}, 2,
     ["--measured-hz", "4 elastic modes"]),
    ("calibrate-sigma-count", "calibrate {d}/crank.toml --measured-hz 530 905 --sigma-hz 1 2 3", {}, 2,
     ["--sigma-hz", "3 values"]),
    ("calibrate-sigma-zero", "calibrate {d}/crank.toml --measured-hz 530 --sigma-hz 0", {}, 2, ["--sigma-hz", "> 0"]),
    ("calibrate-sigma-both", "calibrate {d}/crank.toml --measured-hz 530 --sigma-hz 5 --sigma-percent 1", {}, 2,
     ["--sigma-percent", "--sigma-hz"]),
    ("calibrate-nothing-measured", "calibrate {d}/crank.toml", {}, 2, ["--measured-hz", "--measured"]),
    ("calibrate-uff-truncated", "calibrate {d}/crank.toml --measured {d}/h.uff", {"h.uff": "    -1\n"}, 2,
     ["h.uff", "truncated"]),
    ("calibrate-band-with-hz", "calibrate {d}/crank.toml --measured-hz 530 --band 400 600", {}, 2,
     ["--band", "--measured"]),
    ("calibrate-measured-txt", "calibrate {d}/crank.toml --measured {d}/notes.txt --band 400 600", {}, 2,
     ["--measured", "notes.txt", "universal file"]),
    ("calibrate-measured-missing", "calibrate {d}/crank.toml --measured {d}/none.uff --band 400 600", {}, 2,
     ["--measured", "none.uff", "no such file"]),
    ("calibrate-walkers-few", "calibrate {d}/crank.toml --measured-hz 530 --method bayes --walkers 4", {}, 2,
     ["--walkers", "at least"]),
    ("calibrate-steps-few", "calibrate {d}/crank.toml --measured-hz 530 --steps 10", {}, 2, ["--steps", "at least"]),
    ("calibrate-model-fe", "calibrate {d}/crank.toml --measured-hz 530 --model fe", {}, 2, ["--model"]),
    ("calibrate-stiffness-fe", "calibrate {d}/crank.toml --measured-hz 530 --stiffness fe", {}, 2, ["--stiffness", "fe"]),
    ("calibrate-method", "calibrate {d}/crank.toml --measured-hz 530 --method mcmc", {}, 2, ["--method", "mcmc"]),
    ("calibrate-out-is-input", "calibrate {d}/crank.toml --measured-hz 530 --out {d}/crank.toml --force", {}, 2,
     ["--out", "never over the original"]),
    ("calibrate-out-exists", "calibrate {d}/crank.toml --measured-hz 530 --out {d}/chain.toml", {}, 2,
     ["--out", "exists", "--force"]),
    ("calibrate-out-suffix", "calibrate {d}/crank.toml --measured-hz 530 --out {d}/new.txt", {}, 2, ["--out", ".toml"]),
    ("calibrate-out-folder", "calibrate {d}/crank.toml --measured-hz 530 --out {d}/report", {}, 2, ["--out"]),
    ("calibrate-force-alone", "calibrate {d}/crank.toml --measured-hz 530 --force", {}, 2, ["--force", "--out"]),
    ("calibrate-json-txt", "calibrate {d}/crank.toml --measured-hz 530 --json {d}/notes.txt", {}, 2, ["--json"]),
    ("no-command", "", {}, 2, ["command"]),
    ("unknown-command", "frobnicate {d}/crank.toml", {}, 2, ["frobnicate"]),
]

# Valid descriptions with dimensions that fit no engine: they run, and say which value to check.
WARNINGS = [
    ("metres-for-mm", "lumped {d}/x.toml", {"x.toml": edit('length = "mm"', 'length = "m"')}, 0,
     ["warning", "engine.stroke", '"mm"']),
    ("km-shaft", "lumped {d}/x.toml", {"x.toml": edit("length = 45.0", "length = 1.0e6", CERTAIN)}, 0,
     ["warning", "front.1.length"]),
    ("tiny-rod-ratio", "lumped {d}/x.toml", {"x.toml": edit("rod_length = 149.1", "rod_length = 2000.0")}, 0,
     ["warning", "engine.rod_length"]),
]


# ---------------------------------------------------------------------------
# Measured data (fetorsion.measured): each bad file is one FetorsionError naming the file and the
# problem, raised before any work, and the folder is left as it was.


def uff_bytes(binary: bool = True, kind: str = "frf") -> bytes:
    """A valid dataset-58 file (one FRF, or one order cut), as bytes."""
    import tempfile
    from pathlib import Path

    import numpy as np

    from fetorsion.measured import MeasuredFunction, write_uff58

    f = np.arange(1.0, 65.0)
    if kind == "frf":
        function = MeasuredFunction("frf", f, "frequency", 1 / (1e4 - f**2 + 1j * f), "rad", (1, 4), (1, 4), "N m")
    else:
        function = MeasuredFunction("order function", 1000 + 50 * f, "speed", 1e-3 / f, "rad", (1, 4), order=2.0)
    with tempfile.TemporaryDirectory() as folder:
        return write_uff58(Path(folder) / "f.uff", [function], binary=binary).read_bytes()


HEADER_151 = """    -1
   151
crank
NONE
fetorsion
24-Nov-26 06:00:00           1         0         0
24-Nov-26 06:00:00
fetorsion
24-Nov-26 06:12:52
    -1
"""


# two channels of tooth-edge times: a pulley of 4 teeth, a flywheel
EDGES = "# unit = s\npulley, flywheel\n" + "".join(f"{i * 1e-3:g}, {i * 1e-3 + 1e-4:g}\n" for i in range(9))


def measured(call: str):
    """A call of the measured-data API on the case's folder ``d``."""
    import fetorsion.measured as m

    return lambda d: eval(call, {"m": m, "d": d})


# (id, call on the folder d, extra files, texts the message must hold)
MEASURED_CASES = [
    ("uff-missing", "m.read_uff58(d / 'none.uff')", {}, ["none.uff", "not a file"]),
    ("uff-text", "m.read_uff58(d / 'notes.txt')", {}, ["notes.txt", "not a universal file"]),
    ("uff-truncated-ascii", "m.read_uff58(d / 'f.uff')", {"f.uff": uff_bytes(False)[:1500]}, ["f.uff", "truncated"]),
    ("uff-truncated-binary", "m.read_uff58(d / 'f.uff')", {"f.uff": uff_bytes(True)[:-200]}, ["f.uff", "truncated"]),
    ("uff-values-cut", "m.read_uff58(d / 'f.uff')",  # data lines removed, the closing line kept
     {"f.uff": b"\n".join(uff_bytes(False).split(b"\n")[:30] + [b"    -1", b""])}, ["f.uff", "truncated", "64 values"]),
    ("uff-151-only", "m.read_uff58(d / 'f.uff')", {"f.uff": HEADER_151}, ["f.uff", "151", "no dataset 58"]),
    ("uff-time-response", "m.read_uff58(d / 'f.uff')",
     {"f.uff": uff_bytes(False).replace(b"\n    4         0", b"\n    1         0", 1)}, ["f.uff", "function type 1"]),
    # no label and a record 9 of data type 0 (general): nothing says the unit (a NONE label with a
    # data type is read in its SI unit: tests/test_uff_labels.py)
    ("uff-no-unit", "m.read_uff58(d / 'f.uff')", {"f.uff": uff_bytes(True, "order").replace(
        b"         8    0    0    0 angle                rad                 ",
        b"         0    0    0    0 angle                NONE                ", 1)},
     ["f.uff", "ordinate has no unit label and record 9 says no quantity"]),
    ("uff-unknown-unit", "m.read_uff58(d / 'f.uff')", {"f.uff": uff_bytes(True, "order").replace(
        b"         8    0    0    0 angle                rad                 ",
        b"         0    0    0    0 angle                furlong             ", 1)},
     ["f.uff", "'furlong' is not a unit fetorsion knows, and record 9 field 1 says no quantity"]),
    ("cut-no-unit", "m.read_order_cut_csv(d / 'c.csv')", {"c.csv": "1000, 1\n2000, 2\n3000, 1\n"},
     ["c.csv", "no unit"]),
    ("cut-units-disagree", "m.read_order_cut_csv(d / 'c.csv', unit='rad')", {"c.csv": "# unit = deg\n" + CURVE[13:]},
     ["c.csv", "'# unit = deg'", "'rad'"]),
    ("cut-unknown-unit", "m.read_order_cut_csv(d / 'c.csv')", {"c.csv": "# unit = furlong\n" + CURVE[13:]},
     ["c.csv", "'furlong' is not known"]),
    ("cut-speed-unit", "m.read_order_cut_csv(d / 'c.csv', unit='rpm')", {"c.csv": CURVE[13:]},
     ["c.csv", "'rpm' is a unit of speed"]),
    ("cut-four-columns", "m.read_order_cut_csv(d / 'c.csv', unit='deg')", {"c.csv": "1, 2, 3, 4\n" * 3},
     ["c.csv", "rpm, amplitude[, phase_deg]"]),
    ("cut-order-word", "m.read_order_cut_csv(d / 'c.csv')", {"c.csv": "# order = second\n" + CURVE},
     ["c.csv", "'# order = second' is not a number"]),
    ("edges-no-unit", "m.read_edges_csv(d / 'e.csv')", {"e.csv": EDGES.replace("# unit = s\n", "")},
     ["e.csv", "no unit"]),
    ("edges-backwards", "m.read_edges_csv(d / 'e.csv')", {"e.csv": EDGES.replace("0.003,", "0.0015,")},
     ["e.csv", "'pulley'", "not increasing", "edge 4"]),
    ("edges-no-pulses", "m.read_edges_csv(d / 'e.csv')", {"e.csv": "# unit = s\npulley, flywheel\n" + "".join(
        f"{i * 1e-3},\n" for i in range(9))}, ["e.csv", "'flywheel'", "no pulses"]),
    ("edges-one-revolution", "m.read_edges_csv(d / 'e.csv', teeth={'pulley': 60})",
     {"e.csv": EDGES}, ["e.csv", "'pulley'", "9 pulses", "too few", "60 teeth"]),
    ("edges-word", "m.read_edges_csv(d / 'e.csv')", {"e.csv": EDGES.replace("0.004,", "four,")},
     ["e.csv", "line 7", "'four' is not a number"]),
    ("edges-gap", "m.read_edges_csv(d / 'e.csv')", {"e.csv": EDGES.replace("0.0021", "")},
     ["e.csv", "'flywheel'", "empty cell", "line 5"]),
    ("edges-same-names", "m.read_edges_csv(d / 'e.csv')", {"e.csv": EDGES.replace("flywheel", "pulley")},
     ["e.csv", "distinct channel names"]),
    ("edges-no-header", "m.read_edges_csv(d / 'e.csv')", {"e.csv": EDGES.replace("pulley, flywheel\n", "")},
     ["e.csv", "must name the channels"]),
    ("edges-no-teeth", "m.run_torsiograph(m.read_edges_csv(d / 'e.csv'), {'pulley': 4}, 1)", {"e.csv": EDGES},
     ["'flywheel'", "no teeth per revolution"]),
    ("uff-bad-units-key", "m.read_uff58(d / 'f.uff', units={'y': 'rad'})", {"f.uff": uff_bytes()}, ["f.uff", "'y'"]),
]


@pytest.mark.parametrize("case", MEASURED_CASES, ids=["measured-" + c[0] for c in MEASURED_CASES])
def test_bad_measured_file_is_one_message_naming_it(case, tmp_path):
    from fetorsion.errors import FetorsionError

    name, call, extra, needles = case
    folder = make_folder(tmp_path, extra)
    before = snapshot(folder)
    with pytest.raises(FetorsionError) as info:
        measured(call)(folder)
    text = str(info.value)
    for needle in needles:
        assert needle in text, f"{name}: message does not name {needle!r}: {text}"
    assert "\n" not in text, f"{name}: more than one message: {text}"
    assert snapshot(folder) == before, f"{name}: the folder changed"


def snapshot(folder) -> dict:
    """Every entry below ``folder``: kind, mode and content hash."""
    out = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(root, name)
            st = os.lstat(path)
            digest = "" if os.path.isdir(path) else hashlib.sha256(open(path, "rb").read()).hexdigest()
            out[os.path.relpath(path, folder)] = (st.st_mode, digest)
    return out


def make_folder(tmp_path, extra: dict):
    for name, content in {**BASE, **extra}.items():
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if content is None:  # a sparse file over the size limit: nothing to read, no disk used
            with open(path, "wb") as fh:
                fh.truncate(17 * 2**20)
        elif isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content)
    return tmp_path


def run_cli(argv: list[str], capsys) -> tuple[int, str]:
    try:
        code = cli_main(argv)
    except SystemExit as exc:  # argparse
        code = exc.code
    captured = capsys.readouterr()
    return code, captured.out + captured.err


def _check(case, tmp_path, capsys, monkeypatch):
    name, argv, extra, status, needles = case
    folder = make_folder(tmp_path, extra)
    monkeypatch.chdir(folder)
    before = snapshot(folder)
    code, text = run_cli(argv.format(d=folder).split(), capsys)
    assert code == status, f"{name}: exit {code}\n{text}"
    for needle in needles:
        assert needle in text, f"{name}: message does not name {needle!r}:\n{text}"
    assert "Traceback" not in text
    if status != 0:
        assert "error" in text
    assert snapshot(folder) == before, f"{name}: the folder changed"
    return text


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_bad_input_is_refused_by_name_and_touches_nothing(case, tmp_path, capsys, monkeypatch):
    _check(case, tmp_path, capsys, monkeypatch)


@pytest.mark.parametrize("case", WARNINGS, ids=[c[0] for c in WARNINGS])
def test_implausible_dimension_is_warned_by_name(case, tmp_path, capsys, monkeypatch):
    _check(case, tmp_path, capsys, monkeypatch)


def test_battery_is_large():
    assert len(CASES) + len(WARNINGS) >= 60


def test_each_problem_is_reported_once(tmp_path, capsys, monkeypatch):
    """A too-large fillet breaks its rule against all eight webs: one line, not eight; and a
    negative journal diameter does not drag in its (unset) bore."""
    text = edit("\njournal = 2.5", "\njournal = 30.0", CERTAIN)
    text = text.replace("diameter = 54.8", "diameter = -54.8", 1)
    case = ("once", "lumped {d}/x.toml", {"x.toml": text}, 2, ["fillets.journal", "journals.1.diameter"])
    out = _check(case, tmp_path, capsys, monkeypatch)
    assert out.count("fillets.journal") == 1, out
    assert "bore" not in out, out


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root may write anywhere")
def test_read_only_destination_is_refused_before_work(tmp_path, capsys, monkeypatch):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o555)
    try:
        case = ("read-only", "lumped {d}/crank.toml --json {d}/locked/out.json", {}, 2, ["--json", "permission"])
        _check(case, tmp_path, capsys, monkeypatch)
    finally:
        locked.chmod(0o755)


def test_subprocess_shows_no_traceback(tmp_path):
    """The real program (not main() in-process) on a binary description."""
    import subprocess

    bad = tmp_path / "bin.toml"
    bad.write_bytes(bytes(range(256)))
    p = subprocess.run([sys.executable, "-m", "fetorsion.cli", "lumped", str(bad)], capture_output=True, text=True)
    assert p.returncode == 2 and "not UTF-8" in p.stderr and "Traceback" not in p.stderr


# ---------------------------------------------------------------------------
# Output locations: kills, stale temporaries, user folders


def _tree(folder):
    return snapshot(folder) if folder.exists() else None


def _strays(parent):
    from fetorsion.io import TMP_TAG

    return [p.name for p in parent.iterdir() if TMP_TAG in p.name]


@pytest.mark.fe
@pytest.mark.slow
def test_sigkill_midway_leaves_the_earlier_report_and_the_next_run_cleans_up(tmp_path):
    """SIGKILL during the FE step: the earlier report is intact; the next run removes the
    killed run's temporary folder and leaves no stray of its own; no meshing child lives on."""
    import signal
    import subprocess
    import time

    crank, report = str(GEOMETRY / "renault21.toml"), tmp_path / "report"
    cmd = [sys.executable, "-m", "fetorsion.cli", "run", crank, "--out", str(report)]
    assert subprocess.run(cmd + ["--no-fe"], capture_output=True).returncode == 0
    earlier = _tree(report)
    proc = subprocess.Popen(cmd, stderr=subprocess.PIPE, text=True, cwd=tmp_path)
    for line in proc.stderr:  # kill once the run is inside its FE step
        if "meshing the Gmsh solid" in line:
            break
    mark = f"FETORSION_ISOLATE_PARENT={proc.pid}".encode()
    for _ in range(100):  # ... with its meshing child at work
        children = [p for p in os.listdir("/proc") if p.isdigit() and mark in _read(f"/proc/{p}/environ").split(b"\0")]
        if children:
            break
        time.sleep(0.05)
    assert children, "the run should be meshing in a child process"
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL
    assert _strays(tmp_path), "the killed run should have left its temporary folder"
    assert _tree(report) == earlier
    for _ in range(100):  # the kernel ends the child with its parent (give it 5 s to go)
        alive = [p for p in children if mark in _read(f"/proc/{p}/environ").split(b"\0")]
        if not alive:
            break
        time.sleep(0.05)
    assert not alive, "a meshing child of the killed run lives on"
    assert subprocess.run(cmd + ["--no-fe"], capture_output=True).returncode == 0
    assert not _strays(tmp_path)
    assert (report / "report.md").exists()


def _read(path) -> bytes:
    try:
        with open(path, "rb") as fh:
            return fh.read()
    except OSError:
        return b""


def test_out_folder_of_user_files_is_refused_and_survives(tmp_path, capsys):
    folder = tmp_path / "project"
    folder.mkdir()
    (folder / "crank.toml").write_text(RENAULT)
    (folder / "notes.txt").write_text("mine\n")
    before = snapshot(tmp_path)
    code, text = run_cli(["run", str(folder / "crank.toml"), "--out", str(folder), "--no-fe"], capsys)
    assert code == 2 and "--out" in text and "Traceback" not in text
    assert snapshot(tmp_path) == before
    # the same with --force: the folder holds the description itself, so still refused
    code, text = run_cli(["run", str(folder / "crank.toml"), "--out", str(folder), "--no-fe", "--force"], capsys)
    assert code == 2 and snapshot(tmp_path) == before


@pytest.mark.slow
def test_earlier_report_is_replaced_but_not_one_the_user_added_to(tmp_path, capsys):
    out = tmp_path / "report"
    argv = ["run", str(GEOMETRY / "renault21.toml"), "--out", str(out), "--no-fe"]
    assert run_cli(argv, capsys)[0] == 0
    assert run_cli(argv, capsys)[0] == 0  # an earlier report: replaced
    (out / "my-comments.txt").write_text("keep me\n")
    code, text = run_cli(argv, capsys)
    assert code == 2 and "my-comments.txt" in text
    assert (out / "my-comments.txt").read_text() == "keep me\n"
    assert run_cli(argv + ["--force"], capsys)[0] == 0  # the user said so
    assert not (out / "my-comments.txt").exists() and (out / "report.md").exists()


def test_stale_temporaries_of_dead_runs_are_removed_live_ones_kept(tmp_path):
    from fetorsion.io import TMP_TAG, write_text_atomic

    dead = subprocess_pid_that_has_exited()
    stale = tmp_path / f".out.json{TMP_TAG}{dead}-abc.json"
    live = tmp_path / f".out.json{TMP_TAG}{os.getpid()}-def.json"
    other = tmp_path / ".out.json.user-file"
    for p in (stale, live, other):
        p.write_text("x")
    write_text_atomic(tmp_path / "out.json", "{}")
    assert not stale.exists() and live.exists() and other.exists()


def subprocess_pid_that_has_exited() -> int:
    import subprocess

    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_native_abort_in_isolated_call_is_an_ordinary_error():
    from fetorsion.errors import FetorsionError
    from fetorsion.solid.isolate import call_isolated

    with pytest.raises(FetorsionError, match="SIGABRT"):
        call_isolated(os.abort, what="Gmsh")
    assert call_isolated(sum, [1, 2, 3]) == 6


def test_study_scheduler_from_the_environment_is_checked_by_name(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", "tcp://host:port")
    case = ("study-env-scheduler", "study {d}/crank.toml", {}, 2, ["DASK_SCHEDULER_ADDRESS", "host:port"])
    _check(case, tmp_path, capsys, monkeypatch)


def test_run_checks_the_scheduler_from_the_environment_before_any_work(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", "tcp://host:port")
    case = ("run-env-scheduler", "run {d}/crank.toml --out {d}/new --no-fe", {}, 2, ["DASK_SCHEDULER_ADDRESS"])
    _check(case, tmp_path, capsys, monkeypatch)


def test_unreachable_scheduler_is_one_message():
    from fetorsion.errors import ParameterError
    from fetorsion.studies.runner import open_client

    # Named by the API's parameter; the command line names its option (--scheduler) instead.
    with pytest.raises(ParameterError, match="^scheduler tcp://127.0.0.1:1: no scheduler answered") as info:
        with open_client("tcp://127.0.0.1:1", timeout_s=1.0):
            pass
    assert info.value.parameter == "scheduler"
