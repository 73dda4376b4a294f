"""The sample store is one bounded SQLite file, a named scheduler is always contacted, and a
killed writer's temporaries go with the next write into the same folder."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time


import fetorsion
from fetorsion.studies import runner
from fetorsion.studies.runner import SampleStore, remove_legacy_store

from conftest import GEOMETRY


def record(i: int, pad: int = 0) -> dict:
    return {"outputs": {"y": float(i)}, "values": {"x": i}, "model": "m", "pad": "." * pad}


def test_least_recently_used_records_go_first_when_the_bound_is_passed(tmp_path):
    size = len(__import__("json").dumps(record(0, 1000)))
    store = SampleStore(tmp_path, max_bytes=int(3.5 * size))  # room for three records
    for key in "abc":
        store.put(key, record(ord(key), 1000))
        time.sleep(0.01)
    assert store.get("a")["outputs"]["y"] == ord("a")  # a is now the most recently used
    time.sleep(0.01)
    store.put("d", record(ord("d"), 1000))  # over the bound: trimmed to 90 %, oldest use first
    assert store.keys() == {"a", "c", "d"}
    assert store.get_many(["a", "b", "d"]).keys() == {"a", "d"}


def test_three_runs_of_two_descriptions_leave_one_bounded_file(tmp_path):
    # 6 studies of 300 lumped samples (~0.9 kB a record, 1.6 MB in all) into a store bounded at 100 kB.
    bound = 100_000
    store = SampleStore(tmp_path / "store", max_bytes=bound)
    for seed in range(3):
        for name in ("renault21.toml", "peugeot_glx.toml"):
            res = fetorsion.run_crank_study(fetorsion.load(GEOMETRY / name), "montecarlo", 300, client=False,
                                            store=store, seed=seed, progress=False)
            assert res.summary.computed == 300 and not res.errors
            assert os.listdir(tmp_path / "store") == ["samples.sqlite"]  # one file, however many samples
            with store._db(write=False) as con:
                held = con.execute("SELECT SUM(bytes) FROM samples").fetchone()[0]
            assert held <= bound  # the trim's rule, exactly
            # SQLite rebalances a b-tree page that falls below a third full (btree.c), so the
            # pages hold at most 3x the records' bytes; the key and time indexes add ~100 B a row.
            info = store.info()
            assert info["bytes"] <= 3 * bound + 100 * info["samples"] + 64 * 1024


def test_the_per_file_store_of_earlier_versions_is_removed_and_nothing_else(tmp_path):
    key = "ab" + "0" * 62
    (tmp_path / "ab").mkdir()
    (tmp_path / "ab" / f"{key}.json").write_text("{}")
    (tmp_path / "ab" / f".{key}.json.fetorsion-tmp-1-0").write_text("{")
    (tmp_path / "cd").mkdir()
    (tmp_path / "cd" / "notes.json").write_text("mine")  # not a sample key: kept, and its folder
    (tmp_path / "keep.txt").write_text("mine")
    assert remove_legacy_store(tmp_path) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cd", "keep.txt"]
    assert (tmp_path / "cd" / "notes.json").read_text() == "mine"


def test_store_command_prints_the_store_and_clears_it(tmp_path, capsys):
    from fetorsion.cli import main

    SampleStore(tmp_path).put_many([(str(i), record(i)) for i in range(5)])
    (tmp_path / "recovery").mkdir()
    (tmp_path / "recovery" / f"{'c' * 64}.npz").write_bytes(b"x" * 2048)  # a stress-recovery field of ours
    (tmp_path / "recovery" / "notes.txt").write_text("someone else's")  # never touched
    assert main(["store", "--store", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert str(tmp_path / "samples.sqlite") in out and "5 samples" in out and "MiB" in out
    assert f"{tmp_path / 'recovery'}: 1 stress-recovery fields" in out
    assert main(["store", "--store", str(tmp_path), "--clear"]) == 0
    out = capsys.readouterr().out
    assert "removed 5 samples" in out and "removed 1 stress-recovery fields" in out
    assert [p.name for p in (tmp_path / "recovery").iterdir()] == ["notes.txt"]
    (tmp_path / "recovery" / "notes.txt").unlink()
    (tmp_path / "recovery").rmdir()
    assert not list(tmp_path.iterdir())


def test_a_bad_store_bound_is_named_before_any_work(tmp_path, capsys, monkeypatch):
    from fetorsion.cli import main

    monkeypatch.setenv("FETORSION_STORE_MAX_MB", "lots")
    assert main(["store", "--store", str(tmp_path)]) == 2
    assert "FETORSION_STORE_MAX_MB" in capsys.readouterr().err and not list(tmp_path.iterdir())


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_a_named_scheduler_is_refused_even_when_every_sample_is_stored(tmp_path, capsys, monkeypatch):
    from fetorsion.cli import main

    monkeypatch.setattr(runner, "SCHEDULER_TIMEOUT_S", 2.0)
    argv = ["study", str(GEOMETRY / "peugeot_glx.toml"), "--samples", "20", "--store", str(tmp_path / "store")]
    assert main(argv + ["--out", str(tmp_path / "a"), "--workers", "1"]) == 0
    capsys.readouterr()
    t0 = time.perf_counter()
    code = main(argv + ["--out", str(tmp_path / "b"), "--scheduler", f"tcp://127.0.0.1:{free_port()}"])
    waited = time.perf_counter() - t0
    err = capsys.readouterr().err
    assert code == 2 and "--scheduler" in err and "no scheduler answered" in err
    assert not (tmp_path / "b").exists()
    # refused by the connection's own timeout (2 s), not after some other wait (10 s for a loaded machine)
    assert waited < 2.0 + 10.0


def test_a_sigkilled_writers_stray_goes_with_any_other_write_into_its_folder(tmp_path):
    from fetorsion.io import TMP_TAG

    # A real fetorsion writer killed mid-write: atomic_output's temporary is left behind.
    killer = ("import os, signal, sys\nfrom fetorsion.io import atomic_output\n"
              "with atomic_output(sys.argv[1]) as tmp:\n    tmp.write_text('half')\n"
              "    os.kill(os.getpid(), signal.SIGKILL)\n")
    proc = subprocess.run([sys.executable, "-c", killer, str(tmp_path / "first.json")])
    assert proc.returncode == -signal.SIGKILL
    strays = [p.name for p in tmp_path.iterdir() if TMP_TAG in p.name]
    assert len(strays) == 1 and strays[0].startswith(".first.json")
    (tmp_path / "mine.txt").write_text("the user's")
    # Another command, another name, the same folder.
    out = subprocess.run([sys.executable, "-m", "fetorsion.cli", "lumped", str(GEOMETRY / "peugeot_glx.toml"),
                          "--dof", "5", "--json", str(tmp_path / "other.json")], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.txt", "other.json"]


def test_a_stray_whose_process_number_was_given_out_again_is_removed(tmp_path):
    from fetorsion.io import TMP_TAG, write_text_atomic

    # Named by this (live) process's id, but last written before this process started: the
    # id was reused, its writer is gone. One written since this process started is kept.
    import psutil

    started = psutil.Process().create_time()
    old = tmp_path / f".a.json{TMP_TAG}{os.getpid()}-x.json"
    new = tmp_path / f".b.json{TMP_TAG}{os.getpid()}-y.json"
    for p in (old, new):
        p.write_text("x")
    os.utime(old, (started - 3600, started - 3600))
    write_text_atomic(tmp_path / "c.json", "{}")
    assert not old.exists() and new.exists()
