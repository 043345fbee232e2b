"""Tests of pstlib.figures.flicker's pure functions (run by ctest through pytest)."""
import json
import math

import pytest

from pstlib.figures import flicker


def doc(**streams):
    return {"scene": "scenes/sea.toml", "frames": 3, "width": 16, "height": 8, "truth_samples": 4,
            "streams": streams}


def test_sequence_flicker_is_the_rms_over_frames():
    assert flicker.sequence_flicker([3.0, 4.0]) == pytest.approx(math.sqrt(12.5))
    assert flicker.sequence_flicker([]) == 0.0


def test_row_and_table_give_the_ratio_and_mismatches():
    d = doc(filtered={"temporal_rms": [0.01, 0.01]}, unfiltered={"temporal_rms": [0.04, 0.04]},
            full={"temporal_rms": [0.02, 0.02], "hardware": True, "mismatches": 0})
    r = flicker.row(d)
    assert r["ratio"] == pytest.approx(4.0)
    assert r["flicker"]["full"] == pytest.approx(0.02)
    assert r["mismatches"] == {"full": 0}
    t = flicker.markdown_table([d])
    assert "| sea | 3 | 16x8 | 0.0100 | 0.0400 | 4.00x | 0.0200 (0) |" in t
    assert "full (mismatches)" in t.splitlines()[0]


def test_variant_streams_are_not_hardware():
    d = doc(filtered={"temporal_rms": [0.01]}, unfiltered={"temporal_rms": [0.04]},
            full={"temporal_rms": [0.02], "hardware": True, "mismatches": 3},
            trapezoid={"temporal_rms": [0.005], "hardware": False, "variant": True})
    assert flicker.hardware_streams(d) == ["full"]
    assert flicker.variant_streams(d) == ["trapezoid"]
    t = flicker.markdown_table([d])
    assert t.splitlines()[0].endswith("| full (mismatches) | trapezoid |")
    assert "| 0.0200 (3) | 0.0050 |" in t


def test_validate_names_the_problem(tmp_path):
    with pytest.raises(flicker.FlickerError, match="x.json: streams: expected filtered and unfiltered"):
        flicker.validate(doc(filtered={"temporal_rms": []}), "x.json")
    with pytest.raises(flicker.FlickerError, match="streams.unfiltered.temporal_rms: missing"):
        flicker.validate(doc(filtered={"temporal_rms": []}, unfiltered={}), "x.json")
    with pytest.raises(flicker.FlickerError, match="frames: missing"):
        flicker.validate({"scene": "s"}, "x.json")
    bad = tmp_path / "flicker.json"
    bad.write_text("{")
    with pytest.raises(flicker.FlickerError, match=r"flicker.json:1: "):
        flicker.load(tmp_path)
    with pytest.raises(flicker.FlickerError, match="No such file"):
        flicker.load(tmp_path / "none.json")


def test_plot_writes_a_png(tmp_path):
    d = doc(filtered={"temporal_rms": [0.01, 0.02], "rms_vs_truth": [0.1, 0.1, 0.1]},
            unfiltered={"temporal_rms": [0.04, 0.03], "rms_vs_truth": [0.2, 0.2, 0.2]})
    out = tmp_path / "f.png"
    flicker.plot(d, out)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    json.dumps(d)  # the document stays plain JSON
