"""The report's blocks, read off a hierarchy (pstlib.synth.blocks), and the per-module cache's
counting (pstlib.synth.modules)."""
from pstlib.paths import rtl_source
from pstlib.synth import blocks, modules


def _position(order):
    """Source order of a parent's children as given (a stand-in for reading rtl/*.sv)."""
    return lambda parent, child: order.index(child) if child in order else len(order)


# pst_top -> octave stage (worley, octave fade, fade_lg, noise, term) and colour stage; pst_delay
# and pst_mul_booth are instantiated by several modules (building blocks).
SUBS = {
    "\\pst_top": {"$paramod$1\\pst_octave_stage": 1, "$paramod$2\\pst_colour_stage": 1, "$paramod$9\\pst_delay": 1},
    "$paramod$1\\pst_octave_stage": {"$paramod$3\\pst_worley": 1, "$paramod$4\\pst_octave_fade": 2,
                                     "$paramod$5\\pst_fade_lg": 1, "$paramod$6\\pst_noise": 2,
                                     "$paramod$9\\pst_delay": 4},
    "$paramod$3\\pst_worley": {"$paramod$9\\pst_delay": 3},
    "$paramod$4\\pst_octave_fade": {}, "$paramod$5\\pst_fade_lg": {},
    "$paramod$6\\pst_noise": {"$paramod$7\\pst_noise_lerp": 3},
    "$paramod$7\\pst_noise_lerp": {"$paramod$8\\pst_mul_booth": 2, "$paramod$11\\pst_lerp_core": 1},
    "$paramod$11\\pst_lerp_core": {"$paramod$12\\pst_lerp_leaf": 1}, "$paramod$12\\pst_lerp_leaf": {},
    "$paramod$2\\pst_colour_stage": {"$paramod$10\\pst_clut_filter": 1},
    "$paramod$10\\pst_clut_filter": {"$paramod$8\\pst_mul_booth": 1},
    "$paramod$8\\pst_mul_booth": {}, "$paramod$9\\pst_delay": {},
}
ORDER = _position(["pst_octave_stage", "pst_colour_stage", "pst_noise", "pst_worley", "pst_octave_fade",
                   "pst_fade_lg", "pst_clut_filter"])


def test_worley_and_the_fades_have_their_own_rows_in_hierarchy_order():
    got = blocks.block_instances(SUBS, "\\pst_top", ORDER)
    order = list(dict.fromkeys(b for _, b, _ in got))
    assert order == ["octave_stage", "noise", "noise_lerp", "lerp_core", "worley", "octave_fade", "fade_lg",
                     "colour_stage", "clut_filter", "top"]
    assert got[("$paramod$3\\pst_worley", "worley", "pst_octave_stage")] == 1
    assert got[("$paramod$4\\pst_octave_fade", "octave_fade", "pst_octave_stage")] == 2


def test_building_blocks_and_deeper_modules_count_in_the_block_holding_them():
    got = blocks.block_instances(SUBS, "\\pst_top", ORDER)
    assert blocks.building_blocks(SUBS) == {"pst_delay", "pst_mul_booth"}
    assert got[("$paramod$9\\pst_delay", "worley", "pst_worley")] == 3
    assert got[("$paramod$9\\pst_delay", "octave_stage", "pst_octave_stage")] == 4
    assert got[("$paramod$9\\pst_delay", "top", "pst_top")] == 1
    assert got[("$paramod$7\\pst_noise_lerp", "noise_lerp", "pst_noise")] == 6      # depth 3: its own block
    assert got[("$paramod$8\\pst_mul_booth", "noise_lerp", "pst_noise_lerp")] == 12
    assert got[("$paramod$12\\pst_lerp_leaf", "lerp_core", "pst_lerp_core")] == 6   # depth 5: in its holder
    assert got[("$paramod$8\\pst_mul_booth", "clut_filter", "pst_clut_filter")] == 1
    assert sum(k for (m, _, _), k in got.items() if m == "$paramod$8\\pst_mul_booth") == 13


def test_shared_leaves_are_listed_per_holder_with_their_total_area():
    # Regression: synth.md once listed "pst_delay 168 x 5,368" where 5,368 GE was the LARGEST
    # derived pst_delay, not the mean. Each module row carries its total area, and a building
    # block (pst_mul_booth, pst_delay) is split by the module holding it.
    cells = {"NAND2X1": 24.0, "DFFPOSX1": 96.0}
    stat = {"modules": {
        "\\pst_top": {"num_cells_by_type": {"$paramod$5\\pst_octave_stage": 1, "$paramod$2\\pst_delay": 1,
                                             "$paramod$3\\pst_mul_booth": 1}},
        "$paramod$5\\pst_octave_stage": {"num_cells_by_type": {"$paramod$0\\pst_noise": 1}},
        "$paramod$0\\pst_noise": {"num_cells_by_type": {"$paramod$1\\pst_noise_lerp": 2, "$paramod$2\\pst_delay": 1}},
        "$paramod$1\\pst_noise_lerp": {"num_cells_by_type": {"$paramod$3\\pst_mul_booth": 2,
                                                             "$paramod$4\\pst_mul_booth": 1, "NAND2X1": 1}},
        "$paramod$3\\pst_mul_booth": {"num_cells_by_type": {"NAND2X1": 10}},
        "$paramod$4\\pst_mul_booth": {"num_cells_by_type": {"NAND2X1": 40}},
        "$paramod$2\\pst_delay": {"num_cells_by_type": {"DFFPOSX1": 3}}}}
    a = blocks.analyse(stat, "", cells, {"DFFPOSX1"}, [{"module": "$paramod$1\\pst_noise_lerp", "memory": "rom"},
                                                       {"module": "\\$paramod$4\\pst_mul_booth", "memory": "t"}])
    assert a["mem_instances"] == {("$paramod$1\\pst_noise_lerp", "rom"): 2,
                                  ("\\$paramod$4\\pst_mul_booth", "t"): 2}     # memories per instance
    noise, lerp = a["blocks"]["noise"], a["blocks"]["noise_lerp"]
    booth = lerp["modules"]["pst_mul_booth in pst_noise_lerp"]
    assert booth["instances"] == 6 and booth["area"] == 2 * (2 * 10 + 40) * 24.0
    assert lerp["modules"]["pst_noise_lerp"]["area"] == 2 * 24.0
    assert noise["modules"]["pst_delay in pst_noise"]["area"] == 3 * 96.0
    assert a["blocks"]["top"]["modules"]["pst_mul_booth in pst_top"]["area"] == 10 * 24.0
    top_delay = a["blocks"]["top"]["modules"]["pst_delay in pst_top"]
    assert top_delay["area"] == 3 * 96.0 and a["blocks"]["top"]["ffs"] == 3
    assert noise["area"] == 3 * 96.0 and lerp["area"] == 2 * 24.0 + 2 * 60 * 24.0
    assert list(a["blocks"]) == ["octave_stage", "noise", "noise_lerp", "top"]


def test_the_checked_in_rtl_orders_the_octave_stage_before_the_colour_stage():
    assert blocks.source_position("pst_top", "pst_octave_stage") < blocks.source_position("pst_top", "pst_colour_stage")
    assert blocks.source_position("pst_top", "pst_no_such_module") == len(rtl_source("pst_top").read_text())


def test_module_hierarchy_counts_instances():
    stat = {"modules": {"\\top": {"num_cells_by_type": {"$paramod\\a": 2, "NAND2X1": 5}},
                        "$paramod\\a": {"num_cells_by_type": {"$paramod\\b": 3}},
                        "$paramod\\b": {"num_cells_by_type": {"INVX1": 1}}}}
    subs = modules.hierarchy_of(stat)
    assert modules.instance_counts(subs, "\\top") == {"\\top": 1, "$paramod\\a": 2, "$paramod\\b": 6}


def test_the_module_cache_counts_blocks_as_the_flow_does():
    got = modules.block_counts(SUBS, "\\pst_top")
    assert got[("$paramod$8\\pst_mul_booth", "noise_lerp")] == 12
    assert got[("$paramod$9\\pst_delay", "worley")] == 3 and got[("\\pst_top", "top")] == 1


def test_module_key_changes_with_parameters_source_and_flow():
    k = modules.module_key("$paramod$abc\\pst_noise_lerp", "flow1")
    assert k == modules.module_key("$paramod$abc\\pst_noise_lerp", "flow1")
    assert k != modules.module_key("$paramod$abd\\pst_noise_lerp", "flow1")
    assert k != modules.module_key("$paramod$abc\\pst_noise_lerp", "flow2")
