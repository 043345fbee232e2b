import csv
import io
import json

import numpy as np
import pytest

from pstlib.explore import evaluate, plots, results, rtlcheck, sweep_report


def summary(ref_psnr, truth_psnr, ref_rms=1.0):
    """A render's summary.json as `pst render --truth` writes it (nlohmann writes inf as null)."""
    return json.loads(json.dumps({
        "vs_reference": {"max_lsb": 3, "rms": ref_rms, "psnr": ref_psnr, "within_1lsb_percent": 97.0},
        "vs_truth": {"max_lsb": 9, "rms": 2.0, "psnr": truth_psnr, "within_1lsb_percent": 80.0},
        "reference_vs_truth": {"rms": 1.5, "psnr": 40.0}, "notes": ["octaves dropped"], "fragments": 4096,
        "model": "golden"}))


def test_psnr_of_a_summary_entry():
    assert results.psnr({"psnr": 38.5, "rms": 2}) == 38.5
    assert results.psnr({"psnr": None, "rms": 0}) == results.PSNR_CAP      # exact: inf written as null
    assert results.psnr({"psnr": 250.0, "rms": 0.001}) == results.PSNR_CAP
    assert results.psnr({"psnr": None, "rms": 3}) is None
    assert results.psnr(None) is None


def test_scene_record_keeps_the_comparisons():
    rec = evaluate.scene_record(summary(30.0, 25.0))
    assert set(rec) == {"vs_reference", "vs_truth", "reference_vs_truth", "notes", "fragments"}
    assert rec["vs_reference"]["psnr"] == 30.0


def result(name, knob, value, ref, truth, ge=None, rom=0, status="ok"):
    return {"name": name, "knob": knob, "value": value, "status": status, "profile": f"/p/{name}.toml",
            "profile_sha": name, "scenes": {"a": evaluate.scene_record(summary(ref[0], truth[0])),
                                              "b": evaluate.scene_record(summary(ref[1], truth[1]))},
            "synth": None if ge is None else {"logic_ge": ge, "rom_bits": rom, "ram_bits": 0, "flip_flops": 1}}


def test_summarize_means_and_worst_scene():
    r = result("p", "k", 1, (30.0, 40.0), (20.0, 22.0))
    s = results.summarize(r)
    assert s == {"psnr_ref": 35.0, "psnr_ref_min": 30.0, "psnr_truth": 21.0, "ref_vs_truth": 40.0}
    assert results.summarize(r, ["b"])["psnr_ref"] == 40.0
    r["scenes"]["b"]["vs_reference"] = {"psnr": None, "rms": 5}       # one scene without a number
    assert results.summarize(r)["psnr_ref"] is None


def rows_and_base():
    base = results.row_of(result("base", "base", "-", (40.0, 40.0), (30.0, 30.0), ge=100000, rom=4096), ["a", "b"])
    base.update(base_value={"coord_frac": 12, "hash": "rayshade"}, knob="base")
    rows = [results.row_of(r, ["a", "b"]) for r in [
        result("c8", "coord_frac", 8, (38.0, 38.0), (29.0, 29.0), ge=90000),      # -2 dB: too far
        result("c10", "coord_frac", 10, (39.5, 39.5), (29.5, 29.5), ge=95000),    # -0.5 dB, cheaper
        result("c16", "coord_frac", 16, (41.0, 41.0), (30.0, 30.0), ge=110000),
        result("hp", "hash", "perm256", (39.2, 39.2), (29.0, 29.0), ge=97000, rom=2048),
        result("hx", "hash", "other", (0, 0), (0, 0), status="failed")]]
    return rows, base


def test_row_of_a_failed_point_has_no_numbers():
    rows, _ = rows_and_base()
    assert rows[-1]["psnr_ref"] is None and rows[-1]["status"] == "failed"
    assert rows[1]["logic_ge"] == 95000 and rows[1]["psnr_ref"] == 39.5


def test_filter_points_borrow_the_base_gate_count():
    base = result("base", "base", "-", (40.0, 40.0), (30.0, 30.0), ge=100000)
    f = result("fm", "filter", "mip", (35.0, 35.0), (31.0, 31.0))
    assert results.row_of(f, ["a", "b"], base)["logic_ge"] == 100000


def test_cheapest_within_one_db():
    rows, base = rows_and_base()
    best, ok = results.cheapest_within(rows, base, "coord_frac")
    assert best["name"] == "c10"
    assert sorted(r["name"] for r in ok) == ["base", "c10", "c16"]
    best, _ = results.cheapest_within(rows, base, "hash")
    assert best["name"] == "hp"
    rows[1]["logic_ge"] = None                       # a candidate without a gate count: no ranking
    assert results.cheapest_within(rows, base, "coord_frac")[0] is None


def test_cheapest_within_is_the_rule_of_acceptance_scene_by_scene():
    rows, base = rows_and_base()
    # mean 39.75 dB (0.25 under the base) but scene a 1.5 dB under: it fails the rule
    rows[1] = results.row_of(result("c10", "coord_frac", 10, (38.5, 41.0), (29.5, 29.5), ge=95000), ["a", "b"])
    best, ok = results.cheapest_within(rows, base, "coord_frac")
    assert best["name"] == "base" and "c10" not in [r["name"] for r in ok]
    rows[1] = results.row_of(result("c10", "coord_frac", 10, (39.01, 41.0), (29.5, 29.5), ge=95000), ["a", "b"])
    assert results.cheapest_within(rows, base, "coord_frac")[0]["name"] == "c10"


def test_rtl_subset_takes_the_biggest_savings_then_other_knobs():
    rows, base = rows_and_base()
    assert results.rtl_subset(rows, base, ["coord_frac", "hash"], 1) == ["c10"]
    assert results.rtl_subset(rows, base, ["coord_frac", "hash"], 2) == ["c10", "hp"]
    assert results.rtl_subset(rows, base, ["coord_frac", "hash"], 0) == []


def test_image_psnr():
    a = np.zeros((4, 4, 3))
    b = np.full((4, 4, 4), 0.1)
    assert results.image_psnr(a, a) == results.PSNR_CAP
    assert results.image_psnr(a, b) == pytest.approx(20.0)       # mse 0.01


def test_regress_summary():
    runs = [{"passed": True, "mismatches": 0, "pixels_checked": 4096}] * 2
    assert rtlcheck.regress_summary(runs, 0)["summary"] == "pass: 2 scenes, 8192 px, 0 mismatches"
    bad = runs[:1] + [{"passed": False, "mismatches": 7, "pixels_checked": 4096}]
    s = rtlcheck.regress_summary(bad, 1)
    assert not s["passed"] and s["summary"] == "FAIL: 7 mismatches in 1/2 scenes"
    assert rtlcheck.regress_summary([], 2)["summary"] == "FAIL: regress exited 2"
    assert not rtlcheck.regress_summary(runs, 1)["passed"]


def test_plot_data():
    rows, base = rows_and_base()
    series, missing = plots.ge_psnr_series(rows, ["coord_frac", "hash"], "psnr_ref")
    assert series == [("coord_frac", [(8, 90.0, 38.0), (10, 95.0, 39.5), (16, 110.0, 41.0)]),
                      ("hash", [("perm256", 97.0, 39.2)])]
    assert missing == 0
    pts, xs, numeric = plots.knob_points(rows, base, "coord_frac")
    assert numeric and xs == [8, 10, 12, 16] and pts[2]["name"] == "base"
    pts, xs, numeric = plots.knob_points(rows, base, "hash")
    assert not numeric and xs == [0, 1] and [p["value"] for p in pts] == ["rayshade", "perm256"]
    assert not plots.log_x(rows, base)
    assert plots.psnr_span([30.0, 31.0]) == (28.75, 32.25)
    assert plots.psnr_span([30.0, 40.0]) is None
    lo, hi = plots.ge_limits([100.0, 101.0])
    assert lo < 100.0 - 1.5 and hi > 101.0 + 1.5


def test_csv_rows(tmp_path):
    rows, base = rows_and_base()
    text = sweep_report.csv_text(base, rows, ["a", "b"], {"c10": {"summary": "pass: 2 scenes"}})
    table = list(csv.DictReader(io.StringIO(text)))
    assert [r["point"] for r in table] == ["base", "c8", "c10", "c16", "hp", "hx"]
    c10 = table[2]
    assert c10["logic_ge"] == "95000" and c10["psnr_ref_mean"] == "39.500" and c10["delta_psnr_ref"] == "-0.500"
    assert c10["rtl_check"] == "pass: 2 scenes" and c10["psnr_truth_b"] == "29.500"
    assert table[-1]["psnr_ref_mean"] == "" and table[-1]["status"] == "failed"
