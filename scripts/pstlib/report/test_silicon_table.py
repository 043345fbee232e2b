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
    rows = {r[0]: r[1:] for r in silicon_table.rows([profile(), profile(derate=0.9), profile(post_route_mhz=80.0, derate=0.9)])}
    assert rows["Fmax post-route, or pre-layout x derate"] == ["100.0 MHz (pre-layout)", "90.0 MHz (derated x 0.900)",
                                                              "80.0 MHz (post-route)"]
    assert rows["Mpixel/s at that clock"] == ["50.00", "45.00", "40.00"]
    assert rows["meets 36.9 Mpixel/s"] == ["yes", "yes", "yes"]
    assert rows["logic GE x clocks per pixel"] == ["2,000"] * 3
    assert rows["worst paper scene"] == ["planet 41.0 dB"] * 3


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
