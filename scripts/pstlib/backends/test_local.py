import json
import os
import types

import pytest

from pstlib.explore import evaluate, store
from pstlib.backends import local

SETTINGS = {"size": 64, "truth": 2}


def point(knob="coord_frac", sha="abc"):
    return types.SimpleNamespace(name="p", knob=knob, sha=sha)


def result(**kw):
    r = {"profile_sha": "abc", "settings": dict(SETTINGS), "status": "ok",
         "scenes": {"marble": {}, "zoneplate": {}}, "synth": {"sha": "abc", "logic_ge": 1000}}
    r.update(kw)
    return r


def never():
    raise AssertionError("not asked")


def test_reusable_result():
    assert evaluate.sweep_reusable(result(), point(), SETTINGS, ["marble"], False, never)


def test_changed_profile_settings_or_scenes_start_again():
    assert not evaluate.sweep_reusable(None, point(), SETTINGS, ["marble"], False, never)
    assert not evaluate.sweep_reusable(result(profile_sha="old"), point(), SETTINGS, ["marble"], False, never)
    assert not evaluate.sweep_reusable(result(), point(), {"size": 128, "truth": 2}, ["marble"], False, never)
    assert not evaluate.sweep_reusable(result(), point(), SETTINGS, ["marble", "fire"], False, never)


def test_failed_results_stay_unless_retried():
    assert evaluate.sweep_reusable(result(status="failed"), point(), SETTINGS, ["marble"], False, never)
    assert not evaluate.sweep_reusable(result(status="failed"), point(), SETTINGS, ["marble"], True, never)


def test_missing_synthesis_reruns_only_when_there_is_one_to_run_or_pick_up():
    r = result(synth=None)
    assert not evaluate.sweep_reusable(r, point(), SETTINGS, ["marble"], False, lambda: True)
    assert evaluate.sweep_reusable(r, point(), SETTINGS, ["marble"], False, lambda: False)
    stale = result(synth={"sha": "old"})
    assert not evaluate.sweep_reusable(stale, point(), SETTINGS, ["marble"], False, lambda: True)
    assert evaluate.sweep_reusable(r, point(knob="filter"), SETTINGS, ["marble"], False, never)


def test_synthesis_recorded_under_another_rtl_or_flow_is_stale():
    r = result(synth={"sha": "abc", "key": {"profile": "p", "rtl": "old"}, "logic_ge": 1000})
    now = {"profile": "p", "rtl": "new"}
    assert not evaluate.sweep_reusable(r, point(), SETTINGS, ["marble"], False, lambda: True, now)
    assert evaluate.sweep_reusable(r, point(), SETTINGS, ["marble"], False, never, {"profile": "p", "rtl": "old"})
    # a record from before keys were stored counts as stale once a key is asked for
    assert not evaluate.sweep_reusable(result(), point(), SETTINGS, ["marble"], False, lambda: True, now)
    assert evaluate.sweep_reusable(r, point(knob="filter"), SETTINGS, ["marble"], False, never, now)


def test_synth_cache(tmp_path):
    prof = tmp_path / "p.toml"
    prof.write_text("# one\n[noise]\nout_frac = 8\n")
    rtl = tmp_path / "a.sv"
    rtl.write_text("module a; endmodule\n")
    sj = tmp_path / "p.json"
    assert not evaluate.synth_cache_valid(sj, prof, [rtl])
    sj.write_text(json.dumps({"logic_ge": 5}))
    side = tmp_path / "p.sweep.json"
    side.write_text(json.dumps(evaluate.synth_key(prof, [rtl])))
    assert evaluate.synth_cache_valid(sj, prof, [rtl])
    prof.write_text("# other comment\n[noise]\nout_frac = 8\n")       # comments do not count
    assert evaluate.synth_cache_valid(sj, prof, [rtl])
    rtl.write_text("module a; wire w; endmodule\n")
    assert not evaluate.synth_cache_valid(sj, prof, [rtl])
    # without a sidecar: by modification times
    side.unlink()
    os.utime(sj, (2000, 2000))
    os.utime(prof, (1000, 1000))
    os.utime(rtl, (1000, 1000))
    assert evaluate.synth_cache_valid(sj, prof, [rtl])
    os.utime(rtl, (3000, 3000))
    assert not evaluate.synth_cache_valid(sj, prof, [rtl])
    sj.write_text("{}")                                                  # no gate count
    assert not evaluate.synth_cache_valid(sj, prof, [])


def test_synth_record(tmp_path):
    sj = tmp_path / "x.json"
    sj.write_text(json.dumps({"logic_ge": 98200, "rom_bits": 4096, "flip_flops": 10,
                              "blocks": {"noise": {"logic_ge": 40000}}}))
    r = evaluate.synth_record("abc", sj, {"profile": "p", "rtl": "r"})
    assert r == {"sha": "abc", "key": {"profile": "p", "rtl": "r"}, "file": str(sj), "logic_ge": 98200, "rom_bits": 4096, "ram_bits": None,
                 "flip_flops": 10, "yosys_seconds": None, "blocks": {"noise": 40000}}


def test_read_json(tmp_path):
    assert store.read_json(tmp_path / "none.json") is None
    (tmp_path / "bad.json").write_text("{")
    assert store.read_json(tmp_path / "bad.json") is None
    (tmp_path / "ok.json").write_text('{"a": 1}')
    assert store.read_json(tmp_path / "ok.json") == {"a": 1}


def test_run_reports_exit_status_and_output(tmp_path):
    rc, out, err = local.run(["/bin/sh", "-c", "echo hi; echo no >&2; exit 3"], cwd=tmp_path)
    assert (rc, out, err) == (3, "hi\n", "no\n")
    rc, out, err = local.run(["/bin/sleep", "5"], cwd=tmp_path, timeout=0.2)
    assert rc != 0 and "timed out" in err


def test_run_points_reuses_cached_runs_the_rest_and_records_failures():
    todo = [types.SimpleNamespace(name=n) for n in ("a", "b", "c")]
    seen = []

    def cached(pt):
        return {"v": "stored"} if pt.name == "a" else None

    def work(pt):
        if pt.name == "c":
            raise OSError("no summary.json")
        return {"v": "new"}
    res = local.run_points(todo, 2, cached, work, lambda pt, e: {"v": f"failed: {e}"},
                            lambda pt, r, how: seen.append((pt.name, how)))
    assert res == {"a": {"v": "stored"}, "b": {"v": "new"}, "c": {"v": "failed: no summary.json"}}
    assert sorted(seen) == [("a", "cached"), ("b", "run"), ("c", "run")]


def test_run_points_interrupted_stops_and_raises():
    todo = [types.SimpleNamespace(name=n) for n in ("a", "b")]

    def work(pt):
        raise KeyboardInterrupt
    try:
        with pytest.raises(KeyboardInterrupt):
            local.run_points(todo, 1, lambda pt: None, work, lambda pt, e: None, lambda *a: None)
        assert local.STOP.is_set()
        with pytest.raises(KeyboardInterrupt):            # no new child once stopped
            local.run(["/bin/true"])
    finally:
        local.STOP.clear()


def test_synth_inputs_cover_the_rtl_and_the_synthesis_scripts():
    from pstlib.paths import ROOT
    files = evaluate.synth_inputs()
    names = {p.relative_to(ROOT).as_posix() for p in files if p.is_relative_to(ROOT)}
    assert {"scripts/synth.py", "scripts/pstlib/synth/flow.py", "rtl/top/pst_top.sv", "scripts/synth/cells.lib"} <= names
    assert all((ROOT / n).is_file() for n in names)
    assert "scripts/synth/baseline.json" not in names          # results, not inputs
