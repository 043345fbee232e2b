"""activity.read_vcd on hand-written VCDs: rates per clock, duty, vector bits, ranges, errors."""
import pytest

from pstlib.power import activity

VCD = """$timescale 1ps $end
$scope module TOP $end
$scope module pst_top $end
$var wire 1 ! clk_i $end
$var wire 4 " d_i [3:0] $end
$scope module u_a $end
$var wire 4 " d_i [3:0] $end
$var logic 2 # q [2:1] $end
$var parameter 32 $ Width [31:0] $end
$upscope $end
$upscope $end
$upscope $end
$enddefinitions $end
#0
$dumpvars
0!
b0000 "
b00 #
$end
#1
1!
b0001 "
#2
0!
#3
1!
b0011 "
b10 #
#4
0!
#5
1!
b0000 "
#6
0!
#7
1!
b01 #
#8
0!
"""


@pytest.fixture
def vcd(tmp_path):
    p = tmp_path / "t.vcd"
    p.write_text(VCD)
    return p


def test_rates_per_clock_and_duty(vcd):
    a = activity.read_vcd(vcd)
    assert a.cycles == 4 and a.window == 8
    # d_i bit 0: 0 -> 1 at 1, 1 -> 0 at 5: two transitions in four clocks, high from 1 to 5
    assert a.bit("d_i", 0) == pytest.approx((0.5, 0.5))
    # bit 1: 0 -> 1 at 3, -> 0 at 5
    assert a.bit("d_i", 1) == pytest.approx((0.5, 0.25))
    assert a.bit("d_i", 3) == (0.0, 0.0)
    # aliases (the same id code in a sub-module) share the rates
    assert a.rates["u_a/d_i"] == a.rates["d_i"]
    assert a.changes["d_i"] == 3


def test_declared_range_numbers_the_bits(vcd):
    a = activity.read_vcd(vcd)
    assert a.lsb["u_a/q"] == 1
    # q[2] (value bit 1): 0 -> 1 at 3, -> 0 at 7; q[1]: 0 -> 1 at 7
    assert a.bit("u_a/q", 2) == pytest.approx((0.5, 0.5))
    assert a.bit("u_a/q", 1) == pytest.approx((0.25, 1 / 8))
    assert a.bit("u_a/q", 0) is None
    assert "u_a/Width" not in a.rates          # parameters are not signals


def test_clock_itself(vcd):
    a = activity.read_vcd(vcd)
    assert a.bit("clk_i", 0)[0] == pytest.approx(2.0)


def test_no_clock_is_refused(tmp_path):
    p = tmp_path / "t.vcd"
    p.write_text(VCD.replace("clk_i", "clock"))
    with pytest.raises(activity.VcdError, match="no clock 'clk_i'"):
        activity.read_vcd(p)


def test_no_time_is_refused(tmp_path):
    p = tmp_path / "t.vcd"
    p.write_text(VCD.split("#1")[0])
    with pytest.raises(activity.VcdError, match="no time passes"):
        activity.read_vcd(p)
