"""scripts/pstlib/search*.py: the space, the walk, the fronts, the stored results, the SLURM job."""
import copy
import json
import sys

import pytest

from pstlib import contract
from pstlib.explore import evaluate, search_report, search_run
from pstlib.explore import search as S
from pstlib.backends import slurm
from pstlib.paths import ROOT

FULL = ROOT / "rtl" / "configs" / "full_1clk.toml"   # a one-clock start: the walks below keep cpp 1
REDUCED = ROOT / "rtl" / "configs" / "reduced.toml"


def test_structures_stay_within_the_class_and_go_from_cheap_to_dear():
    for octs, c in ((8, 1), (8, 4), (8, 28), (4, 28)):
        ss = S.structures(octs, c, contract.read_profile(FULL))
        assert ss
        for s in ss:
            doc = copy.deepcopy(contract.read_profile(FULL))
            doc["pipeline"].update(s)
            assert not contract.validate(doc)
            assert S.cycles_per_pixel(doc) <= c
        corners = [s["noise_units"] * 8 // s["noise_steps"] for s in ss]
        assert corners == sorted(corners)
    assert S.structures(8, 1) == [{"octaves": 8, "noise_units": 8, "noise_steps": 1, "datapath": "parallel"}]
    assert {"octaves": 4, "noise_units": 1, "noise_steps": 4, "datapath": "serial"} in \
        S.structures(4, 28, contract.read_profile(REDUCED))
    assert all(s["datapath"] == "parallel" for s in S.structures(8, 4))     # serial needs >= 7 clocks


def test_neighbours_move_one_knob_one_value_cheaper():
    doc = contract.read_profile(FULL)
    moves = S.neighbours(doc, S.KNOB_NAMES, S.structures(8, 4))
    assert {k for k, *_ in moves} >= {"coord_frac", "out_frac", "interp", "hash", "norm", "structure"}
    for k, a, b, d in moves:
        assert not contract.validate(d)
        diff = [(s, key) for s in doc for key in doc[s] if doc[s][key] != d[s][key]]
        assert diff, k
        if k == "structure":
            assert {key for _, key in diff} <= {"octaves", "noise_units", "noise_steps", "datapath"}
        else:
            knob = next(x for x in S.KNOBS if x["name"] == k)
            assert knob["get"](doc) == a and knob["get"](d) == b
            vals = knob["values"]
            assert b in vals and (a not in vals or vals.index(b) == vals.index(a) - 1)
    only = S.neighbours(doc, ["coord_frac"], [])
    assert [(k, a, b) for k, a, b, _ in only] == [("coord_frac", 20, 18)]


def test_noise_grad_frac_moves_the_derivative_lanes_and_is_refused_on_a_worley_unit():
    full = contract.read_profile(FULL)          # grad_frac 16 of its 20 node bits
    (move,) = [m for m in S.neighbours(full, ["noise_grad_frac"], []) if m[0] == "noise_grad_frac"]
    _, a, b, d = move
    assert (a, b) == (16, 14) and d["noise"]["grad_frac"] == 14
    assert {k for k in d["noise"] if d["noise"][k] != full["noise"][k]} == {"grad_frac"}
    worley = contract.read_profile(ROOT / "sim" / "test_profiles" / "reduced_worley.toml")
    assert worley["noise"]["grad_frac"] == worley["noise"]["out_frac"] + worley["noise"]["guard_bits"]
    # rtl/contract.toml: a worley unit has no derivative lanes to floor, so no cheaper value is valid
    assert S.neighbours(worley, ["noise_grad_frac"], []) == []


def test_a_point_is_named_by_its_values_and_keeps_the_text():
    text = FULL.read_text()
    doc = contract.read_profile(FULL)
    d = copy.deepcopy(doc)
    d["noise"]["out_frac"] = 14
    p = S.make_point(text, doc, d, "out_frac 16->14")
    q = S.make_point(text, doc, copy.deepcopy(d), "another way there")
    assert p.name == q.name and p.name != S.make_point(text, doc, doc, "start").name
    assert "out_frac = 14" in p.text and "Search point: out_frac 16->14" in p.text
    assert p.cpp == 1


class FakeSpace:
    """Area = sum of weights x value index; PSNR = 60 - sum of losses of the cut values."""

    def __init__(self, weights, losses, base_doc, knobs):
        self.w, self.l, self.base, self.knobs, self.calls = weights, losses, base_doc, knobs, 0

    def idx(self, doc):
        return {k["name"]: k["values"].index(k["get"](doc)) for k in S.KNOBS if k["name"] in self.knobs}

    def __call__(self, points):
        self.calls += len(points)
        out = {}
        base_i = self.idx(self.base)
        for p in points:
            i = self.idx(p.doc)
            area = 1000 + sum(self.w[k] * v for k, v in i.items())
            loss = sum(self.l[k] * (base_i[k] - v) for k, v in i.items())
            out[p.name] = {"status": "ok", "train_worst": 60 - loss, "logic_ge": area, "cpp": p.cpp}
        return out


def _walk(weights, losses, target, budget=200, backtracks=0):
    text = FULL.read_text()
    doc = contract.read_profile(FULL)
    knobs = list(weights)
    ev = FakeSpace(weights, losses, doc, knobs)
    start = S.make_point(text, doc, doc, "start")
    w = S.walk(start, ev, S.Targets(target, 1), knobs, [], text, doc, budget, backtracks, say=lambda *_: None)
    return w, ev


def test_walk_spends_the_margin_where_it_buys_most_area():
    # coord_frac: 7 values, cheap in quality; out_frac: 6 values, dear; target allows 5 dB.
    w, ev = _walk({"coord_frac": 100, "out_frac": 500}, {"coord_frac": 0.5, "out_frac": 2.0}, 55.0)
    p, r = w["archive"][w["best"]]
    assert r["train_worst"] >= 55.0
    # The optimum by enumeration: out_frac cuts a (2 dB, 500 GE), coord_frac cuts b (0.5 dB, 100 GE).
    best = min(1000 + 500 * (5 - a) + 100 * (6 - b) for a in range(6) for b in range(7) if 2 * a + 0.5 * b <= 5)
    assert r["logic_ge"] == best
    assert ev.calls < 6 * 7      # fewer evaluations than the grid


def test_walk_reports_a_start_that_misses_the_target():
    w, _ = _walk({"coord_frac": 100}, {"coord_frac": 0.5}, 70.0)
    assert w["best"] is None


def test_backtracking_finds_a_cheaper_branch():
    # 3 dB of margin; interp's cut saves 110 GE for 1 dB (the better ratio, taken first), hash's
    # 300 GE for 3 dB: after interp nothing fits; the branch through hash alone saves more.
    weights, losses = {"interp": 110, "hash": 300}, {"interp": 1.0, "hash": 3.0}
    w0, _ = _walk(weights, losses, 57.0, backtracks=0)
    w1, _ = _walk(weights, losses, 57.0, backtracks=1)
    assert w0["archive"][w0["best"]][1]["logic_ge"] == 1000 + 300
    assert w1["archive"][w1["best"]][1]["logic_ge"] == 1000 + 110 and w1["backtracks"] == 1


def test_max_loss_bounds_every_training_scene_not_only_the_worst():
    # Scene "paper" is the worst (40 dB) and no knob moves it; out_frac's cut costs scene "wrap"
    # (60 dB) 3 dB a step, coord_frac's 0.4 dB a step. On the worst scene alone every cut is free;
    # texture by texture within 1 dB, out_frac may not move and coord_frac only twice.
    text = FULL.read_text()
    doc = contract.read_profile(FULL)
    base = {k["name"]: k["values"].index(k["get"](doc)) for k in S.KNOBS if k["name"] in ("out_frac", "coord_frac")}

    def ev(points):
        out = {}
        for p in points:
            i = {k["name"]: k["values"].index(k["get"](p.doc)) for k in S.KNOBS if k["name"] in base}
            cut = {k: base[k] - v for k, v in i.items()}
            wrap = 60.0 - 3.0 * cut["out_frac"] - 0.4 * cut["coord_frac"]
            out[p.name] = {"status": "ok", "train": {"paper": 40.0, "wrap": wrap}, "train_worst": min(40.0, wrap),
                           "logic_ge": 1000 + 500 * i["out_frac"] + 100 * i["coord_frac"], "cpp": p.cpp}
        return out

    start = S.make_point(text, doc, doc, "start")
    free = S.walk(start, ev, S.Targets(35.0, 1), ["out_frac", "coord_frac"], [], text, doc, 200, 0,
                  say=lambda *_: None)
    bound = S.walk(start, ev, S.Targets(35.0, 1, max_loss=1.0), ["out_frac", "coord_frac"], [], text, doc, 200, 0,
                   say=lambda *_: None)
    pf, rf = free["archive"][free["best"]]
    pb, rb = bound["archive"][bound["best"]]
    assert rf["train"]["wrap"] < 59.0                    # the worst-scene rule lets the wrap texture go
    assert pb.doc["noise"]["out_frac"] == doc["noise"]["out_frac"]
    assert pb.doc["formats"]["coord"]["frac"] == doc["formats"]["coord"]["frac"] - 4     # two steps: 0.8 dB
    assert S.scene_loss({"paper": 40.0, "wrap": 60.0}, rb["train"]) == pytest.approx(0.8)
    assert S.scene_loss({"paper": 40.0, "gone": 50.0}, rb["train"]) == float("inf")


def test_front_points_are_judged_by_the_rule_of_acceptance_against_the_start():
    start = {"train": {"a": 50.0, "b": 60.0}, "valid": {"c": 55.0, "d": 45.0}}
    r = {"train": {"a": 49.5, "b": 60.0}, "valid": {"c": 52.5, "d": 46.0}}
    got = search_report.losses(r, start)
    assert got["train_loss"] == pytest.approx(0.5) and got["valid_loss"] == pytest.approx(2.5)
    assert got["valid_loss_scene"] == "c" and got["valid_pass"] is False
    ok = search_report.losses({"train": r["train"], "valid": {"c": 54.01, "d": 44.01}}, start)
    assert ok["valid_pass"] is True and ok["valid_loss"] == pytest.approx(0.99)
    bad = search_report.losses({"train": r["train"], "valid": {"c": 55.0, "d": 43.99}}, start)
    assert bad["valid_pass"] is False and bad["valid_loss_scene"] == "d"
    assert search_report.losses(r, None) == {}
    assert search_report.losses({"train": r["train"]}, start)["valid_pass"] is None       # not validated
    md = search_report.markdown("t", [dict(**{"class": 1, "name": "p", "cpp": 1, "logic_ge": 5,
                                                        "train_worst": 49.5, "train_mean": 50.0, "valid_worst": 46.0,
                                                        "valid_mean": 49.0, "rtl": None, "move": "m"}, **got)],
                                {1: 40.0}, {1: None}, {"points": 1, "synthesized": 1, "modules_synthesized": 0,
                                                      "wall_s": 1.0, "points_per_hour": 1.0, "train": 2, "valid": 2,
                                                      "size": 32}, {1: 1.0})
    assert "0.50 / 2.50 (c) | **FAIL**" in md and "within 1 dB (class 1)" in md


def test_pareto_front():
    rows = [{"name": n, "logic_ge": a, "train_worst": q} for n, a, q in
            [("a", 10, 30), ("b", 20, 40), ("c", 25, 35), ("d", 30, 50), ("e", 10, 20), ("f", 40, 50)]]
    assert [r["name"] for r in S.pareto(rows)] == ["a", "b", "d"]
    noisy = [{"name": n, "logic_ge": a, "train_worst": q} for n, a, q in
             [("a", 10, 44.64), ("b", 12, 44.65), ("c", 13, 44.70), ("d", 14, 44.69)]]
    assert [r["name"] for r in S.pareto(noisy)] == ["a", "c"]      # b: +0.01 dB is noise
    assert [r["name"] for r in S.pareto(noisy, eps=0.0)] == ["a", "b", "c"]
    fr = search_report.fronts([dict(r, cpp=1 if r["name"] in "ab" else 4) for r in rows], [1, 4])
    assert [r["name"] for r in fr[1]] == ["a", "b"] and [r["name"] for r in fr[4]] == ["a", "b", "d"]


def test_stored_results_are_reused_only_when_complete(tmp_path):
    job = {"size": 32, "synth_floor": 30, "scenes": {"train": ["x/a.toml", "x/b.toml"], "valid": ["y/c.toml"]}}
    r = {"status": "ok", "profile_sha": "s1", "size": 32, "train": {"a": 40.0, "b": 41.0}, "train_worst": 40.0,
         "logic_ge": 1234}
    assert evaluate.search_reusable(r, "s1", job, ("train",))
    assert not evaluate.search_reusable(r, "s2", job, ("train",))
    assert not evaluate.search_reusable(dict(r, size=64), "s1", job, ("train",))
    assert not evaluate.search_reusable(r, "s1", dict(job, pst_sha="another build"), ("train",))
    assert not evaluate.search_reusable(r, "s1", job, ("train", "valid"))
    assert not evaluate.search_reusable(dict(r, logic_ge=None), "s1", job, ("train",))         # area missing
    assert evaluate.search_reusable(dict(r, logic_ge=None, train_worst=20.0), "s1", job, ("train",))   # under the floor
    assert evaluate.search_reusable({"status": "failed", "profile_sha": "s1", "size": 32}, "s1", job, ("train",))
    assert not evaluate.search_reusable({"status": "failed", "profile_sha": "s1", "size": 32}, "s1",
                                    dict(job, retry_failed=True), ("train",))


def test_per_class_arguments(tmp_path):
    from pstlib.cli import search as cli     # scripts/search.py
    assert search_run.per_class("40", [1, 22], float, "--psnr") == {1: 40.0, 22: 40.0}
    assert search_run.per_class("1=50,22=30", [1, 22], float, "--psnr") == {1: 50.0, 22: 30.0}
    with pytest.raises(ValueError):
        search_run.per_class("1=50", [1, 22], float, "--psnr")
    with pytest.raises(ValueError, match="--max-loss: not a valid value: 'x'"):
        search_run.per_class("1=1,22=x", [1, 22], float, "--max-loss")
    for bad in (["--max-loss", "nan"], ["--max-loss", "-1"], ["--psnr", "inf"], ["--max-loss", "4=1"],
                ["--start", "1=nosuch"], ["--classes", "x"]):
        with pytest.raises(SystemExit) as e:
            cli.parse_args(bad)
        assert e.value.code == 2, bad
    (tmp_path / "hash4096.memh").write_text("0\n")     # stand-ins: parse_args checks they exist
    ok = cli.parse_args(["--max-loss", "1=1,2=1,3=1,4=1.5,32=2", "--pst", sys.executable, "--rom-dir", str(tmp_path)])
    assert ok.max_losses == {1: 1.0, 2: 1.0, 3: 1.0, 4: 1.5, 32: 2.0}
    assert {c: p.name for c, (p, _) in ok.start_docs.items()} == {1: "full_1clk.toml", 2: "full_2clk.toml",
                                                                   3: "full.toml", 4: "full_2clk.toml",
                                                                   32: "reduced.toml"}


def test_slurm_job_script_names_the_cluster_options(tmp_path):
    s = slurm.search_job_script(tmp_path, "b1", 5, ("train", "valid"), partition="gpu", account="hw",
                                time_limit="00:30:00", extra=["--mem=4G"])
    lines = s.splitlines()
    assert lines[0] == "#!/bin/sh" and "#SBATCH --array=0-4" in lines
    assert {"#SBATCH --partition=gpu", "#SBATCH --account=hw", "#SBATCH --time=00:30:00", "#SBATCH --mem=4G"} <= set(lines)
    assert lines[-1].endswith(f"worker {tmp_path} b1.names train,valid")
    assert "--partition" not in slurm.search_job_script(tmp_path, "b1", 1, ("train",))


def test_fmax_is_asked_only_of_feasible_candidates_and_enforced():
    text = FULL.read_text()
    doc = contract.read_profile(FULL)
    weights, losses = {"interp": 110, "hash": 300}, {"interp": 0.0, "hash": 0.0}
    ev = FakeSpace(weights, losses, doc, list(weights))
    asked = []

    def fmax_of(p, r):          # the perm256 hash "misses" the clock; the rest make it
        asked.append(p.name)
        return dict(r, fmax_mhz=50.0 if p.doc["noise"]["hash"] == "perm256" else 120.0)

    start = S.make_point(text, doc, doc, "start")
    w = S.walk(start, ev, S.Targets(55.0, 1, 100.0), list(weights), [], text, doc, 50, 0,
               say=lambda *_: None, fmax_of=fmax_of)
    best = w["archive"][w["best"]]
    assert best[0].doc["noise"]["hash"] == "rayshade" and best[0].doc["noise"]["interp"] == "linear"
    assert best[1]["fmax_mhz"] == 120.0
    assert len(asked) == len(set(asked)) and start.name in asked


def test_the_clock_target_is_judged_by_the_derated_fmax_where_there_is_one():
    ok = {"status": "ok", "train_worst": 60.0, "cpp": 1}
    t = S.Targets(55.0, 1, 100.0)
    assert S.feasible(dict(ok, fmax_mhz=120.0), t)
    assert not S.feasible(dict(ok, fmax_mhz=120.0, fmax_derated_mhz=95.0), t)   # meets it only before layout
    assert S.feasible(dict(ok, fmax_mhz=120.0, fmax_derated_mhz=110.0), t)
    assert not S.feasible(dict(ok), t)                                           # not timed
    assert S.timing_fmax(dict(ok, fmax_mhz=120.0, fmax_derated_mhz=None)) == 120.0


def test_a_point_is_evaluated_once_and_resumed(tmp_path):
    calls = tmp_path / "calls.txt"
    pst = tmp_path / "pst"
    pst.write_text("#!/bin/sh\n"
                   f'echo "$2" >> {calls}\n'
                   'while [ $# -gt 0 ]; do if [ "$1" = "-o" ]; then out=$2; fi; shift; done\n'
                   'mkdir -p "$out"; echo \'{"vs_reference": {"psnr": 41.5, "rms": 0.01}}\' > "$out/summary.json"\n')
    pst.chmod(0o755)
    scenes = []
    for s in ("a", "b"):
        f = tmp_path / f"{s}.toml"
        f.write_text("")
        scenes.append(str(f))
    out = tmp_path / "out"
    text = REDUCED.read_text()
    doc = contract.read_profile(REDUCED)
    p = S.make_point(text, doc, doc, "start")
    (out / "points").mkdir(parents=True)
    (out / "points" / f"{p.name}.toml").write_text(p.text)
    job = {"size": 16, "synth_floor": 30.0, "pst": str(pst), "scenes": {"train": scenes[:1], "valid": scenes[1:]},
           "points": {p.name: p.sha}}
    (out / "job.json").write_text(json.dumps(job))

    class Area:
        n = 0

        def area(self, profile):
            Area.n += 1
            return {"logic_ge": 777, "modules_synthesized": 1, "modules_total": 2, "seconds": 0.0}

    r = evaluate.search_point(out, p.name, ("train",), module_cache=Area())
    assert r["status"] == "ok" and r["train_worst"] == 41.5 and r["logic_ge"] == 777 and r["cpp"] == 32
    assert evaluate.search_reusable(json.loads((out / "results" / f"{p.name}.json").read_text()), p.sha, job, ("train",))
    r = evaluate.search_point(out, p.name, ("train", "valid"), module_cache=Area())
    assert r["valid_worst"] == 41.5 and r["area_new"] is False
    assert calls.read_text().split() == scenes and Area.n == 1     # a, then b only
