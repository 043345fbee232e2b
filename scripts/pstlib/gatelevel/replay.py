"""Gate-level simulation with Icarus Verilog: the netlist replays the RTL's own port trace.

Why a second simulator: Verilator compiles the netlist into a model whose optimizations decide
what it computes (Verilator 5.006's bit-op-tree folding mis-evaluates OSU018 XOR trees unless it
is turned off: docs/VERIFICATION.md "The netlist against the RTL"); Icarus Verilog, an
event-driven simulator, evaluates the cells one by one. It is far slower (minutes for a 16 x 16
scene), so this check replays small scenes, not the harness's random regressions.

Steps: the RTL model of PROFILE (the `pst` tool of the main build) renders SCENE with a port
trace (`pst render --trace`); every input of pst_top at every half clock is written to a stimulus
file and every output beside it; a generated test bench drives the netlist (NAME_gl.v of the model
folder, its memories as behavioural models) with the same inputs, the cell models' flip-flops
starting at 0 like the verilated RTL's, and writes the netlist's outputs; the two are compared:
the handshake outputs (out_valid_o, frag_ready_o, idle_o) on every half clock after reset, the
payload (out_tag_o, out_rgba_o, out_f_o, out_grad_o, out_w_o) wherever out_valid_o is 1. The RTL
equals the golden model bit for bit on the same scene (`pst regress`), so a netlist equal to the
RTL's ports equals the golden model too. The probes are left out (DebugProbes is 0 in synthesis).
"""
import json
import pathlib
import re
import shutil
import subprocess
import time

from .. import atomic
from ..paths import ROOT
from ..power import activity

HANDSHAKE = ("out_valid_o", "frag_ready_o", "idle_o")
PAYLOAD = ("out_tag_o", "out_rgba_o", "out_f_o", "out_grad_o", "out_w_o")


class ReplayError(RuntimeError):
    pass


def ports(netlist: pathlib.Path) -> dict:
    """pst_top's ports of the netlist: name -> (direction, width)."""
    out = {}
    inside = False
    with open(netlist) as f:
        for line in f:
            if line.startswith("module pst_top"):
                inside = True
                continue
            if not inside:
                continue
            m = re.match(r"\s*(input|output)\s+(?:wire\s+|reg\s+)?(?:\[(\d+):(\d+)\]\s+)?(\w+)\s*;", line)
            if m:
                w = int(m.group(2)) - int(m.group(3)) + 1 if m.group(2) else 1
                out[m.group(4)] = (m.group(1), w)
            elif line.startswith("endmodule"):
                break
    if "clk_i" not in out:
        raise ReplayError(f"{netlist}: no pst_top ports found")
    return out


def read_vcd_top(vcd: pathlib.Path, names) -> list:
    """Values of NAMES (top-scope signals) at every time step of VCD: a list of dicts (ints; x/z as
    None)."""
    code = {}
    depth, cur, rows, t = 0, {}, [], None
    with open(vcd) as f:
        for line in f:
            if line.startswith("$scope"):
                depth += 1
            elif line.startswith("$upscope"):
                depth -= 1
            elif line.startswith("$var"):
                p = line.split()
                if depth == 1 and p[4] in names:
                    code.setdefault(p[3], p[4])
            elif line.startswith("#"):
                if t is not None:
                    rows.append(dict(cur))
                t = int(line[1:])
            elif line[:1] in ("b", "B"):
                v, c = line[1:].split()
                if c in code:
                    cur[code[c]] = None if re.search("[xzXZ]", v) else int(v, 2)
            elif line[:1] in ("0", "1", "x", "z", "X", "Z"):
                c = line[1:].strip()
                if c in code:
                    cur[code[c]] = None if line[0] in "xzXZ" else int(line[0])
    rows.append(dict(cur))
    return rows


def testbench(pins: dict, inputs: list, outputs: list) -> str:
    """A test bench that reads stim.txt (one line per half clock: the inputs in hex, clk_i first),
    applies the inputs, then the clock, and writes the outputs to got.txt."""
    decl = [f"  reg [{pins[n][1] - 1}:0] {n};" for n in inputs]
    decl += [f"  wire [{pins[n][1] - 1}:0] {n};" for n in outputs]
    conn = ", ".join(f".{n}({n})" for n in inputs + outputs)
    rest = [n for n in inputs if n != "clk_i"]
    fmt = " ".join(["%h"] * len(inputs))
    return "\n".join([
        "`timescale 1ns/1ps", "module pst_gl_replay_tb;", *decl, "  reg clk_q;", "  integer fi, fo, r;",
        f"  pst_top dut({conn});", "  initial begin",
        '    fi = $fopen("stim.txt", "r"); fo = $fopen("got.txt", "w"); clk_i = 0;',
        "    while (!$feof(fi)) begin",
        f'      r = $fscanf(fi, "{fmt}\\n", clk_q, {", ".join(rest)});',
        "      #0.3 clk_i = clk_q;",
        f'      #0.6 $fwrite(fo, "{" ".join(["%h"] * len(outputs))}\\n", {", ".join(outputs)});',
        "      #0.1;", "    end", "    $fclose(fo); $finish;", "  end", "endmodule", ""])


def zero_init_cells(cells_v: str) -> str:
    """The cell models with every flip-flop and latch starting at 0, as the verilated RTL's do
    (pstlib/gatelevel/cells.py writes the UDPs as modules with `output reg out`)."""
    text, n = re.subn(r"(module udp_(?:dff|tlat|rslat) \(output reg out[^;]*;)", r"\1\n  initial out = 1'b0;", cells_v)
    if n == 0:
        raise ReplayError("cell models: no udp_dff/udp_tlat/udp_rslat module to initialize")
    return text


class Refused(ReplayError):
    """The RTL's `pst render` refused the scene for this profile (exit 2: a feature the profile lacks)."""


def run(pst: pathlib.Path, profile: str, models: pathlib.Path, model: str, scene: pathlib.Path, size: int,
        work: pathlib.Path, timeout: int = 3600, gap_rate: float = 0.0, stall_rate: float = 0.0,
        sim_seed: int = 1) -> dict:
    """The replay of SCENE at SIZE x SIZE, the RTL run with GAP_RATE input gaps and STALL_RATE output
    stalls (seed SIM_SEED: the trace holds them, so the netlist sees the same); the result as a dict
    (also WORK/replay.json)."""
    for tool in ("iverilog", "vvp", "fst2vcd"):
        if not shutil.which(tool):
            raise ReplayError(f"{tool}: not found (scripts/setup.sh installs iverilog and gtkwave)")
    models, work, scene, pst = models.resolve(), work.resolve(), scene.resolve(), pst.resolve()
    netlist = models / f"{model}.v"
    if not netlist.exists():
        raise ReplayError(f"{netlist}: no such netlist (scripts/gatelevel.py writes it)")
    work.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    fst = work / "rtl.fst"
    r = subprocess.run([str(pst), "render", str(scene), "--size", str(size), "--profile", profile, "--trace",
                        str(fst), "-o", str(work / "render"), "-q", "--gap-rate", str(gap_rate), "--stall-rate",
                        str(stall_rate), "--sim-seed", str(sim_seed)], capture_output=True, text=True, cwd=ROOT)
    if r.returncode == 2:
        raise Refused(f"pst render {scene.name} --profile {profile}: refused ({r.stderr.strip().splitlines()[-1:]})")
    if r.returncode or not fst.exists():
        raise ReplayError(f"pst render --trace: exit {r.returncode}\n{r.stderr[-1500:]}")
    vcd = work / "rtl.vcd"
    try:
        activity.fst_to_vcd(fst, vcd)
    except RuntimeError as e:
        raise ReplayError(str(e)) from None
    pins = ports(netlist)
    inputs = ["clk_i"] + sorted(n for n, (d, _) in pins.items() if d == "input" and n != "clk_i")
    outputs = sorted(n for n, (d, _) in pins.items() if d == "output" and not n.startswith("probe_"))
    rows = read_vcd_top(vcd, set(inputs + outputs))
    if any(r.get(n) is None for r in rows[1:] for n in inputs):
        raise ReplayError("the RTL trace has an unknown input value")
    (work / "stim.txt").write_text("".join(" ".join(format(r.get(n) or 0, "x") for n in inputs) + "\n" for r in rows))
    (work / "tb.v").write_text(testbench(pins, inputs, outputs))
    cells = work / "cells_zero.v"
    cells.write_text(zero_init_cells((models / "osu018_cells.v").read_text()))
    t1 = time.time()
    r = subprocess.run(["iverilog", "-g2012", "-o", str(work / "sim.vvp"), "-s", "pst_gl_replay_tb", str(work / "tb.v"),
                        str(cells), str(netlist)], capture_output=True, text=True)
    if r.returncode:
        raise ReplayError(f"iverilog: exit {r.returncode}\n{r.stderr[-2000:]}")
    t2 = time.time()
    r = subprocess.run(["vvp", "-n", str(work / "sim.vvp")], capture_output=True, text=True, cwd=work, timeout=timeout)
    if r.returncode:
        raise ReplayError(f"vvp: exit {r.returncode}\n{r.stderr[-2000:]}")
    t3 = time.time()
    got = [line.split() for line in (work / "got.txt").read_text().splitlines()]
    if len(got) != len(rows):
        raise ReplayError(f"the netlist ran {len(got)} half clocks of {len(rows)}")
    res = compare(rows, got, outputs)
    res.update({"profile": profile, "model": model, "scene": str(scene), "size": size, "half_clocks": len(rows),
                "gap_rate": gap_rate, "stall_rate": stall_rate, "sim_seed": sim_seed,
                "seconds": {"trace": round(t1 - t0, 1), "compile": round(t2 - t1, 1), "simulate": round(t3 - t2, 1)},
                "simulator": subprocess.run(["iverilog", "-V"], capture_output=True, text=True).stdout.splitlines()[0]})
    atomic.write_text(work / "replay.json", json.dumps(res, indent=1) + "\n")
    return res


def compare(rows: list, got: list, outputs: list) -> dict:
    """The netlist's outputs (GOT, hex strings per half clock) against the RTL's (ROWS)."""
    col = {n: i for i, n in enumerate(outputs)}
    start = next((i for i, r in enumerate(rows) if r.get("rst_ni") == 1), len(rows))
    checked, pixels, bad, first = 0, 0, 0, None

    def val(s):
        return None if re.search("[xzXZ]", s) else int(s, 16)

    for i in range(start, len(rows)):
        names = [n for n in HANDSHAKE if n in col]
        if rows[i].get("out_valid_o") == 1:
            names += [n for n in PAYLOAD if n in col]
            if rows[i].get("clk_i") == 1 and rows[i].get("out_ready_i") == 1:
                pixels += 1
        for n in names:
            checked += 1
            if val(got[i][col[n]]) != rows[i].get(n):
                bad += 1
                if first is None:
                    first = {"half_clock": i, "output": n, "rtl": rows[i].get(n), "netlist": got[i][col[n]]}
    return {"compared": checked, "outputs_taken": pixels, "mismatches": bad, "first": first,
            "passed": bad == 0 and checked > 0}
