"""pstlib.report: the data collected from an out/ folder and its two renderings.
(The page in a real browser: scripts/tests/browser/report.test.mjs.)"""
import base64
import json
import pathlib
import re
import sys

from pstlib.paths import ROOT
from pstlib.report import data as report_data, html as report_html, md as report_md

# A 1x1 PNG (a real file: the page embeds it as a data: URI).
PNG = base64.b64decode("iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4z8AAAAMBAQDJ/pLvAAAAAElFTkSuQmCC")


def run(scene, profile, mismatches, psnr):
    return {"scene": f"scenes/{scene}.toml", "profile": profile, "model": "rtl", "passed": mismatches == 0,
            "mismatches": mismatches, "pixels_checked": 4, "cycles_per_pixel": 1.0,
            "vs_reference": {"psnr": psnr, "within_1lsb_percent": 90.0, "max_lsb": 2},
            "pixels_per_second": {"rtl": 10.0, "golden": 100.0}, "notes": []}


def make_out(tmp: pathlib.Path) -> pathlib.Path:
    out = tmp / "out"
    runs = [run("a", "full", 0, 40.0), run("a", "reduced", 2, 30.0), run("b", "full", 0, 50.0),
            run("b", "reduced", 7, 20.0)]
    for r in runs:
        d = out / report_data.scene_stem(r) / r["profile"]
        d.mkdir(parents=True)
        for k in ("rtl", "reference", "difference"):
            (d / f"{k}.png").write_bytes(PNG)
    (out / "a" / "truth.png").write_bytes(PNG)
    (out / "c").mkdir()
    (out / "c" / "report.json").write_text(json.dumps({"title": "C", "width": 1, "height": 1, "fragments": 1,
                                                       "seconds": {"total": 1, "truth": 0}}))
    for k in ("filtered", "unfiltered", "width"):
        (out / "c" / f"{k}.png").write_bytes(PNG)
    (out / "regress.json").write_text(json.dumps(runs))
    (out / "synth").mkdir()
    (out / "synth" / "reduced.json").write_text(json.dumps({"profile": "reduced", "logic_ge": 98000, "fmax_mhz": 50.5,
                "timing": {"fmax_mhz": 51.25, "worst": {"slack_ns": -1}}, "throughput": {"meets_realtime": True},
                "depth": {"pst_noise": 40}}))
    (out / "synth" / "full.json").write_text(json.dumps({"profile": "full", "logic_ge": 3000000}))
    (out / "synth" / "full.md").write_text("## Gates\n\n| a | b |\n|---|---|\n| 1 | 2 |\n")
    (out / "synth" / "reduced_octaves_2.json").write_text(json.dumps({"profile": "reduced_octaves_2", "logic_ge": 1}))
    (out / "figures").mkdir()
    (out / "figures" / "fig11.md").write_text("# Fig\n\n![x](fig11.png) [link](fig11_a.png) [web](https://x.y/z)\n")
    return out


def test_failures_first_most_mismatches_first(tmp_path):
    rep = report_data.collect(make_out(tmp_path))
    t = report_data.regress_table(rep.runs, lambda r: [])
    assert [(row[0], row[1]) for row in t.rows] == [("b", "reduced"), ("a", "reduced"), ("a", "full"), ("b", "full")]
    assert t.failed == [True, True, False, False]


def test_viewer_layers_reference_profiles_truth_differences(tmp_path):
    rep = report_data.collect(make_out(tmp_path))
    a = next(v for v in rep.scenes if v.name == "a")
    # The two profiles' reference images are the same file content: one reference layer.
    assert [l.kind for l in a.layers] == ["reference", "rtl", "rtl", "truth", "difference", "difference"]
    b = next(v for v in rep.scenes if v.name == "b")
    assert "truth" not in [l.kind for l in b.layers]
    c = next(v for v in rep.scenes if v.name == "c")
    assert [l.kind for l in c.layers] == ["filtered", "unfiltered", "width"] and c.runs == []


def test_gate_summary_tolerates_missing_keys(tmp_path):
    rep = report_data.collect(make_out(tmp_path))
    t = report_data.gate_summary(rep.gates, rep.root, rep.runs)
    assert t.columns == ["figure", "full", "reduced"]        # named profiles, the paper's order
    rows = {r[0]: i for i, r in enumerate(t.rows)}
    fmax = rows["Fmax pre-layout (typical, no wire)"]
    assert t.cell(fmax, 1) == "-" and t.cell(fmax, 2) == "50.5 MHz (ideal clock)"
    assert t.cell(rows["logic GE"], 1) == "3,000,000"
    assert t.links[rows["raw figures"]]["reduced"] == [("synth/reduced.json", "synth/reduced.json")]
    md = report_md.render(rep, lambda r: [])
    assert "(not synthesized: scripts/synth.py reduced)" in md   # json without md


def test_included_links_rebased_headings_demoted(tmp_path):
    rep = report_data.collect(make_out(tmp_path))
    fig11 = next(f for f in rep.figures if f.anchor == "fig11")
    assert "](figures/fig11.png)" in fig11.text and "](figures/fig11_a.png)" in fig11.text
    assert "](https://x.y/z)" in fig11.text
    assert fig11.text.startswith("## Fig")


def test_fidelity_table_is_a_section(tmp_path):
    out = make_out(tmp_path)
    (out / "fidelity").mkdir()
    (out / "fidelity" / "fidelity.md").write_text("| scene | unfiltered | sat | trapezoid |\n|---|---|---|---|\n")
    rep = report_data.collect(out)
    ex = next(e for e in rep.extras if e.anchor == "fidelity-fidelity")
    assert ex.title == "Filter options against the ground truth"
    assert "| scene | unfiltered | sat | trapezoid |" in report_md.render(rep, lambda r: [])


def test_atlas_runs_are_sections(tmp_path):
    out = make_out(tmp_path)
    d = out / "atlas" / "wood_teapot"
    d.mkdir(parents=True)
    (d / "atlas.md").write_text("# Atlas: wood_teapot\n\n![atlas](atlas.png)\n")
    (d / "atlas.json").write_text('{"coverage": 0.9}')
    rep = report_data.collect(out)
    ex = next(e for e in rep.extras if e.anchor == "atlas-wood_teapot")
    assert ex.title == "Texture atlas: wood_teapot" and ex.data == {"coverage": 0.9}
    assert "](atlas/wood_teapot/atlas.png)" in ex.text   # links from the report's folder


# A `pst atlas --profile reduced` run's folder as the tool leaves it (fake 1x1 images): its
# atlas.md (tables, the image line) and atlas.json.
ATLAS_MD = """# Atlas: wood_teapot (length, 64 x 64, seam-free for bilinear)

| measure | ours | paper Table 1 (rhino, length) |
|---|---|---|
| coverage C (eq. 1) | 0.91 | 0.93 |
| relative scale S (eq. 2) | 1.13 | 0.86 |

![atlas](atlas.png) ![textured, bilinear](render_bilinear.png) ![per-pixel](per_pixel.png) ![truth](truth.png) ![relative scale (Fig. 7)](scale.png)

| seams (screen pixels reading a background or foreign texel) | nearest | bilinear |
|---|---|---|
| seam-free layout | 0 | 0 |

Fill through reduced RTL: 4096 texels, 131072 cycles, 0 mismatches.
"""


def make_atlas_run(out: pathlib.Path) -> pathlib.Path:
    d = out / "atlas" / "wood_teapot"
    d.mkdir(parents=True)
    (d / "atlas.md").write_text(ATLAS_MD)
    (d / "atlas.json").write_text(json.dumps({"coverage": 0.91, "hardware": {"profile": "reduced", "model": "rtl"}}))
    for k in ("atlas", "atlas_rtl", "render_nearest", "render_bilinear", "per_pixel", "truth", "scale"):
        (d / f"{k}.png").write_bytes(PNG)
    return d


def test_atlas_run_has_a_viewer(tmp_path):
    out = make_out(tmp_path)
    make_atlas_run(out)
    rep = report_data.collect(out)
    ex = next(e for e in rep.extras if e.anchor == "atlas-wood_teapot")
    # The textured render and the per-pixel one first (A and B), the atlas images last; no
    # trilinear render (not a --mip run).
    assert [(l.label, l.kind) for l in ex.view.layers] == [
        ("textured, bilinear", "atlas_render"), ("per-pixel render", "per_pixel"), ("textured, nearest", "atlas_render"),
        ("ground truth", "truth"), ("relative scale (Fig. 7)", "scale"), ("atlas (reference fill)", "atlas"),
        ("atlas (reduced RTL fill)", "atlas")]
    page = report_html.render(rep)
    section = re.search(r'<section id="atlas-wood_teapot">(.*?)</section>', page, flags=re.S).group(1)
    specs = [json.loads(s) for s in re.findall(r'<script type="application/json">(.*?)</script>', section, flags=re.S)]
    assert len(specs) == 1 and specs[0]["name"] == "atlas-wood_teapot"
    assert [l["label"] for l in specs[0]["layers"]] == [l.label for l in ex.view.layers]
    assert all(l["src"].startswith("data:image/png;base64,") for l in specs[0]["layers"])
    assert (specs[0]["a"], specs[0]["b"]) == (0, 1)
    # The tables stay, above the viewer; the images the viewer shows are not repeated as <img>.
    assert section.index("coverage C (eq. 1)") < section.index("seam-free layout") < section.index('class="pv"')
    assert "Fill through reduced RTL: 4096 texels, 131072 cycles" in section
    assert "<img" not in section
    assert 'id="viewer-atlas-wood_teapot"' in page
    # report.md keeps the images as links.
    assert "![atlas](atlas/wood_teapot/atlas.png)" in report_md.render(rep, lambda r: [])


def test_html_page_self_contained(tmp_path):
    out = make_out(tmp_path)
    rep = report_data.collect(out)
    page = report_html.render(rep)
    assert not re.search(r"<(script|link|img)[^>]+(src|href)=\"https?:", page)   # no network
    scripts = re.findall(r"<script[^>]*>(.*?)</script>", page, flags=re.S)
    specs = [json.loads(s) for s in scripts if s.startswith("{") and '"layers"' in s]     # the viewers'
    assert [s["name"] for s in specs] == ["a", "b", "c"]   # c: a reference render alone
    assert all(l["src"].startswith("data:image/png;base64,") for s in specs for l in s["layers"])
    assert 'id="scene-a"' in page and 'id="gates"' in page and 'id="fig11"' in page
    assert '<img alt="x" src="figures/fig11.png"' in page
    assert '<a href="figures/fig11_a.png">link</a><br><img class="plot" src="figures/fig11_a.png" alt="link">' in page
    embedded = report_html.render(rep, embed_all=True)
    assert '<img alt="x" src="data:image/png;base64,' not in embedded   # fig11.png does not exist: left as is
    (out / "figures" / "fig11.png").write_bytes(PNG)
    assert '<img alt="x" src="data:image/png;base64,' in report_html.render(rep, embed_all=True)


def test_numbers_sort_as_numbers(tmp_path):
    rep = report_data.collect(make_out(tmp_path))
    page = report_html.render(rep)
    assert 'data-v="20.0"' in page and 'data-v="7"' in page


def test_bad_input_names_the_file(tmp_path):
    out = make_out(tmp_path)
    (out / "regress.json").write_text("[{\"scene\": 1}]")
    try:
        report_data.collect(out)
    except report_data.InputError as e:
        assert str(e).startswith(str(out / "regress.json") + ": expected a list of runs")
    else:
        raise AssertionError("no error")


def test_sweep_page_puts_the_points_side_by_side(tmp_path):
    import subprocess
    sweep = tmp_path / "sweep"
    for point in ("base", "base_octaves_2"):
        d = sweep / "renders" / point / "a"
        d.mkdir(parents=True)
        r = run("a", "base", 0, 40.0)
        r["model"] = "golden"
        (d / "summary.json").write_text(json.dumps(r))
        for k in ("golden", "reference", "difference"):
            (d / f"{k}.png").write_bytes(PNG)
    (sweep / "sweep.md").write_text("# Precision sweep\n\n- [plot](knobs/octaves.png)\n")
    page = sweep / "index.html"
    script = ROOT / "scripts" / "report.py"
    subprocess.run([sys.executable, str(script), "--html", str(page), "--sweep", str(sweep)], check=True)
    text = page.read_text()
    specs = [json.loads(s) for s in re.findall(r'<script type="application/json">(.*?)</script>', text, flags=re.S)]
    assert [l["label"] for l in specs[0]["layers"]] == [
        "reference", "base (golden)", "base_octaves_2 (golden)", "|base - reference| x8", "|base_octaves_2 - reference| x8"]
    assert 'id="sweep"' in text and '<img class="plot" src="knobs/octaves.png"' in text


# The report's top: the regression's and the baseline check's verdicts side by side, where the
# silicon figures came from, the provenance.

def passing_out(tmp: pathlib.Path) -> pathlib.Path:
    out = make_out(tmp)
    runs = [run("a", "full", 0, 40.0), run("b", "full", 0, 50.0)]
    (out / "regress.json").write_text(json.dumps(runs))
    return out


def top_of(md: str) -> str:
    return md.split("## RTL regression")[0]


MOVED = {"schema": 1, "status": "fail", "tolerance": 0.02, "figures_checked": 120,
         "moved": [{"figure": "reduced.fmax_mhz", "baseline": 116.6, "current": 113.2, "change": -0.0292},
                   {"figure": "reduced.block_ge.isqrt", "baseline": 1000, "current": 1076, "change": 0.076}],
         "signoff_failures": [], "tool_mismatches": [], "stale": [], "messages": []}


def test_top_shows_a_failed_baseline_beside_a_passed_regression(tmp_path):
    out = passing_out(tmp_path)
    (out / "baseline_check.json").write_text(json.dumps(MOVED))
    rep = report_data.collect(out)
    top = top_of(report_md.render(rep, lambda r: []))
    assert "**Regression: PASSED** (2 runs) · **Baseline: FAILED** (2 figures moved beyond 2 %)" in top
    assert "- reduced.fmax_mhz: 116.6 -> 113.2 (-2.9 %)" in top
    assert "- reduced.block_ge.isqrt: 1000 -> 1076 (+7.6 %)" in top
    page = report_html.render(rep)
    head = page.split('<section id="regression">')[0]
    assert 'data-label="Regression" data-status="PASSED"' in head
    assert 'data-label="Baseline" data-status="FAILED"' in head
    assert '<span class="status-fail">FAILED</span> (2 figures moved beyond 2 %)' in head
    assert "<li>reduced.fmax_mhz: 116.6 -&gt; 113.2 (-2.9 %)</li>" in head


def test_top_baseline_passed_not_run_and_error(tmp_path):
    out = passing_out(tmp_path)
    top = top_of(report_md.render(report_data.collect(out), lambda r: []))
    assert "**Regression: PASSED** (2 runs) · **Baseline: not run**" in top
    (out / "baseline_check.json").write_text(json.dumps(dict(MOVED, status="pass", moved=[])))
    top = top_of(report_md.render(report_data.collect(out), lambda r: []))
    assert "**Baseline: PASSED** (120 figures within 2 %)" in top
    (out / "baseline_check.json").write_text(json.dumps(dict(MOVED, status="error", moved=[],
                                                             messages=["error: out/regress.json: missing"])))
    top = top_of(report_md.render(report_data.collect(out), lambda r: []))
    assert "**Baseline: ERROR** (error: out/regress.json: missing)" in top
    (out / "baseline_check.json").write_text("{not json")
    assert "**Baseline: ERROR**" in top_of(report_md.render(report_data.collect(out), lambda r: []))


def test_top_failed_regression(tmp_path):
    top = top_of(report_md.render(report_data.collect(make_out(tmp_path)), lambda r: []))
    assert "**Regression: FAILED** (2 of 4 runs with mismatches) · **Baseline: not run**" in top


def test_top_says_where_the_silicon_figures_came_from(tmp_path):
    out = passing_out(tmp_path)
    md = report_md.render(report_data.collect(out), lambda r: [])
    assert "Silicon figures: synthesized in this run." in top_of(md)
    (out / "synth" / "source.json").write_text(json.dumps({"source": "record", "digest": "0123456789abcdef"}))
    rep = report_data.collect(out)
    md = report_md.render(rep, lambda r: [])
    assert ("Silicon figures: from the silicon record (inputs unchanged since the baseline, digest "
            "0123456789abcdef).") in top_of(md)
    assert 'data-status="from the silicon record"' in report_html.render(rep)
    (out / "synth" / "source.json").write_text(json.dumps({"source": "none", "stale": ["rtl/pst_top.sv changed"]}))
    md = report_md.render(report_data.collect(out), lambda r: [])
    assert "Silicon figures: not from the record (the inputs changed since the baseline: rtl/pst_top.sv changed" in md


def test_provenance_in_md_and_html(tmp_path):
    rep = report_data.collect(passing_out(tmp_path), argv=["scripts/report.py", "out"])
    p = rep.provenance
    assert p["schema"] == report_data.SCHEMA and p["command"] == "scripts/report.py out"
    assert set(p["tools"]) == {"verilator", "yosys", "opensta", "python"} and p["commit"]
    md = report_md.render(rep, lambda r: [])
    assert f"Provenance: commit {p['commit']};" in top_of(md) and "command `scripts/report.py out`" in md
    page = report_html.render(rep)
    data = re.search(r'<script type="application/json" id="provenance">(.*?)</script>', page, flags=re.S).group(1)
    assert json.loads(data) == p


def synth_record(name="full", fmax=121.8, cpp=3, derate=0.904) -> dict:
    """A synthesis record (scripts/synth.py's JSON) with the fields its Markdown reads."""
    mpix = fmax / cpp
    derated = round(fmax * derate, 1)
    worst = {"stage": "octave stage [A] -> [B]", "startpoint": "a", "endpoint": "b", "through": [],
             "arrival_ns": 8.0, "cells": 10}
    return {
        "profile": name, "library": {"ge_um2": 24.0}, "seconds": {"yosys": 1, "memories": 1, "sta": 1},
        "tools": {"yosys": "Yosys 0.23", "opensta": "2.0.17"}, "logic_ge": 1000, "logic_area_um2": 24000,
        "memory_ge": 10, "memory_area_um2": 240, "total_ge": 1010, "total_area_mm2": 0.024, "flip_flops": 5,
        "rom_bits": 1, "ram_bits": 2, "paper_gates": None, "logic_ge_cells_lib": None, "clocks_per_pixel": cpp,
        "clocks_per_pixel_regress": None, "blocks": {}, "memories": [], "fmax_mhz": fmax,
        "fmax_derated_mhz": derated, "fmax_derate": {"ratio": derate, "profile": "reduced", "source": "pnr"},
        "throughput": {"fmax_mhz": fmax, "fmax_basis": "pre-layout", "mpixel_s": round(mpix, 2),
                       "realtime_mpixel_s": 36.9, "meets_realtime": mpix >= 36.9, "area_time_ge_clocks": 3000,
                       "fmax_derated_mhz": derated, "mpixel_s_derated": round(derated / cpp, 2),
                       "meets_realtime_derated": derated / cpp >= 36.9},
        "mpixel_s": round(mpix, 2), "worst_path_ns": 8.0,
        "timing": {"fmax_mhz": fmax, "wns_ns": 1.0, "period_ns": 10, "worst": worst,
                   "constraints": {"setup_uncertainty_ns": 0.4, "hold_uncertainty_ns": 0.1, "max_transition_ns": 1.2,
                                   "period_ns": 10, "clock_transition_ns": 0.35, "input_transition_ns": 0.2},
                   "hold": {"wns_ns": 0.1, "violations": 0, "stages": []},
                   "max_transition": {"violations": 0, "worst": {"transition_ns": 0.5, "pin": "p"}},
                   "max_capacitance": {"violations": 0, "checked": 9,
                                       "worst": {"load_pf": 0.1, "limit_pf": 0.2, "pin": "p"}},
                   "stages": []},
    }


def test_one_throughput_per_profile(tmp_path):
    """scripts/synth.py's Markdown states a pre-layout and a derated throughput (40.60 and 36.70
    Mpixel/s for full); the report states one, the silicon table's, labelled with its basis."""
    from pstlib.synth import report as synth_report
    out = passing_out(tmp_path)
    rec = synth_record()
    (out / "synth" / "full.json").write_text(json.dumps(rec))
    md_in = synth_report.markdown(rec)
    assert "40.60 Mpixel/s" in md_in and "36.70 Mpixel/s" in md_in      # the two figures of the input
    (out / "synth" / "full.md").write_text(md_in)
    rep = report_data.collect(out)
    md = report_md.render(rep, lambda r: [])
    section = md.split("## Gates and timing: full\n")[1].split("\n## ")[0]
    figures = [m for m in re.findall(r"([\d.,]+) Mpixel/s", section) if m != "36.9"]   # 36.9: the real-time bar
    assert figures == ["36.70"], figures
    assert "| throughput, derated (post-route ratio x 0.904) (the summary's: 110.1 MHz / 3 clocks per pixel) | " \
           "36.70 Mpixel/s (misses 640x480 60 Hz depth 2: 36.9 Mpixel/s) |" in section
    t = report_data.gate_summary(rep.gates, rep.root, rep.runs)
    row = next(r for r in t.rows if r[0] == "Mpixel/s at that clock")
    assert row[t.columns.index("full")] == "36.70"                          # the same figure
    page = report_html.render(rep)
    full = page.split('<section id="gates-full">')[1].split("</section>")[0]
    assert [m for m in re.findall(r"([\d.,]+) Mpixel/s", full) if m != "36.9"] == ["36.70"]


def test_one_throughput_pre_layout_without_derate(tmp_path):
    from pstlib.synth import report as synth_report
    out = passing_out(tmp_path)
    rec = synth_record()
    for k in ("fmax_derated_mhz", "fmax_derate"):
        del rec[k]
    for k in ("fmax_derated_mhz", "mpixel_s_derated", "meets_realtime_derated"):
        del rec["throughput"][k]
    (out / "synth" / "full.json").write_text(json.dumps(rec))
    (out / "synth" / "full.md").write_text(synth_report.markdown(rec))
    md = report_md.render(report_data.collect(out), lambda r: [])
    section = md.split("## Gates and timing: full\n")[1].split("\n## ")[0]
    assert [m for m in re.findall(r"([\d.,]+) Mpixel/s", section) if m != "36.9"] == ["40.60"]
    assert "| throughput, pre-layout (the summary's: 121.8 MHz / 3 clocks per pixel) | 40.60 Mpixel/s (meets" in section
