"""scripts/validate.py: bad input is refused (exit 2, nothing written); a run through a stand-in
`pst` writes validate.md / validate.json with the rule's verdict per profile and its exit status."""
import json
import shutil
import subprocess

import pytest

from pstlib.paths import ROOT
from pstlib.validation import validate as validation

CLI = ROOT / "scripts" / "validate.py"

# A stand-in pst: `pst render SCENE ... -o DIR --profile P...` writes DIR/<stem of P>/summary.json
# (DIR itself for one profile) with a PSNR per profile stem: full_exact 50, good 49.01 (0.99 dB
# lost), bad 48.99 on val_003 only (1.01 dB lost there), full and the rest 50.
FAKE = r"""#!/usr/bin/python3
import json, pathlib, sys
a = sys.argv[1:]
scene = pathlib.Path(a[1]).stem
out = pathlib.Path(a[a.index("-o") + 1])
profs = [pathlib.Path(a[i + 1]).stem for i, x in enumerate(a) if x == "--profile"]
for p in profs:
    v = {"full_exact": 50.0, "full": 50.0, "good": 49.01}.get(p, 48.99 if scene == "val_003" else 50.0)
    d = out / p if len(profs) > 1 else out
    d.mkdir(parents=True, exist_ok=True)
    (d / "summary.json").write_text(json.dumps({"vs_reference": {"psnr": v, "rms": 0.01}}))
"""


def cli(*args):
    r = subprocess.run(["/usr/bin/python3", str(CLI), *map(str, args)], capture_output=True, text=True, timeout=120)
    return r.returncode, r.stdout + r.stderr


@pytest.fixture
def fake(tmp_path):
    pst = tmp_path / "pst"
    pst.write_text(FAKE)
    pst.chmod(0o755)
    for n in ("good", "bad"):
        shutil.copy(ROOT / "rtl" / "configs" / "full.toml", tmp_path / f"{n}.toml")
    return pst


@pytest.mark.parametrize("args,msg", [
    (["nosuch"], "unknown profile 'nosuch'"),
    (["full", "no/such.toml"], "unknown profile 'no/such.toml'"),
    (["full", "--count", "0"], "--count: 1..4096"),
    (["full", "--count", "-3"], "--count"),
    (["full", "--size", "4"], "--size: 16..2048"),
    (["full", "--size", "100000"], "--size"),
    (["full", "--seed", "1"], "--seed: validation seeds"),
    (["full", "--train", "--seed", "1000001"], "--seed: training seeds are 0..999999"),
    (["full", "--jobs", "0"], "--jobs"),
    (["full", "--pst", "/no/such/pst"], "--pst"),
    ([], "name at least one PROFILE"),
    (["full", "--count", "x"], "invalid int value"),
])
def test_bad_input_exit_2_and_nothing_written(tmp_path, fake, args, msg):
    out = tmp_path / "out"
    extra = [] if "--pst" in args else ["--pst", fake]
    rc, text = cli(*args, *extra, "--out", out)
    assert rc == 2 and msg in text, text
    assert not out.exists()


def test_a_run_judges_each_profile_against_full_exact(tmp_path, fake):
    out = tmp_path / "out"
    rc, text = cli("full", tmp_path / "good.toml", tmp_path / "bad.toml", "--count", 8, "--size", 16,
                   "--pst", fake, "--out", out)
    assert rc == 1, text                  # bad fails the rule
    doc = json.loads((out / "validate.json").read_text())
    res = doc["results"]
    assert list(res) == ["full_exact", "full", "good", "bad"]
    assert res["good"]["passed"] is True and res["good"]["worst_loss"] == pytest.approx(0.99)
    assert res["bad"]["passed"] is False and res["bad"]["worst_loss_scene"] == "val_003"
    assert res["bad"]["worst_loss"] == pytest.approx(1.01) and res["bad"]["failing"] == ["val_003"]
    assert res["bad"]["worst_loss_features"]["stratum"] == "rotated_clamp"      # scene 3's stratum
    assert res["bad"]["worst_psnr"] == 48.99 and res["bad"]["median_psnr"] == 50.0
    assert res["full_exact"]["passed"] is True and res["full_exact"]["worst_loss"] == 0.0
    md = (out / "validate.md").read_text()
    assert "| bad | 48.99 | 50.00 | 1.01 | 1 / 8 | val_003 (48.99 vs 50.00) | rotated_clamp: " in md
    assert "| good | 49.01 | 49.01 | 0.99 | 0 / 8 |" in md and "**FAIL**" in md
    assert len(list((out / "scenes").glob("val_*.toml"))) == 8
    rc, text = cli("full", tmp_path / "good.toml", "--count", 8, "--size", 16, "--pst", fake, "--out", out)
    assert rc == 0, text


def test_scenes_only_writes_the_set_alone(tmp_path):
    rc, text = cli("--scenes-only", "--count", 9, "--size", 32, "--out", tmp_path / "o", "--pst", "/no/such")
    assert rc == 0, text
    assert len(list((tmp_path / "o" / "scenes").glob("val_*.toml"))) == 9 and not (tmp_path / "o" / "validate.md").exists()


def test_profiles_resolve_to_files_full_exact_first():
    got = validation.resolve_profiles(["balanced", "full_exact", "full"])
    assert [n for n, _ in got] == ["full_exact", "balanced", "full"]
    assert all(p.is_file() for _, p in got)


def test_train_draws_the_strata_on_training_seeds_and_says_so(tmp_path, fake):
    out = tmp_path / "t"
    rc, text = cli("full", "--train", "--count", 8, "--size", 16, "--pst", fake, "--out", out)
    assert rc == 0, text
    doc = json.loads((out / "validate.json").read_text())
    assert doc["split"] == "training" and doc["seed"] == 1 and "--train" in doc["command"]
    assert sorted(p.name for p in (out / "scenes").glob("*.toml")) == [f"trn_{i:03d}.toml" for i in range(8)]
    assert (out / "validate.md").read_text().startswith("# Training strata: 8 training scenes")
