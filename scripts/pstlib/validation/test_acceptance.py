"""scripts/pstlib/validation/acceptance.py: the rule of acceptance (every scene within 1 dB of the
reference) and its worst case; the search's walk and front use it."""
import math

import pytest

from pstlib.validation import acceptance
from pstlib.explore import search as S
from pstlib.explore import search_report

REF = {"a": 50.0, "b": 60.0, "c": 40.0}


def test_a_scene_1_01_db_worse_fails_and_0_99_passes():
    assert acceptance.TOLERANCE_DB == 1.0
    worse = lambda d: dict(REF, b=REF["b"] - d)      # noqa: E731
    v = acceptance.judge(REF, worse(1.01))
    assert v["passed"] is False and v["failing"] == ["b"] and v["worst_loss"] == pytest.approx(1.01)
    assert acceptance.judge(REF, worse(0.99))["passed"] is True
    assert acceptance.judge(REF, worse(1.0))["passed"] is True          # exactly the tolerance passes
    assert acceptance.judge(REF, REF)["passed"] is True
    # a better scene does not make up for a worse one
    assert acceptance.judge(REF, {"a": 55.0, "b": 58.9, "c": 45.0})["passed"] is False


def test_the_worst_case_is_the_scene_that_loses_most_with_its_features():
    got = {"a": 49.5, "b": 57.0, "c": 36.5}        # losses 0.5, 3.0, 3.5: c loses most; c is also the lowest
    feats = {s: {"stratum": f"st_{s}"} for s in REF}
    v = acceptance.judge(REF, got, features=feats)
    assert v["worst_loss_scene"] == "c" and v["worst_loss"] == pytest.approx(3.5)
    assert v["failing"] == ["c", "b"] and v["worst_loss_features"] == {"stratum": "st_c"}
    assert (v["worst_loss_psnr"], v["worst_loss_ref_psnr"]) == (36.5, 40.0)
    # the worst loss and the worst PSNR can be different scenes
    v = acceptance.judge(REF, {"a": 49.9, "b": 55.0, "c": 39.9}, features=feats)
    assert v["worst_loss_scene"] == "b" and v["worst_psnr_scene"] == "c" and v["worst_psnr"] == 39.9
    assert v["worst_psnr_features"] == {"stratum": "st_c"}
    # ties: the first scene by name
    assert acceptance.judge(REF, REF)["worst_loss_scene"] == "a"


def test_a_scene_missing_from_the_candidate_fails_and_an_empty_reference_judges_nothing():
    v = acceptance.judge(REF, {"a": 50.0, "b": 60.0})
    assert v["passed"] is False and v["worst_loss_scene"] == "c" and math.isinf(v["worst_loss"])
    assert acceptance.judge({}, REF)["passed"] is None
    assert acceptance.scene_loss(REF, {"a": 49.0}, missing=None) == pytest.approx(1.0)
    assert acceptance.scene_loss({}, REF) == 0.0 and acceptance.scene_loss({}, REF, missing=None) is None


def test_one_rule_in_one_place():
    # the search's walk (feasible, merit) and the front's verdict use acceptance's functions
    assert S.scene_loss is acceptance.scene_loss
    assert not hasattr(search_report, "gap_flag") and not hasattr(search_report, "VALIDATION_GAP_DB")
    t = S.Targets(30.0, 1, max_loss=1.0, ref={"a": 50.0})
    ok = {"status": "ok", "train_worst": 49.01, "cpp": 1, "train": {"a": 49.01}}
    assert S.feasible(ok, t) and not S.feasible(dict(ok, train={"a": 48.99}), t)
    start = {"train": {"a": 50.0}, "valid": REF}
    assert search_report.losses({"train": {"a": 50.0}, "valid": dict(REF, c=38.99)}, start)["valid_pass"] is False
    assert search_report.losses({"train": {"a": 50.0}, "valid": dict(REF, c=39.01)}, start)["valid_pass"] is True
