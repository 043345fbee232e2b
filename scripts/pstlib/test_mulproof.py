"""The multiplier proof proves what is equal and refuses what is not (small widths)."""
import shutil

import pytest

from . import mulproof

pytestmark = pytest.mark.skipif(shutil.which("yosys-abc") is None or shutil.which("yosys") is None,
                                reason="needs Yosys and its ABC")
z3 = pytest.importorskip("z3")

W = [mulproof.Width(6, 6, 1, 12), mulproof.Width(7, 5, 0, 12), mulproof.Width(9, 6, 1, 8)]


@pytest.mark.parametrize("w", W, ids=str)
def test_the_forms_are_proven_equal(w, tmp_path):
    r = mulproof.prove(w, tmp_path)
    assert r["proven"], r


def _mutant(tmp_path, src, old, new):
    text = src.read_text()
    assert old in text
    path = tmp_path / src.name
    path.write_text(text.replace(old, new, 1))
    return path


def test_a_wrong_booth_digit_is_refused(tmp_path):
    # |d| = 2 decoded from 011 only: the synthesis form no longer multiplies
    booth = _mutant(tmp_path, mulproof.BOOTH, "(sel == 3'b011) || (sel == 3'b100)", "(sel == 3'b011)")
    ok, verdict = mulproof.q1(W[0], tmp_path, booth=booth)
    assert not ok and "NOT EQUIVALENT" in verdict.upper()


def test_a_wrong_digit_weight_is_refused(tmp_path):
    # the digit form's b_{2i+1} weighing -1 instead of -2: Q2 (and Q1) fail
    digits = _mutant(tmp_path, mulproof.DIGITS, "as * PW'(bx[2*i+2]) * PW'(2)", "as * PW'(bx[2*i+2])")
    r = mulproof.q023(W[0], tmp_path, digits=digits)
    assert not r["Q2"]
    assert not mulproof.q1(W[0], tmp_path, digits=digits)[0]


def test_a_wrong_simulation_form_is_refused(tmp_path):
    # b zero-extended although it is signed
    booth = _mutant(tmp_path, mulproof.BOOTH, "assign bxw = XB'($signed(b_i));", "assign bxw = XB'(b_i);")
    assert not mulproof.q023(W[0], tmp_path, booth=booth)["Q0"]
