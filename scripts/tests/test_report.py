"""pstlib.report_*: the data collected from an out/ folder and its two renderings.
(The page in a real browser: scripts/tests/browser/report.test.mjs.)"""
import base64
import json
import pathlib
import re
import sys

from pstlib import report_data, report_html, report_md

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
    specs = [json.loads(s) for s in scripts if s.startswith("{")]
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
    script = pathlib.Path(__file__).resolve().parent.parent / "report.py"
    subprocess.run([sys.executable, str(script), "--html", str(page), "--sweep", str(sweep)], check=True)
    text = page.read_text()
    specs = [json.loads(s) for s in re.findall(r'<script type="application/json">(.*?)</script>', text, flags=re.S)]
    assert [l["label"] for l in specs[0]["layers"]] == [
        "reference", "base (golden)", "base_octaves_2 (golden)", "|base - reference| x8", "|base_octaves_2 - reference| x8"]
    assert 'id="sweep"' in text and '<img class="plot" src="knobs/octaves.png"' in text
