"""The gate-level model's parts: the cell library conversion and the memory models in place of
the stand-ins (the whole flow: ctest -L gatelevel)."""
import re

import pytest

from pstlib.gatelevel import cells, memories
from pstlib.synth import liberty

CELLS = """\
`timescale 1ns/10ps
`celldefine
module DFFPOSX1 (CLK, D, Q);
input  CLK ;
input  D ;
output Q ;
reg NOTIFIER ;

   udp_dff (DS0000, D, CLK, 1'B0, 1'B0, NOTIFIER);
   not (P0002, DS0000);
   buf (Q, DS0000);

   specify
     specparam tpllh$CLK$Q = 0.094:0.094:0.094;
     (CLK *> Q) = (tpllh$CLK$Q, tpllh$CLK$Q);
     $setup(negedge D, posedge CLK, 0.1, NOTIFIER);
   endspecify

endmodule
`endcelldefine

module NAND2X1 (A, B, Y);
input  A ;
input  B ;
output Y ;
   nand (Y, A, B);
endmodule

primitive udp_dff (out, in, clk, clr, set, NOTIFIER);
   output out;
   input  in, clk, clr, set, NOTIFIER;
   reg    out;
   table
   0  r   ?   0   ?   : ?  :  0  ;
   endtable
endprimitive // udp_dff
"""


def test_cells_udps_become_named_module_instances():
    out = cells.convert(CELLS)
    code = "\n".join(line for line in out.splitlines() if not line.startswith("//"))
    assert "primitive" not in code and "specify" not in code and "`timescale" not in code
    assert re.search(r"udp_dff u_udp_dff_1 \(DS0000, D, CLK", out)
    assert "module udp_dff (output reg out" in out
    assert cells.cell_names(out)[-2:] == ["DFFPOSX1", "NAND2X1"]


def test_cells_refuse_what_they_cannot_convert():
    bad = CELLS.replace("   nand (Y, A, B);", "   assign Y = ~(A & B);")
    with pytest.raises(cells.CellError, match=r"osu018_stdcells.v:\d+: cell NAND2X1"):
        cells.convert(bad)


def test_cells_shipped_library_converts_whole():
    try:
        lib = liberty.osu018_lib()
    except Exception:
        pytest.skip("OSU018 library not unpacked (scripts/setup.sh)")
    v = lib.with_suffix(".v") if hasattr(lib, "with_suffix") else None
    if v is None or not v.exists():
        pytest.skip("no osu018_stdcells.v")
    text = v.read_text()
    out = cells.convert(text, str(v))
    shipped = [n for n in re.findall(r"^module\s+(\w+)", text, flags=re.M)]
    assert set(shipped) <= set(cells.cell_names(out))
    for u in cells.UDPS:
        assert f"module {u} " in out


# A module with a 4 x 2 ROM (one read port, content 3, 2, 1, 0) and a 4 x 2 RAM (one write, one
# read port), as Yosys's dump and the stand-in map give them.
DUMP = """\
$paramod$aa\\pst_m/rom
$paramod$aa\\pst_m/ram

module $paramod$aa\\pst_m
  cell $mem_v2 \\rom
    parameter \\ABITS 2
    parameter \\INIT 8'00011011
    parameter \\OFFSET 0
    parameter \\RD_CLK_ENABLE 1'0
    parameter \\RD_PORTS 1
    parameter \\SIZE 4
    parameter \\WIDTH 2
    parameter \\WR_CLK_ENABLE 0'
    parameter \\WR_CLK_POLARITY 0'
    parameter \\WR_PORTS 0
  end
  cell $mem_v2 \\ram
    parameter \\ABITS 2
    parameter \\INIT 8'xxxxxxxx
    parameter \\OFFSET 0
    parameter \\RD_CLK_ENABLE 1'0
    parameter \\RD_PORTS 1
    parameter \\SIZE 4
    parameter \\WIDTH 2
    parameter \\WR_CLK_ENABLE 1'1
    parameter \\WR_CLK_POLARITY 1'1
    parameter \\WR_PORTS 1
  end
end
"""


def _rd(mem, bit, addr, y):
    pins = "".join(f"    .A{k}({addr[k] if k < len(addr) else chr(49) + chr(39) + 'h0'}),\n" for k in range(16))
    return f"  PST_MEMRD \\{mem}.rd[0].bit[{bit}].cell  (\n{pins}    .Y({y})\n  );\n"


def _wr(mem, kind, bit, leaf, d):
    return f"  PST_MEMWR \\{mem}.wr[0].{kind}[{bit}].{leaf}  (\n    .CK(clk_i),\n    .D({d})\n  );\n"


NETLIST = ("module \\$paramod$aa\\pst_m (clk_i, a_i, w_i, q_o, r_o);\n  input clk_i;\n"
           "  NAND2X1 _1_ (\n    .A(a_i[0]),\n    .B(a_i[1]),\n    .Y(_n_)\n  );\n"
           + _rd("rom", 0, ["a_i[0]", "a_i[1]"], "q_o[0]") + _rd("rom", 1, ["a_i[0]", "a_i[1]"], "\\q.x [1]")
           + _rd("ram", 0, ["a_i[0]", "a_i[1]"], "r_o[0]") + _rd("ram", 1, ["a_i[0]", "a_i[1]"], "r_o[1]")
           + _wr("ram", "dbit", 0, "wd", "w_i[0]") + _wr("ram", "dbit", 1, "wd", "w_i[1]")
           + _wr("ram", "dbit", 0, "we", "w_i[2]") + _wr("ram", "dbit", 1, "we", "w_i[2]")
           + _wr("ram", "abit", 0, "wa", "a_i[0]") + _wr("ram", "abit", 1, "wa", "a_i[1]")
           + "endmodule\n")


def test_memories_replace_every_standin_with_one_model():
    text, mems = memories.replace_standins(NETLIST, DUMP)
    assert [(k, m["memory"]) for k, m in mems] == [(0, "ram"), (1, "rom")]
    assert "PST_MEM" not in text
    assert "NAND2X1 _1_" in text                       # the logic is kept as it was
    assert "pst_gl_mem_1 \\rom.gl  (" in text and "pst_gl_mem_0 \\ram.gl  (" in text
    assert ".rd0_data_o({\\q.x [1] , q_o[0]})" in text   # bit 1 most significant, escaped net closed
    assert ".rd0_addr_i({a_i[1], a_i[0]})" in text
    assert ".wr0_en_i({w_i[2], w_i[2]})" in text and ".wr0_data_i({w_i[1], w_i[0]})" in text
    assert ".wr0_clk_i(clk_i)" in text
    assert text.count("endmodule") == 1


def test_memory_model_holds_the_content_word_0_least_significant():
    _, mems = memories.replace_standins(NETLIST, DUMP)
    rom = memories.memory_module(*mems[1])
    # content word 0 = 3 ... word 3 = 0 (INIT 8'00011011: word 3 first)
    assert "Init = 8'h1b;" in rom
    assert "assign rd0_data_o" in rom and "always_ff" not in rom
    ram = memories.memory_module(*mems[0])
    assert "always_ff @(posedge wr0_clk_i)" in ram
    stub = memories.memory_module(*mems[0], stub=True)
    assert stub.startswith("(* blackbox *)") and "mem_q" not in stub


def test_memories_refuse_a_standin_without_memory_and_a_memory_without_standin():
    with pytest.raises(memories.NetlistError, match="ghost: no such memory"):
        memories.replace_standins(NETLIST.replace("\\ram.wr[0].abit[1]", "\\ghost.wr[0].abit[1]"), DUMP)
    only_rom = NETLIST.split("  PST_MEMRD \\ram")[0] + "endmodule\n"
    with pytest.raises(memories.NetlistError, match="ram has no stand-in"):
        memories.replace_standins(only_rom, DUMP)


def test_memories_refuse_falling_edge_writes():
    with pytest.raises(memories.NetlistError, match="rising-edge"):
        memories.replace_standins(NETLIST, DUMP.replace("WR_CLK_POLARITY 1'1", "WR_CLK_POLARITY 1'0"))


# --simulator iverilog (replay.py): the comparison of the netlist's outputs with the RTL's trace.
def _rows(valid, f):
    return [{"clk_i": k % 2, "rst_ni": 1 if k > 1 else 0, "out_ready_i": 1, "out_valid_o": v, "frag_ready_o": 1,
             "idle_o": 0, "out_f_o": x} for k, (v, x) in enumerate(zip(valid, f))]


def test_replay_compare_equal_and_payload_only_when_valid():
    from . import replay
    rows = _rows([0, 0, 0, 1, 1, 0], [0, 0, 5, 7, 7, 9])
    # the payload of a cycle without out_valid_o is not compared (9 vs 3), nor anything in reset
    got = [[f"{r['frag_ready_o']:x}", f"{r['idle_o']:x}", f"{r['out_f_o']:x}", f"{r['out_valid_o']:x}"] for r in rows]
    got[5][2] = "3"
    got[0][0] = "x"
    res = replay.compare(rows, got, ["frag_ready_o", "idle_o", "out_f_o", "out_valid_o"])
    assert res["passed"] and res["mismatches"] == 0 and res["outputs_taken"] == 1


def test_replay_compare_finds_a_payload_and_an_unknown():
    from . import replay
    rows = _rows([0, 0, 1, 1], [0, 0, 7, 7])
    outs = ["frag_ready_o", "idle_o", "out_f_o", "out_valid_o"]
    got = [[f"{r['frag_ready_o']:x}", f"{r['idle_o']:x}", f"{r['out_f_o']:x}", f"{r['out_valid_o']:x}"] for r in rows]
    got[2][2] = "6"
    got[3][2] = "x"
    res = replay.compare(rows, got, outs)
    assert not res["passed"] and res["mismatches"] == 2
    assert res["first"] == {"half_clock": 2, "output": "out_f_o", "rtl": 7, "netlist": "6"}


def test_replay_zero_init_needs_the_udp_modules():
    from . import replay
    text = replay.zero_init_cells("module udp_dff (output reg out, input in, input clk);\nendmodule\n")
    assert "initial out = 1'b0;" in text
    try:
        replay.zero_init_cells("module DFF (Q);\nendmodule\n")
    except replay.ReplayError:
        pass
    else:
        raise AssertionError("no flip-flop model accepted")


def test_replay_scenes_all_and_default():
    """--scene all: every scene of scenes/ in name order; none given: marble alone."""
    import argparse
    from pstlib.gatelevel.__main__ import _replay_runs
    from pstlib.paths import ROOT
    every = _replay_runs(argparse.Namespace(scene=["all"]))
    assert every == sorted((ROOT / "scenes").glob("*.toml")) and len(every) > 5
    assert _replay_runs(argparse.Namespace(scene=None)) == [ROOT / "scenes" / "marble.toml"]
    assert _replay_runs(argparse.Namespace(scene=["x.toml", "all"]))[0].name == "x.toml"
