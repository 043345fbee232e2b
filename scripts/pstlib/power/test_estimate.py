"""pstlib.power.estimate: the design search's energy model from the measured records."""
import json

import pytest

from pstlib.explore import search_report
from pstlib.power import estimate


def _root(tmp_path, profiles):
    """A tree with a power record and synthesis records: name -> (pJ/pixel, clocks/pixel, logic GE)."""
    (tmp_path / "docs/data").mkdir(parents=True)
    (tmp_path / "scripts/synth/records").mkdir(parents=True)
    power = {"profiles": {n: {"summary": {"pj_per_pixel": pj, "clocks_per_pixel": c}} for n, (pj, c, _) in profiles.items()}}
    (tmp_path / "docs/data/power.json").write_text(json.dumps(power))
    for n, (_, c, ge) in profiles.items():
        (tmp_path / f"scripts/synth/records/{n}.json").write_text(json.dumps({"logic_ge": ge, "clocks_per_pixel": c}))
    return tmp_path


def test_density_and_scaling(tmp_path):
    refs = estimate.references(_root(tmp_path, {"a": (1000.0, 4, 50), "b": (300.0, 1, 100)}))
    a = refs["a"]
    assert a.density == pytest.approx(1000.0 / (50 * 4))
    # the reference's own area and clocks give its measurement back; the model is linear in both
    assert estimate.estimate_pj(50, 4, a) == pytest.approx(1000.0)
    assert estimate.estimate_pj(100, 4, a) == pytest.approx(2000.0)
    assert estimate.estimate_pj(50, 2, a) == pytest.approx(500.0)
    assert estimate.figure_of_merit(100, 2, 3000.0) == pytest.approx(100 * 2 * 3.0)


def test_nearest(tmp_path):
    refs = estimate.references(_root(tmp_path, {"one": (1.0, 1, 10), "one_big": (1.0, 1, 20), "three": (1.0, 3, 10),
                                                "many": (1.0, 32, 10)}))
    assert estimate.nearest(refs, 3).profile == "three"
    assert estimate.nearest(refs, 1).profile == "one_big"             # tie on clocks: the larger area
    assert estimate.nearest(refs, 1, prefer="one").profile == "one"   # the class's start, same clocks
    assert estimate.nearest(refs, 2, prefer="one").profile == "three"    # start of other clocks: not taken; log-nearest
    assert estimate.nearest(refs, 16).profile == "many"
    assert estimate.nearest(refs, 3, exclude="three").profile in ("one_big", "many")
    assert estimate.nearest({}, 3) is None


def test_leave_one_out_and_markdown(tmp_path):
    root = _root(tmp_path, {"a": (1000.0, 2, 100), "b": (1500.0, 2, 100)})
    rows = {r["profile"]: r for r in estimate.leave_one_out(estimate.references(root))}
    assert rows["a"]["reference"] == "b"
    assert rows["a"]["error"] == pytest.approx(0.5)
    assert rows["b"]["error"] == pytest.approx(1000 / 1500 - 1)
    md = estimate.markdown(root)
    assert "| a | 2 | 100 |" in md and "+50.0 %" in md


def test_markdown_without_records(tmp_path):
    with pytest.raises(ValueError, match="no profile"):
        estimate.markdown(tmp_path)


def test_search_rows_get_energy(tmp_path):
    refs = estimate.references(_root(tmp_path, {"s1": (100.0, 1, 10), "s32": (3200.0, 32, 10)}))
    rows = [{"name": "p", "cpp": 1, "logic_ge": 20}, {"name": "q", "cpp": 24, "logic_ge": 5},
            {"name": "r", "cpp": 1, "logic_ge": None}]
    search_report.add_energy(rows, {1: "s1", 32: "s32"}, refs)
    assert rows[0]["energy_pj"] == pytest.approx(200.0) and rows[0]["energy_ref"] == "s1"
    assert rows[0]["ace"] == round(20 * 1 * 0.2)
    assert rows[1]["energy_ref"] == "s32" and rows[1]["energy_pj"] == pytest.approx(10.0 * 5 * 24)
    assert "energy_pj" not in rows[2]
