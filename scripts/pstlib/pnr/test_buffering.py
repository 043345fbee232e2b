"""Test of the removal of fanout.py's buffers (pstlib/pnr/buffering.py) on fanout.py's own output."""
from pstlib.pnr import buffering
from pstlib.synth import fanout

NETLIST = """module sub(a, y);
  input a;
  output y;
  INVX1 _1_ (.A(a), .Y(y));
endmodule
module top(x, y0, y1);
  input x;
  output y0;
  output y1;
  sub u0 (
    .a(x),
    .y(y0)
  );
  sub u1 (
    .a(x),
    .y(y1)
  );
endmodule
"""


def test_strip_undoes_insert():
    # fanout.py hangs the per-instance buffers on a tree: the removal follows it to the driver.
    buffered, counts = fanout.insert_buffers(NETLIST)
    assert counts["top"] >= 2 and "_fob" in buffered
    plain, n = buffering.strip_fanout_buffers(buffered)
    assert n == counts["top"] and "_fob" not in plain
    assert plain == NETLIST


def test_strip_undoes_a_deep_tree():
    n = 3 * fanout.MAX_FANOUT
    insts = "".join(f"  sub u{i} (\n    .a(x),\n    .y(y[{i}])\n  );\n" for i in range(n))
    net = NETLIST.split("module top")[0] + f"module top(x, y);\n  input x;\n  output [{n - 1}:0] y;\n{insts}endmodule\n"
    buffered, counts = fanout.insert_buffers(net)
    assert counts["top"] > n          # the per-instance buffers and the tree above them
    plain, removed = buffering.strip_fanout_buffers(buffered)
    assert removed == counts["top"] and plain == net
