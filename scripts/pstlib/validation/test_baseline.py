"""The silicon and quality baseline (pstlib/validation/baseline.py, scripts/check_baseline.py): figures
that moved beyond the tolerance, collected from synth.py's and pst regress' JSON."""
import json
import subprocess

from pstlib.validation import baseline
from pstlib.synth import record
from pstlib.paths import ROOT

SCRIPTS = ROOT / "scripts"
# The sign-off part of a synthesis record's timing that passes (pstlib.synth.report.timing_result).
SIGNOFF_MET = {"hold": {"wns_ns": 0.1, "violations": 0, "worst": {}},
               "max_transition": {"violations": 0, "worst": {}}, "max_capacitance": {"violations": 0, "worst": {}}}
POWER = {"reduced": {"pj_per_pixel": 1000.0}}
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


def _one_profile_run(tmp_path):
    """An out/ folder of one synthesized profile (reduced) and its regression: (out, synth JSON)."""
    import json
    out = tmp_path / "out"
    (out / "synth").mkdir(parents=True)
    s = {"logic_ge": 100, "blocks": {}, "flip_flops": 1, "memory_ge": 2, "total_ge": 102, "rom_bits": 8,
         "ram_bits": 9, "clocks_per_pixel": 1, "timing": dict(SIGNOFF_MET, fmax_mhz=50.0), "tools": {"yosys": "y"}}
    (out / "synth" / "reduced.json").write_text(json.dumps(s))
    (out / "regress.json").write_text(json.dumps(
        [{"scene": "scenes/a.toml", "profile": "reduced", "vs_reference": {"psnr": 40.0}}]))
    # energy per pixel measured in this run (scripts/power.py): read before the record
    (out / "power").mkdir()
    (out / "power" / "reduced.json").write_text(json.dumps({"summary": POWER["reduced"]}))
    return out, s


def test_check_baseline_cli_fails_on_a_move(tmp_path):
    import json
    out, s = _one_profile_run(tmp_path)
    base = {"tolerance": 0.02, "tools": {"yosys": "y"},
            "profiles": baseline.collect({"reduced": s}, json.loads((out / "regress.json").read_text()), POWER)}
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



def test_check_baseline_cli_fails_when_energy_moves(tmp_path):
    out, s = _one_profile_run(tmp_path)
    base = {"tolerance": 0.02, "tools": {"yosys": "y"},
            "profiles": baseline.collect({"reduced": s}, json.loads((out / "regress.json").read_text()), POWER)}
    assert base["profiles"]["reduced"]["energy_pj_per_pixel"] == 1000.0
    bfile = tmp_path / "baseline.json"
    bfile.write_text(json.dumps(base))
    cmd = ["/usr/bin/python3", str(SCRIPTS / "check_baseline.py"), "--out", str(out), "--baseline", str(bfile)]
    (out / "power" / "reduced.json").write_text(json.dumps({"summary": {"pj_per_pixel": 1030.0}}))
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 1 and "reduced.energy_pj_per_pixel: 1000.0 -> 1030.0 (+3.0 %)" in r.stdout, r.stdout

def test_check_baseline_cli_tools_signoff_and_add(tmp_path):
    import copy
    out = tmp_path / "out"
    (out / "synth").mkdir(parents=True)
    s = {"logic_ge": 100, "blocks": {}, "flip_flops": 1, "memory_ge": 2, "total_ge": 102, "rom_bits": 8,
         "ram_bits": 9, "clocks_per_pixel": 1, "timing": dict(SIGNOFF_MET, fmax_mhz=50.0),
         "tools": {"yosys": "y", "opensta": "2.0.17"}}
    (out / "synth" / "reduced.json").write_text(json.dumps(s))
    (out / "regress.json").write_text("[]")
    (out / "power").mkdir()
    (out / "power" / "reduced.json").write_text(json.dumps({"summary": POWER["reduced"]}))
    rom, records = tmp_path / "rom", tmp_path / "records"
    rom.mkdir()
    (rom / "t.memh").write_text("00\n")
    bfile = tmp_path / "baseline.json"
    bfile.write_text(json.dumps({"tolerance": 0.02, "tools": s["tools"], "profiles": baseline.collect({"reduced": s}, [], POWER),
                                 "inputs": record.inputs(rom)}))
    cmd = ["/usr/bin/python3", str(SCRIPTS / "check_baseline.py"), "--out", str(out), "--baseline", str(bfile),
           "--rom-dir", str(rom), "--records", str(records)]
    assert subprocess.run(cmd, capture_output=True, text=True).returncode == 0
    # another OpenSTA: not comparable, said so
    other = dict(s, tools={"yosys": "y", "opensta": "2.1.0"})
    (out / "synth" / "reduced.json").write_text(json.dumps(other))
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 1 and "not comparable" in r.stdout and "2.1.0" in r.stdout
    # a hold violation fails even with every figure in place
    bad = copy.deepcopy(s)
    bad["timing"]["hold"] = {"wns_ns": -0.05, "violations": 2,
                             "worst": {"slack_ns": -0.05, "startpoint": "a/q", "endpoint": "b/d", "stage": "s"}}
    (out / "synth" / "reduced.json").write_text(json.dumps(bad))
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 1 and "sign-off check failed: hold: 2 endpoints" in r.stdout
    # --add: one more profile, the others untouched
    (out / "synth" / "reduced.json").write_text(json.dumps(s))
    (out / "synth" / "balanced.json").write_text(json.dumps(dict(s, logic_ge=500)))
    (out / "synth" / "balanced.md").write_text("# balanced\n")
    before = json.loads(bfile.read_text())["profiles"]["reduced"]
    assert subprocess.run(cmd + ["--add", "balanced"], capture_output=True, text=True).returncode == 0
    after = json.loads(bfile.read_text())["profiles"]
    assert after["reduced"] == before and after["balanced"]["logic_ge"] == 500
    assert subprocess.run(cmd, capture_output=True, text=True).returncode == 0
    assert (records / "balanced.json").exists() and not (records / "reduced.json").exists()
    # --add refuses once an input of the synthesis changed: the digest stands for every profile
    (rom / "t.memh").write_text("01\n")
    r = subprocess.run(cmd + ["--add", "balanced"], capture_output=True, text=True)
    assert r.returncode == 1 and "rom/t.memh changed" in r.stderr


def test_stale_names_what_changed_and_restore_copies_the_record(tmp_path):
    rom, records, out = tmp_path / "rom", tmp_path / "records", tmp_path / "out"
    rom.mkdir()
    records.mkdir()
    (rom / "t.memh").write_text("00\n")
    for suffix in ("json", "md"):
        (records / f"reduced.{suffix}").write_text("{}" if suffix == "json" else "# reduced\n")
    bfile = tmp_path / "baseline.json"
    bfile.write_text(json.dumps({"tolerance": 0.02, "tools": {}, "profiles": {"reduced": {}},
                                 "inputs": record.inputs(rom)}))
    cmd = ["/usr/bin/python3", str(SCRIPTS / "check_baseline.py"), "--out", str(out), "--baseline", str(bfile),
           "--rom-dir", str(rom), "--records", str(records)]
    r = subprocess.run(cmd + ["--stale"], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    r = subprocess.run(cmd + ["--restore"], capture_output=True, text=True)
    assert r.returncode == 0 and (out / "synth" / "reduced.md").read_text() == "# reduced\n"
    (rom / "t.memh").write_text("01\n")
    r = subprocess.run(cmd + ["--stale"], capture_output=True, text=True)
    assert r.returncode == 1 and "rom/t.memh changed" in r.stdout
    (records / "reduced.md").unlink()
    (rom / "t.memh").write_text("00\n")
    r = subprocess.run(cmd + ["--stale"], capture_output=True, text=True)
    assert r.returncode == 1 and "no record of reduced" in r.stdout


def test_stage_paths_are_recorded_not_checked():
    cur = json.loads(json.dumps(BASE))
    for p in cur.values():
        p["stage_path_ns"] = {"octave stage [A] -> [B]": 99.0}
    assert baseline.compare(BASE, cur) == []


def test_check_baseline_json_on_every_exit_path(tmp_path):
    """--json FILE: the result (pass, fail with the moved figures, error) as JSON, always."""
    out, s = _one_profile_run(tmp_path)
    bfile = tmp_path / "baseline.json"
    bfile.write_text(json.dumps({"tolerance": 0.02, "tools": {"yosys": "y"},
                                 "profiles": baseline.collect({"reduced": s}, json.loads((out / "regress.json").read_text()), POWER)}))
    res = tmp_path / "check.json"
    cmd = ["/usr/bin/python3", str(SCRIPTS / "check_baseline.py"), "--out", str(out), "--baseline", str(bfile),
           "--json", str(res)]

    def result(rc):
        r = subprocess.run(cmd, capture_output=True, text=True)
        assert r.returncode == rc, r.stdout + r.stderr
        data = json.loads(res.read_text())
        assert data["schema"] == 1 and data["exit_status"] == rc
        assert set(data["provenance"]) >= {"schema", "commit", "tools", "command"}
        assert not list(tmp_path.glob(".check*"))        # atomic: no temporary left
        return data

    ok = result(0)
    assert ok["status"] == "pass" and ok["moved"] == [] and ok["figures_checked"] == 11 and ok["tolerance"] == 0.02
    s["logic_ge"] = 103
    (out / "synth" / "reduced.json").write_text(json.dumps(s))
    bad = result(1)
    assert bad["status"] == "fail"
    assert bad["moved"] == [{"figure": "reduced.logic_ge", "baseline": 100, "current": 103, "change": 0.03}]
    s["logic_ge"] = 97
    (out / "synth" / "reduced.json").write_text(json.dumps(s))
    assert result(1)["moved"][0]["change"] == -0.03                          # a fall, signed
    s["logic_ge"] = 100
    s["timing"] = dict(s["timing"], hold={"wns_ns": -0.05, "violations": 2, "worst": {
        "slack_ns": -0.05, "startpoint": "a/q", "endpoint": "b/d", "stage": "s"}})
    (out / "synth" / "reduced.json").write_text(json.dumps(s))
    signoff = result(1)
    assert signoff["status"] == "fail" and signoff["moved"] == []
    assert signoff["signoff_failures"][0]["profile"] == "reduced"
    assert "hold" in signoff["signoff_failures"][0]["error"]
    (out / "regress.json").unlink()
    err = result(2)
    assert err["status"] == "error" and any("regress.json: missing" in m for m in err["messages"])
    (out / "regress.json").write_text("{not json")
    assert result(2)["status"] == "error"        # an exception: still a result


def test_restore_writes_the_silicon_source(tmp_path):
    """--restore: OUT/synth/source.json says the figures came from the record (with the digest)
    while the inputs stand, and that they did not when an input changed."""
    from pstlib.synth import record
    out = tmp_path / "out"
    bfile = tmp_path / "baseline.json"
    base = {"tolerance": 0.02, "tools": {}, "profiles": {}, "inputs": record.inputs(None)}
    bfile.write_text(json.dumps(base))
    res = tmp_path / "restore.json"
    cmd = ["/usr/bin/python3", str(SCRIPTS / "check_baseline.py"), "--restore", "--out", str(out),
           "--baseline", str(bfile), "--rom-dir", str(tmp_path / "no_rom"), "--json", str(res)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    src = json.loads((out / "synth" / "source.json").read_text())
    assert src["source"] == "record" and src["digest"] == record.digest.summary(base["inputs"], {})
    assert json.loads(res.read_text())["status"] == "pass"
    base["inputs"]["rtl/gone.sv"] = "0" * 64
    bfile.write_text(json.dumps(base))
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 1
    src = json.loads((out / "synth" / "source.json").read_text())
    assert src["source"] == "none" and "rtl/gone.sv removed" in src["stale"]
    data = json.loads(res.read_text())
    assert data["status"] == "fail" and "rtl/gone.sv removed" in data["stale"]


def test_energy_measured_with_another_ram_model_is_not_compared(tmp_path):
    # scripts/power.py --ram-reads measures another figure than the record's (reduced 140,190 pJ
    # with the RAMs' read ports, 77,782 without): the record is compared, and the run says so.
    from pstlib.cli import check_baseline
    from pstlib.docs import power_doc
    from pstlib.paths import ROOT
    rec = power_doc.load(ROOT)["profiles"]["reduced"]["summary"]
    assert "rams_modelled" not in rec
    out = tmp_path / "out"
    (out / "power").mkdir(parents=True)
    (out / "power" / "reduced.json").write_text(json.dumps({"summary": {"pj_per_pixel": 140189.7,
                                                                         "rams_modelled": {"clut": 1}}}))
    res = {"messages": []}
    got = check_baseline.power_summaries(out, ["reduced"], res)
    assert got["reduced"]["pj_per_pixel"] == rec["pj_per_pixel"]
    (out / "power" / "reduced.json").write_text(json.dumps({"summary": {"pj_per_pixel": 77000.0}}))
    assert check_baseline.power_summaries(out, ["reduced"], {"messages": []})["reduced"]["pj_per_pixel"] == 77000.0
