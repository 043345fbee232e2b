"""The step driver of pstlib/pnr/qflow.py: resume, and the retries when qrouter leaves nets
unrouted: pins placed from the cells first, then lower densities (the steps themselves
replaced by stand-ins; the placement stand-in writes a small placed DEF)."""
import json

import pytest

from pstlib.pnr import qflow
from pstlib.pnr.test_pins import DEF


@pytest.fixture
def project(tmp_path, monkeypatch):
    (tmp_path / "log").mkdir()
    (tmp_path / "layout").mkdir()
    (tmp_path / "layout" / "blk.par").write_text("*padspacing           : variable\n*minimum_pad_space    : 120\n")
    (tmp_path / "project_vars.sh").write_text("set initial_density = 0.70\n")
    calls = []
    fails = {"route": 2}

    def step(name):
        def run(p):
            calls.append((name, qflow.density(p)))
            if name == "place":
                (p.layout / "blk.def").write_text(DEF)
            if fails.get(name, 0):
                fails[name] -= 1
                raise qflow.Unrouted("nets left")
            return 1.0
        return run
    monkeypatch.setattr(qflow, "STEPS", [(n, step(n)) for n in ("synthesize", "place", "route", "drc")])
    return qflow.Project(tmp_path, "blk"), calls, fails


def test_unrouted_block_is_placed_again_less_dense_with_pins_from_cells(project):
    p, calls, _ = project
    times = qflow.run_steps(p)
    assert [c[0] for c in calls] == ["synthesize", "place", "route", "place", "route", "place", "route", "drc"]
    # Each retry less dense, with the pins placed from the cells.
    assert [c[1] for c in calls if c[0] == "place"] == [0.7, 0.6, 0.5]
    assert times["density"] == 0.5 and (p.path / "log" / "drc.done").exists()
    assert "restrict side L" in (p.layout / "blk.cel2").read_text()
    assert "*minimum_pad_space    : 0\n" in (p.layout / "blk.par").read_text()
    tries = json.loads((p.log / "pins.json").read_text())
    assert [t["density"] for t in tries] == [0.7, 0.6] and tries[0]["hinted"] == 4


def test_resume_skips_finished_steps(project):
    p, calls, fails = project
    fails["route"] = 0
    qflow.run_steps(p)
    (p.path / "log" / "drc.done").unlink()
    calls.clear()
    qflow.run_steps(p, resume=True)
    assert [c[0] for c in calls] == ["drc"]


def test_gives_up_below_the_least_density(project):
    p, _, fails = project
    fails["route"] = 10
    with pytest.raises(qflow.Unrouted):
        qflow.run_steps(p)
    assert qflow.density(p) == pytest.approx(0.4)


def test_spice_ports_rewritten_from_the_blif():
    # blif2BSpice's header for a large block: one long name cut in pieces and garbled bytes.
    spc = (b"*SPICE netlist\n.include cells.sp\n.subckt blk vdd gnd clk_i u.o \xc2\xb5`\xc2\xae ct_o_i[97] y\n"
           b"XINVX1_1 vdd gnd clk_i y INVX1\n.ends\n")
    blif_text = ".model blk\n.inputs clk_i u.oct_o_i[97]\n.outputs y\n.gate INVX1 A=clk_i Y=y\n.end\n"
    out = qflow.spice_ports(spc, qflow.blif_ports(blif_text))
    assert out.split(b"\n")[2] == b".subckt blk vdd gnd clk_i u.oct_o_i[97] y"
    # Only the header changes.
    assert out.split(b"\n")[3:] == spc.split(b"\n")[3:] and out.split(b"\n")[:2] == spc.split(b"\n")[:2]


def test_spice_without_subckt_is_an_error():
    with pytest.raises(qflow.FlowError, match="subckt"):
        qflow.spice_ports(b"* nothing\n", ["a"])
