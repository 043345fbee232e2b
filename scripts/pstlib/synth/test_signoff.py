"""Tests of the sign-off checks (hold, max transition, max capacitance) on report texts OpenSTA
2.0.17 wrote for reduced's netlist (scripts/synth.py reduced --keep; the violating ones with
the SDC made stricter: hold uncertainty 0.5 ns, max transition 0.5 ns, DFFPOSX1/Q limited to
0.1 pF), the cell-area and memory-instance assertions, and the synthesis cache keys."""
import pytest

from pstlib.synth import inputs, liberty, memories, modules, report, sta
from pstlib.synth.tools import SDC

HOLD_PATH = """\
Startpoint: u_reg_a/_1341_ (rising edge-triggered flip-flop clocked by clk)
Endpoint: u_reg_a/_1341_ (rising edge-triggered flip-flop clocked by clk)
Path Group: pst_g0
Path Type: min

     Cap     Slew    Delay     Time   Description
---------------------------------------------------------------------------
            0.350    0.000    0.000   clock clk (rise edge)
                     0.000    0.000   clock network delay (ideal)
            0.350    0.000    0.000 ^ u_reg_a/_1341_/CLK (DFFPOSX1)
   0.022    0.066    0.148    0.148 ^ u_reg_a/_1341_/Q (DFFPOSX1)
   0.013    0.039    0.047    0.195 v u_reg_a/_682_/Y (NAND2X1)
   0.009    0.048    0.049    0.244 ^ u_reg_a/_683_/Y (OAI21X1)
            0.048    0.000    0.244 ^ u_reg_a/_1341_/D (DFFPOSX1)
                              0.244   data arrival time

            0.350    0.000    0.000   clock clk (rise edge)
                     0.000    0.000   clock network delay (ideal)
                     0.100    0.100   clock uncertainty
                     0.000    0.100   clock reconvergence pessimism
                              0.100 ^ u_reg_a/_1341_/CLK (DFFPOSX1)
                    -0.006    0.094   library hold time
                              0.094   data required time
---------------------------------------------------------------------------
                              0.094   data required time
                             -0.244   data arrival time
---------------------------------------------------------------------------
                              0.150   slack (MET)

"""

HOLD_VIOLATORS = """\
min_delay/hold group clk

                                     Required   Actual
Endpoint                                Delay    Delay    Slack
---------------------------------------------------------------
u_colour/u_clut/g_ch[0].u_r1/_290_/D (DFFPOSX1)    0.494    0.242   -0.251 (VIOLATED)
u_colour/u_clut/g_ch[0].u_r1/_291_/D (DFFPOSX1)    0.494    0.242   -0.251 (VIOLATED)
"""

TRANSITION_MET = """\
max_transition

Pin                                     Limit    Trans    Slack
---------------------------------------------------------------
u_width/u_width/_7619_/Y                1.200    0.546    0.654 (MET)

"""

TRANSITION_VIOLATED = """\
max_transition

Pin                                     Limit    Trans    Slack
---------------------------------------------------------------
u_width/u_width/_7619_/Y                0.500    0.546   -0.046 (VIOLATED)

max_transition

Pin                                     Limit    Trans    Slack
---------------------------------------------------------------
u_width/u_width/_7619_/Y                0.500    0.546   -0.046 (VIOLATED)
u_width/u_width/_7622_/A                0.500    0.546   -0.046 (VIOLATED)

"""

CAP_OUT = """\
group pst_g7 pst_width_stage u_width pst_width_stage
max_capacitance u_reg_c/_887_/Q DFFPOSX1 0.1015 0.1000
max_capacitance u_reg_c/_959_/Q DFFPOSX1 0.1044 0.1000
max_capacitance_worst u_octave/g_noise[0].g_lattice.u_noise/u_b1/_427_/Q DFFPOSX1 0.1197 0.1000 21779
"""

# The start of the OSU018 liberty's BUFX2 (its tables left out).
LIB_BUFX2 = """\
library(osu018_stdcells) {
cell (BUFX2) {
  cell_footprint : buf;
area : 24;
  pin(A)  {
    direction : input;
    capacitance : 0.00933171;
  }
  pin(Y)  {
    direction : output;
    capacitance : 0;
    max_capacitance : 0.975984;
    function : "A";
  }
}
}
"""


def test_hold_path_parsed_like_a_setup_path():
    (p,) = sta.parse_checks(HOLD_PATH)
    assert (p["startpoint"], p["endpoint"], p["group"]) == ("u_reg_a/_1341_", "u_reg_a/_1341_", "pst_g0")
    assert (p["arrival"], p["required"], p["slack"]) == (0.244, 0.094, 0.150)
    assert p["cells"] == ["NAND2X1", "OAI21X1"]


def test_hold_violators():
    v = sta.parse_hold_violators(HOLD_VIOLATORS)
    assert [x["endpoint"] for x in v] == ["u_colour/u_clut/g_ch[0].u_r1/_290_/D", "u_colour/u_clut/g_ch[0].u_r1/_291_/D"]
    assert v[0] == {"endpoint": "u_colour/u_clut/g_ch[0].u_r1/_290_/D", "cell": "DFFPOSX1", "slack_ns": -0.251}
    assert sta.parse_hold_violators("\n") == []       # what OpenSTA writes when none is violated


def test_transition_worst_and_violators_once_per_pin():
    met = sta.parse_transition(TRANSITION_MET)
    assert met["violations"] == []
    assert met["worst"] == {"pin": "u_width/u_width/_7619_/Y", "limit_ns": 1.2, "transition_ns": 0.546, "slack_ns": 0.654}
    bad = sta.parse_transition(TRANSITION_VIOLATED)
    assert [v["pin"] for v in bad["violations"]] == ["u_width/u_width/_7619_/Y", "u_width/u_width/_7622_/A"]
    assert bad["worst"]["slack_ns"] == -0.046


def test_capacitance_check_lines():
    c = sta.parse_capacitance(CAP_OUT)
    assert c["checked"] == 21779
    assert c["worst"] == {"pin": "u_octave/g_noise[0].g_lattice.u_noise/u_b1/_427_/Q", "cell": "DFFPOSX1",
                          "load_pf": 0.1197, "limit_pf": 0.1}
    assert [v["pin"] for v in c["violations"]] == ["u_reg_c/_887_/Q", "u_reg_c/_959_/Q"]


def test_cap_check_tcl_holds_the_limits_and_the_input_limit():
    tcl = sta.cap_check_tcl({"BUFX2/Y": 0.975984, "DFFPOSX1/Q": 0.967534}, 0.975984)
    assert "set pst_limits [dict create BUFX2/Y 0.975984 DFFPOSX1/Q 0.967534]" in tcl
    assert "[get_nets -quiet [get_full_name $port]] 0.975984" in tcl
    assert "%%" not in tcl


def test_sdc_constraints_and_driving_cell():
    text = SDC.read_text()
    c = sta.sdc_constraints(text)
    assert c["period_ns"] == 10.0
    assert c["setup_uncertainty_ns"] > c["hold_uncertainty_ns"] > 0
    assert c["clock_transition_ns"] > 0 and c["input_transition_ns"] > 0
    assert sta.sdc_driving_cell(text) == "BUFX2"


def test_sdc_max_transition_is_the_liberty_table_limit():
    lib = liberty.osu018_lib()
    if lib is None:
        pytest.skip("OSU018 liberty not installed (scripts/setup.sh)")
    import re
    ends = {float(m.group(1).split(",")[-1]) for m in re.finditer(r'index_2 \("([0-9., ]+)"\)', lib.read_text())
            if not m.group(1).startswith("1000")}
    assert sta.sdc_constraints(SDC.read_text())["max_transition_ns"] == min(ends)


def test_liberty_max_capacitance_per_output_pin():
    assert liberty.max_capacitance(LIB_BUFX2) == {"BUFX2/Y": 0.975984}


def test_cells_area_refuses_a_cell_type_without_area():
    areas = {"NAND2X1": 24.0, "BUFX4": 32.0}
    assert liberty.cells_area({"NAND2X1": 2, "BUFX4": 1}, areas) == 80.0
    assert liberty.cells_area({"NAND2X1": 1, "PST_MEMRD": 8, "sub": 2}, areas, skip=("PST_MEMRD", "sub")) == 24.0
    with pytest.raises(RuntimeError, match="XOR9X1"):
        liberty.cells_area({"NAND2X1": 1, "XOR9X1": 1}, areas)


def test_memory_without_instance_is_an_error(tmp_path):
    mem = {"module": "\\pst_noise", "memory": "\\tab", "size": 16, "width": 8, "read_ports": 1,
           "write_ports": 1, "abits": 4}
    with pytest.raises(RuntimeError, match="no instance"):
        memories.memory_rows([mem], {}, {("\\pst_noise", "\\tab"): 0}, tmp_path / "lib", 24.0)


def record(hold=0.1, hold_n=0, trans_n=0, cap_n=0):
    w = {"slack_ns": hold, "startpoint": "a/q", "endpoint": "b/d", "stage": "s"}
    return {"timing": {"hold": {"wns_ns": hold, "violations": hold_n, "worst": w},
                       "max_transition": {"violations": trans_n, "worst": {"pin": "u/x/Y", "transition_ns": 1.3,
                                                                           "limit_ns": 1.2}},
                       "max_capacitance": {"violations": cap_n, "worst": {"pin": "u/y/Y", "cell": "INVX1",
                                                                          "load_pf": 0.6, "limit_pf": 0.49}}}}


def test_signoff_errors_name_the_worst_offender():
    assert report.signoff_errors(record()) == []
    assert report.signoff_errors({"timing": None}) == []
    (h,) = report.signoff_errors(record(hold=-0.05, hold_n=3))
    assert "hold: 3 endpoints" in h and "a/q -> b/d" in h
    t, c = report.signoff_errors(record(trans_n=1, cap_n=2))
    assert "u/x/Y" in t and "u/y/Y (INVX1)" in c


def test_flow_inputs_cover_every_input():
    from pstlib.paths import ROOT
    names = {p.relative_to(ROOT).as_posix() for p in inputs.code_files()}
    assert {"scripts/synth.py", "scripts/profile.py", "scripts/pstlib/contract.py", "scripts/pstlib/synth/fanout.py",
            "scripts/synth/pst.sdc", "rtl/contract.toml", "rtl/top/pst_top.sv", "rtl/pst_pkg.sv"} <= names
    assert not any(n.rsplit("/", 1)[-1].startswith("test_") for n in names)
    assert not any("/sva/" in n for n in names)
    assert "rtl/top/pst_top.sv" not in {p.relative_to(ROOT).as_posix() for p in inputs.code_files(rtl_sv=False)}


def test_digest_follows_content_and_tool_versions(tmp_path):
    f = tmp_path / "a.memh"
    f.write_text("00\n")
    k = inputs.digest([f], ("Yosys 0.23",))
    assert k == inputs.digest([f], ("Yosys 0.23",))
    assert k != inputs.digest([f], ("Yosys 0.24",))
    f.write_text("01\n")
    assert k != inputs.digest([f], ("Yosys 0.23",))


def test_module_and_memory_salts_follow_the_liberty_and_the_roms(tmp_path):
    lib = tmp_path / "cells.lib"
    lib.write_text(LIB_BUFX2)
    roms = tmp_path / "rom"
    roms.mkdir()
    (roms / "perm256.memh").write_text("00\n")
    salt, mem = modules.flow_salt(lib, roms), memories.mem_flow_salt(lib)
    (roms / "perm256.memh").write_text("01\n")
    assert modules.flow_salt(lib, roms) != salt
    lib.write_text(LIB_BUFX2.replace("area : 24", "area : 25"))
    assert memories.mem_flow_salt(lib) != mem


def test_sweep_key_follows_the_tool_versions(tmp_path, monkeypatch):
    from pstlib.explore import evaluate
    prof = tmp_path / "p.toml"
    prof.write_text("[noise]\nout_frac = 8\n")
    rtl = tmp_path / "a.sv"
    rtl.write_text("module a; endmodule\n")
    k = evaluate.synth_key(prof, [rtl])
    monkeypatch.setattr(inputs, "tool_versions", lambda: ("Yosys 0.99", "2.9"))
    assert evaluate.synth_key(prof, [rtl]) != k
