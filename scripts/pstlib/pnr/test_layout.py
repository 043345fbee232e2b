"""Tests of the routed-block figures (pstlib/pnr/layout.py) on a hand-made two-cell DEF."""
import pytest

from pstlib.pnr import layout

LEF = """MACRO NAND2X1
  CLASS CORE ;
  SIZE 2.400 BY 10.000 ;
END NAND2X1
MACRO DFFPOSX1
  SIZE 19.200 BY 10.000 ;
END DFFPOSX1
MACRO FILL
  SIZE 0.800 BY 10.000 ;
END FILL
"""
DEF = """VERSION 5.6 ;
UNITS DISTANCE MICRONS 100 ;
DIEAREA ( 0 0 ) ( 10000 2000 ) ;
COMPONENTS 3 ;
- NAND2X1_1 NAND2X1 + PLACED ( 0 0 ) N ;
- DFFPOSX1_1 DFFPOSX1 + PLACED ( 300 0 ) N ;
- FILL_0_1 FILL + PLACED ( 2300 0 ) N ;
END COMPONENTS
NETS 1 ;
- n1
  ( NAND2X1_1 Y ) ( DFFPOSX1_1 D )
+ ROUTED metal1 ( 100 500 ) M2_M1
  NEW metal2 ( 100 500 ) ( * 1500 ) M2_M1
  NEW metal3 ( 100 1500 ) ( 2100 * ) ;
END NETS
END DESIGN
"""


def test_def_figures():
    f = layout.def_figures(DEF, layout.lef_sizes(LEF))
    assert f["die_um"] == [100.0, 20.0] and f["die_mm2"] == pytest.approx(0.002)
    assert f["cells"] == 2 and f["flip_flops"] == 1            # the filler is no cell
    assert f["cell_area_mm2"] == pytest.approx((24 + 192) / 1e6, abs=1e-4)
    assert f["utilization"] == pytest.approx(216 / 2000, abs=1e-3)
    assert f["wirelength_mm"] == pytest.approx(0.0, abs=0.05)   # 10 + 20 um = 0.03 mm


def test_wirelength_counts_every_segment():
    long = DEF.replace("( 2100 * )", "( 100100 * )")
    assert layout.def_figures(long, layout.lef_sizes(LEF))["wirelength_mm"] == pytest.approx(1.0, abs=0.05)


def test_unknown_cell_is_refused():
    with pytest.raises(ValueError, match="XOR9"):
        layout.def_figures(DEF.replace("DFFPOSX1_1 DFFPOSX1", "DFFPOSX1_1 XOR9"), layout.lef_sizes(LEF))


def test_small_pins_drawn_taller():
    from pstlib.pnr import qflow
    d = ("UNITS DISTANCE MICRONS 100 ;\nPINS 3 ;\n- a + NET a\n  + LAYER metal2 ( -15 -15 ) ( 15 15 )\n"
         "- b + NET b\n  + LAYER metal3 ( -15 -15 ) ( 15 15 )\n- vdd + NET vdd\n  + LAYER metal6 ( -80 -40 ) ( 80 40 )\n")
    out, n = qflow.widen_pins(d)
    assert n == 2
    assert "+ LAYER metal2 ( -15 -35 ) ( 15 35 )" in out      # 0.3 x 0.7 um = 0.21 um^2
    assert "+ LAYER metal3 ( -15 -35 ) ( 15 35 )" in out
    assert "+ LAYER metal6 ( -80 -40 ) ( 80 40 )" in out      # 1.28 um^2: left alone
    assert qflow.widen_pins(out)[1] == 0
