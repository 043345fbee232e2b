"""scripts/pstlib/synth/fanout.py: fanout buffers across the module hierarchy, on a hand-made
netlist in Yosys' write_verilog form (escaped names, concatenations, assign aliases)."""
import re
import shutil
import subprocess

import pytest

from pstlib.synth import fanout

NETLIST = r"""module leaf(clk_i, en_i, d_i, q_o);
  input clk_i;
  wire clk_i;
  input en_i;
  wire en_i;
  input [3:0] d_i;
  wire [3:0] d_i;
  output [3:0] q_o;
  wire [3:0] q_o;
  NAND2X1 _1_ (
    .A(en_i),
    .B(d_i[0]),
    .Y(q_o[0])
  );
  assign q_o[3:1] = d_i[3:1];
endmodule

module top(clk_i, a_i, b_i, d_i, q_o);
  input clk_i;
  wire clk_i;
  input a_i;
  wire a_i;
  input b_i;
  wire b_i;
  input [3:0] d_i;
  wire [3:0] d_i;
  output [3:0] q_o;
  wire [3:0] q_o;
  wire \en.q ;
  wire en_alias;
  wire [3:0] \u2.q ;
  wire [3:0] lone;
  wire spare;
  NAND2X1 _5_ (
    .A(a_i),
    .B(b_i),
    .Y(\en.q )
  );
  NAND2X1 _6_ (
    .A(lone[2]),
    .B(lone[2]),
    .Y(spare)
  );
  leaf \u0.x  (
    .clk_i(clk_i),
    .en_i(\en.q ),
    .d_i({ 3'h0, d_i[0] }),
    .q_o(q_o)
  );
  leaf u1 (
    .clk_i(clk_i),
    .en_i(en_alias),
    .d_i({ d_i[3:1], d_i[0] }),
    .q_o(lone)
  );
  leaf u2 (
    .clk_i(clk_i),
    .en_i(\en.q ),
    .d_i({ lone[3], lone[1], a_i, a_i }),
    .q_o(\u2.q )
  );
  assign en_alias = \en.q ;
endmodule
"""


def buffers(text: str) -> dict:
    """Inserted buffer -> (its input, its output wire)."""
    return {m.group(1): (m.group(2).strip(), m.group(3))
            for m in re.finditer(rf"{fanout.CELL} (_fobc\d+_) \(\.A\((.+?)\), \.Y\((_fob\d+_)\)\);", text)}


def pin(text: str, inst: str, name: str) -> str:
    block = text[text.index(f"{inst}  (" if inst.startswith("\\") else f"{inst} ("):]
    return re.search(rf"\.{name}\((.*)\),?\n", block).group(1)


def test_buffers_where_the_rule_says():
    out, counts = fanout.insert_buffers(NETLIST, min_instances=2)
    bufs = buffers(out)
    src = sorted(a for a, _ in bufs.values())
    # The enable (3 instances, one through an alias) and d_i[0] (u0 and u1). Not: clk_i (clock),
    # d_i[3:1] (u1 only), lone[*] (one instance each), a_i (two pins of u2: one instance),
    # q_o (an output port), the library cells' pins.
    assert src == sorted(["\\en.q", "\\en.q", "en_alias", "d_i[0]", "d_i[0]"])   # u1's through its alias
    assert counts == {"top": 5}
    wire = {a: y for a, y in bufs.values()}
    assert pin(out, "\\u0.x", "en_i").startswith("_fob")
    assert pin(out, "u1", "en_i").startswith("_fob")
    assert pin(out, "u2", "en_i").startswith("_fob")
    assert len({pin(out, i, "en_i") for i in ("\\u0.x", "u1", "u2")}) == 3   # one buffer each
    assert re.fullmatch(r"\{ 3'h0, _fob\d+_ \}", pin(out, "\\u0.x", "d_i"))
    assert re.fullmatch(r"\{ d_i\[3:1\], _fob\d+_ \}", pin(out, "u1", "d_i"))
    assert pin(out, "u2", "d_i") == "{ lone[3], lone[1], a_i, a_i }"
    assert pin(out, "u1", "clk_i") == "clk_i"
    assert wire  # every buffer drives a wire used by exactly one instance pin
    for _, y in bufs.values():
        assert len(re.findall(rf"\b{y}\b", out)) == 3   # declared, driven, used once
    # The leaf module and everything else unchanged.
    assert out.split("module top")[0] == NETLIST.split("module top")[0]


def test_threshold():
    out, counts = fanout.insert_buffers(NETLIST, min_instances=3)
    assert counts == {"top": 3}
    assert sorted(a for a, _ in buffers(out).values()) == ["\\en.q", "\\en.q", "en_alias"]
    out, counts = fanout.insert_buffers(NETLIST, min_instances=4)
    assert out == NETLIST and counts == {}


@pytest.mark.skipif(shutil.which("yosys") is None, reason="yosys not installed (scripts/setup.sh)")
def test_buffered_netlist_parses(tmp_path):
    out, _ = fanout.insert_buffers(NETLIST)
    (tmp_path / "net.v").write_text(out)
    (tmp_path / "cells.v").write_text(
        "module NAND2X1(input A, input B, output Y); endmodule\n"
        f"module {fanout.CELL}(input A, output Y); endmodule\n")
    run = subprocess.run(["yosys", "-q", "-p", f"read_verilog -lib {tmp_path}/cells.v; read_verilog {tmp_path}/net.v; "
                          "hierarchy -check -top top; check -assert; stat"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr + run.stdout
