"""Trace names -> netlist names: generate blocks, unnamed genblks, ports, bits."""
from pstlib.power import activity, annotate

NETLIST = r"""module \$paramod$abc\pst_leaf (clk_i, d_i, q_o);
  input clk_i;
  input [1:0] d_i;
  output [1:0] q_o;
  DFFPOSX1 _1_ (
    .CLK(clk_i),
    .D(d_i[0]),
    .Q(q_o[0])
  );
endmodule
module pst_mid (clk_i, x_i);
  input clk_i;
  input [1:0] x_i;
  \$paramod$abc\pst_leaf \g_unit[0].genblk1.u_leaf  (
    .clk_i(clk_i),
    .d_i(x_i)
  );
endmodule
module pst_top (clk_i, a_i);
  input clk_i;
  input [1:0] a_i;
  pst_mid u_mid (
    .clk_i(clk_i),
    .x_i(a_i)
  );
endmodule
"""


def test_scope_with_generate_blocks_maps_to_the_instance():
    tree = annotate.instance_tree(NETLIST)
    assert annotate.map_scope(["u_mid", "g_unit[0]", "u_leaf"], tree) == "u_mid/g_unit[0].genblk1.u_leaf"
    assert annotate.map_scope(["u_mid"], tree) == "u_mid"
    assert annotate.map_scope([], tree) == ""
    assert annotate.map_scope(["u_mid", "g_unit[0]"], tree) is None     # a generate block alone
    assert annotate.map_scope(["u_nowhere"], tree) is None


def test_net_names_per_bit():
    tree = annotate.instance_tree(NETLIST)
    act = activity.Activity(cycles=10, window=20, rates={
        "a_i": [(0.1, 0.5), (0.2, 0.5)],
        "u_mid/g_unit[0]/u_leaf/q_o": [(0.3, 0.4), (0.4, 0.4)],
        "u_mid/g_unit[0]/u_leaf/en": [(0.5, 0.5)],
        "u_mid/g_unit[0]/tmp": [(0.9, 0.5)],
    }, lsb={"a_i": 0, "u_mid/g_unit[0]/u_leaf/q_o": 0, "u_mid/g_unit[0]/u_leaf/en": 0})
    nets = annotate.net_activities(act, tree)
    assert ("a_i[1]", 0.2, 0.5) in nets
    assert ("u_mid/g_unit[0].genblk1.u_leaf/q_o[0]", 0.3, 0.4) in nets
    assert ("u_mid/g_unit[0].genblk1.u_leaf/en", 0.5, 0.5) in nets
    assert not any(n.endswith("tmp") for n, _, _ in nets)      # a generate block's own wire
    scopes = annotate.scope_activity(act, tree)
    # the generate block's wire counts in its enclosing instance (u_mid)
    assert scopes["u_mid"] == 0.9
    assert scopes["u_mid/g_unit[0].genblk1.u_leaf"] == (0.3 + 0.4 + 0.5) / 3


def test_the_cell_driving_a_port_bit_takes_its_rate():
    tree = annotate.instance_tree(NETLIST)
    drivers = annotate.port_drivers(NETLIST)
    assert drivers["$paramod$abc\\pst_leaf"] == {"q_o[0]": "_1_"}
    nets = [("u_mid/g_unit[0].genblk1.u_leaf/q_o[0]", 0.3, 0.4), ("u_mid/g_unit[0].genblk1.u_leaf/q_o[1]", 0.4, 0.4),
            ("a_i[0]", 0.1, 0.5)]
    assert annotate.driven_cells(nets, tree, drivers) == {"u_mid/g_unit[0].genblk1.u_leaf/_1_": 0.3}
    assert annotate.has_driver(nets[0][0], tree, drivers)
    assert not annotate.has_driver(nets[1][0], tree, drivers)     # q_o[1] is driven by nothing here
