"""Issue 40: the condensed crank built once and kept; every command answers for it."""

from pathlib import Path
import ast
import json
import os

import numpy as np
import pytest

import fetorsion
from conftest import GEOMETRY, ROOT, plain
from fetorsion.fe.store import (NOT_READ_BY_FE, condensed_crank, condensed_folder, condensed_key, condensed_store_info,
                                clear_condensed, stored_condensed, trim)


def _numbers(tree, path=()):
    """Every number in a parsed description: (path, value)."""
    if isinstance(tree, dict):
        for k, v in tree.items():
            yield from _numbers(v, path + (k,))
    elif isinstance(tree, list):
        for i, v in enumerate(tree):
            yield from _numbers(v, path + (i,))
    elif isinstance(tree, (int, float)) and not isinstance(tree, bool):
        yield path, tree


def _set(tree, path, value):
    for k in path[:-1]:
        tree = tree[k]
    tree[path[-1]] = value


def test_every_number_the_fe_reads_is_in_the_key_and_no_other():
    import copy
    import dataclasses

    crank = fetorsion.load(GEOMETRY / "renault21.toml")
    base = condensed_key(crank, 0.01)
    moved = 0
    for path, v in _numbers(crank.raw):
        raw = copy.deepcopy(crank.raw)
        _set(raw, path, v * 1.01 + 1e-3)
        other = dataclasses.replace(crank, raw=raw)
        same = condensed_key(other, 0.01) == base
        assert same == (path[0] in NOT_READ_BY_FE), path
        moved += not same
    assert moved > 50  # the Renault's geometry, material, attachments and bearings
    assert condensed_key(crank, 0.011) != base and condensed_key(crank, 0.01, np.zeros((1, 3))) != base


def test_no_fe_stage_reads_the_tables_the_key_leaves_out():
    # the key may leave a table out only while no module that builds the condensed crank reads it
    attrs = {"meta": "notes", "excitation": "excitation", "dampers": "dampers", "limits": "limits",
             "uncertainty": "uncertainty"}
    assert set(attrs) == set(NOT_READ_BY_FE)
    for folder in ("fe", "solid"):
        for path in (ROOT / "fetorsion" / folder).glob("*.py"):
            tree = ast.parse(path.read_text())
            read = {n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)}
            assert not read & (set(attrs.values()) - {"notes"}), (path, read & set(attrs.values()))


@pytest.mark.fe
def test_a_condensed_crank_is_built_once_kept_exactly_and_bounded(tmp_path, capsys):
    from fetorsion.design.stress import fillet_cuts, fillets_of

    crank = plain("renault21.toml")
    cuts = fillet_cuts(crank, fillets_of(crank))
    said = []
    cc, cached = condensed_crank(crank, 0.03, cuts, store=tmp_path, progress=said.append)
    assert not cached and len(said) == 1
    again, cached = condensed_crank(crank, 0.03, cuts, store=tmp_path, progress=said.append)
    assert cached and len(said) == 1 and again.crank is crank
    for name in ("cut_rows", "cut_centres", "gyroscopic", "centrifugal", "sections", "bearing_stiffness"):
        np.testing.assert_array_equal(getattr(again, name), getattr(cc, name), err_msg=name)
    np.testing.assert_array_equal(again.reduced.K, cc.reduced.K)
    np.testing.assert_array_equal(again.reduced.M, cc.reduced.M)
    assert again.modes("bearings").first_torsional() == cc.modes("bearings").first_torsional()
    info = condensed_store_info(tmp_path)
    assert info["cranks"] == 1 and info["bytes"] < 4 * 2**20  # no mesh shapes kept
    # a file the store cannot read is removed and the crank built again, never trusted
    (path,) = condensed_folder(tmp_path).glob("*.npz")
    path.write_bytes(b"not an npz")
    assert stored_condensed(crank, 0.03, cuts, store=tmp_path) is None and not path.exists()
    assert "unreadable" in capsys.readouterr().err
    # bounded: the least recently used go first, down to the bound
    folder = condensed_folder(tmp_path)
    for k in range(4):
        f = folder / f"{k:064x}.npz"
        f.write_bytes(b"x" * 1000)
        os.utime(f, (1e9 + k, 1e9 + k))
    other = folder / "notes.npz"  # not a name the store writes: never touched
    other.write_bytes(b"y")
    assert trim(folder, max_bytes=2500) == 2
    assert sorted(p.name[:4] for p in folder.glob("0*.npz")) == ["0000", "0000"]
    assert sorted(p.stat().st_mtime for p in folder.glob("0*.npz")) == [1e9 + 2, 1e9 + 3]
    assert clear_condensed(tmp_path) == 2 and other.exists()


def test_store_command_lists_and_clears_the_condensed_cranks(tmp_path, capsys):
    from fetorsion.cli.commands import main

    folder = condensed_folder(tmp_path)
    folder.mkdir(parents=True)
    (folder / ("a" * 64 + ".npz")).write_bytes(b"x" * 2048)
    assert main(["store", "--store", str(tmp_path)]) == 0
    assert "1 condensed cranks" in capsys.readouterr().out
    assert main(["store", "--store", str(tmp_path), "--clear"]) == 0
    out = capsys.readouterr().out
    assert "removed 1 condensed cranks" in out and "0 condensed cranks" in out
    assert json.dumps(condensed_store_info(tmp_path))  # plain numbers


def _plain_renault(tmp_path):
    """The Renault 21 without fillets, drillings and uncertainty ranges (a cheap mesh), as a file."""
    import re

    text = (GEOMETRY / "renault21.toml").read_text()
    text = re.sub(r"^\[uncertainty\].*", "", text, flags=re.M | re.S)
    text = re.sub(r"^(journal|pin|diameter) = (2\.5|5\.0)", r"\1 = 0.0", text, flags=re.M)
    src = tmp_path / "r21.toml"
    src.write_text(text)
    return src


@pytest.mark.fe
@pytest.mark.slow
def test_every_command_answers_for_the_runs_condensed_crank(tmp_path, capsys):
    """Issue 40: after a run, campbell, response and damper take the run's condensed crank from the
    store (no build) and give its numbers: the same f1 in bearings, crossings and section torques
    (one computation on one model: equal to round-off); the lumped answer says how far it is."""
    from fetorsion.app.run import DEFAULT_STEPS, RunOptions, run
    from fetorsion.cli.commands import main

    src = _plain_renault(tmp_path)
    out = Path(run(src, tmp_path / "r", steps=DEFAULT_STEPS[:4], options=RunOptions(mesh_size=0.03)).folder)
    data = json.loads((out / "results.json").read_text())
    capsys.readouterr()

    def command(*argv):
        path = tmp_path / f"{argv[0]}.json"
        assert main([*argv, str(src), "--mesh-size", "30", "--json", str(path)]) == 0
        text = capsys.readouterr()
        assert "building the condensed crank" not in text.err  # the run's, from the store
        return json.loads(path.read_text()), text.out

    camp, _ = command("campbell")
    assert camp["source"] == data["campbell"]["source"]
    np.testing.assert_allclose(camp["frequencies_hz"], data["campbell"]["frequencies_hz"], rtol=1e-12)
    f1 = data["bearings"]["f1_bearings_hz"]
    first = [c for c in camp["crossings"] if c["mode_kind"].startswith("torsional")]
    assert first[0]["frequency_hz"] == pytest.approx(f1, rel=1e-12)
    run_rows = {(c["mode"], c["order"]): c for c in data["campbell"]["crossings"]}
    for c in camp["crossings"]:
        r = run_rows[(c["mode"], c["order"])]
        assert (c["rpm"], c["worst_section"]) == (pytest.approx(r["rpm"], rel=1e-12), r["worst_section"])
        assert c["severity"] == pytest.approx(r["severity"], rel=1e-9)
    order6 = next(c for c in first if c["order"] == 6.0 and c["mode"] == first[0]["mode"])
    assert order6["rpm"] == pytest.approx(60 * f1 / 6, rel=1e-12)

    resp, text = command("response")
    assert resp["rpm"] == data["response"]["rpm"] and resp["sections"] == data["response"]["sections"]
    np.testing.assert_allclose(resp["section_torque_nm"], data["response"]["section_torque_nm"], rtol=1e-9)
    worst = next(x for x in text.splitlines() if "largest section torque " in x).strip()

    damper, text = command("damper", "--optimise", "--objective", "twist")
    assert damper["mode_hz"] == pytest.approx(f1, rel=1e-9)  # tuned on the engine model's first torsional mode
    assert f"without a damper: {worst}" in text

    # the fast chain, and how far it is from the stored engine model
    assert main(["response", str(src), "--source", "lumped17", "--mesh-size", "30"]) == 0
    gap = capsys.readouterr().out.splitlines()[-1]
    assert "condensed crank in its bearings, stored" in gap and "N m" in gap
    lumped = float(gap.split("the lumped one is ")[1].split(" %")[0])
    engine = float(worst.split("largest section torque ")[1].split(" N m")[0])
    assert engine == pytest.approx(float(gap.split("gives the largest section torque ")[1].split(" N m")[0]), rel=1e-3)
    assert abs(lumped) < 30  # the two models of one crank, not two cranks
    assert main(["damper", str(src), "--source", "lumped17", "--objective", "twist", "--mesh-size", "30"]) == 0
    gap = capsys.readouterr().out.splitlines()[-1]
    assert "stored, gives the largest section torque without a damper" in gap
    assert float(gap.split("without a damper ")[1].split(" N m")[0]) == pytest.approx(engine, rel=1e-3)


@pytest.mark.fe
def test_transient_on_the_condensed_crank_equals_the_response_at_that_speed(tmp_path, capsys):
    """Issue 40: `transient --rpm N` on a crank is the condensed crank in its bearings, steady, in
    the time domain (exact propagation of the crank and its order oscillators), and equals
    `response` at N — the frequency domain's projected modal solve — within 0.5 % on every fillet's
    alternating torque (the peaks are sampled at 200 steps per period of order 12: ~1e-4). One
    cycle is enough (it once ended in an empty maximum) and gives the same range."""
    from fetorsion.cli.commands import main

    src = _plain_renault(tmp_path)
    rpm = 5000.0
    ranges = []
    for cycles in (1, 2):
        assert main(["transient", str(src), "--rpm", f"{rpm:g}", "--mesh-size", "30", "--cycles", str(cycles),
                     "--json", str(tmp_path / "t.json")]) == 0
        out = capsys.readouterr().out
        assert "condensed crank, bearings" in out and "exact propagation" in out
        tr = json.loads((tmp_path / "t.json").read_text())
        assert tr["signals"]["every"] == 1
        T = np.array(tr["signals"]["section_torque_nm"])
        ranges.append(0.5 * (T.max(axis=1) - T.min(axis=1)))
    np.testing.assert_allclose(ranges[0], ranges[1], rtol=1e-3)  # settled: every cycle alike
    time_domain = ranges[1]
    assert main(["response", str(src), "--speed-range", f"{rpm:g}", f"{rpm + 1:g}", "--steps", "2", "--mesh-size", "30",
                 "--json", str(tmp_path / "r.json")]) == 0
    capsys.readouterr()
    resp = json.loads((tmp_path / "r.json").read_text())
    assert resp["sections"] == tr["sections"] and resp["rpm"][0] == rpm
    frequency_domain = np.array(resp["section_torque_nm"][0])
    np.testing.assert_allclose(time_domain, frequency_domain, rtol=5e-3)
    assert frequency_domain.max() > 100.0  # a real load, not two zeros agreeing
    # what the condensed crank cannot do yet goes to the chain, which says so
    assert main(["transient", str(src), "--run-up", "3000", "3100", "--rate", "2000", "--mesh-size", "30"]) == 0
    assert "lumped 17-DOF chain, not the condensed crank" in capsys.readouterr().out
