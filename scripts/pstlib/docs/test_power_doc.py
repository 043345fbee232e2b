"""pstlib.docs.power_doc: docs/POWER.md's table from docs/data/power.json, and --record's merge."""
import json

import pytest

from pstlib.docs import power_doc


def summary(pj):
    return {"workloads": 2, "pj_per_pixel": pj, "pj_per_pixel_min": pj - 1, "pj_per_pixel_max": pj + 1,
            "fmax_mhz": 100.0, "mw_at_fmax": 50.0, "mw_at_realtime": 120.0, "realtime_copies": 2,
            "leakage_mw": 0.001, "sequential_share": 0.5, "memory_model_share": 0.25,
            "blocks_mw_at_sdc_clock": {"a": 3.0, "b": 2.0, "c": 1.0, "d": 0.5}}


def doc(name, pj):
    return {"profile": name, "summary": summary(pj), "window": {"start": 1, "cycles": 2, "size": 3, "random_seed": 4},
            "activity_source": "trace", "basis": "pre-layout", "seconds": 1.0,
            "workloads": {"marble": {"pj_per_pixel": pj}, "random/valid_000": {"pj_per_pixel": pj + 2}}}


def test_record_merges_profiles_and_the_table_reads_them(tmp_path):
    power_doc.record(tmp_path, doc("reduced", 100.0))
    power_doc.record(tmp_path, doc("full", 200.0))
    power_doc.record(tmp_path, doc("reduced", 110.0))         # a profile measured again replaces its entry
    d = json.loads((tmp_path / power_doc.SOURCE).read_text())
    assert list(d["profiles"]) == ["full", "reduced"]
    assert d["profiles"]["reduced"]["workloads"] == {"marble": 110.0, "random/valid_000": 112.0}
    md = power_doc.markdown(tmp_path)
    assert "| reduced | 2 (3) | 110 | 109 - 111 | 100.0 | 50.0 | 120.0 (2) | 0.001 | 50 % | 25 % | no | a 3.0, b 2.0, c 1.0 |" in md
    assert "| full | 200 | 202 |" in md
    # a record measured with the RAMs' read-port model says so
    d2 = doc("reduced", 110.0)
    d2["summary"]["rams_modelled"] = "m.clut_q (256 x 32, 3 read ports)"
    power_doc.record(tmp_path, d2)
    assert "| 25 % | yes | a 3.0" in power_doc.markdown(tmp_path)


def test_a_missing_record_is_an_error(tmp_path):
    with pytest.raises(ValueError, match="power.json: missing"):
        power_doc.markdown(tmp_path)
