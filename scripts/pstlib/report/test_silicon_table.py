"""The silicon tables (pstlib/report/silicon_table.py): the summary's rows, the logic per block and
the critical path per stage. That docs/HARDWARE.md's copy is the generated
ones is scripts/tests/test_gen_docs.py's (and ctest docs_stale's) check."""
from pstlib.report import silicon_table


def profile(**kw):
    p = {"profile": "x", "logic_ge": 1000, "memory_ge": 500, "total_ge": 1500, "flip_flops": 10, "fmax_mhz": 100.0,
         "signoff_sdc": True, "post_route_mhz": None, "derate": None, "clocks_per_pixel": 2,
         "worst_psnr": ("planet", 41.04), "worst_path": None, "paper_gates": None, "block_ge": {}, "stage_path_ns": {}}
    p.update(kw)
    return p


def test_clock_is_post_route_else_derated_else_pre_layout():
    rows = {r[0]: r[1:] for r in silicon_table.rows([profile(), profile(derate=0.9, fmax_derated_mhz=90.0),
                                                     profile(post_route_mhz=80.0, derate=0.9, fmax_derated_mhz=90.0)])}
    assert rows["Fmax post-route, or pre-layout x derate"] == ["100.0 MHz (pre-layout)", "90.0 MHz (derated x 0.900)",
                                                              "80.0 MHz (post-route)"]
    assert rows["Mpixel/s at that clock"] == ["50.00", "45.00", "40.00"]
    assert rows["meets 36.9 Mpixel/s"] == ["yes", "yes", "yes"]
    assert rows["logic GE x clocks per pixel"] == ["2,000"] * 3
    assert rows["worst paper scene"] == ["planet 41.0 dB"] * 3


def test_the_derated_clock_is_the_synthesis_records_never_recomputed():
    # pstlib/synth/report.py derates (fmax_derated_mhz); the table quotes that figure as it is.
    rec = {"fmax_derated_mhz": 91.0}
    base = {"logic_ge": 1000, "memory_ge": 500, "total_ge": 1500, "flip_flops": 10, "fmax_mhz": 100.0,
            "clocks_per_pixel": 2}
    p = silicon_table.from_baseline("full", base, {"profile": "reduced", "ratio": 0.9, "post_route_fmax_mhz": 80.0},
                                    rec)
    assert silicon_table.layout_clock(p) == (91.0, "derated")
    assert silicon_table.layout_clock(silicon_table.from_baseline("full", base, None)) == (100.0, "pre-layout")
    s = silicon_table.from_synth({"profile": "full", "fmax_mhz": 100.0, "fmax_derated_mhz": 91.0,
                                  "fmax_derate": {"ratio": 0.9}, "clocks_per_pixel": 2})
    assert silicon_table.layout_clock(s) == (91.0, "derated")


def test_data_json_states_the_clocks_the_cpp_tool_reads():
    import json
    d = json.loads(silicon_table.data_json([profile(profile="a"), profile(profile="b", derate=0.9, fmax_derated_mhz=90.0),
                                             profile(profile="c", post_route_mhz=80.0)]))["profiles"]
    assert d["a"] == {"fmax_mhz": 100.0, "fmax_layout_mhz": None, "fmax_layout_basis": None, "clocks_per_pixel": 2}
    assert (d["b"]["fmax_layout_mhz"], d["b"]["fmax_layout_basis"]) == (90.0, "derated")
    assert (d["c"]["fmax_layout_mhz"], d["c"]["fmax_layout_basis"]) == (80.0, "post-route")


def test_post_route_from_the_assembled_chip_when_the_place_and_route_timed_it():
    derate = {"profile": "reduced", "ratio": 0.9, "post_route_fmax_mhz": 104.3, "not_routed": ["u_regs"],
              "assembled_fmax_mhz": 112.1}
    base = {"logic_ge": 1000, "memory_ge": 500, "total_ge": 1500, "flip_flops": 10, "fmax_mhz": 116.6,
            "clocks_per_pixel": 2}
    p = silicon_table.from_baseline("reduced", base, derate)
    rows = {r[0]: r[1:] for r in silicon_table.rows([p])}
    assert rows["Fmax post-route, or pre-layout x derate"] == ["112.1 MHz (post-route, blocks assembled; some without layout)"]
    del derate["assembled_fmax_mhz"]
    p = silicon_table.from_baseline("reduced", base, derate)
    rows = {r[0]: r[1:] for r in silicon_table.rows([p])}
    assert rows["Fmax post-route, or pre-layout x derate"] == ["104.3 MHz (post-route, timed blocks only)"]


def test_blocks_union_of_profiles_top_last():
    a = profile(profile="a", block_ge={"top": 5, "noise": 700, "quadric": 295})
    b = profile(profile="b", block_ge={"quadric_serial": 90, "top": 5, "noise": 905})
    lines = silicon_table.blocks_markdown([a, b]).splitlines()
    assert lines[0] == "| block (logic GE) | a | b |"
    assert [ln.split(" | ")[0] for ln in lines[2:]] == ["| `noise`", "| `quadric`", "| `quadric_serial`", "| `top`",
                                                        "| **logic**"]
    assert lines[3] == "| `quadric` | 295 | - |"
    assert lines[-1] == "| **logic** | **1,000** | **1,000** |"


def test_stages_in_pipeline_order_worst_in_bold():
    a = profile(profile="a", stage_path_ns={"clk": 3.0, "filter width [B] -> [C]": 8.5, "[A] input register": 4.0,
                                            "octave stage [A] -> [B]": 9.25})
    lines = silicon_table.stages_markdown([a]).splitlines()
    assert lines[2:] == ["| [A] input register | 4.00 |", "| octave stage [A] -> [B] | **9.25** |",
                         "| filter width [B] -> [C] | 8.50 |", "| clk | 3.00 |"]


def test_each_profile_is_derated_by_its_own_routed_blocks_else_the_worst_routed_ratio():
    from pstlib.synth import report as synth_report
    red = {"profile": "reduced", "ratio": 0.904, "post_route_fmax_mhz": 103.9, "blocks": ["a", "b"],
           "assembled_fmax_mhz": 105.1}
    full = {"profile": "full", "ratio": 0.93, "post_route_fmax_mhz": 120.0, "blocks": ["c", "d", "e"],
            "critical_blocks_only": True}
    doc = {"profiles": {"reduced": red, "full": full}}
    assert synth_report.derate_for(doc, "full") is full
    assert synth_report.derate_for(doc, "reduced") is red
    assert synth_report.derate_for(doc, "balanced") is red          # the worst ratio of the routed
    assert synth_report.derate_for(None, "full") is None
    base = {"logic_ge": 1000, "memory_ge": 500, "total_ge": 1500, "flip_flops": 10, "fmax_mhz": 121.8,
            "clocks_per_pixel": 3}
    # full routed in part (its critical blocks): derated by their ratio, never the slowest block's Fmax
    p = silicon_table.from_baseline("full", base, full, {"fmax_derated_mhz": 113.3})
    assert silicon_table.layout_clock(p) == (113.3, "derated")
    assert p["clock_source"] == "its own 3 critical blocks routed: x 0.930, their worst ratio"
    q = silicon_table.from_baseline("balanced", base, red, {"fmax_derated_mhz": 110.1})
    assert q["clock_source"].startswith("not routed: x 0.904") and "reduced's 2 blocks" in q["clock_source"]
    r = silicon_table.from_baseline("reduced", base, red)
    assert silicon_table.layout_clock(r) == (105.1, "post-route, blocks assembled")
    rows = {row[0]: row[1:] for row in silicon_table.rows([p, q, r])}
    assert rows["clock after layout from"][2] == "its 2 blocks routed, assembled"
