"""One small block through the whole per-block flow (qflow place and route, DRC, LVS, GDS,
SPEF, OpenSTA before and after layout, PNG, the routed netlist's equivalence): skipped where qflow is not installed
(scripts/setup.sh --pnr); about a minute here."""
import shutil
import subprocess

import pytest

from pstlib.pnr import flow, qflow
from pstlib.synth import liberty

RTL = """module small (input clk_i, input rst_ni, input [7:0] a_i, input [7:0] b_i, output reg [8:0] s_o,
                output reg [7:0] n_o);
  always @(posedge clk_i) begin
    s_o <= a_i + b_i;
    n_o <= rst_ni ? n_o + 8'd1 : 8'd0;
  end
endmodule
"""


@pytest.mark.skipif(not (qflow.available() and shutil.which("klayout") and liberty.osu018_lib()),
                    reason="qflow, KLayout or the OSU018 library not installed (scripts/setup.sh --pnr)")
def test_small_block(tmp_path):
    lib = liberty.osu018_lib()
    (tmp_path / "small.v").write_text(RTL)
    netlist = tmp_path / "blk_small.v"
    subprocess.run(["yosys", "-q", "-p", f"read_verilog {tmp_path / 'small.v'}; synth -top small; "
                    f"dfflibmap -liberty {lib}; abc -liberty {lib}; opt_clean; rename small blk_small; "
                    f"write_verilog -noattr {netlist}; write_blif -buf BUFX2 A Y -gates {netlist.with_suffix('.blif')}"],
                   check=True, timeout=120)
    out = tmp_path / "out"
    out.mkdir()
    rec = flow.run_block("small", {"netlist": netlist, "instance": "small", "cells_synth": 0}, tmp_path / "work",
                         lib, out)
    assert rec["lvs_match"] and rec["drc_errors"] == 0
    assert rec["flip_flops"] == 17 and 0 < rec["utilization"] < 1 and rec["wirelength_mm"] > 0
    pre, post = rec["sta"]["pre_layout"], rec["sta"]["post_route"]
    assert pre["fmax_mhz"] > 0 and post["fmax_mhz"] > 0
    # Pin paths are timed on the ideal clock before and after routing: the wires only add delay.
    assert post["pin"]["slack_ns"] < pre["pin"]["slack_ns"]
    # The routed netlist is proven equal to the block as cut; one swapped cell is caught.
    assert rec["lec"]["routed"]["result"] == "proven", rec["lec"]
    assert rec["lec"]["mutant"]["result"] == "differs", rec["lec"]
    spef = (out / "small.spef").read_text()
    assert spef.count("*D_NET") > 20 and "*RES" in spef
    for ext in ("def", "gds", "png"):
        assert (out / f"small.{ext}").stat().st_size > 0
