"""The time domain's cost: a 20-station geared, branched network run up from 1000 to 6000 rpm at
1000 rpm/s (5 s of running), orders to 12 resolved.

    python benchmarks/bench_transient.py            # prints wall, CPU, samples and the load average

The network: the MWM six-cylinder chain of examples/mendes2008 (9 stations: pulley, gear train,
six throws, flywheel; its engine and excitation), a clutch damper to a gearbox input gear, the
gearbox (input gear, output gear at 0.35), a propeller shaft, a differential (crown wheel at
0.3 of the pinion's speed), a half shaft (with a station) to the left wheel and one to the right
(a branch), and an accessory branch geared off the gear-train station (1.8 : 1) to a pump: 20 stations, 8 of them behind gears. Illustrative
driveline numbers (not a validation case). The order track of the pulley (a 120-tooth wheel,
blocks of 2 revolutions) resolves orders 0.5 … 59.5, 12 among them; the step is 0.5° of crank at
6000 rpm (the torque's orders to 360 sampled).

The nonlinear line (issue 43's case): the same engine and driveline with a dual-mass flywheel and a
multi-stage clutch damper, both with friction, and the slider-crank's variable inertia on, run up 1000
to 6000 rpm at 1000 rpm/s by the compiled integrator. The MWM flywheel is split into the DMF's primary
(55 %) and secondary (45 %) on arc springs of 2e3 N m/rad to 35°, 2e4 beyond, 30 N m friction; the
clutch damper (secondary to clutch hub) has three stages, 3e3, 1.5e4 and 3e4 N m/rad from 0°, 4° and
8°, 20 N m friction; the left half shaft's station is dropped (both half shafts 8e3 N m/rad) so that
there are still 20 stations. Illustrative numbers, as above.

    python benchmarks/bench_transient.py --reference    # also the scipy LSODA run (about 25 min)

``--reference`` runs the same case by scipy's LSODA (friction by Bouc–Wen's rate law), the integrator
the compiled one replaced, and prints the largest section torque of each and where.

Target (issue): ≤ 10 s on 2 cores. The machine's 1-minute load average is printed before the run:
a figure taken above 0.5 is indicative only.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import fetorsion  # noqa: E402

from fetorsion.description.chain_model import GearPair, Network, NonlinearSpring, Shaft
from fetorsion.response.transient import run_transient  # noqa: E402

from bench_run import cpu_name as cpu_model  # noqa: E402  (this folder is on the path: one CPU reader)


#: The clutch damper's (first-stage) stiffness, N m/rad.
CLUTCH_NM_PER_RAD = 3.0e3


def network() -> Network:
    """The 20-station driveline (module docs)."""
    chain = fetorsion.load(ROOT / "examples" / "mendes2008" / "mwm6_chain.toml")
    labels = list(chain.labels) + ["clutch hub", "gearbox in", "gearbox out", "propshaft", "pinion", "crown wheel",
                                   "half shaft L", "wheel L", "wheel R", "pump gear", "pump"]
    inertias = list(chain.inertias) + [0.02, 0.01, 0.03, 0.02, 0.005, 0.08, 0.01, 1.5, 1.5, 0.002, 0.01]
    n0 = len(chain.inertias)
    shafts = [Shaft(i, i + 1, k, 0.0, 0.035) for i, k in enumerate(chain.stiffnesses)]
    idx = {s: i for i, s in enumerate(labels)}
    for a, b, k in (("flywheel", "clutch hub", CLUTCH_NM_PER_RAD), ("clutch hub", "gearbox in", 2.0e5),
                    ("gearbox out", "propshaft", 4.0e4), ("propshaft", "pinion", 4.0e4),
                    ("crown wheel", "half shaft L", 3.0e4), ("half shaft L", "wheel L", 1.0e4),
                    ("crown wheel", "wheel R", 8.0e3), ("pump gear", "pump", 2.0e3)):
        shafts.append(Shaft(idx[a], idx[b], k, 0.0, 0.05))
    gears = (GearPair(idx["gearbox in"], idx["gearbox out"], 0.35), GearPair(idx["pinion"], idx["crown wheel"], 0.3),
             GearPair(idx["gear train"], idx["pump gear"], 1.8))
    assert len(labels) == 20 and n0 == 9
    return Network("20-station geared driveline (bench)", tuple(labels), tuple(inertias), tuple(shafts), gears,
                   tuple(chain.absolute_damping) + (0.0,) * 11, "benchmarks/bench_transient.py",
                   chain.cylinder_stations, chain.engine, chain.excitation, chain.length_unit)


def nonlinear_network() -> Network:
    """The 20-station driveline with a dual-mass flywheel and a three-stage clutch damper (module docs)."""
    chain = fetorsion.load(ROOT / "examples" / "mendes2008" / "mwm6_chain.toml")
    labels = list(chain.labels[:-1]) + ["DMF primary", "DMF secondary", "clutch hub", "gearbox in", "gearbox out",
                                        "propshaft", "pinion", "crown wheel", "wheel L", "wheel R", "pump gear", "pump"]
    flywheel = chain.inertias[-1]
    inertias = list(chain.inertias[:-1]) + [0.55 * flywheel, 0.45 * flywheel, 0.02, 0.01, 0.03, 0.02, 0.005, 0.08,
                                            1.5, 1.5, 0.002, 0.01]
    shafts = [Shaft(i, i + 1, k, 0.0, 0.035) for i, k in enumerate(chain.stiffnesses)]
    idx = {s: i for i, s in enumerate(labels)}
    for a, b, k in (("clutch hub", "gearbox in", 2.0e5), ("gearbox out", "propshaft", 4.0e4),
                    ("propshaft", "pinion", 4.0e4), ("crown wheel", "wheel L", 8.0e3),
                    ("crown wheel", "wheel R", 8.0e3), ("pump gear", "pump", 2.0e3)):
        shafts.append(Shaft(idx[a], idx[b], k, 0.0, 0.05))
    gears = (GearPair(idx["gearbox in"], idx["gearbox out"], 0.35), GearPair(idx["pinion"], idx["crown wheel"], 0.3),
             GearPair(idx["gear train"], idx["pump gear"], 1.8))
    elements = (NonlinearSpring(idx["DMF primary"], idx["DMF secondary"], (2.0e3, 2.0e4), (np.radians(35.0),), 30.0,
                                name="DMF arc springs"),
                NonlinearSpring(idx["DMF secondary"], idx["clutch hub"], (3.0e3, 1.5e4, 3.0e4),
                                (np.radians(4.0), np.radians(8.0)), 20.0, name="clutch damper"))
    assert len(labels) == 20
    return Network("20-station driveline with a DMF and a clutch damper (bench)", tuple(labels), tuple(inertias),
                   tuple(shafts), gears, tuple(chain.absolute_damping) + (0.0,) * 11, "benchmarks/bench_transient.py",
                   chain.cylinder_stations, chain.engine, chain.excitation, chain.length_unit, nonlinear=elements)


def largest(res) -> str:
    """The largest section torque of a run and where it is."""
    P = res.block_peak_nm
    i, s = np.unravel_index(np.argmax(P), P.shape)
    return f"{P[i, s]:.1f} N m in {res.section_labels[s]} at {res.block_rpm[i]:.1f} rpm"


def main() -> int:
    net = network()
    load = os.getloadavg()[0]
    print(f"load average (1 min) before the run: {load:.2f}" + ("  -> figure indicative only" if load > 0.5 else ""))
    t0, c0 = time.perf_counter(), time.process_time()
    res = run_transient(net, run=(1000.0, 6000.0), rate_rpm_per_s=1000.0)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    orders = res.track.orders
    print(f"{res.name}: {res.mode}")
    print(f"  samples {res.time_s.size:,} (step {res.step_s * 1e6:.2f} us), {len(res.labels)} coordinates, "
          f"{len(res.section_labels)} sections; order track {res.track.rpm.size} blocks, orders "
          f"{orders[0]:g} ... {orders[-1]:g} (12 resolved: {bool(np.any(np.isclose(orders, 12.0)))})")
    print(f"  wall {wall:.2f} s, CPU {cpu:.2f} s (target <= 10 s on 2 cores)")
    # the nonlinear line: DMF, three-stage clutch damper, variable inertia; 1000-6000 rpm
    nl = nonlinear_network()
    run_transient(nl, run=(1000.0, 1250.0), rate_rpm_per_s=1000.0, variable_inertia=True)  # compiles once
    t0, c0 = time.perf_counter(), time.process_time()
    res = run_transient(nl, run=(1000.0, 6000.0), rate_rpm_per_s=1000.0, variable_inertia=True)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    print(f"nonlinear: {res.mode}, {res.time_s.size:,} samples; {res.scheme}")
    print(f"  wall {wall:.2f} s, CPU {cpu:.2f} s on {cpu_model()} (target <= 10 s on 2 cores)")
    print(f"  largest section torque {largest(res)}")
    if "--reference" in sys.argv[1:]:
        t0 = time.perf_counter()
        ref = run_transient(nl, run=(1000.0, 6000.0), rate_rpm_per_s=1000.0, variable_inertia=True, method="LSODA")
        print(f"reference: {ref.scheme}; wall {time.perf_counter() - t0:.1f} s")
        print(f"  largest section torque {largest(ref)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
