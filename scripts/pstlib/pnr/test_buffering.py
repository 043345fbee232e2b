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
    buffered, counts = fanout.insert_buffers(NETLIST)
    assert counts == {"top": 2} and "_fob" in buffered
    plain, n = buffering.strip_fanout_buffers(buffered)
    assert n == 2 and "_fob" not in plain
    assert plain == NETLIST
