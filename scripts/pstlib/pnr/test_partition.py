"""Tests of the block cut (pstlib/pnr/partition.py)."""
from pstlib.pnr import partition


def names(spec: dict) -> list:
    """{'u_a.u_b': 3} -> ['u_a.u_b._0_', 'u_a.u_b._1_', 'u_a.u_b._2_']."""
    return [f"{p}._{i}_" if p else f"_{i}_" for p, k in spec.items() for i in range(k)]


def test_parent_and_counts():
    assert partition.parent("u_a.g[0].u_b._3_") == "u_a.g[0].u_b"
    assert partition.parent("_3_") == ""
    n = partition.subtree_counts(names({"u_a": 2, "u_a.u_b": 3, "": 1}))
    assert n[""] == 6 and n["u_a"] == 5 and n["u_a.u_b"] == 3


def test_small_instances_stay_in_top_and_large_ones_are_cut():
    cells = names({"u_big": 10, "u_big.u_x": 30, "u_big.u_y": 5, "u_mid": 20, "u_tiny": 3, "": 4})
    blocks = partition.choose(cells, limit=25, min_cells=10)
    # u_big has 45 cells > 25: its largest child (30) is pulled out, the rest (15) stays.
    assert blocks == ["u_big", "u_big.u_x", "u_mid"]
    parts = partition.assign(cells, blocks)
    assert {k: len(v) for k, v in parts.items()} == {"u_big": 15, "u_big_u_x": 30, "u_mid": 20, "top": 7}


def test_every_cell_in_exactly_one_block():
    cells = names({"u_a": 40, "u_a.g[0].u_n": 60, "u_a.g[0].u_n.u_m": 50, "u_b": 12, "": 2})
    blocks = partition.choose(cells, limit=55, min_cells=5)
    # u_n keeps its own 60 cells (more than the limit: a module is not split); the generate
    # scope u_a.g[0] holds no cell of its own and is no block.
    assert blocks == ["u_a", "u_a.g[0].u_n", "u_a.g[0].u_n.u_m", "u_b"]
    parts = partition.assign(cells, blocks)
    assert sorted(c for v in parts.values() for c in v) == sorted(cells)
    assert {k: len(v) for k, v in parts.items()} == {"u_a": 40, "u_a_g_0_u_n": 60, "u_a_g_0_u_n_u_m": 50,
                                                     "u_b": 12, "top": 2}


def test_block_name():
    assert partition.block_name("u_octave.g_noise[0].g_lattice.u_noise") == "u_octave_g_noise_0_g_lattice_u_noise"


def test_groups_claim_their_cells_first():
    cells = names({"u_a": 10, "u_a.u_r": 4, "u_b": 30, "u_b.u_l3": 8, "": 2})
    name, paths = partition.parse_group("crit=u_a.u_r+u_b.u_l3")
    assert name == "crit" and paths == ["u_a.u_r", "u_b.u_l3"]
    got, left = partition.claim(cells, {name: paths})
    assert len(got["crit"]) == 12 and len(left) == len(cells) - 12
    assert not any(c.startswith(("u_a.u_r.", "u_b.u_l3.")) for c in left)


def test_bad_groups_are_refused():
    import pytest
    for spec in ("crit", "crit=", "top=u_a", "1x=u_a", "a-b=u_a"):
        with pytest.raises(ValueError):
            partition.parse_group(spec)
    with pytest.raises(ValueError, match="u_nope"):
        partition.claim(names({"u_a": 3}), {"g": ["u_a", "u_nope"]})


def test_write_derate_keeps_the_other_profiles(tmp_path):
    import json
    from pstlib.pnr import report
    f = tmp_path / "layout_derate.json"
    f.write_text(json.dumps({"profiles": {"reduced": {"profile": "reduced", "ratio": 0.904}}}))
    blk = {"block": "noise_l3", "fmax_ratio": 0.95, "sta": {"pre_layout": {"fmax_mhz": 120.0}}}
    r = {"profile": "full", "fmax_ratio_post_over_pre": 0.95, "blocks": [blk], "post_route_slowest_block": "noise_l3",
         "post_route_fmax_mhz": 114.0, "method": "qflow", "skipped_blocks": ["top"], "command": "scripts/pnr.py full"}
    report.write_derate(r, f)
    d = json.loads(f.read_text())["profiles"]
    assert d["reduced"]["ratio"] == 0.904
    assert d["full"]["ratio"] == 0.95 and d["full"]["critical_blocks_only"] and d["full"]["blocks"] == ["noise_l3"]


def test_split_of_a_few_blocks_keeps_only_their_modules():
    full = partition.split_script(["osu.lib"], "n.v", "pst_top", {"a": "a.sel", "b": "b.sel"}, "out", "PST_MEMRD*")
    few = partition.split_script(["osu.lib"], "n.v", "pst_top", {"a": "a.sel"}, "out", "PST_MEMRD*", assembly=False)
    assert "design -save split" in full and partition.ASSEMBLY_BLIF in full
    # a few blocks: the flattened design is never saved whole; only the blocks' modules are copied
    assert "design -save split" not in few and partition.ASSEMBLY_BLIF not in few
    assert "design -copy-to pst_blocks blk_a" in few and "write_verilog -noattr out/blk_a.v" in few


def test_block_ratio_is_the_worse_of_its_critical_path_and_its_register_paths():
    from pstlib.pnr import flow
    sta = {"pre_layout": {"fmax_mhz": 116.0, "reg2reg": {"fmax_mhz": 126.7}},
           "post_route": {"fmax_mhz": 113.0, "reg2reg": {"fmax_mhz": 116.2}}}
    r = flow.ratios(sta)
    # the pin path (2 ns budgets) is critical before layout: its ratio (0.974) hides the wires'
    assert r == {"fmax_ratio": 0.917, "fmax_ratio_combined": 0.974, "fmax_ratio_reg2reg": 0.917}


def test_block_sdc_drops_commands_on_ports_the_block_lacks():
    from pstlib.pnr import timing
    sdc = "create_clock -period 10 [get_ports clk_i]\nset_false_path -from [get_ports rst_ni]\nset_input_delay 2 [all_inputs]\n"
    got = timing.block_sdc(sdc, {"clk_i", "a_0_"})
    assert "create_clock -period 10 [get_ports clk_i]\n" in got
    assert "# not a port of this block: set_false_path" in got and "\nset_false_path" not in got
    assert timing.block_sdc(sdc, {"clk_i", "rst_ni"}) == sdc
    assert timing.netlist_ports("module blk_x (clk_i, a_0_, y);\ninput clk_i;\n") == {"clk_i", "a_0_", "y"}
