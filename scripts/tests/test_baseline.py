"""The silicon and quality baseline (pstlib/baseline.py, scripts/check_baseline.py): figures
that moved beyond the tolerance, collected from synth.py's and pst regress' JSON."""
import json
import subprocess

from pstlib import baseline
from pstlib.paths import ROOT

SCRIPTS = ROOT / "scripts"
BASE = {"reduced": {"logic_ge": 100000, "fmax_mhz": 40.0, "psnr_db": {"marble": 40.0}, "rom_bits": 70849}}


def test_compare_within_tolerance():
    cur = {"reduced": {"logic_ge": 101900, "fmax_mhz": 39.3, "psnr_db": {"marble": 40.7}, "rom_bits": 70849}}
    assert baseline.compare(BASE, cur) == []


def test_compare_flags_moves_and_missing():
    cur = {"reduced": {"logic_ge": 102100, "fmax_mhz": 40.0, "psnr_db": {"marble": 40.0, "wood": 30.0}}}
    moved = {k: (a, b) for k, a, b, _ in baseline.compare(BASE, cur)}
    assert set(moved) == {"reduced.logic_ge", "reduced.psnr_db.wood", "reduced.rom_bits"}
    assert moved["reduced.rom_bits"] == (70849, None)


def test_compare_flags_a_decrease_too():
    cur = {"reduced": dict(BASE["reduced"], fmax_mhz=39.0)}
    assert [k for k, *_ in baseline.compare(BASE, cur)] == ["reduced.fmax_mhz"]


def test_collect_from_synth_and_regress():
    synth = {"reduced": {"logic_ge": 5, "blocks": {"noise": {"logic_ge": 3}}, "flip_flops": 1, "memory_ge": 2,
                         "total_ge": 7, "rom_bits": 8, "ram_bits": 9, "clocks_per_pixel": 22,
                         "timing": {"fmax_mhz": 33.3}}}
    regress = [{"scene": "scenes/marble.toml", "profile": "reduced", "vs_reference": {"psnr": 41.23456}},
               {"scene": "scenes/marble.toml", "profile": "full", "vs_reference": {"psnr": 60.0}}]
    c = baseline.collect(synth, regress)
    assert c["reduced"]["psnr_db"] == {"marble": 41.235}
    assert c["reduced"]["block_ge"] == {"noise": 3} and c["reduced"]["fmax_mhz"] == 33.3
    assert "full" not in c


def test_check_baseline_cli_fails_on_a_move(tmp_path):
    import json
    out = tmp_path / "out"
    (out / "synth").mkdir(parents=True)
    s = {"logic_ge": 100, "blocks": {}, "flip_flops": 1, "memory_ge": 2, "total_ge": 102, "rom_bits": 8,
         "ram_bits": 9, "clocks_per_pixel": 1, "timing": {"fmax_mhz": 50.0}, "tools": {"yosys": "y"}}
    (out / "synth" / "reduced.json").write_text(json.dumps(s))
    (out / "regress.json").write_text(json.dumps(
        [{"scene": "scenes/a.toml", "profile": "reduced", "vs_reference": {"psnr": 40.0}}]))
    base = {"tolerance": 0.02, "tools": {"yosys": "y"},
            "profiles": baseline.collect({"reduced": s}, json.loads((out / "regress.json").read_text()))}
    bfile = tmp_path / "baseline.json"
    bfile.write_text(json.dumps(base))
    cmd = ["/usr/bin/python3", str(SCRIPTS / "check_baseline.py"), "--out", str(out), "--baseline", str(bfile)]
    ok = subprocess.run(cmd, capture_output=True, text=True)
    assert ok.returncode == 0, ok.stdout + ok.stderr
    s["logic_ge"] = 103
    (out / "synth" / "reduced.json").write_text(json.dumps(s))
    bad = subprocess.run(cmd, capture_output=True, text=True)
    assert bad.returncode == 1 and "reduced.logic_ge: 100 -> 103" in bad.stdout
    (out / "regress.json").unlink()
    assert subprocess.run(cmd, capture_output=True, text=True).returncode == 2
