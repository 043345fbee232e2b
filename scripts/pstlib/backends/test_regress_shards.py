"""The sharded regression (scripts/regress.py, pstlib/backends/regress_shards.py) without a build: the
split, the merge of the shards' JSON and JUnit, the first failure, and the launcher's re-run of
a killed shard and its resume, driven by a stand-in for `pst` (a small script below that speaks
`pst regress --list` and writes what `pst regress -o --junit` writes)."""
import json
import os
import pathlib
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

from pstlib.backends import regress_shards as R

from pstlib.paths import ROOT  # noqa: E402

FAKE_PST = r'''#!/usr/bin/python3
# Stand-in for `pst regress`, steered by FAKE_PST (JSON): segments (random segment starts),
# profiles, scenes, bad (a fragment that fails), assert (the failure is an RTL assertion),
# kill_once (shard names killed by SIGKILL on their first run), calls (a file: one line per run).
import json, os, pathlib, signal, sys
cfg = json.loads(os.environ["FAKE_PST"])
a = sys.argv[2:]
def opt(name, default=None):
    return a[a.index(name) + 1] if name in a else default
profiles = [a[i + 1] for i, x in enumerate(a) if x == "--profile"] or cfg["profiles"]
if "--list" in a:
    if "--random" in a:
        for p in profiles: print("profile", p)
        end = int(opt("--from", 0)) + int(opt("--random"))
        segs = cfg["segments"]
        for s, t in zip(segs, segs[1:] + [10**12]):
            if s < end and t > int(opt("--from", 0)): print("segment", s)
    else:
        for sc in [x for x in a if x.endswith(".toml")] or cfg["scenes"]:
            for p in profiles: print(sc + "\t" + p)
    sys.exit(0)
out, junit = pathlib.Path(opt("-o")), pathlib.Path(opt("--junit"))
name = out.stem
with open(cfg["calls"], "a") as f: f.write(name + "\n")
if name in cfg.get("kill_once", []):
    mark = out.with_suffix(".killed")
    if not mark.exists():
        mark.write_text("")
        os.kill(os.getpid(), signal.SIGKILL)
bad = cfg.get("bad")
if "--random" in a:
    k, n = int(opt("--from")), int(opt("--random"))
    start = max(s for s in cfg["segments"] if s <= k)
    hit = bad is not None and start <= bad < k + n and profiles[0] == cfg.get("bad_profile", profiles[0])
    run = {"profile": profiles[0], "seed": int(opt("--seed")), "first_fragment": start, "fragments": k + n - start,
           "mismatches": 0 if not hit or cfg.get("assert") else 3, "first_bad": bad if hit else None,
           "passed": not hit, "seconds": 0.5, "assertion": {"cycle": 77} if hit and cfg.get("assert") else None,
           "replay": f"pst regress --random 9 --seed {opt('--seed')} --from {bad} --profile {profiles[0]}" if hit else None}
    if hit and cfg.get("assert"):
        print("[77] %Error: pst_top_sva.sv:27: Assertion failed in pst_top.u_sva.RegWriteOnlyWhenIdle: boom")
    runs, cname, tname = [run], "regress.random." + profiles[0], f"seed {opt('--seed')} fragments {start}..{k + n}"
else:
    scene = a[0]
    hit = bad is not None and pathlib.Path(scene).stem == bad
    runs = [{"scene": scene, "profile": profiles[0], "passed": not hit, "mismatches": 5 if hit else 0,
             "replay": f"pst regress {scene} --profile {profiles[0]}" if hit else None}]
    cname, tname = "regress." + profiles[0], pathlib.Path(scene).stem
out.write_text(json.dumps(runs))
fail = '<failure message="x"/>' if hit else ""
junit.write_text(f'<?xml version="1.0"?><testsuites><testsuite name="t" tests="1"><testcase classname="{cname}" '
                 f'name="{tname}" time="0.5">{fail}</testcase></testsuite></testsuites>')
sys.exit(1 if hit else 0)
'''


@pytest.fixture
def fake(tmp_path):
    pst = tmp_path / "pst"
    pst.write_text(FAKE_PST)
    pst.chmod(0o755)
    calls = tmp_path / "calls.txt"

    def launch(*args, **cfg):
        base = {"segments": [0, 700, 1500, 2600, 3100, 4000, 5200], "profiles": ["reduced"],
                "scenes": ["scenes/fire.toml", "scenes/marble.toml"], "calls": str(calls)}
        env = dict(os.environ, FAKE_PST=json.dumps(base | cfg))
        r = subprocess.run([sys.executable, str(ROOT / "scripts" / "regress.py"), "--pst", str(pst),
                            "--out", str(tmp_path / "out"), *map(str, args)], capture_output=True, text=True, env=env,
                           timeout=60)
        runs = calls.read_text().split() if calls.exists() else []
        calls.unlink(missing_ok=True)
        return r, runs
    launch.out = tmp_path / "out"
    return launch


# ---- the split

def test_chunks_cut_at_segment_starts_and_cover_the_range_once():
    starts = [0, 700, 1500, 2600, 3100, 4000]
    assert R.chunks(0, 4500, starts, 1000) == [(0, 1500), (1500, 1100), (2600, 1400), (4000, 500)]
    # --from inside a segment: the first piece starts there (pst runs its segment whole).
    assert R.chunks(800, 3000, starts, 1) == [(800, 700), (1500, 1100), (2600, 500), (3100, 700)]
    assert R.chunks(0, 4500, starts, 10**6) == [(0, 4500)]
    pieces = R.chunks(100, 4000, starts, 900)
    assert pieces[0][0] == 100 and sum(n for _, n in pieces) == 4000
    assert all(a + n == b for (a, n), (b, _) in zip(pieces, pieces[1:]))
    assert all(k in starts for k, _ in pieces[1:])


def test_chunks_refuse_bad_segment_lists():
    with pytest.raises(ValueError):
        R.chunks(0, 10, [5, 9], 4)          # does not hold fragment 0
    with pytest.raises(ValueError):
        R.chunks(0, 10, [0, 4, 4], 4)
    with pytest.raises(ValueError):
        R.chunks(0, 0, [0], 4)


def test_default_chunk():
    assert R.default_chunk(100_000_000, 64) == 781_250
    assert R.default_chunk(10**9, 2) == 1_000_000
    assert R.default_chunk(40_000, 2) == 10_000
    assert R.default_chunk(1, 8) == 1


def test_plan_random_and_scenes():
    plan = R.plan_random(["full", "reduced"], [0, 700, 1500], 2000, 5, 0, 1000, batch=512, extra=["--probes"])
    assert [s.name for s in plan] == ["random-full-0000000000", "random-full-0000001500",
                                      "random-reduced-0000000000", "random-reduced-0000001500"]
    assert plan[1].args == ("--random", "500", "--seed", "5", "--from", "1500", "--batch", "512", "--profile", "full",
                            "-q", "--probes")
    scenes = R.plan_scenes([("a/fire.toml", "full"), ("a/fire.toml", "reduced"), ("b/fire.toml", "full")], 32)
    assert [s.name for s in scenes] == ["scene000-fire-full", "scene000-fire-reduced", "scene001-fire-full"]
    assert scenes[2].args == ("b/fire.toml", "--size", "32", "--profile", "full")
    assert R.Shard.from_json(json.loads(json.dumps(plan[1].to_json()))) == plan[1]


def test_parse_list():
    assert R.parse_list("profile full\nprofile reduced\nsegment 0\nsegment 812\n", True) == (["full", "reduced"], [0, 812])
    assert R.parse_list("scenes/a b.toml\tfull\n", False) == [("scenes/a b.toml", "full")]
    with pytest.raises(ValueError):
        R.parse_list("full\n", True)
    with pytest.raises(ValueError):
        R.parse_list("scenes/a.toml full\n", False)


# ---- one shard's completeness

def shard_files(out, s, rc=0, runs=None, args=None):
    p = R.paths(out, s.name)
    p["json"].parent.mkdir(parents=True, exist_ok=True)
    p["json"].write_text(json.dumps(runs if runs is not None else [{"profile": s.profile, "passed": rc == 0}]))
    p["xml"].write_text('<testsuites><testsuite><testcase classname="c" name="n"/></testsuite></testsuites>')
    p["done"].write_text(json.dumps({"name": s.name, "args": list(args or s.args), "rc": rc}))
    return p


def test_complete_needs_the_plans_arguments_a_result_exit_and_readable_outputs(tmp_path):
    s = R.plan_random(["reduced"], [0], 100, 1, 0, 100)[0]
    p = shard_files(tmp_path, s)
    assert R.complete(tmp_path, s)["rc"] == 0
    shard_files(tmp_path, s, rc=1)
    assert R.complete(tmp_path, s)["rc"] == 1               # a failed run is a result
    shard_files(tmp_path, s, rc=2)
    assert R.complete(tmp_path, s) is None                  # refused input: none
    shard_files(tmp_path, s, args=["--random", "50"])
    assert R.complete(tmp_path, s) is None                  # another command's result
    shard_files(tmp_path, s)
    p["json"].write_text('[{"profile": "red')               # cut short
    assert R.complete(tmp_path, s) is None
    shard_files(tmp_path, s)
    p["xml"].unlink()
    assert R.complete(tmp_path, s) is None


# ---- merging

def test_merge_names_the_lowest_failing_fragment_and_lists_missing_shards(tmp_path):
    plan = R.plan_random(["full", "reduced"], [0, 1000, 2000], 3000, 9, 0, 1000)
    runs = {"random-full-0000000000": [{"profile": "full", "fragments": 1000, "mismatches": 0, "passed": True}],
            "random-full-0000001000": [{"profile": "full", "fragments": 700, "mismatches": 2, "passed": False,
                                        "first_bad": 1700, "seed": 9, "replay": "pst regress --random 1 --from 1700"}],
            "random-reduced-0000001000": [{"profile": "reduced", "fragments": 200, "mismatches": 0, "passed": False,
                                           "first_bad": 1200, "seed": 9, "assertion": {"cycle": 5},
                                           "replay": "pst regress --random 800 --from 1200 --profile reduced"}],
            "random-reduced-0000002000": [{"profile": "reduced", "fragments": 1000, "mismatches": 0, "passed": True}]}
    for s in plan:
        if s.name in runs:
            shard_files(tmp_path, s, rc=0 if runs[s.name][0]["passed"] else 1, runs=runs[s.name])
    R.paths(tmp_path, "random-reduced-0000001000")["log"].write_text(
        "[5] %Error: pst_top.sv:216: Assertion failed in pst_top.pst_top: 'assert' failed.\n"
        "[5] %Error: pst_top_sva.sv:27: Assertion failed in pst_top.u_sva.RegWriteOnlyWhenIdle: x\n")
    m = R.merge(tmp_path, plan, "/b/pst", {"random-full-0000002000": 2})
    assert not m["passed"] and not m["complete"]
    assert m["missing"] == ["random-full-0000002000", "random-reduced-0000000000"]
    assert m["failed_shards"] == ["random-full-0000001000", "random-reduced-0000001000"]
    f = m["first_failure"]
    assert (f["shard"], f["fragment"], f["seed"], f["kind"]) == ("random-reduced-0000001000", 1200, 9, "assertion")
    assert f["replay"] == "/b/pst regress --random 800 --from 1200 --profile reduced"
    assert f["assertion"] == "pst_top_sva.sv:27: pst_top.u_sva.RegWriteOnlyWhenIdle: x"
    assert m["profiles"]["full"]["simulated"] == 1700 and m["profiles"]["full"]["mismatches"] == 2
    assert (m["profiles"]["reduced"]["from"], m["profiles"]["reduced"]["to"]) == (0, 3000)
    assert m["shards"]["random-full-0000002000"] == {"complete": False, "attempts": 2}
    assert "first failure: shard random-reduced-0000001000 [reduced]: seed 9, fragment 1200" in R.summary(m)


def test_merge_of_scene_shards_takes_the_plans_order(tmp_path):
    plan = R.plan_scenes([("s/a.toml", "full"), ("s/b.toml", "full")], 16)
    shard_files(tmp_path, plan[0], rc=1, runs=[{"scene": "s/a.toml", "profile": "full", "passed": False, "replay": "pst r"}])
    shard_files(tmp_path, plan[1], rc=1, runs=[{"scene": "s/b.toml", "profile": "full", "passed": False}])
    m = R.merge(tmp_path, plan, "build/pst")
    assert m["mode"] == "scenes" and m["first_failure"]["scene"] == "s/a.toml"
    assert m["first_failure"]["replay"] == "build/pst r"
    shard_files(tmp_path, plan[0], runs=[])           # a skipped scene: no run, passes
    shard_files(tmp_path, plan[1], runs=[{"scene": "s/b.toml", "profile": "full", "passed": True}])
    assert R.merge(tmp_path, plan, "pst")["passed"]


def test_merge_junit_keeps_every_case_and_an_error_per_missing_shard(tmp_path):
    plan = R.plan_random(["reduced"], [0, 10], 20, 1, 0, 10)
    p = shard_files(tmp_path, plan[0])
    p["xml"].write_text('<testsuites><testsuite><testcase classname="regress.random.reduced" name="seed 1 fragments 0..10" '
                        'time="1.5"><failure message="m"/></testcase></testsuite></testsuites>')
    root = ET.fromstring(R.merge_junit(tmp_path, plan, "suite"))
    ts = root.find("testsuite")
    assert (ts.get("tests"), ts.get("failures"), ts.get("errors")) == ("2", "1", "1")
    names = [tc.get("name") for tc in ts.iter("testcase")]
    assert names == ["seed 1 fragments 0..10 [random-reduced-0000000000]", "random-reduced-0000000010"]


# ---- the launcher with a stand-in pst

def test_launcher_reruns_a_killed_shard_alone_and_resumes(fake):
    r, runs = fake("--random", 4500, "--seed", 3, "--chunk", 1000, "--jobs", 2,
                   kill_once=["random-reduced-0000001500"])
    assert r.returncode == 0, r.stdout + r.stderr
    assert sorted(runs) == sorted(["random-reduced-0000000000", "random-reduced-0000001500", "random-reduced-0000002600",
                                   "random-reduced-0000004000", "random-reduced-0000001500"])
    assert "re-running 1 shard(s) without a result, alone: random-reduced-0000001500" in r.stdout
    m = json.loads((fake.out / "merged.json").read_text())
    assert m["passed"] and m["complete"] and m["profiles"]["reduced"]["simulated"] == 4500
    assert m["shards"]["random-reduced-0000001500"]["attempts"] == 2
    assert m["shards"]["random-reduced-0000002600"]["attempts"] == 1
    # Resumed: every shard has a result, nothing runs; --shard runs one again.
    r, runs = fake("--random", 4500, "--seed", 3, "--chunk", 1000, "--jobs", 2)
    assert r.returncode == 0 and runs == [] and "4 with a complete result, 0 to run" in r.stdout
    r, runs = fake("--random", 4500, "--seed", 3, "--chunk", 1000, "--shard", "random-reduced-0000002600")
    assert r.returncode == 0 and runs == ["random-reduced-0000002600"]
    # Another seed is another command: every shard runs again.
    r, runs = fake("--random", 4500, "--seed", 4, "--chunk", 1000)
    assert r.returncode == 0 and len(runs) == 4


def test_launcher_without_retries_reports_the_missing_shard_and_the_next_run_completes_it(fake):
    r, runs = fake("--random", 4500, "--chunk", 1000, "--retries", 0, kill_once=["random-reduced-0000002600"])
    assert r.returncode == 1 and "incomplete: 1 of 4 shards left no result: random-reduced-0000002600" in r.stdout
    root = ET.parse(fake.out / "merged.xml").getroot()
    assert [tc.get("name") for tc in root.iter("testcase") if tc.find("error") is not None] == ["random-reduced-0000002600"]
    r, runs = fake("--random", 4500, "--chunk", 1000, "--retries", 0, kill_once=["random-reduced-0000002600"])
    assert r.returncode == 0 and runs == ["random-reduced-0000002600"]


def test_launcher_names_the_first_failure_and_does_not_rerun_a_failed_shard(fake):
    cfg = dict(bad=3300, profiles=["full", "reduced"], bad_profile="reduced")
    r, runs = fake("--random", 4500, "--seed", 8, "--chunk", 1000, "--jobs", 2, **{"assert": True}, **cfg)
    assert r.returncode == 1
    assert "first failure: shard random-reduced-0000002600 [reduced]: seed 8, fragment 3300: RTL assertion " \
           "(pst_top_sva.sv:27: pst_top.u_sva.RegWriteOnlyWhenIdle: boom)" in r.stdout
    assert f"replay alone: {fake.out.parent / 'pst'} regress --random 9 --seed 8 --from 3300 --profile reduced" in r.stdout
    r, runs = fake("--random", 4500, "--seed", 8, "--chunk", 1000, **{"assert": True}, **cfg)
    assert r.returncode == 1 and runs == []           # a failure is a result: not run again


def test_launcher_scene_shards(fake):
    r, runs = fake("--size", 16, "--profile", "full", "--profile", "reduced", bad="marble")
    assert r.returncode == 1, r.stdout + r.stderr
    assert sorted(runs) == ["scene000-fire-full", "scene000-fire-reduced", "scene001-marble-full",
                            "scene001-marble-reduced"]
    m = json.loads((fake.out / "merged.json").read_text())
    assert m["first_failure"]["shard"] == "scene001-marble-full" and len(m["runs"]) == 4


@pytest.mark.parametrize("args, msg", [
    (["--jobs", "0"], "error: --jobs: must be >= 1"),
    (["--random", "10", "scenes/fire.toml"], "error: --random: takes no scene files"),
    (["--chunk", "5"], "error: --chunk: a positive fragment count, with --random"),
    (["--random", "10", "--pst-arg=--seed=3"], "error: --pst-arg: '--seed=3' is the launcher's to set"),
    (["--shard", "nope"], "error: --shard: 'nope' is not a shard of this plan"),
])
def test_bad_arguments_exit_2_and_write_nothing(fake, args, msg):
    r, runs = fake(*args)
    assert r.returncode == 2 and msg in r.stderr and runs == []
    assert not fake.out.exists()


def test_inject_assert_goes_only_to_the_shard_holding_it():
    plan = R.plan_random(["p"], [0, 100, 200], 300, 1, 0, 100, 0, ["--inject-assert=150", "--probes"])
    held = [s.first for s in plan if "--inject-assert=150" in s.args]
    assert held == [100] and all("--probes" in s.args for s in plan)
