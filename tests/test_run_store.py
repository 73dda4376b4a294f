"""The run's sections kept between runs (issue 55, fetorsion.app.run_store): what a key reads and
does not read, the files kept, an unreadable file. The end to end check (a second run of the
Renault takes its FE step and verdict from the store and writes the same report) is in
tests/test_m53.py, beside the verdict run it repeats."""

import dataclasses
from pathlib import Path

import numpy as np

import fetorsion
from fetorsion.app import run_store
from fetorsion.app.run import RunOptions
from fetorsion.description.edit import with_values

ROOT = Path(__file__).resolve().parents[1]


def test_a_kept_section_comes_back_as_it_was_written(tmp_path):
    entry = {"frequencies_hz": [491.7, 1023.4], "kinds": ["torsional", "bending"], "note": "é", "none": None}
    files = {"mode_01_torsional.png": bytes(range(256)) * 3, "modes_view.html": "<div id=modes></div>".encode()}
    run_store.remember("a" * 64, entry, files, store=tmp_path)
    got, got_files = run_store.stored("a" * 64, store=tmp_path)
    assert got == entry and got_files == files and list(got_files) == list(files)  # the order names the pictures
    assert run_store.stored("b" * 64, store=tmp_path) is None


def test_an_unreadable_kept_section_is_removed_and_computed_again(tmp_path):
    path = run_store.folder(tmp_path) / f"{'c' * 64}.npz"
    path.parent.mkdir(parents=True)
    path.write_bytes(b"not an npz")
    assert run_store.stored("c" * 64, store=tmp_path) is None
    assert not path.exists()


def test_the_verdicts_key_reads_the_whole_description_and_the_verdicts_options():
    crank = fetorsion.load(ROOT / "geometry" / "renault21.toml")
    options = RunOptions()
    key = run_store.fatigue_key(crank, options)
    assert run_store.fatigue_key(fetorsion.load(ROOT / "geometry" / "renault21.toml"), options) == key  # reproducible
    damped = with_values(crank, {"excitation.modal_damping_ratio": 0.03})
    assert run_store.fatigue_key(damped, options) != key
    for change in ({"inertia_ratio": 0.5}, {"fatigue_method": "fe"}, {"fe_path": False}, {"mesh_size": 0.012}):
        assert run_store.fatigue_key(crank, dataclasses.replace(options, **change)) != key, change
    # what the verdict does not read leaves it: the report's page, the studies' workers
    assert run_store.fatigue_key(crank, dataclasses.replace(options, html=False, workers=3)) == key


def test_the_fe_steps_key_reads_the_fe_tables_and_not_the_excitation():
    crank = fetorsion.load(ROOT / "geometry" / "renault21.toml")
    cuts = np.array([[0.1, 0.0, 0.0]])
    key = run_store.fe_key(crank, 0.01, cuts, 20)
    assert run_store.fe_key(with_values(crank, {"excitation.modal_damping_ratio": 0.03}), 0.01, cuts, 20) == key
    assert run_store.fe_key(with_values(crank, {"pins.*.diameter": 47.0}), 0.01, cuts, 20) != key
    assert run_store.fe_key(crank, 0.012, cuts, 20) != key
    assert run_store.fe_key(crank, 0.01, cuts, 12) != key
    assert run_store.fe_key(crank, 0.01, cuts + 1e-9, 20) != key


def test_a_pressure_curves_content_is_in_the_verdicts_key(tmp_path):
    """The description names its pressure CSV by path: the key reads the curve, so an edited CSV
    under the same name is a new verdict."""
    text = (ROOT / "geometry" / "renault21.toml").read_text()
    text = text.replace("imep_pa = [[750.0, 8.0e5], [3000.0, 11.1e5], [5500.0, 10.0e5], [6500.0, 9.0e5]]",
                        'pressure_csv = "p.csv"')
    for synthetic in ("compression_ratio", "combustion_start_deg", "combustion_duration_deg"):  # the curve's
        text = "\n".join(x for x in text.splitlines() if not x.startswith(synthetic)) + "\n"
    (tmp_path / "r.toml").write_text(text)
    angles = np.arange(0.0, 720.0, 1.0) - 360.0

    def key(peak):
        p = 1e5 + peak * np.exp(-((angles - 10.0) / 30.0) ** 2)
        (tmp_path / "p.csv").write_text("".join(f"{a},{v}\n" for a, v in zip(angles, p)))
        return run_store.fatigue_key(fetorsion.load(tmp_path / "r.toml"), RunOptions())

    assert key(60e5) != key(65e5)


def test_the_code_hash_reads_the_shipped_tables():
    """A shipped SCF or throw-stiffness table answers as the code does: it is in every stored key."""
    import hashlib

    from fetorsion import io

    root = Path(io.__file__).resolve().parent
    h = hashlib.sha256()
    for path in sorted([*root.rglob("*.py"), *root.rglob("data/*.json")]):
        h.update(str(path.relative_to(root)).encode())
        h.update(path.read_bytes())
    assert io.code_hash() == h.hexdigest()
    assert any(p.name == "fillet_scf.json" for p in root.rglob("data/*.json"))
