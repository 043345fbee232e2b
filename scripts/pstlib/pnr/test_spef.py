"""Tests of the qrouter .rc -> SPEF rewrite (pstlib/pnr/spef.py), on lines qrouter 1.4.71 wrote
for the reduced profile's colour-table block."""
import pytest

from pstlib.pnr import spef

# A register output into three loads, and a block input pin into four (copied from
# blk_colour.rc).
REG = ("u_colour.u_clut.g_ch[0].sn[15] 1 DFFPOSX1_40/Q 3 ( 0.266667 6.57e-05 ( 19.68 0.00459282 "
       "( 3.52 0.00077988 XNOR2X1_29/B ) , ( 4.53333 0.0011169 NAND2X1_2/B ) ) , "
       "( 5.01333 0.0011166 INVX1_509/A ) ) ")
PIN = ("u_colour.u_clut.f_i[5] 1 PIN/u_colour.u_clut.f_i[5] 4 ( 7.09333 0.0017289 ( 0.64 0.00021936 "
       "OAI21X1_606/A ) , ( 2.4 0.0005601 ( 2.66667 0.000657 NAND2X1_866/A ) , ( 8.8 0.0020345 "
       "NOR2X1_503/B , ( 1.17333 0.00040216 INVX2_80/A ) ) ) ) ")
NETLIST = """module blk (clk_i, u_colour_u_clut_f_i);
input clk_i;
input [7:0] u_colour_u_clut_f_i;
DFFPOSX1 DFFPOSX1_40 ( .CLK(clk_i), .D(n1), .Q(u_colour_u_clut_g_ch_0__sn[15]) );
XNOR2X1 XNOR2X1_29 ( .A(n2), .B(u_colour_u_clut_g_ch_0__sn[15]), .Y(n3) );
NAND2X1 NAND2X1_2 ( .A(n2), .B(u_colour_u_clut_g_ch_0__sn[15]), .Y(n4) );
INVX1 INVX1_509 ( .A(u_colour_u_clut_g_ch_0__sn[15]), .Y(n5) );
OAI21X1 OAI21X1_606 ( .A(u_colour_u_clut_f_i[5]), .B(n2), .C(n3), .Y(n6) );
endmodule
"""


def total_c(tree) -> float:
    r, c, node, kids = tree
    return c + sum(total_c(k) for k in kids)


def test_parse_tree():
    rec = spef.parse_rc_line(REG)
    assert rec["net"] == "u_colour.u_clut.g_ch[0].sn[15]" and rec["driver"] == "DFFPOSX1_40/Q"
    r, c, node, kids = rec["tree"]
    assert (r, c, node) == (0.266667, 6.57e-05, None) and len(kids) == 2
    assert kids[1][2] == "INVX1_509/A"
    # A branch ending at a pin and continuing (NOR2X1_503/B then INVX2_80/A).
    t = spef.parse_rc_line(PIN)["tree"]
    assert t[3][1][3][1][2] == "NOR2X1_503/B" and t[3][1][3][1][3][0][2] == "INVX2_80/A"


def test_bad_record_is_refused():
    with pytest.raises(ValueError):
        spef.parse_rc_line("net 2 X/Y 1 ( 1 2 )")


def test_spef_names_the_netlist_net_and_keeps_the_capacitance():
    pins = spef.netlist_pins(NETLIST)
    assert pins[("INVX1_509", "A")] == "u_colour_u_clut_g_ch_0__sn[15]"
    dirs = spef.port_directions(NETLIST)
    assert dirs == {"clk_i": "I", "u_colour_u_clut_f_i": "I"}
    text, unmatched = spef.to_spef(REG + "\n" + PIN + "\n", pins, "blk", dirs, cap_factor=2.0)
    assert unmatched == []
    nets = [l for l in text.splitlines() if l.startswith("*D_NET")]
    assert nets[0].split()[1] == "u_colour_u_clut_g_ch_0__sn[15]"
    assert float(nets[0].split()[2]) == pytest.approx(2.0 * total_c(spef.parse_rc_line(REG)["tree"]))
    # The block pin's net is the port itself, an input.
    assert nets[1].split()[1] == "u_colour_u_clut_f_i[5]"
    assert "*P u_colour_u_clut_f_i[5] I" in text
    assert "*I DFFPOSX1_40:Q O" in text and "*I INVX1_509:A I" in text


def test_unknown_net_is_reported():
    _, unmatched = spef.to_spef(REG, {}, "blk", {})
    assert unmatched == ["u_colour.u_clut.g_ch[0].sn[15]"]


def test_dangling_stub_is_an_internal_node():
    # qrouter 1.4.71 writes ERROR where a routed branch ends at no pin (blk_top.rc, 4 nets).
    line = "n1 1 INVX1_1/Y 1 ( 1.0 0.001 ( 2.0 0.002 ERROR ) , ( 3.0 0.003 NAND2X1_2/A ) ) "
    t = spef.parse_rc_line(line)["tree"]
    assert t[3][0][2] is None and t[3][1][2] == "NAND2X1_2/A"
    pins = {("INVX1_1", "Y"): "n1", ("NAND2X1_2", "A"): "n1"}
    text, unmatched = spef.to_spef(line, pins, "blk", {})
    assert unmatched == [] and "*D_NET n1 0.006" in text
