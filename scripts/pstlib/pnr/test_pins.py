"""Tests of the pin hints (pstlib/pnr/pins.py) on a hand-made placed DEF."""
import pytest

from pstlib.pnr import pins

# A 100 x 40 µm die (DEF units of 0.01 µm); cell a sits by the left edge, b by the top right,
# c in the middle of the bottom; the pins were placed far from them.
DEF = """VERSION 5.6 ;
UNITS DISTANCE MICRONS 100 ;
DIEAREA ( 0 0 ) ( 10000 4000 ) ;
TRACKS X 40 DO 125 STEP 80 LAYER metal2 ;
TRACKS Y 50 DO 40 STEP 100 LAYER metal3 ;
COMPONENTS 3 ;
- a DFFPOSX1 + PLACED ( 200 2000 ) N ;
- b DFFPOSX1 + PLACED ( 9000 3800 ) N ;
- c NAND2X1 + PLACED ( 5000 100 ) N ;
END COMPONENTS
PINS 4 ;
- qa + NET qa + DIRECTION OUTPUT + LAYER metal2 ( -15 -15 ) ( 15 15 ) + PLACED ( 9900 100 ) N ;
- qb + NET qb + DIRECTION OUTPUT + LAYER metal2 ( -15 -15 ) ( 15 15 ) + PLACED ( 100 100 ) N ;
- qc + NET qc + DIRECTION OUTPUT + LAYER metal2 ( -15 -15 ) ( 15 15 ) + PLACED ( 5000 3900 ) N ;
- d + NET d + DIRECTION INPUT + LAYER metal2 ( -15 -15 ) ( 15 15 ) + PLACED ( 5000 3900 ) N ;
END PINS
NETS 4 ;
- qa
  ( PIN qa ) ( a Q ) ;
- qb
  ( PIN qb ) ( b Q ) ;
- qc
  ( PIN qc ) ( c Y ) ;
- d
  ( PIN d ) ( a D ) ( b D ) ;
END NETS
END DESIGN
"""


def test_parse_def():
    die, pos, cells = pins.parse_def(DEF)
    assert die == pins.Die(0, 0, 10000, 4000)
    assert pos["b"] == (9000, 3800)
    assert cells == {"qa": ["a"], "qb": ["b"], "qc": ["c"], "d": ["a", "b"]}


def test_hints_nearest_side_and_position():
    die, pos, cells = pins.parse_def(DEF)
    h = pins.hints(die, pos, cells, 100)
    assert h["qa"] == ("L", pytest.approx(0.5))
    assert h["qb"] == ("T", pytest.approx(0.9))
    assert h["qc"] == ("B", pytest.approx(0.5))
    assert h["d"][0] == "T"                       # centroid (46, 29) µm: 11 µm from the top


def test_overfull_side_gives_pins_away():
    # A 10 µm tall die: the L and R sides hold 2 pins each (ten 1 µm tracks less five kept
    # clear at the corners, two tracks apart); five pins by the left.
    die = pins.Die(0, 0, 10000, 1000)
    assert pins.side_capacity(die, 100, 5)["L"] == 2
    pos = {f"c{i}": (10, 500) for i in range(5)}
    cells = {f"p{i}": [f"c{i}"] for i in range(5)}
    h = pins.hints(die, pos, cells, 100)
    sides = sorted(s for s, _ in h.values())
    assert sides.count("L") == 2 and len(h) == 5   # the other three on B or T


def test_spread_keeps_order_and_slots():
    assert pins.spread([0.0, 0.0, 0.0], 10) == [0, 1, 2]
    assert pins.spread([1.0, 1.0, 1.0], 10) == [7, 8, 9]
    assert pins.spread([0.1, 0.5, 0.9], 10) == [1, 5, 9]
    with pytest.raises(ValueError):
        pins.spread([0.5] * 4, 3)


def test_cel2_groups():
    die, pos, cells = pins.parse_def(DEF)
    text = pins.cel2(die, pins.hints(die, pos, cells, 100), 100)
    groups = text.strip().split("\n\n")
    assert len(groups) == 4                          # L, B, and T twice (d and qb a span apart)
    left = next(g for g in groups if "restrict side L" in g)
    assert left.splitlines() == ["padgroup pg_L0 permute", "twpin_qa nonfixed", "restrict side L",
                                 "sidespace 0.0000 1.0000"]
    bottom = next(g for g in groups if "restrict side B" in g)
    assert "twpin_qc nonfixed" in bottom and "sidespace 0.5000 1.0000" in bottom   # 100 µm: 2 spans


def test_pin_distance():
    # qa 97 + 19 = 116 µm from a, qb 89 + 37 = 126 from b, qc 38 from c, d 40 + 1 = 41 from b:
    # the median of four is the third.
    assert pins.pin_distance_um(DEF) == pytest.approx(116.0)


def test_snap_moves_pins_by_their_cells():
    new, summary = pins.snap(DEF)
    placed = {m.group(1): (m.group(4), int(m.group(6)), int(m.group(7))) for m in pins.PIN_ENTRY.finditer(new)}
    assert set(placed) == {"qa", "qb", "qc", "d"}
    layer, x, y = placed["qa"]                   # left side, level with cell a (y 20 µm), metal3 track
    assert layer == "metal3" and x in (0, 100) and abs(y - 2000) <= 100 and (y - 50) % 100 == 0
    layer, x, y = placed["qc"]                   # bottom, under cell c (x 50 µm), metal2 track
    assert layer == "metal2" and abs(x - 5000) <= 80 and (x - 40) % 80 == 0
    assert placed["qb"][1:] != placed["d"][1:]   # two pins on the top side, apart
    assert summary["moved"] == 4
    assert summary["median_pin_to_cell_um"] < summary["median_pin_to_cell_um_before_snap"]
    assert pins.pin_distance_um(new) == summary["median_pin_to_cell_um"]


def test_ring_ratio():
    # Cells span 88 x 37 µm of a 100 x 40 µm die: about 1 (no ring).
    assert pins.ring_ratio(DEF) == pytest.approx(4000 * 10000 / (8800 * 3700))
    ringed = DEF.replace("DIEAREA ( 0 0 ) ( 10000 4000 )", "DIEAREA ( -5000 -5000 ) ( 15000 9000 )")
    assert pins.ring_ratio(ringed) > pins.RING_RATIO


def test_far():
    # Median 116 µm of a 140 µm half perimeter: far; the pins snapped by their cells (2.6 µm): not.
    assert pins.far(DEF)
    assert not pins.far(pins.snap(DEF)[0])


def test_snap_gives_cellless_pins_a_track_of_their_own():
    # Pin u drives nothing (an unused input bit): it stays on its side but must not share a
    # track with qa, which moves by cell a to the left side level with it.
    text = DEF.replace("PINS 4 ;", "PINS 5 ;").replace(
        "END PINS", "- u + NET u + DIRECTION INPUT + LAYER metal3 ( -15 -15 ) ( 15 15 ) + PLACED ( 0 2050 ) N ;\nEND PINS").replace(
        "NETS 4 ;", "NETS 5 ;").replace("END NETS", "- u\n  ( PIN u ) ;\nEND NETS")
    # gnd is a special net (not in NETS): qflow's power pin stays where it is, on its layer.
    gnd = "- gnd + NET gnd\n  + LAYER metal6 ( -80 -40 ) ( 80 40 )\n  + PLACED ( 3000 -60 ) N ;"
    text = text.replace("END PINS", gnd + "\nEND PINS").replace("PINS 5 ;", "PINS 6 ;")
    new, summary = pins.snap(text)
    placed = {m.group(1): (int(m.group(6)), int(m.group(7))) for m in pins.PIN_ENTRY.finditer(new)}
    assert len(placed) == 6 and len(set(placed.values())) == 6
    assert placed["u"][0] == placed["qa"][0]        # both on the left side
    assert summary["moved"] == 5
    assert gnd in new
