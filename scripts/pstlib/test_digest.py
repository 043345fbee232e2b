"""Input digests name what changed, and a proof record stands only for the tree it was made from."""
import copy

import pytest

from . import digest, mulproof


def _tree(tmp_path):
    (tmp_path / "rtl").mkdir()
    (tmp_path / "rtl" / "a.sv").write_text("module a; endmodule\n")
    (tmp_path / "rtl" / "b.sv").write_text("module b; endmodule\n")
    return tmp_path


def test_unchanged_tree_is_not_stale(tmp_path):
    root = _tree(tmp_path)
    rec = digest.inputs(["rtl/*.sv"], root)
    assert set(rec) == {"rtl/a.sv", "rtl/b.sv"}
    assert digest.stale(rec, digest.inputs(["rtl/*.sv"], root), {"yosys": "1"}, {"yosys": "1"}) == []


def test_a_one_byte_change_an_added_and_a_removed_file_are_named(tmp_path):
    root = _tree(tmp_path)
    rec = digest.inputs(["rtl/*.sv"], root)
    (root / "rtl" / "a.sv").write_text("module a;  endmodule\n")
    (root / "rtl" / "b.sv").unlink()
    (root / "rtl" / "c.sv").write_text("")
    assert digest.stale(rec, digest.inputs(["rtl/*.sv"], root)) == [
        "rtl/a.sv changed", "rtl/b.sv removed", "rtl/c.sv added"]


def test_a_toml_comment_is_not_a_change_but_a_value_is(tmp_path):
    (tmp_path / "p.toml").write_text("a = 1  # one\n")
    rec = digest.inputs(["*.toml"], tmp_path)
    (tmp_path / "p.toml").write_text("# a profile\na = 1\n")
    assert digest.stale(rec, digest.inputs(["*.toml"], tmp_path)) == []
    (tmp_path / "p.toml").write_text("a = 2\n")
    assert digest.stale(rec, digest.inputs(["*.toml"], tmp_path)) == ["p.toml changed"]


def test_a_tool_version_change_is_named():
    assert digest.stale({}, {}, {"z3": "4.8"}, {"z3": "4.9"}) == ["tool z3: 4.8 -> 4.9"]


def test_the_committed_proof_record_stands_for_this_tree():
    # The default suite's mul_proof takes its widths from this record: it must be current
    # (scripts/mul_proof.py --record after a change to the multiplier, the RTL or a profile).
    pytest.importorskip("z3")
    rec = mulproof.read_record()
    assert rec is not None, "sim/formal/mul_proof.record.json missing: scripts/mul_proof.py --record"
    elab, proof = mulproof.record_status(rec)
    assert proof == [], proof
    assert rec["widths"], "a record with no width proves nothing"


def test_a_changed_booth_form_voids_the_record():
    pytest.importorskip("z3")
    rec = copy.deepcopy(mulproof.read_record())
    rec["proof_inputs"]["rtl/common/pst_mul_booth.sv"] = "0" * 64
    rec["elaboration_inputs"]["rtl/common/pst_mul_booth.sv"] = "0" * 64
    elab, proof = mulproof.record_status(rec)
    assert "rtl/common/pst_mul_booth.sv changed" in proof
    assert "rtl/common/pst_mul_booth.sv changed" in elab
