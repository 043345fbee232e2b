"""Tests of pstlib.docs.multipass_doc (docs/MULTIPASS.md's generated tables from docs/data/multipass.json)."""
import json

import pytest

from pstlib.docs import multipass_doc
from pstlib.paths import ROOT


def test_the_checked_in_record_renders_every_row():
    d = multipass_doc.load(ROOT)
    q = multipass_doc.quality_markdown(ROOT)
    p = multipass_doc.proposals_markdown(ROOT)
    # one table row per quality entry, three tables' worth (the references skip rc, the lattice sgi_scurve)
    assert q.count("| register combiners (5) |") == 2 * sum(e["variant"] == "rc" for e in d["quality"])
    assert all(f"| {r['name']} | {r['target']} | {r['size']} |" in p for r in d["proposals"]["rows"])
    # the GL output equals the CPU model in every RGBA8 row of the record
    assert all(e["gl_pixels_differing_from_cpu_model"] == 0 for e in d["quality"])


def test_missing_record_and_missing_proposals(tmp_path):
    with pytest.raises(ValueError, match=r"multipass.json: missing"):
        multipass_doc.load(tmp_path)
    (tmp_path / "docs" / "data").mkdir(parents=True)
    (tmp_path / multipass_doc.SOURCE).write_text(json.dumps({"renderer": "r", "gl_version": "v", "quality": []}))
    assert multipass_doc.proposals_markdown(tmp_path).startswith("Not measured yet")
    (tmp_path / multipass_doc.SOURCE).write_text(json.dumps({"renderer": "r"}))
    with pytest.raises(ValueError, match=r"\.quality: missing"):
        multipass_doc.quality_markdown(tmp_path)
