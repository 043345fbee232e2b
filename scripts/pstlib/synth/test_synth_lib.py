"""Pure parts of the synthesis flow: liberty parsing, OpenSTA report parsing, the memory model,
the stand-ins, the command line's refusal of a bad profile. Fixtures are real tool output
(scripts/tests/fixtures/synth/): an excerpt of osu018_stdcells.lib, Yosys 0.23's dump of two
$mem_v2 cells, OpenSTA 2.0.17's report_checks of a two-register design with a stand-in memory."""
import re
import subprocess

import pytest

from pstlib.paths import ROOT
from pstlib.synth import liberty, memarea, sta

SCRIPTS = ROOT / "scripts"
FIX = SCRIPTS / "tests" / "fixtures" / "synth"


def test_osu018_excerpt_areas():
    text = (FIX / "osu018_excerpt.lib").read_text()
    areas = liberty.cell_areas(text)
    assert areas == {"NAND2X1": 24.0, "DFFPOSX1": 96.0}
    assert liberty.ge_unit(areas) == 24.0
    assert liberty.flip_flop_cells(text) == {"DFFPOSX1"}
    assert liberty.library_name(text) == "osu018_stdcells"


def test_old_cells_lib_still_parses():
    areas = liberty.cell_areas((SCRIPTS / "synth" / "cells.lib").read_text())
    assert len(areas) == 10 and areas["NAND2"] == 1.0 and areas["DFF"] == 4.33


def test_area_in_comment_is_ignored():
    text = "library(x) { cell (A) { /* area : 99; */ area : 3; } cell(B) { pin(Y) { } } }"
    assert liberty.cell_areas(text) == {"A": 3.0}


def test_ge_unit_needs_nand2():
    with pytest.raises(ValueError):
        liberty.ge_unit({"INVX1": 16.0})


def test_standin_liberty_has_one_cell_per_memory_and_the_delay():
    text = liberty.standin_liberty({0: 2.5, 3: 0.75}, 0.2, 0.01)
    assert set(liberty.cell_areas(text)) == {"PST_MEMRD", "PST_MEMRD_0", "PST_MEMRD_3", "PST_MEMWR"}
    cell3 = text[text.index("cell(PST_MEMRD_3)"):text.index("cell(PST_MEMWR)")]
    assert 'cell_rise(scalar) { values("0.7500"); }' in cell3
    assert "A15" in cell3 and "setup_rising" in text
    assert text.count("{") == text.count("}")


# ---- memories ------------------------------------------------------------------------------


def test_parse_yosys_memory_dump():
    mems = memarea.parse_memories((FIX / "yosys_mem_dump.txt").read_text())
    assert [(m["module"], m["memory"], m["size"], m["width"], m["abits"], m["read_ports"], m["write_ports"])
            for m in mems] == [("f", "m", 8, 4, 3, 1, 1), ("f", "r", 6, 4, 3, 2, 0)]
    assert mems[0]["init"] is None
    # f.v: r = {1, 2, 4, 8, 3, c}
    assert memarea.init_words(mems[1]) == [1, 2, 4, 8, 3, 0xC]


def test_memory_verilog_rom_and_ram():
    mems = memarea.parse_memories((FIX / "yosys_mem_dump.txt").read_text())
    ram, rom = mems
    v = memarea.memory_verilog(rom, 1)
    assert "m[5] = 4'hc;" in v and "assign d0 = m[a0];" in v and "d1" not in v
    v = memarea.memory_verilog(ram, 2)
    assert "always @(posedge clk) if (we) m[wa] <= wd;" in v and "assign d1 = m[a1];" in v
    assert memarea.synth_ports(rom) == 1 and memarea.synth_ports(ram) == 1


def test_memory_area_replicates_rom_ports_only():
    rom = {"write_ports": 0, "read_ports": 14}
    ram = {"write_ports": 1, "read_ports": 3}
    assert memarea.memory_area(rom, 100.0) == 1400.0
    assert memarea.memory_area(ram, 100.0) == 100.0


def test_port_options():
    opts = {o["option"]: o for o in memarea.port_options({"read_ports": 14}, 10.0, pairs_even_odd=7)}
    assert opts["replicate"]["copies"] == 14 and opts["replicate"]["area"] == 140.0
    assert opts["bank even/odd"]["copies"] == 7
    assert opts["schedule over 2 ports"]["cycles_factor"] == 7
    assert opts["schedule over 1 port"]["cycles_factor"] == 14
    quad = {o["option"]: o for o in memarea.port_options({"read_ports": 32}, 1.0, quads_mod4=8)}
    assert quad["bank by address mod 4"]["copies"] == 8 and "bank even/odd" not in quad


def test_memory_key_follows_content():
    mems = memarea.parse_memories((FIX / "yosys_mem_dump.txt").read_text())
    rom = dict(mems[1])
    k = memarea.memory_key(rom, "s")
    assert k == memarea.memory_key(dict(rom), "s")
    assert k != memarea.memory_key(rom, "t")
    rom["init"] = "0" + rom["init"][1:]
    assert k != memarea.memory_key(rom, "s")


# ---- OpenSTA -------------------------------------------------------------------------------


def test_parse_opensta_report():
    paths = sta.parse_checks((FIX / "opensta_report_checks.txt").read_text())
    assert [p["group"] for p in paths] == ["pst_g0", "pst_g1", "pst_g2", "clk"]
    p = paths[2]
    assert p["startpoint"] == "u_reg_a/_2_" and p["endpoint"] == "u_reg_b/_3_"
    assert p["arrival"] == 3.874 and p["required"] == 9.816 and p["slack"] == 5.942
    # the combinational cells on the path, two memory read stand-ins among them
    assert p["cells"] == ["PST_MEMRD_0", "XOR2X1", "PST_MEMRD_0", "XNOR2X1", "OAI21X1", "AOI21X1", "XNOR2X1"]
    assert paths[1]["start_kind"] == "input port clocked by clk"
    assert paths[1]["cells"] == []
    assert p["through"] == ["(top)"]


def test_parse_groups():
    g = sta.parse_groups((FIX / "opensta_groups.txt").read_text())
    assert g["pst_g2"] == {"key": "u_reg_b", "instance": "u_reg_b", "module": "pst_pipe_reg"}
    assert g["pst_g0"]["key"] == "(top)"


def test_fmax():
    assert sta.fmax_mhz(10.0, 0.0) == pytest.approx(100.0)
    assert sta.fmax_mhz(10.0, -15.0) == pytest.approx(40.0)
    assert sta.fmax_mhz(10.0, 5.0) == pytest.approx(200.0)
    with pytest.raises(ValueError):
        sta.fmax_mhz(10.0, 10.0)


def test_sdc_period_of_the_checked_in_sdc():
    assert sta.sdc_period((SCRIPTS / "synth" / "pst.sdc").read_text()) == 10.0


def test_standin_techmap_names_match_the_rename():
    """The techmap's read-port instance names are what flow.rename_standins expects."""
    text = (SCRIPTS / "synth" / "mem_standin_map.v").read_text()
    assert re.search(r"begin : rd\b", text) and "PST_MEMRD cell" in text


def test_ram_model():
    ram = {"size": 256, "width": 32, "abits": 8, "read_ports": 3, "write_ports": 1}
    m = memarea.ram_model(ram)
    assert m["sram_area_um2"] == pytest.approx(3 * 8192 * 13.5 / 0.5)
    # the flip-flop fit (the area counted) reproduces the two syntheses it came from within 0.1 %
    assert m["area_um2"] == pytest.approx(2527668, rel=1e-3)
    assert memarea.ram_model(dict(ram, read_ports=2))["area_um2"] == pytest.approx(2114172, rel=1e-3)
    assert m["delay_ns"] == pytest.approx(1.652)


NETLIST = r"""module \$paramod$ab\pst_pipe_reg (clk_i, d_i, q_o);
  DFFPOSX1 _3_ (
    .CLK(clk_i),
    .D(d_i[0]),
    .Q(q_o[0])
  );
endmodule

module pst_top(clk_i);
  DFFPOSX1 _7_ (
    .CLK(clk_i),
    .D(_1_),
    .Q(_2_)
  );
  \$paramod$ab\pst_pipe_reg  u_reg_b (
    .clk_i(clk_i)
  );
endmodule
"""


def test_register_names_from_the_netlist():
    mods = sta.netlist_instances(NETLIST)
    assert mods["pst_top"]["u_reg_b"] == ("$paramod$ab\\pst_pipe_reg", None)
    assert sta.register_name("u_reg_b/_3_", mods, "pst_top") == "u_reg_b/_3_ (q_o[0])"
    assert sta.register_name("_7_", mods, "pst_top") == "_7_"          # private net: no name
    assert sta.register_name("rst_ni", mods, "pst_top") == "rst_ni"


def test_synth_cli_rejects_a_bad_profile_before_any_tool_runs(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((SCRIPTS.parent / "rtl" / "configs" / "reduced.toml").read_text().replace(
        "octaves = 5", "octaves = 99"))
    out = tmp_path / "out"
    r = subprocess.run(["/usr/bin/python3", str(SCRIPTS / "synth.py"), str(bad), "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert re.fullmatch(rf"error: {re.escape(str(bad))}:\d+: pipeline.octaves: .*\n", r.stderr)
    assert not out.exists()
