"""pstlib.lec.miter: which modules a miter decides, the mutant, the names Yosys is given."""
import pytest

from pstlib.lec import miter

NETLIST = r"""module \$paramod$aa\pst_leaf (a_i, b_i, y_o);
  input a_i;
  input b_i;
  output y_o;
  NAND2X1 _1_ (
    .A(a_i),
    .B(b_i),
    .Y(y_o)
  );
endmodule
module \$paramod$bb\pst_reg (clk_i, d_i, q_o);
  input clk_i;
  input d_i;
  output q_o;
  DFFPOSX1 _1_ (
    .CLK(clk_i),
    .D(d_i),
    .Q(q_o)
  );
endmodule
module pst_mem (a_i, y_o);
  input a_i;
  output y_o;
  PST_MEMRD_0 \rom.rd[0].bit[0].cell  (
    .A0(a_i),
    .Y(y_o)
  );
endmodule
module pst_mid (clk_i, a_i, y_o);
  input clk_i;
  input a_i;
  output y_o;
  \$paramod$aa\pst_leaf u_leaf (
    .a_i(a_i),
    .b_i(a_i),
    .y_o(n)
  );
  \$paramod$bb\pst_reg u_reg (
    .clk_i(clk_i),
    .d_i(n),
    .q_o(y_o)
  );
endmodule
module pst_top (clk_i, a_i, y_o);
  input clk_i;
  input a_i;
  output y_o;
  pst_mid u_mid (
    .clk_i(clk_i),
    .a_i(a_i),
    .y_o(y_o)
  );
  pst_mem u_mem (
    .a_i(a_i)
  );
endmodule
"""


def test_modules_own_cells_and_the_checks_they_get():
    m = miter.modules(NETLIST)
    assert m["$paramod$aa\\pst_leaf"] == {"cells": 1, "children": [], "seq": False, "mem": False}
    assert m["$paramod$bb\\pst_reg"]["seq"]
    # pst_mid's own logic is wiring: its sub-modules are cut out of its check and checked alone
    assert not m["pst_mid"]["seq"] and m["pst_mid"]["cells"] == 0
    assert miter.subtree_cells(m, "pst_mid") == 2
    assert m["pst_mem"]["mem"] and not m["pst_top"]["mem"]
    # the top and a module with a memory stand-in of its own are left to simulation; smallest first
    assert miter.comparable(m) == ["pst_mid", "$paramod$aa\\pst_leaf", "$paramod$bb\\pst_reg"]


def test_a_module_stands_when_everything_below_it_is_proven():
    m = miter.modules(NETLIST)
    v = {"pst_mid": "proven", "$paramod$aa\\pst_leaf": "proven", "$paramod$bb\\pst_reg": "timeout"}
    assert not miter.standing(m, v, "pst_mid")
    v["$paramod$bb\\pst_reg"] = "proven"
    assert miter.standing(m, v, "pst_mid")


def test_names_as_yosys_takes_them():
    assert miter.gold_name("$paramod$aa\\pst_leaf") == "$paramod$aa\\pst_leaf"
    assert miter.gate_name("$paramod$aa\\pst_leaf") == "\\$paramod$aa\\pst_leaf"
    assert miter.gate_name("pst_mid") == "pst_mid"


def test_the_mutant_swaps_one_cell_of_that_module_only():
    text, what = miter.mutate(NETLIST, "$paramod$aa\\pst_leaf")
    assert what == "_1_: NAND2X1 -> NOR2X1"
    assert text.count("NOR2X1") == 1 and text.count("NAND2X1") == 0
    assert text.count("DFFPOSX1") == 1
    with pytest.raises(ValueError, match="no two-input cell"):
        miter.mutate(NETLIST, "$paramod$bb\\pst_reg")
