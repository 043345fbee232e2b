"""pstlib.pstjson: the runs of a `pst regress -o` file of either schema, the provenance keys."""
from pstlib import pstjson as provenance
from pstlib.synth import report


def test_regress_runs_reads_both_schemas():
    runs = [{"scene": "a.toml", "profile": "full", "cycles_per_pixel": 1.5}]
    assert provenance.regress_runs(runs) == runs                                   # schema 1: the list
    doc = {"schema": 2, "commit": "abc", "tool_versions": {}, "command_line": ["pst"], "runs": runs}
    assert provenance.regress_runs(doc) == runs
    assert provenance.of(doc) == {"schema": 2, "commit": "abc", "tool_versions": {}, "command_line": ["pst"]}
    assert provenance.of(runs) == {}


def test_synth_report_reads_schema_2(tmp_path):
    import json
    p = tmp_path / "regress.json"
    p.write_text(json.dumps({"schema": 2, "runs": [{"profile": "full", "cycles_per_pixel": 1.5},
                                                   {"profile": "full", "cycles_per_pixel": 2.0}]}))
    assert report.regress_cpp(p, "full") == 2.0
