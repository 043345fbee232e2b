"""The routed-block equivalence (pstlib/pnr/lec.py) on a small netlist of OSU018 cells: the same
logic with a buffer inserted and every instance renamed (what qflow does) is proven; a swapped
cell differs."""
import shutil

import pytest

from pstlib.pnr import blif, lec
from pstlib.synth import liberty

GOLD_BLIF = """.model blk_t
.inputs clk a[0] b
.outputs y
.gate NAND2X1 A=a[0] B=q Y=n1
.gate DFFPOSX1 CLK=clk D=n1 Q=q
.gate XOR2X1 A=q B=b Y=y
.end
"""
ROUTED = """module blk_t(clk, a_0_, b, y);
  input clk; input a_0_; input b; output y;
  wire n1, q, qb, clkb;
  BUFX2 BUFX2_1 (.A(clk), .Y(clkb));
  NAND2X1 NAND2X1_1 (.A(a_0_), .B(qb), .Y(n1));
  DFFPOSX1 DFFPOSX1_1 (.CLK(clkb), .D(n1), .Q(q));
  BUFX2 BUFX2_2 (.A(q), .Y(qb));
  XOR2X1 XOR2X1_1 (.A(qb), .B(b), .Y(y));
endmodule
"""

needs_tools = pytest.mark.skipif(not (shutil.which("yosys") and shutil.which("yosys-abc") and liberty.osu018_lib()),
                                 reason="yosys, yosys-abc and the OSU018 liberty (scripts/setup.sh)")


@needs_tools
def test_routed_netlist_proven_and_mutant_differs(tmp_path):
    gold, gate = tmp_path / "gold.v", tmp_path / "routed.v"
    gold.write_text(blif.to_verilog(GOLD_BLIF))
    gate.write_text(ROUTED)
    lib = liberty.osu018_lib()
    ok = lec.check(lib, gold, gate, "blk_t", tmp_path / "w", timeout=120)
    assert ok["result"] == "proven", ok
    bad = lec.check(lib, gold, gate, "blk_t", tmp_path / "m", timeout=120, mutate=True)
    assert bad["mutation"] == "NAND2X1_1: NAND2X1 -> NOR2X1"
    assert bad["result"] == "differs", bad
