"""Minimum-area islands in qrouter's routed DEF, repaired from magic's DRC boxes
(pstlib/pnr/islands.py): the DEF excerpts are the three kinds the routed blocks of reduced had."""
from pstlib.pnr import islands

# A cell 3.2 x 10 um with pin B (metal1) at x 1.0-1.4, y 3.9-4.7, as OSU018's OAI21X1.
LEF = """VIA M2_M1 DEFAULT
  LAYER metal1 ;
    RECT -0.200 -0.200 0.200 0.200 ;
  LAYER via1 ;
    RECT -0.100 -0.100 0.100 0.100 ;
  LAYER metal2 ;
    RECT -0.200 -0.200 0.200 0.200 ;
END M2_M1

VIA M3_M2 DEFAULT
  LAYER metal2 ;
    RECT -0.200 -0.200 0.200 0.200 ;
  LAYER via2 ;
    RECT -0.100 -0.100 0.100 0.100 ;
  LAYER metal3 ;
    RECT -0.200 -0.200 0.200 0.200 ;
END M3_M2

MACRO OAI21X1
  CLASS CORE ;
  SIZE 3.200 BY 10.000 ;
  PIN B
    DIRECTION INPUT ;
    PORT
      LAYER metal1 ;
        RECT 1.000 3.900 1.400 4.700 ;
    END
  END B
END OAI21X1
"""

# Cell OAI21X1_1 flipped (FS) at (100.00, 10.00) um: pin B spans x 101.00-101.40, y 15.30-16.10.
DEF = """VERSION 5.6 ;
UNITS DISTANCE MICRONS 100 ;
COMPONENTS 1 ;
- OAI21X1_1 OAI21X1 + PLACED ( 10000 1000 ) FS ;
END COMPONENTS
NETS 3 ;
- n1
  ( OAI21X1_1 B ) 
+ ROUTED metal3 ( 10200 1000 ) ( * 1560 ) M3_M2 
  NEW metal2 ( 10120 1560 ) ( 10040 * ) M2_M1 
  NEW metal2 ( 10040 1560 ) ( * 1000 ) M3_M2 ;
- n2
  ( PIN n2 ) 
+ ROUTED metal2 ( 480 -2999 ) ( 320 * ) M3_M2 
  NEW metal2 ( -79 -2999 ) M3_M2 
  NEW metal3 ( -79 -2999 ) ( 320 * ) ;
- n3
  ( PIN n3 ) 
+ ROUTED metal1 ( 5000 5000 ) M2_M1 
  NEW metal2 ( 5000 5000 ) M3_M2 
  NEW metal2 ( 5000 5000 ) ( * 6000 ) ;
END NETS
END DESIGN
"""


def test_parse_magic_listing():
    text = ("Loading...\nWHY: Metal2 area < 20 (Mosis #+++)\n  BOX -10 -302 -6 -298\n"
            "WHY: Metal1 spacing < 3\n  BOX 0 0 4 4\nWHY: Metal1 area < 20 (Mosis #+++)\n"
            "  BOX 1702 1858 1706 1862\nSCALE 0.1\n")
    assert islands.parse_magic_islands(text) == [("metal2", -8.0, -300.0), ("metal1", 1704.0, 1860.0)]


def test_via_off_its_pin_moves_onto_the_pin():
    # n1's stub runs on metal2 from 10120 (over pin B) to 10040, its via down to metal1 at 10040.
    text, counts = islands.repair(DEF, [("metal1", 10040, 1560)], LEF)
    assert counts == {"moved": 1, "removed": 0, "left": 0}
    assert "NEW metal2 ( 10040 1560 ) ( 10120 1560 ) M2_M1" in text
    assert "( 10120 1560 ) ( 10040 * ) M2_M1" not in text


def test_dangling_via_is_removed():
    text, counts = islands.repair(DEF, [("metal2", -80, -3000)], LEF)
    assert counts == {"moved": 0, "removed": 1, "left": 0}
    assert "( -79 -2999 ) M3_M2" not in text
    assert "NEW metal3 ( -79 -2999 ) ( 320 * ) ;" in text and "\n\n" not in text


def test_island_under_a_stacked_via_is_left():
    # n3: M2_M1 and M3_M2 both have a metal2 pad at (5000, 5000): moving or removing either
    # could open the net.
    text, counts = islands.repair(DEF, [("metal2", 5000, 5000)], LEF)
    assert counts == {"moved": 0, "removed": 0, "left": 1} and text == DEF


def test_no_via_at_the_box_is_left():
    text, counts = islands.repair(DEF, [("metal1", 0, 0)], LEF)
    assert counts["left"] == 1 and text == DEF
