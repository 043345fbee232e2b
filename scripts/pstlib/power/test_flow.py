"""flow.run on a two-module OSU018 netlist through Debian's OpenSTA: per-cell activity from the
trace, the linear model, the groups and blocks."""
import shutil

import pytest

from pstlib.power import activity, figures, flow
from pstlib.synth import liberty

NETLIST = r"""module pst_leaf (clk_i, d_i, q_o);
  input clk_i;
  input d_i;
  output q_o;
  wire n;
  DFFPOSX1 _1_ (
    .CLK(clk_i),
    .D(d_i),
    .Q(n)
  );
  INVX1 _2_ (
    .A(n),
    .Y(q_o)
  );
endmodule
module pst_top (clk_i, rst_ni, a_i, y_o);
  input clk_i;
  input rst_ni;
  input a_i;
  output y_o;
  pst_leaf u_leaf (
    .clk_i(clk_i),
    .d_i(a_i),
    .q_o(y_o)
  );
endmodule
"""

needs_tools = pytest.mark.skipif(liberty.osu018_lib() is None or shutil.which("sta") is None,
                                 reason="scripts/setup.sh installs OpenSTA and the OSU018 library")


def run(tmp_path, a_q: float):
    (tmp_path / "netlist_sta.v").write_text(NETLIST)
    (tmp_path / "standin.lib").write_text(liberty.standin_liberty({}, 0.1, 0.01))
    act = activity.Activity(cycles=100, window=200, rates={
        "a_i": [(0.2, 0.5)], "u_leaf/q_o": [(a_q, 0.5)], "u_leaf/d_i": [(0.2, 0.5)]},
        lsb={})
    lib = liberty.osu018_lib()
    return flow.run(tmp_path, act, [str(lib)], liberty.cell_areas(lib.read_text()))


@needs_tools
def test_power_follows_the_traced_activity(tmp_path):
    p0 = run(tmp_path, 0.0)
    p1 = run(tmp_path, 0.5)
    p2 = run(tmp_path, 1.0)
    assert p0.port_driven_cells == 1 and p0.cells == 2 and p0.traced_bits == 3
    # the inverter drives u_leaf/q_o: its dynamic power grows linearly with that activity
    c = [p.groups["Combinational"] for p in (p0, p1, p2)]
    assert c[1][3] > c[0][3]
    assert c[2][3] - c[1][3] == pytest.approx(c[1][3] - c[0][3], rel=1e-6)
    # the flop clocks whatever its data does: its clock pin's internal power is there at 0
    assert p0.groups["Sequential"][0] > 0
    assert set(p1.blocks) == {"leaf"}
    assert p1.blocks["leaf"][3] == pytest.approx(p1.groups["Total"][3])


def test_energy_per_pixel_and_real_time():
    pw = flow.Power(groups={"Sequential": (0.01, 0.0, 0.0, 0.01), "Combinational": (0.02, 0.01, 1e-6, 0.030001),
                            "Total": (0.03, 0.01, 1e-6, 0.040001)},
                    blocks={"x": (0.03, 0.01, 1e-6, 0.040001)}, comb_area_um2=3e4, traced_bits=1, missing_bits=0,
                    port_driven_cells=1, cells=2, period_ns=10.0)
    row = figures.workload_figures(pw, cycles=1000, pixels=100, rom_area_um2=1e4)
    # ROM model: 1e4 um^2 at the combinational density 0.03 W / 3e4 um^2
    assert row["memory_model_w"] == pytest.approx(0.01)
    # (0.04 + 0.01 W dynamic + 1 uW) over 1000 clocks of 10 ns, 100 pixels
    assert row["pj_per_pixel"] == pytest.approx((0.05 + 1e-6) * 1e-5 / 100 * 1e12)
    s = figures.profile_figures({"w": row}, {"clocks_per_pixel": 10, "fmax_mhz": 200.0})
    assert s["mw_at_fmax"] == pytest.approx((0.05 * 2 + 1e-6) * 1e3)
    # 36.9 Mpixel/s x 10 clocks = 369 MHz: two copies at 200 MHz
    assert s["realtime_copies"] == 2
    assert s["mw_at_realtime"] == pytest.approx((0.05 / 100e6 * 10 * 36.9e6 + 2e-6) * 1e3)


def test_ram_read_ports_modelled_like_roms():
    from pstlib.synth import memarea
    pw = flow.Power(groups={"Sequential": (0.01, 0.0, 0.0, 0.01), "Combinational": (0.02, 0.01, 0.0, 0.03),
                            "Total": (0.03, 0.01, 0.0, 0.04)},
                    blocks={"x": (0.03, 0.01, 0.0, 0.04)}, comb_area_um2=3e4, traced_bits=1, missing_bits=0,
                    port_driven_cells=1, cells=2, period_ns=10.0)
    ram = {"instances": 2, "size": 256, "width": 32, "read_ports": 3}
    area = memarea.ram_read_area_um2(ram)
    # the read multiplexers only: bits x ports x the per-bit-port area, every instance; no storage
    assert area == pytest.approx(2 * 256 * 32 * 3 * memarea.FLOP_RAM_UM2_PER_BIT_PORT)
    assert area < 2 * memarea.ram_model(dict(ram, abits=8))["area_um2"]
    row = figures.workload_figures(pw, cycles=1000, pixels=100, rom_area_um2=1e4, ram_read_area_um2=2e4)
    assert row["rom_model_w"] == pytest.approx(0.01)
    assert row["ram_model_w"] == pytest.approx(0.02)
    assert row["memory_model_w"] == pytest.approx(0.03)
    s = figures.profile_figures({"w": row}, {"clocks_per_pixel": 10, "fmax_mhz": 200.0})
    assert s["ram_model_share"] == pytest.approx(0.02 / 0.07)
    # the profile's page says which: the RAMs' read ports modelled (--ram-reads) or listed as not
    s["rams_modelled"] = "m.ram (256 x 32, 3 read ports)"
    md = figures.markdown("p", s, {"w": row}, "method")
    assert "of which the RAMs' read ports | 29 % (m.ram" in md and "ROMs and the RAMs' read ports" in md
    del s["rams_modelled"]
    s["rams_not_modelled"] = "m.ram (256 x 32, 3 read ports)"
    assert "RAMs (not modelled; --ram-reads models their read ports) | m.ram" in figures.markdown("p", s, {"w": row}, "m")
