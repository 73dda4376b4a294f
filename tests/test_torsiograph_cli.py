"""Issue 42: tooth-edge records as a test engineer brings them to the command line — with their
calibration run, two channels and their twist, a lost or a spurious edge, a 60-2 reference wheel
— each checked against the vibration the record was made from."""

from __future__ import annotations

import json

import numpy as np
import pytest

from conftest import GEOMETRY
from fetorsion.cli import main
from test_measured import JITTER_S, edge_times, expected, sines

SPEED = 2 * np.pi * 3000 / 60  # rad/s
#: three orders on the pulley (a half order, the firing order, a high one), one on the flywheel
PULLEY = [(np.radians(0.04), 1.5, -2.0), (np.radians(0.12), 2.0, 0.7), (np.radians(0.03), 4.0, 1.1)]
FLYWHEEL = [(np.radians(0.03), 2.0, 2.2), (np.radians(0.01), 4.0, -0.4)]
TEETH = {"pulley": 60, "flywheel": 132}


def tooth_errors(z, rng):
    """Fixed spacing errors of a real wheel: eccentric (order 1), oval (order 2), random pitch."""
    at = 2 * np.pi * np.arange(z) / z
    e = np.radians(0.04 * np.cos(at) + 0.05 * np.sin(2 * at + 0.3) + rng.normal(0, 0.02, z))
    return e - e.mean()


def record(theta, dtheta, z, revolutions, errors, speed, rng, places=None):
    """Edge times of a wheel of ``z`` places turning by theta(t), its teeth at 2πi/z + e, with
    timing jitter; ``places`` keeps only those tooth places (a reference-gap wheel)."""
    i = np.arange(revolutions * z + 1)
    if places is not None:
        i = i[np.isin(i % z, places)]
    t = edge_times(theta, dtheta, 2 * np.pi * i / z + errors[i % z], speed)
    return t + rng.normal(0.0, JITTER_S, t.size)


@pytest.fixture(scope="module")
def engine():
    rng = np.random.default_rng(42)
    errors = {name: tooth_errors(z, rng) for name, z in TEETH.items()}
    coast, slowing = 2 * np.pi * 800 / 60, -5.0
    edges = {name: record(*sines(SPEED, terms), TEETH[name], 40, errors[name], SPEED, rng)
             for name, terms in (("pulley", PULLEY), ("flywheel", FLYWHEEL))}
    calibration = {name: record(lambda t: coast * t + 0.5 * slowing * t**2, lambda t: coast + slowing * t, z, 30,
                                errors[name], coast, rng) for name, z in TEETH.items()}
    return dict(edges=edges, calibration=calibration, errors=errors, rng=rng)


def write_edges(path, channels: dict) -> str:
    """A tooth-edge CSV (seconds, no unit line: the unit comes from --time-unit)."""
    names = list(channels)
    n = max(len(t) for t in channels.values())
    rows = [", ".join(f"{channels[c][r]:.12e}" if r < len(channels[c]) else "" for c in names) for r in range(n)]
    path.write_text(", ".join(names) + "\n" + "\n".join(rows) + "\n")
    return str(path)


def track(out, channel, order):
    """(complex amplitudes per block) of one tracked order from the command's JSON."""
    w = next(x for x in out["waterfalls"] if x["name"].endswith(f": {channel}"))["track"]
    k = w["orders"].index(order)
    amp, phase = np.radians(np.array(w["amplitude_deg"])[:, k]), np.radians(np.array(w["phase_deg"])[:, k])
    return amp * np.exp(1j * phase)


def assert_orders(c, truth, what):
    """Every block within 1 % and 1 degree of the truth (the issue's bound; the timing jitter
    leaves ~0.2 % and ~0.1 degree on the weakest order)."""
    assert np.max(np.abs(np.abs(c) / abs(truth) - 1)) < 0.01, what
    assert np.max(np.abs(np.degrees(np.angle(c / truth)))) < 1.0, what


def compare(tmp_path, capsys, *args):
    """`compare` of tooth-edge records against the chain, orders against time: the records are
    made as vibrations in time, and against the shaft's own angle an order differs at second order
    (0.5 k a², up to 0.9 % on order 4 here: ``test_orders_against_time_or_against_the_shafts_angle``)."""
    capsys.readouterr()
    path = tmp_path / "c.json"
    assert main(["compare", str(GEOMETRY / "renault21.toml"), *args, "--source", "lumped17", "--order-definition",
                 "time", "--track-orders", "1.5", "2", "4", "--json", str(path)]) == 0
    return json.loads(path.read_text()), capsys.readouterr()


def test_two_channels_their_calibration_run_and_twist_through_the_command_line(tmp_path, capsys, engine):
    """Issue 42: `compare REC.csv --teeth pulley=60 flywheel=132 --calibration CAL.csv --twist
    pulley flywheel --time-unit s`: every order of both wheels and of their twist within 1 % and
    1° of the truth; each channel compared at the station it is named after (the flywheel channel
    at the flywheel end, not the pulley's), and the steady record's line gives the amplitude and
    phase of each order."""
    rec = write_edges(tmp_path / "rec.csv", engine["edges"])
    cal = write_edges(tmp_path / "cal.csv", engine["calibration"])
    out, said = compare(tmp_path, capsys, rec, "--teeth", "pulley=60", "flywheel=132", "--calibration", cal,
                        "--twist", "pulley", "flywheel", "--time-unit", "s")
    for a, k, phi in PULLEY:
        assert_orders(track(out, "pulley", k), expected(a, phi), f"pulley order {k}")
    fly = {k: expected(a, phi) for a, k, phi in FLYWHEEL}
    for a, k, phi in FLYWHEEL:
        assert_orders(track(out, "flywheel", k), expected(a, phi), f"flywheel order {k}")
    for a, k, phi in PULLEY:
        assert_orders(track(out, "twist", k), expected(a, phi) - fly.get(k, 0), f"twist order {k}")
    stations = {c["name"].split(": ")[1].split(",")[0]: c["station"] for c in out["order_cuts"]}
    assert stations["pulley"].endswith("(pulley end)") and stations["flywheel"].endswith("(flywheel end)")
    assert stations["twist"] == "J1 (pulley end) - J5 (flywheel end) twist"
    line = next(x for x in said.out.splitlines() if x.startswith("order 2 at J1") and ": pulley" in x)
    assert "steady at 3000 rpm over 20 blocks" in line
    measured_phase = float(line.split("phase ")[1].split(" deg")[0])
    assert measured_phase == pytest.approx(np.degrees(np.angle(expected(*PULLEY[1][::2]))), abs=1.0)
    # uncalibrated, the oval wheel's 0.05 deg is read as order 2 (the reason the run is needed)
    raw, _ = compare(tmp_path, capsys, rec, "--teeth", "pulley=60", "flywheel=132", "--time-unit", "s")
    assert np.max(np.abs(np.abs(track(raw, "pulley", 2.0)) / PULLEY[1][0] - 1)) > 0.2


def test_a_lost_and_a_spurious_edge_are_repaired_and_named(tmp_path, capsys, engine):
    """The pulley record with edge 1001 removed, and one with a spurious edge 40 % into a pitch:
    the same orders within 1 % (and 1°) as the intact record, each with a warning naming the
    edge and its time."""
    t = engine["edges"]["pulley"]
    lost = np.delete(t, 1000)
    spurious = np.insert(t, 2001, t[2000] + 0.4 * (t[2001] - t[2000]))
    cal = write_edges(tmp_path / "cal.csv", {"pulley": engine["calibration"]["pulley"]})
    for name, edges, warning in (("lost", lost, f"1 edge(s) missing after edge 1000 ({t[999]:.6f} s"),
                                 ("spurious", spurious, f"edge 2002 at {spurious[2001]:.6f} s is spurious")):
        rec = write_edges(tmp_path / f"{name}.csv", {"pulley": edges})
        out, said = compare(tmp_path, capsys, rec, "--teeth", "60", "--calibration", cal, "--time-unit", "s")
        assert warning in said.err and warning in out["notes"][0], name
        for a, k, phi in PULLEY:
            assert_orders(track(out, "pulley", k), expected(a, phi), f"{name}: order {k}")


def test_a_60_minus_2_wheel_starts_its_revolutions_at_the_gap(tmp_path, capsys, engine):
    """A 60-2 wheel (58 teeth, a gap of three pitches once a revolution), recorded from the
    middle of a revolution, with its calibration run: orders within 1 % and 1°, with tooth 0 the
    first tooth after the gap (the record here first passes the gap in its third revolution, so
    the truth's phase holds for the half order too); the gaps are not warned of."""
    rng = np.random.default_rng(7)
    errors = tooth_errors(60, rng)
    teeth = np.arange(58)
    coast, slowing = 2 * np.pi * 800 / 60, -5.0
    rec = record(*sines(SPEED, PULLEY), 60, 40, errors, SPEED, rng, teeth)[17 + 58:]
    cal = record(lambda t: coast * t + 0.5 * slowing * t**2, lambda t: coast + slowing * t, 60, 30, errors, coast,
                 rng, teeth)[5:]
    out, said = compare(tmp_path, capsys, write_edges(tmp_path / "rec.csv", {"pulley": rec}), "--teeth", "60-2",
                        "--calibration", write_edges(tmp_path / "cal.csv", {"pulley": cal}), "--time-unit", "s")
    assert "warning" not in said.err and out["notes"] == []
    for a, k, phi in PULLEY:
        assert_orders(track(out, "pulley", k), expected(a, phi), f"60-2: order {k}")


def test_orders_against_time_or_against_the_shafts_angle(tmp_path, capsys):
    """A strong order 6 (a = 0.5°) made as a vibration in time, θ = Ωt + a sin(6Ωt + φ). Against
    time (`--order-definition time`) it is that one order: amplitude within 0.3 % (jitter and
    interpolation), order 12 below 1 % of the next figure. Against the shaft's own angle (the
    default) ψ = a sin(kθ − kψ + φ) ≈ a sin(kθ + φ) − (k a²/2) sin(2(kθ + φ)): the same order 6
    (to (ka)² = 0.3 %) and an order 12 of k a²/2 = 2.28e-4 rad, found within 2 % (the
    expansion's next term, (ka)² relative). The JSON says which definition was used."""
    rng = np.random.default_rng(3)
    a, k = np.radians(0.5), 6.0
    rec = write_edges(tmp_path / "rec.csv", {"pulley": record(*sines(SPEED, [(a, k, 0.4)]), 60, 20, np.zeros(60),
                                                               SPEED, rng)})
    amp = {}
    for definition in ("time", "angle"):
        capsys.readouterr()
        assert main(["compare", str(GEOMETRY / "renault21.toml"), rec, "--teeth", "60", "--time-unit", "s",
                     "--source", "lumped17", "--track-orders", "6", "--order-definition", definition,
                     "--json", str(tmp_path / f"{definition}.json")]) == 0
        out = json.loads((tmp_path / f"{definition}.json").read_text())
        assert out["waterfalls"][0]["track"]["order_definition"] == definition
        amp[definition] = {q: np.abs(track(out, "pulley", q)) for q in (k, 2 * k)}
    second = k * a**2 / 2
    for definition in ("time", "angle"):
        assert np.max(np.abs(amp[definition][k] / a - 1)) < 0.003, definition
    assert np.max(amp["time"][2 * k]) < 0.01 * second
    assert np.max(np.abs(amp["angle"][2 * k] / second - 1)) < 0.02


@pytest.mark.parametrize("args, message", [
    (["--teeth", "60-40"], "cannot leave out 40 teeth"),
    (["--teeth", "pulley=60", "--twist", "pulley", "crank"], "has no channel 'crank'"),
    (["--teeth", "60", "--channel-station", "pulley=J9"], "station 'J9' is not in the model"),
    (["--teeth", "60", "--channel-station", "pulley"], "give CHANNEL=STATION"),
    (["--teeth", "flywheel=132"], "--teeth of rec.csv's channel 'pulley': not given (give pulley=TEETH)"),
    (["--teeth", "60", "--frf-unit", "furlong"], "unit 'furlong' is not known"),
])
def test_bad_torsiograph_options_give_one_message(tmp_path, capsys, args, message):
    t = np.arange(200) * 1e-4
    rec = write_edges(tmp_path / "rec.csv", {"pulley": t})
    assert main(["compare", str(GEOMETRY / "renault21.toml"), rec, "--time-unit", "s", "--source", "lumped17",
                 *args]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


def test_a_reference_wheel_record_that_never_passes_its_gap_is_refused():
    """A 60-2 record of less than a revolution from the gap on: no tooth 0 to start from, one
    message naming the record (not a wrong phase)."""
    from fetorsion.errors import FetorsionError
    from fetorsion.measured.wheels import repaired_edges

    rng = np.random.default_rng(5)
    t = record(*sines(SPEED, PULLEY), 60, 3, np.zeros(60), SPEED, rng, np.arange(58))
    with pytest.raises(FetorsionError, match="no reference gap|last 4 edges"):
        repaired_edges(t[5:50], "60-2", "rec.csv: pulley")
    with pytest.raises(FetorsionError, match="only reference gap is among its last"):
        repaired_edges(t[20:60], "60-2", "rec.csv: pulley")


def write_one(path, times, channel=None) -> str:
    """A one-wheel tooth-edge CSV as a test rig writes it: its column headed ``t_s`` (the unit in
    the column's name), the wheel named by a ``# channel`` line or not at all."""
    head = f"# channel = {channel}\n" if channel else ""
    path.write_text(head + "t_s\n" + "\n".join(f"{t:.12e}" for t in times) + "\n")
    return str(path)


@pytest.mark.parametrize("swap", [False, True])
def test_one_file_per_wheel_and_their_calibrations_are_matched_by_channel(tmp_path, capsys, engine, swap):
    """Issue 54: a record and a calibration run per wheel, each file one column headed `t_s` and
    its wheel named by a `# channel` line: with the calibration files in either order and no
    --time-unit (the column's name gives it), every order of both wheels within 1 % and 1° of the
    truth. Before, the second calibration file's `t_s` replaced the first's and the flywheel's
    tooth errors corrected the pulley (order 6 read 20 % low)."""
    rec = [write_one(tmp_path / f"{w}.csv", engine["edges"][w], w) for w in TEETH]
    cal = [write_one(tmp_path / f"{w}_calibration.csv", engine["calibration"][w], w) for w in TEETH]
    out, _ = compare(tmp_path, capsys, *rec, "--teeth", "pulley=60", "flywheel=132", "--calibration",
                     *(cal[::-1] if swap else cal))
    for a, k, phi in PULLEY:
        assert_orders(track(out, "pulley", k), expected(a, phi), f"pulley order {k}")
    for a, k, phi in FLYWHEEL:
        assert_orders(track(out, "flywheel", k), expected(a, phi), f"flywheel order {k}")


def test_a_calibration_that_fits_no_record_or_two_is_refused_naming_the_files(tmp_path, capsys, engine):
    """Two calibration runs of one channel name, a calibration of a channel no record has, and one
    that two records would share: each refused before any work, naming both files."""
    p, f = engine["edges"]["pulley"], engine["edges"]["flywheel"]
    cp, cf = engine["calibration"]["pulley"], engine["calibration"]["flywheel"]
    cases = [
        ([write_one(tmp_path / "p1.csv", p, "pulley"), write_one(tmp_path / "f1.csv", f, "flywheel")],
         [write_one(tmp_path / "pulley_cal.csv", cp), write_one(tmp_path / "flywheel_cal.csv", cf)],
         ["pulley_cal.csv and flywheel_cal.csv both calibrate channel 't_s'"]),
        ([write_one(tmp_path / "p2.csv", p, "pulley")], [write_one(tmp_path / "c2.csv", cf, "flywheel")],
         ["c2.csv", "'flywheel' is in no measured record", "'pulley'"]),
        ([write_one(tmp_path / "a3.csv", p), write_one(tmp_path / "b3.csv", f)], [write_one(tmp_path / "c3.csv", cp)],
         ["c3.csv", "'t_s' is in both a3.csv and b3.csv"]),
    ]
    for records, calibrations, messages in cases:
        capsys.readouterr()
        assert main(["compare", str(GEOMETRY / "renault21.toml"), *records, "--teeth", "60", "--calibration",
                     *calibrations, "--source", "lumped17"]) == 2
        err = capsys.readouterr().err
        assert all(m in err for m in messages), err
        assert "Traceback" not in err


def test_the_tracked_orders_default_to_the_engines_major_orders(tmp_path, capsys, engine):
    """Issue 54: without --track-orders a record is compared in the engine's lowest major orders
    (the Renault's in-line four: 2, 4, 6, where every cylinder's torque adds), not in order 2 alone;
    each is the record's own (the pulley's order 4 within 1 % and 1° of the truth)."""
    import fetorsion
    from fetorsion.cli.measured import tracked_orders
    from fetorsion.excitation.campbell import order_sums

    crank = fetorsion.load(GEOMETRY / "renault21.toml")
    orders = tracked_orders(crank)
    assert orders == (2.0, 4.0, 6.0)
    sums = order_sums(crank.engine, np.ones(4), np.array(orders))[0]
    assert sums == pytest.approx(1.0)  # a rigid crank's cylinders add fully in each
    rec = write_edges(tmp_path / "rec.csv", engine["edges"])
    cal = write_edges(tmp_path / "cal.csv", engine["calibration"])
    path = tmp_path / "c.json"
    assert main(["compare", str(GEOMETRY / "renault21.toml"), rec, "--teeth", "pulley=60", "flywheel=132",
                 "--calibration", cal, "--time-unit", "s", "--source", "lumped17", "--order-definition", "time",
                 "--json", str(path)]) == 0
    out = json.loads(path.read_text())
    said = capsys.readouterr().out
    for k in (2, 4, 6):
        assert sum(line.startswith(f"order {k} at ") for line in said.splitlines()) == 2, said  # both wheels
    assert said.count("phases (deg): arg c_k of the cosine series") == 1  # what a phase is, said once
    a, k, phi = PULLEY[2]
    assert_orders(track(out, "pulley", k), expected(a, phi), "pulley order 4")


def test_a_files_station_line_places_its_channel_and_the_option_overrides_it(tmp_path, capsys, engine):
    """Issue 54: a one-wheel file's `# station = NAME` line says where its wheel sat (its channel,
    `wheel B`, is no station's name), and the table names that station for each of its orders;
    --channel-station overrides the file. A station line on a file of two channels is refused,
    naming the file and the option."""
    head = "# channel = wheel B\n# station = flywheel\nt_s\n"
    rec = tmp_path / "b.csv"
    rec.write_text(head + "\n".join(f"{t:.12e}" for t in engine["edges"]["flywheel"]) + "\n")
    out, said = compare(tmp_path, capsys, str(rec), "--teeth", "132")
    stations = {c["station"] for c in out["order_cuts"]}
    assert stations == {"J5 (flywheel end)"}, stations
    assert all("at J5 (flywheel end)" in x for x in said.out.splitlines() if x.startswith("order ")), said.out
    out, _ = compare(tmp_path, capsys, str(rec), "--teeth", "132", "--channel-station", "wheel B=J3")
    assert {c["station"] for c in out["order_cuts"]} == {"J3"}
    two = tmp_path / "two.csv"
    two.write_text("# station = flywheel\n" + open(write_edges(tmp_path / "x.csv", engine["edges"])).read())
    assert main(["compare", str(GEOMETRY / "renault21.toml"), str(two), "--teeth", "pulley=60", "flywheel=132",
                 "--time-unit", "s", "--source", "lumped17"]) == 2
    err = capsys.readouterr().err
    assert "--channel-station CHANNEL=STATION: " in err and "two.csv's '# station = flywheel' line" in err, err


def test_a_steady_record_is_drawn_as_an_order_spectrum_not_a_map(tmp_path, capsys, engine):
    """Issue 54: a steady 3000 rpm record has no speed axis: the figure draws its order spectrum
    (every tracked order's mean amplitude, the compared orders' model amplitudes beside them), not
    a map over ±0.02 rpm, and no per-order cut panels; the title says the speed and the blocks."""
    import matplotlib.pyplot as plt

    from fetorsion.measured import MeasuredOptions, read_measured
    from fetorsion.studies.comparison import run_comparison

    import fetorsion

    rec = write_edges(tmp_path / "rec.csv", {"pulley": engine["edges"]["pulley"]})
    measured = read_measured([rec], MeasuredOptions(teeth=60, time_unit="s", track_orders=(1.5, 2.0, 4.0)))
    res = run_comparison(fetorsion.load(GEOMETRY / "renault21.toml"), measured)
    fig = res.plot()
    titles = [ax.get_title() for ax in fig.axes]
    assert titles == ["rec.csv: pulley: order spectrum, steady at 3000 rpm over 20 blocks"], titles
    ax = fig.axes[0]
    model = [line for line in ax.lines if line.get_label() == "model at this speed"]
    assert len(model) == 1  # one legend entry for the three compared orders' diamonds
    diamonds = [line.get_xydata()[0] for line in ax.lines if line.get_marker() == "D"]
    assert sorted(x for x, _ in diamonds) == [1.5, 2.0, 4.0]
    plt.close(fig)


@pytest.mark.parametrize("swap", [False, True])
def test_the_issues_two_wheels_need_no_option_but_the_files_teeth_and_definition(tmp_path, capsys, engine, swap):
    """Issue 54's done-when: one file per wheel and a calibration file per wheel (their wheels named
    by '# channel' lines, their time unit by the column's name), given in either order, with no
    option but the files, --teeth, --calibration and --order-definition time (and the model, the
    lumped chain, to spare the FE): the default orders are the engine's major orders and the
    record's largest others, so every order of both wheels (1.5, 2, 4 on the pulley) is compared,
    each within 1 % and 1° of the truth."""
    rec = [write_one(tmp_path / f"{w}.csv", engine["edges"][w], w) for w in TEETH]
    cal = [write_one(tmp_path / f"{w}_calibration.csv", engine["calibration"][w], w) for w in TEETH]
    path = tmp_path / "c.json"
    assert main(["compare", str(GEOMETRY / "renault21.toml"), *rec, "--teeth", "pulley=60", "flywheel=132",
                 "--calibration", *(cal[::-1] if swap else cal), "--order-definition", "time",
                 "--source", "lumped17", "--json", str(path)]) == 0
    out = json.loads(path.read_text())
    for wheel, terms in (("pulley", PULLEY), ("flywheel", FLYWHEEL)):
        compared = {c["order"] for c in out["order_cuts"] if f": {wheel}," in c["name"]}
        for a, k, phi in terms:
            assert k in compared, (wheel, k, sorted(compared))
            assert_orders(track(out, wheel, k), expected(a, phi), f"{wheel} order {k}")
