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
    # One root buffer per net on the net's driver, one leaf buffer per instance fed by the root.
    roots = {y: a for a, y in bufs.values() if not a.startswith("_fob")}
    assert sorted(roots.values()) == ["\\en.q", "d_i[0]"]
    leaves = sorted(a for a, _ in bufs.values() if a.startswith("_fob"))
    en_root = next(y for y, a in roots.items() if a == "\\en.q")
    d_root = next(y for y, a in roots.items() if a == "d_i[0]")
    assert leaves == sorted([en_root] * 3 + [d_root] * 2)   # the enable's three (u1's through its alias)
    assert counts == {"top": 7}
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
        uses = {en_root: 3, d_root: 2}.get(y, 1)
        assert len(re.findall(rf"\b{y}\b", out)) == 2 + uses   # declared, driven, its loads
    # The leaf module and everything else unchanged.
    assert out.split("module top")[0] == NETLIST.split("module top")[0]


def test_tree_feeds_limits_every_buffer_fanout():
    made = []

    def buf(src):
        made.append(src)
        return f"w{len(made)}"
    assert fanout.tree_feeds("r", 5, buf, max_fanout=16) == ["r"] * 5 and made == []
    feeds = fanout.tree_feeds("r", 40, buf, max_fanout=16)
    assert len(feeds) == 40 and made == ["r", "r", "r"]            # three buffers under the root
    assert [feeds.count(w) for w in ("w1", "w2", "w3")] == [16, 16, 8]
    made.clear()
    feeds = fanout.tree_feeds("r", 300, buf, max_fanout=16)       # 19 buffers need a level of 2
    assert len(feeds) == 300 and max(feeds.count(w) for w in set(feeds)) <= 16
    assert made.count("r") == 2 and len(made) == 21


def test_threshold():
    out, counts = fanout.insert_buffers(NETLIST, min_instances=3)
    assert counts == {"top": 4}
    assert sorted(a for a, _ in buffers(out).values() if not a.startswith("_fob")) == ["\\en.q"]
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
