"""Tests of pstlib.figures.fidelity (the ground-truth table of the filter options)."""
import json
import math

import pytest

from pstlib.figures import fidelity


def still(tmp_path, name, unf, variants, title=""):
    d = tmp_path / name
    d.mkdir()
    doc = {"scene": f"scenes/{name}.toml", "width": 64, "height": 64, "truth_samples": 256, "title": title,
           "vs_truth": {"unfiltered": {"rms": unf}, "filtered": {"rms": variants.get("sat", 0)}},
           "variants": {k: {"filter": k, "bandlimit": "off", "vs_truth": {"rms": v}} for k, v in variants.items()}}
    (d / "report.json").write_text(json.dumps(doc))
    return d


def seq(name, **streams):
    return {"scene": f"scenes/{name}.toml", "frames": 3, "width": 16, "height": 16, "truth_samples": 64,
            "streams": streams}


def test_psnr():
    assert fidelity.psnr(0.1) == pytest.approx(20.0)
    assert fidelity.psnr(0) == float("inf")


def test_still_table_and_goals(tmp_path):
    s = [fidelity.load_still(still(tmp_path, "seascape", 0.06, {"sat": 0.05, "trapezoid": 0.025})),
         fidelity.load_still(still(tmp_path, "planet", 0.04, {"sat": 0.045, "trapezoid": 0.02}))]
    md = fidelity.markdown(s, [])
    assert "| scene | size | unfiltered | sat | trapezoid |" in md
    # The option's cell: its RMS, PSNR and the paper's RMS over it.
    assert "| seascape | 64x64 | 0.0600 (24.4 dB, 0.83x) | 0.0500 (26.0 dB) | 0.0250 (32.0 dB, 2.00x) |" in md
    g = {goal: (m, ok) for goal, m, ok in fidelity.goals(s, [])}
    assert g["seascape: filtered error >= 2x lower than unfiltered"][1] is True    # the trapezoid: 2.4x
    assert g["planet: filtered error lower than unfiltered"][1] is False           # the paper's: 0.045 > 0.04
    assert "worst planet 0.89x" in g["every scene: filtered error >= 1.5x lower than unfiltered"][0]


def test_still_goal_per_paper_scene_and_one_option_for_all(tmp_path):
    s = [fidelity.load_still(still(tmp_path, "fire", 0.05, {"sat": 0.045, "sat+isotropic": 0.04}, "Fig. 4: fire")),
         fidelity.load_still(still(tmp_path, "bases", 0.05, {"sat": 0.06, "sat+isotropic": 0.07}, "Noise bases")),
         fidelity.load_still(still(tmp_path, "planet", 0.04, {"sat": 0.035, "sat+isotropic": 0.036}, "Fig. 5")),
         fidelity.load_still(still(tmp_path, "seascape_subband", 0.06,
                                   {"sat": 0.05, "sat+isotropic": 0.01, "sat+anisotropic": 0.01}, "Fig. 3"))]
    g = {goal: (m, ok) for goal, m, ok in fidelity.goals(s, [])}
    # bases is not a paper scene: no row.
    assert not any("still bases" in k for k in g)
    m, ok = g["still fire: best hardware option closer to the truth than unfiltered, not worse than the paper's"]
    assert ok and m == "unfiltered 0.0500; sat 0.0450; sat+isotropic 0.0400; best sat+isotropic"
    # On the subband basis +isotropic/+anisotropic are the reference's weights: the paper's filter only.
    m, ok = g["still seascape_subband: best hardware option closer to the truth than unfiltered, not worse than the paper's"]
    assert ok and m == "unfiltered 0.0600; sat 0.0500; best sat"
    m, ok = g["every paper scene's still, one hardware option: closer than unfiltered and not worse than the paper's"]
    # sat+isotropic is worse than the paper's on planet (0.036 > 0.035); the paper's filter meets all.
    assert ok and m == "sat: all; sat+isotropic: fails planet"
    # Both options worse than unfiltered on planet: no option meets every paper scene.
    s[2]["rms"].update({"sat": 0.041, "sat+isotropic": 0.042})
    g = {goal: (m, ok) for goal, m, ok in fidelity.goals(s, [])}
    assert g["still planet: best hardware option closer to the truth than unfiltered, not worse than the paper's"][1] is False
    m, ok = g["every paper scene's still, one hardware option: closer than unfiltered and not worse than the paper's"]
    assert not ok and m == "sat: fails planet; sat+isotropic: fails planet"


def test_sequence_figures_mean_psnr_and_flicker():
    d = seq("seascape",
            filtered={"temporal_rms": [0.02, 0.02], "rms_vs_truth": [0.1, 0.1, 0.1]},
            unfiltered={"temporal_rms": [0.08, 0.08], "rms_vs_truth": [0.3, 0.1, 0.2]},
            full={"temporal_rms": [0.02, 0.02], "hardware": True, "mismatches": 0},
            trapezoid={"temporal_rms": [0.01, 0.01], "rms_vs_truth": [0.05, 0.05, 0.05], "variant": True})
    f = fidelity.sequence_figures(d)
    assert set(f["rms"]) == {"unfiltered", "sat", "trapezoid"}      # no hardware stream
    assert f["rms"]["unfiltered"] == pytest.approx(0.2)
    assert f["psnr"]["unfiltered"] == pytest.approx(fidelity.psnr(math.sqrt((0.09 + 0.01 + 0.04) / 3)))
    assert f["flicker"]["sat"] == pytest.approx(0.02)
    g = {goal: (m, ok) for goal, m, ok in fidelity.goals([], [f])}
    m, ok = g["seascape fly-in: flicker >= 4x lower than unfiltered"]
    assert ok and m.startswith("paper 4.00x; best option trapezoid 8.00x (reference model")
    assert "flicker 0.0100 (8.00x)" in fidelity.markdown([], [f])
    m, ok = g["seascape fly-in in hardware: flicker >= 4x lower than unfiltered"]
    assert ok and m == "best seascape sat 4.00x"     # the trapezoid has no hardware unit


def test_hardware_streams_are_columns_and_the_hardware_goal():
    d = seq("seascape_subband_hw",
            filtered={"temporal_rms": [0.02, 0.02], "rms_vs_truth": [0.1, 0.1, 0.1]},
            unfiltered={"temporal_rms": [0.06, 0.06], "rms_vs_truth": [0.3, 0.1, 0.2]},
            reduced_subband={"temporal_rms": [0.03, 0.03], "rms_vs_truth": [0.2, 0.2, 0.2], "hardware": True,
                             "mismatches": 0},
            **{"sat+isotropic": {"temporal_rms": [0.005, 0.005], "rms_vs_truth": [0.05] * 3, "variant": True}})
    f = fidelity.sequence_figures(d)
    assert f["flicker"]["rtl:reduced_subband"] == pytest.approx(0.03)
    assert f["rms"]["rtl:reduced_subband"] == pytest.approx(0.2)
    g = {goal: (m, ok) for goal, m, ok in fidelity.goals([], [f])}
    # On the subband basis +isotropic is the reference's subband weights: not a hardware option.
    m, ok = g["seascape fly-in in hardware: flicker >= 4x lower than unfiltered"]
    assert not ok and m == "best seascape_subband_hw sat 3.00x"
    assert "| sat+isotropic | rtl:reduced_subband |" in fidelity.markdown([], [f])


def test_bad_input_names_the_file(tmp_path):
    d = tmp_path / "x"
    d.mkdir()
    (d / "report.json").write_text(json.dumps({"vs_truth": {"unfiltered": {"rms": 0.1}}, "width": 1, "height": 1}))
    with pytest.raises(fidelity.FidelityError, match="report.json: variants: missing the paper's filter 'sat'"):
        fidelity.load_still(d)
    (d / "report.json").write_text(json.dumps({"width": 1}))
    with pytest.raises(fidelity.FidelityError, match="vs_truth: missing"):
        fidelity.load_still(d)
    (d / "report.json").write_text("{")
    with pytest.raises(fidelity.FidelityError, match=r"report.json:1: "):
        fidelity.load_still(d)
