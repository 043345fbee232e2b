#!/usr/bin/python3
"""Silicon figures of one hardware profile: Yosys 0.23 synthesis of pst_top to the OSU 0.18 um
standard cells (Debian's qflow-tech-osu018), OpenSTA timing, memory area, throughput.

    scripts/synth.py PROFILE [--out DIR] [--rom-dir DIR] [--no-sta] [--no-old-basis] [--jobs N]

PROFILE is a name (rtl/configs/NAME.toml) or a profile file. Writes DIR/NAME.json and
DIR/NAME.md (default DIR: out/synth) and prints the Markdown. Exit 2 on bad input (no such
profile, no ROM images, no OSU018 library: run scripts/setup.sh), 1 when a tool fails.

Method (the Markdown repeats it beside the figures):
- Hierarchical synthesis: every module is synthesized once per parameter set and counted once
  per instance, so the eight identical noise units of `full` cost one synthesis.
- Mapping: one netlist for area and timing. ABC maps each module's logic for area (`map -a`),
  then buffers fanout (`buffer -p`: an unbuffered netlist cannot be timed, one gate would
  drive picofarads) and sizes gates against the 10 ns target (`upsize`, `dnsize`; ABC sees
  module ports as driven by BUFX2 and loaded by 0.02 pF). The area includes those buffers.
- Fanout buffers across the hierarchy (scripts/pstlib/fanout.py): ABC buffers the nets inside
  one module only, so a net leaving a module into many sub-module instances (the octave
  stage's stall enable into 32 sub-modules and on to their registers) would be one gate
  driving picofarads. Standing in for a back end's high-fanout repair (repair_design), every
  net of a module into the input ports of >= fanout.MIN_INSTANCES sub-module instances gets
  one fanout.CELL (BUFX4) in front of each such instance, in the netlist that is timed and
  counted (area in the module holding it; the report has a row with their number).
  Flip-flops: asynchronous resets become logic (`async2sync`), every flop a DFFPOSX1.
- GE = cell area / NAND2X1 area (24 um^2). The old basis (scripts/synth/cells.lib, a
  21-cell generic library written by hand, ABC's fast delay mapping) is kept as a second
  column for one release; its GE are not comparable with a real library's.
- Memories stay memories (`memory -nomap`), outside the logic. Each distinct ROM is
  synthesized alone to OSU018 cells with one read port (cached by content in
  out/synth/memories/, --mem-cache)
  and counted once per read port (replication); OpenSTA gives its address-to-data delay
  (inputs driven by BUFX2, outputs loaded with 0.02 pF). RAMs: a per-bit SRAM-macro model per
  read port (scripts/pstlib/memarea.py says where its numbers come from).
- Timing: in the design's netlist every memory read bit is a stand-in cell with that delay
  (scripts/synth/mem_standin_map.v), every memory write bit a capture cell with a setup
  check; OpenSTA 2.0.17 links the hierarchical netlist flat and reads scripts/synth/pst.sdc.
  Every register is in the path group of its top-level block: the worst path per block is
  the critical path of that stage. Fmax = 1 / (period - worst slack).
- Logic depth: `ltp -noff` per module on the mapped netlist (cells on the longest
  combinational path; a sub-module instance counts as one cell).
- Yosys runs with -e "implicitly declared|has no driver" so a silent mis-build fails.
"""
import argparse
import concurrent.futures
import hashlib
import json
import pathlib
import re
import subprocess
import sys
import tempfile
import time
import tomllib

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
from pstlib import contract, fanout, liberty, memarea, sta  # noqa: E402

SYNTH_DIR = ROOT / "scripts" / "synth"
OLD_LIB = SYNTH_DIR / "cells.lib"
SDC = SYNTH_DIR / "pst.sdc"
STANDIN_MAP = SYNTH_DIR / "mem_standin_map.v"
STANDIN_CELLS = SYNTH_DIR / "mem_standin_cells.v"
# ABC: area mapping, then fanout buffering and sizing against the delay target (ps).
ABC_SCRIPT = "+strash;dretime;map,-a;topo;buffer,-p;upsize,{D};dnsize,{D}"
ABC_DELAY_PS = 10000
ABC_CONSTR = "set_driving_cell BUFX2\nset_load 0.02\n"
MEM_LOAD_PF = 0.02        # stand-alone memory: output load; stand-in: address-pin load
MEM_SETUP_NS = 0.2        # stand-in write capture: setup (about DFFPOSX1's)
REALTIME_MPIX = 640 * 480 * 60 * 2 / 1e6   # 640 x 480, 60 Hz, depth complexity 2
PAPER_GATES = {"reduced": 100_000, "full": 1_250_000}

# Module (base name) -> block of the report.
BLOCKS = {
    "pst_quadric": "quadric",
    "pst_quadric_serial": "quadric",
    "pst_octave_transform": "noise",
    "pst_noise": "noise",
    "pst_noise_weight": "noise",
    "pst_noise_corner": "noise",
    "pst_noise_lerp": "noise",
    "pst_octave_term": "octave accumulation",
    "pst_filter_width": "gradient and filter width",
    "pst_isqrt": "gradient and filter width",
    "pst_clut_filter": "colour-table filter",
    "pst_width_stage": "gradient and filter width",
    "pst_colour_stage": "colour-table filter",
    "pst_octave_stage": "control",
    "pst_regs": "control",
    "pst_pipe_reg": "control",
    "pst_top": "control",
}
# A module not named above (pst_delay: pipeline registers, pst_pipe_flow, pst_floor_sat,
# pst_mul_booth, ...)
# is counted in the block of the instance that holds it.
BLOCK_ORDER = ["quadric", "noise", "octave accumulation", "gradient and filter width",
               "colour-table filter", "control"]
# Path-group key (top-level block) -> pipeline stage it ends in.
STAGE_OF = {
    "u_reg_a": "[A] input register",
    "(top)": "octave stage [A] -> [B] (sequencer, accumulators)",
    "pst_quadric": "octave stage [A] -> [B] (quadric)",
    "pst_quadric_serial": "octave stage [A] -> [B] (quadric)",
    "pst_octave_transform": "octave stage [A] -> [B] (octave transform)",
    "pst_noise": "octave stage [A] -> [B] (noise unit)",
    "pst_octave_term": "octave stage [A] -> [B] (octave term)",
    "pst_octave_stage": "octave stage [A] -> [B]",
    "pst_width_stage": "filter width [B] -> [C]",
    "pst_colour_stage": "colour-table filter [C] -> [D]",
    "u_reg_b": "octave stage [A] -> [B] (into [B])",
    "pst_step_counter": "serial step counters",
    "pst_filter_width": "filter width [B] -> [C]",
    "u_reg_c": "filter width [B] -> [C] (into [C])",
    "pst_clut_filter": "colour-table filter [C] -> [D]",
    "u_reg_d": "colour-table filter [C] -> [D] (into [D])",
}


def profile_path(name: str) -> pathlib.Path:
    p = pathlib.Path(name)
    if p.suffix == ".toml" or "/" in name:
        return p
    return ROOT / "rtl" / "configs" / f"{name}.toml"


def base_name(module: str) -> str:
    m = re.search(r"(pst_[A-Za-z0-9_]+)", module)
    return m.group(1) if m else module.lstrip("\\")


def sha(path: pathlib.Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()[:16]


def tool_version(cmd: list) -> str:
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, input="exit\n", timeout=60)
        return (r.stdout or r.stderr).strip().splitlines()[0]
    except (OSError, IndexError, subprocess.SubprocessError):
        return "unknown"


def abc_line(lib: pathlib.Path, constr: pathlib.Path) -> str:
    return f"abc -liberty {lib} -constr {constr} -D {ABC_DELAY_PS} -script {ABC_SCRIPT}"


def yosys_script(profile: pathlib.Path, rom_dir: pathlib.Path, lib: pathlib.Path, tmp: pathlib.Path,
                 old_basis: bool) -> str:
    params = subprocess.run(["/usr/bin/python3", str(ROOT / "scripts" / "profile.py"), str(profile), "--yosys"],
                            check=True, capture_output=True, text=True).stdout.split("\n")
    chparams = [f"{line} pst_top" for line in params if line.strip()]
    sources = " ".join(str(p) for p in sorted((ROOT / "rtl").glob("*.sv")))
    lines = [
        f"read_liberty -lib {lib}",  # cell port directions, for ltp
        f"read_verilog -lib {STANDIN_CELLS}",
        f'read_verilog -sv -D SYNTHESIS -D PST_ROM_DIR="{rom_dir}" {sources}',
        *chparams,
        "chparam -set DebugProbes 0 pst_top",
        "hierarchy -check -top pst_top",
        # Coarse synthesis with memories kept as $mem cells.
        "synth -top pst_top -run :fine",
        # The memories' shapes and contents for the memory table and their own synthesis.
        f"tee -q -o {tmp}/mem.txt select -list t:$mem_v2",
        f"tee -q -a {tmp}/mem.txt dump t:$mem_v2",
        "opt -fast -full",
        # Memories -> timing stand-ins (no area).
        f"techmap -map {STANDIN_MAP} t:$mem_v2",
        "techmap",
        "opt -fast",
        "async2sync",
        "dfflegalize -cell $_DFF_P_ 01",
        "design -save generic",
        abc_line(lib, tmp / "abc.constr"),
        "opt_clean -purge",
        # Depth before the flops become library cells: ltp -noff skips the internal $_DFF_P_
        # cells, so a path ends at a register (a library DFF would be walked through).
        f"tee -q -o {tmp}/ltp.txt ltp -noff",
        f"dfflibmap -liberty {lib}",
        "opt_clean -purge",
        f"tee -q -o {tmp}/stat.json stat -json",
        "rename -enumerate",
        f"write_verilog -noattr -simple-lhs {tmp}/netlist.v",
    ]
    if old_basis:
        lines += [
            "design -load generic",
            f"abc -fast -liberty {OLD_LIB}",
            "opt_clean -purge",
            f"dfflibmap -liberty {OLD_LIB}",
            "opt_clean -purge",
            f"tee -q -o {tmp}/stat_old.json stat -json",
        ]
    return "\n".join(lines) + "\n"


def parse_stat_json(text: str) -> dict:
    """Yosys 0.23's `stat -json` prints the hierarchy as plain text inside its "design"
    section when the design has sub-modules; only the "modules" section is used here, so the
    text is cut after it."""
    end = text.find("\n   },\n")
    return json.loads(text if end < 0 else text[:end] + "\n   }\n}\n")


def run_yosys(yosys: str, script: str, tmp: pathlib.Path, tag: str) -> float:
    path = tmp / f"{tag}.ys"
    path.write_text(script)
    t0 = time.time()
    run = subprocess.run([yosys, "-q", "-e", "implicitly declared|has no driver", "-l", str(tmp / f"{tag}.log"),
                          "-s", str(path)], capture_output=True, text=True)
    if run.returncode != 0:
        log = tmp / f"{tag}.log"
        tail = "\n".join(log.read_text().splitlines()[-30:]) if log.exists() else ""
        raise RuntimeError(f"yosys ({tag}) failed:\n{tail}\n{run.stderr}")
    return time.time() - t0


def run_sta(sta_bin: str, script: str, tmp: pathlib.Path, tag: str) -> tuple:
    path = tmp / f"{tag}.tcl"
    path.write_text(script)
    t0 = time.time()
    run = subprocess.run([sta_bin, "-no_init", "-no_splash", "-exit", str(path)], capture_output=True, text=True)
    if run.returncode != 0 or "Error" in run.stdout or "Error" in run.stderr:
        raise RuntimeError(f"OpenSTA ({tag}) failed:\n{run.stdout[-3000:]}\n{run.stderr[-3000:]}")
    return time.time() - t0, run.stdout


# ---- hierarchy and blocks ------------------------------------------------------------------

def block_instances(subs: dict, top: str) -> dict:
    """(derived module, block, holder) -> instances in the flattened design. A module named in
    BLOCKS is in that block; any other (pst_delay, pst_mul_booth, ...) in its holder's block.
    holder: the base name of the nearest enclosing module named in BLOCKS (None for the top)."""
    count = {}

    def walk(name: str, k: int, block: str, holder) -> None:
        own = base_name(name)
        b = BLOCKS.get(own, block)
        count[(name, b, holder)] = count.get((name, b, holder), 0) + k
        inner = own if own in BLOCKS else holder
        for sub, n in subs[name].items():
            walk(sub, k * n, b, inner)
    walk(top, 1, "control", None)
    return count


def analyse(stat: dict, ltp_text: str, areas: dict, ff_cells: set, mems: list) -> dict:
    modules = stat["modules"]
    own = {}
    for name, m in modules.items():
        cells = m.get("num_cells_by_type", {})
        logic = sum(n * areas[c] for c, n in cells.items() if c in areas)
        ffs = sum(n for c, n in cells.items() if c in ff_cells)
        subs = {c: n for c, n in cells.items() if c in modules}
        own[name] = {"logic": logic, "ffs": ffs, "subs": subs,
                     "cells": sum(n for c, n in cells.items() if c in areas)}
    depth = {}
    for m in re.finditer(r"Longest topological path in (\S+) \(length=(\d+)\)", ltp_text):
        depth[m.group(1)] = int(m.group(2))

    subs = {name: v["subs"] for name, v in own.items()}
    top = next(n for n in modules if base_name(n) == "pst_top")
    held = block_instances(subs, top)
    blocks = {b: {"area": 0.0, "ffs": 0, "cells": 0, "modules": {}} for b in BLOCK_ORDER}
    for (name, b, holder), k in held.items():
        blocks[b]["area"] += k * own[name]["logic"]
        blocks[b]["ffs"] += k * own[name]["ffs"]
        blocks[b]["cells"] += k * own[name]["cells"]
        # A shared leaf (pst_mul_booth, pst_delay, ...) is listed per module holding it: "the
        # Booth products of the lerps" is the figure a designer acts on.
        label = base_name(name) if base_name(name) in BLOCKS or holder is None else f"{base_name(name)} in {holder}"
        entry = blocks[b]["modules"].setdefault(label, {"instances": 0, "area": 0.0, "depth": 0})
        entry["instances"] += k
        entry["area"] += k * own[name]["logic"]
        entry["depth"] = max(entry["depth"], depth.get(name.lstrip("\\"), depth.get(name, 0)))
    inst = {}
    for m in mems:
        inst[(m["module"], m["memory"])] = sum(k for (name, _, _), k in held.items()
                                               if name.lstrip("\\") == m["module"].lstrip("\\"))
    return {"blocks": blocks, "depth": depth, "held": held, "mem_instances": inst, "top": top}


# ---- memories ------------------------------------------------------------------------------

def mem_flow_salt(lib: pathlib.Path) -> str:
    return f"{ABC_SCRIPT}|{ABC_DELAY_PS}|{ABC_CONSTR}|{MEM_LOAD_PF}|{sha(lib)}|mem-flow-1"


def synth_memory(mem: dict, lib: pathlib.Path, cache: pathlib.Path, yosys: str, sta_bin: str,
                 areas: dict, ff_cells: set) -> dict:
    """One memory alone: OSU018 area and address-to-data delay (cached by content key)."""
    key = memarea.memory_key(mem, mem_flow_salt(lib))
    hit = cache / f"{key}.json"
    if hit.exists():
        rec = json.loads(hit.read_text())
        rec["cached"] = True
        return rec
    ports = memarea.synth_ports(mem)
    with tempfile.TemporaryDirectory(prefix="pst_mem_") as t:
        tmp = pathlib.Path(t)
        (tmp / "mem.v").write_text(memarea.memory_verilog(mem, ports))
        (tmp / "abc.constr").write_text(ABC_CONSTR)
        script = "\n".join([
            f"read_verilog {tmp}/mem.v",
            "synth -top pst_mem -flatten",
            "dfflegalize -cell $_DFF_P_ 01",
            abc_line(lib, tmp / "abc.constr"),
            "opt_clean -purge",
            f"dfflibmap -liberty {lib}",
            "opt_clean -purge",
            f"tee -q -o {tmp}/stat.json stat -json",
            f"write_verilog -noattr -simple-lhs {tmp}/net.v",
        ]) + "\n"
        secs = run_yosys(yosys, script, tmp, "mem")
        stat = parse_stat_json((tmp / "stat.json").read_text())
        cells = next(iter(stat["modules"].values()))["num_cells_by_type"]
        area = sum(n * areas[c] for c, n in cells.items() if c in areas)
        ffs = sum(n for c, n in cells.items() if c in ff_cells)
        clock = "create_clock -name clk -period 10 [get_ports clk]" if not memarea.is_rom(mem) else \
            "create_clock -name clk -period 10"
        tcl = "\n".join([
            f"read_liberty {lib}", f"read_verilog {tmp}/net.v", "link_design pst_mem", clock,
            "set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports clk -quiet]]",
            "set_driving_cell -lib_cell BUFX2 [delete_from_list [all_inputs] [get_ports clk -quiet]]",
            "set_output_delay 0 -clock clk [all_outputs]",
            f"set_load {MEM_LOAD_PF} [all_outputs]",
            f"report_checks -path_delay max -from [get_ports a*] -digits 3 > {tmp}/rep.txt",
            "exit"]) + "\n"
        ssecs, _ = run_sta(sta_bin, tcl, tmp, "mem")
        paths = sta.parse_checks((tmp / "rep.txt").read_text())
        if not paths or paths[0]["arrival"] is None:
            raise RuntimeError(f"memory {mem['memory']}: no address-to-data path in OpenSTA's report")
        rec = {"key": key, "ports_synthesized": ports, "area_um2": area, "cells": sum(cells.values()),
               "flip_flops": ffs, "delay_ns": paths[0]["arrival"], "yosys_seconds": round(secs, 1),
               "sta_seconds": round(ssecs, 1), "cached": False}
    cache.mkdir(parents=True, exist_ok=True)
    hit.write_text(json.dumps(rec, indent=1) + "\n")
    return rec


# ---- main ----------------------------------------------------------------------------------

def rename_standins(netlist: str, mem_index: dict) -> str:
    """PST_MEMRD cells -> PST_MEMRD_<k> by the memory their instance name starts with, in the
    module being written (mem_index: (module, memory cell) -> k)."""
    out = []
    module = None
    for line in netlist.splitlines(keepends=True):
        m = re.match(r"module\s+(\\\S+|[A-Za-z_][\w$]*)", line)
        if m:
            module = m.group(1).lstrip("\\")
        m = re.match(r"(\s*)PST_MEMRD (\\?)(\S+?)\.rd\[", line)
        if m:
            mem = m.group(3)
            k = mem_index.get((module, mem), mem_index.get((module, "\\" + mem)))
            if k is None:
                raise RuntimeError(f"stand-in {mem} in {module}: no such memory")
            line = line.replace("PST_MEMRD ", f"{liberty.standin_cell_name(k)} ", 1)
        out.append(line)
    return "".join(out)


def clocks_per_pixel(prof: dict) -> int:
    """The pipeline's clocks per pixel (the slowest stage: pstlib.contract.stage_cycles, the
    docs' cycle table; model/golden/profile.h cyclesPerPixel for the octave stage)."""
    return contract.stage_cycles(prof)["pixel"]


def regress_cpp(regress: pathlib.Path, name: str):
    """Measured clocks per pixel of `pst regress` (out/regress.json), max over scenes."""
    if not regress.exists():
        return None
    try:
        runs = [r for r in json.loads(regress.read_text()) if r.get("profile") == name]
    except (ValueError, AttributeError):
        return None
    return max((r["cycles_per_pixel"] for r in runs), default=None)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profile")
    ap.add_argument("--out", default=str(ROOT / "out" / "synth"))
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"))
    ap.add_argument("--regress", default=str(ROOT / "out" / "regress.json"),
                    help="pst regress output for the measured clocks per pixel")
    ap.add_argument("--yosys", default="yosys")
    ap.add_argument("--sta", default="sta")
    ap.add_argument("--no-sta", action="store_true", help="area only (no OpenSTA run)")
    ap.add_argument("--no-old-basis", action="store_true",
                    help="skip the cells.lib column (only the named profiles rtl/configs/*.toml get it)")
    ap.add_argument("--jobs", type=int, default=1, help="memory syntheses in parallel")
    ap.add_argument("--mem-cache", default=str(ROOT / "out" / "synth" / "memories"),
                    help="cache of the stand-alone memory syntheses (by content)")
    ap.add_argument("--keep", action="store_true", help="keep the netlists and tool logs in DIR/NAME.work/")
    ap.add_argument("--reuse", action="store_true", help=argparse.SUPPRESS)   # development: skip Yosys if kept
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args()

    profile = profile_path(args.profile)
    if not profile.exists():
        print(f"error: {profile}: no such profile", file=sys.stderr)
        return 2
    rom_dir = pathlib.Path(args.rom_dir)
    if not (rom_dir / "hash4096.memh").exists():
        print(f"error: {rom_dir}: no ROM images (build first: cmake --build build --target pst_rom_images)",
              file=sys.stderr)
        return 2
    lib = liberty.osu018_lib()
    if lib is None:
        print("error: OSU018 liberty not found (run scripts/setup.sh; looked in "
              + ", ".join(str(p) for p in liberty.osu018_candidates()) + ")", file=sys.stderr)
        return 2
    try:
        prof = tomllib.loads(profile.read_text())
    except tomllib.TOMLDecodeError as e:
        print(f"error: {profile}: {e}", file=sys.stderr)
        return 2
    name = profile.stem
    # The old basis is kept for one release for the named profiles only (a sweep point skips it).
    if profile.resolve().parent != (ROOT / "rtl" / "configs").resolve():
        args.no_old_basis = True
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lib_text = lib.read_text()
    areas = liberty.cell_areas(lib_text)
    ge = liberty.ge_unit(areas)
    ff_cells = liberty.flip_flop_cells(lib_text)
    old_text = OLD_LIB.read_text()
    old_areas = liberty.cell_areas(old_text)
    old_ff = liberty.flip_flop_cells(old_text)
    old_ge = old_areas["NAND2"]     # cells.lib is written in NAND2 units
    times = {}
    t_all = time.time()

    try:
        with tempfile.TemporaryDirectory(prefix=f"pst_synth_{name}_") as t:
            tmp = pathlib.Path(t)
            if args.keep:
                tmp = out / f"{name}.work"
                tmp.mkdir(exist_ok=True)
            (tmp / "abc.constr").write_text(ABC_CONSTR)
            if args.reuse and (tmp / "netlist.v").exists():
                times["yosys"] = 0.0
            else:
                times["yosys"] = run_yosys(args.yosys,
                                           yosys_script(profile, rom_dir, lib, tmp, not args.no_old_basis), tmp, "synth")
            stat = parse_stat_json((tmp / "stat.json").read_text())
            ltp_text = (tmp / "ltp.txt").read_text()
            mem_raw = (tmp / "mem.txt").read_text()
            mems = memarea.parse_memories(mem_raw)
            stat_old = parse_stat_json((tmp / "stat_old.json").read_text()) if not args.no_old_basis else None
            (out / f"{name}.ltp.txt").write_text(ltp_text)
            netlist = (tmp / "netlist.v").read_text()
            # Fanout buffers across the hierarchy (a back end's repair_design; ABC buffers inside
            # a module only): in the netlist that is timed, counted in the module holding them.
            netlist, fob = fanout.insert_buffers(netlist)
            add_cells(stat, fob, fanout.CELL)

            a = analyse(stat, ltp_text, areas, ff_cells, mems)
            a_old = analyse(stat_old, "", old_areas, old_ff, mems) if stat_old else None

            # Memories alone (distinct contents once).
            t0 = time.time()
            distinct = {}
            for m in mems:
                if memarea.is_rom(m):
                    distinct.setdefault(memarea.memory_key(m, mem_flow_salt(lib)), m)
            with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
                futs = {k: ex.submit(synth_memory, m, lib, pathlib.Path(args.mem_cache), args.yosys, args.sta, areas, ff_cells)
                        for k, m in distinct.items()}
                mem_syn = {k: f.result() for k, f in futs.items()}
            times["memories"] = time.time() - t0

            memories = []
            mem_index = {}
            delays = {}
            for i, m in enumerate(mems):
                if memarea.is_rom(m):
                    rec = mem_syn[memarea.memory_key(m, mem_flow_salt(lib))]
                    each = memarea.memory_area(m, rec["area_um2"])
                else:
                    model = memarea.ram_model(m)
                    rec = {"delay_ns": model["delay_ns"], "ports_synthesized": 0, "area_um2": 0, "cells": 0,
                           "flip_flops": 0}
                    each = model["area_um2"]
                delays[i] = rec["delay_ns"]
                n = a["mem_instances"][(m["module"], m["memory"])]
                mem_index[(m["module"].lstrip("\\"), m["memory"].lstrip("\\"))] = i
                entry = {"module": base_name(m["module"]), "memory": m["memory"].lstrip("\\"),
                         "kind": "ROM" if memarea.is_rom(m) else "RAM", "instances": n,
                         "size": m["size"], "width": m["width"], "read_ports": m["read_ports"],
                         "write_ports": m["write_ports"], "bits_each": m["size"] * m["width"],
                         "area_um2_each": round(each), "ge_each": round(each / ge),
                         "area_um2": round(n * each), "ge": round(n * each / ge),
                         "delay_ns": rec["delay_ns"], "synthesized_ports": rec["ports_synthesized"],
                         "synth_area_um2": round(rec["area_um2"]), "synth_cells": rec["cells"],
                         "synth_flip_flops": rec["flip_flops"], "stand_in": liberty.standin_cell_name(i),
                         "model": "cell-built ROM, one copy per read port" if memarea.is_rom(m) else
                                  "SRAM macro per read port (13.5 um^2 bit cell / 0.5)"}
                if not memarea.is_rom(m):
                    entry["flop_ram_ge"] = round(n * memarea.ram_model(m)["flop_area_um2"] / ge)
                if memarea.is_rom(m) and m["read_ports"] > 1:
                    # The noise unit's tables are banked in the RTL already (hash even/odd, value
                    # table by address mod 4: each bank is a memory of its own here), so the
                    # options left on a bank are replication (as built) and scheduling.
                    entry["port_options"] = [dict(o, area_um2=round(o["area"]), ge=round(o["area"] / ge),
                                                  total_ge=round(n * o["area"] / ge))
                                             for o in memarea.port_options(m, rec["area_um2"])]
                    for o in entry["port_options"]:
                        o.pop("area")
                if n:
                    memories.append(entry)

            # Static timing.
            timing = None
            if not args.no_sta:
                (tmp / "standin.lib").write_text(liberty.standin_liberty(
                    delays,
                    MEM_SETUP_NS, MEM_LOAD_PF / 8))
                (tmp / "netlist_sta.v").write_text(rename_standins(netlist, mem_index))
                top = a["top"].lstrip("\\")
                tcl = sta.sta_script([str(lib), str(tmp / "standin.lib")], str(tmp / "netlist_sta.v"), top,
                                     str(SDC), str(tmp / "checks.txt"))
                times["sta"], sta_out = run_sta(args.sta, tcl, tmp, "sta")
                rep = (tmp / "checks.txt").read_text()
                (out / f"{name}.sta.txt").write_text(rep)
                mods = sta.netlist_instances(netlist)
                timing = timing_result(rep, sta_out, lambda pt: sta.register_name(pt, mods, top))
    except RuntimeError as e:
        print(f"error: {profile}: {e}", file=sys.stderr)
        return 1
    times["total"] = time.time() - t_all

    result = assemble(name, profile, prof, a, a_old, ge, old_ge, memories, timing, times, lib, args)
    result["fanout_buffers"] = fanout_summary(fob, a, areas[fanout.CELL], ge)
    (out / f"{name}.json").write_text(json.dumps(result, indent=2) + "\n")
    text = markdown(result)
    (out / f"{name}.md").write_text(text)
    if not args.quiet:
        print(text)
    return 0


def add_cells(stat: dict, per_module: dict, cell: str) -> None:
    """Count inserted cells (module name -> number) in Yosys' `stat -json` modules."""
    names = {n.lstrip("\\"): n for n in stat["modules"]}
    for m, k in per_module.items():
        if m not in names:
            raise RuntimeError(f"fanout buffers in {m}: no such module in the statistics")
        cells = stat["modules"][names[m]].setdefault("num_cells_by_type", {})
        cells[cell] = cells.get(cell, 0) + k


def fanout_summary(per_module: dict, a: dict, cell_area: float, ge: float) -> dict:
    """Inserted fanout buffers: instances in the flattened design, area, per block."""
    per = {m.lstrip("\\"): k for m, k in per_module.items()}
    blocks = {}
    for (name, b, _), k in a["held"].items():
        n = k * per.get(name.lstrip("\\"), 0)
        if n:
            blocks[b] = blocks.get(b, 0) + n
    total = sum(blocks.values())
    return {"cell": fanout.CELL, "min_instances": fanout.MIN_INSTANCES, "in_netlist": sum(per.values()),
            "instances": total, "area_um2": round(total * cell_area), "ge": round(total * cell_area / ge),
            "blocks": blocks}


def timing_result(rep: str, sta_out: str, name=lambda p: p) -> dict:
    period = sta.sdc_period(SDC.read_text())
    groups = sta.parse_groups(sta_out)
    paths = sta.parse_checks(rep)
    if not paths:
        raise RuntimeError("OpenSTA reported no path")
    stages = []
    for p in paths:
        g = groups.get(p["group"], {"key": p["group"], "instance": "", "module": ""})
        stages.append({"group": g["key"], "stage": STAGE_OF.get(g["key"], g["key"]),
                       "startpoint": name(p["startpoint"]), "endpoint": name(p["endpoint"]),
                       "arrival_ns": p["arrival"], "slack_ns": p["slack"],
                       "min_period_ns": round(period - p["slack"], 3), "cells": len(p["cells"]),
                       "through": p["through"]})
    worst = min(stages, key=lambda s: s["slack_ns"])
    return {"period_ns": period, "wns_ns": worst["slack_ns"], "fmax_mhz": round(sta.fmax_mhz(period, worst["slack_ns"]), 1),
            "worst": worst, "stages": stages}


def assemble(name, profile, prof, a, a_old, ge, old_ge, memories, timing, times, lib, args) -> dict:
    blocks = {}
    for b in BLOCK_ORDER:
        v = a["blocks"][b]
        blocks[b] = {"area_um2": round(v["area"]), "logic_ge": round(v["area"] / ge), "flip_flops": v["ffs"],
                     "cells": v["cells"],
                     "logic_ge_cells_lib": round(a_old["blocks"][b]["area"] / old_ge) if a_old else None,
                     "modules": {m: {"instances": e["instances"], "ge": round(e["area"] / ge),
                                     "ge_each": round(e["area"] / ge / e["instances"]), "depth": e["depth"]}
                                 for m, e in sorted(v["modules"].items(), key=lambda kv: -kv[1]["area"])}}
    logic_area = sum(v["area"] for v in a["blocks"].values())
    mem_area = sum(m["area_um2"] for m in memories)
    cpp = clocks_per_pixel(prof)
    res = {
        "profile": name, "profile_file": str(profile),
        "library": {"file": str(lib), "name": "osu018_stdcells (qflow-tech-osu018), typical 1.8 V 25 C",
                    "ge_cell": liberty.REFERENCE_CELL, "ge_um2": ge},
        "tools": {"yosys": tool_version([args.yosys, "-V"]), "opensta": tool_version([args.sta, "-version"])},
        "mapping": f"abc -liberty -D {ABC_DELAY_PS} -script {ABC_SCRIPT} (area map, buffered, sized); {ABC_CONSTR!r}",
        "seconds": {k: round(v, 1) for k, v in times.items()},
        "yosys_seconds": round(times["yosys"], 1),
        "logic_area_um2": round(logic_area), "logic_ge": round(logic_area / ge),
        "logic_ge_cells_lib": round(sum(v["area"] for v in a_old["blocks"].values()) / old_ge) if a_old else None,
        "flip_flops": sum(v["ffs"] for v in a["blocks"].values()),
        "blocks": blocks, "memories": memories,
        "memory_area_um2": round(mem_area), "memory_ge": round(mem_area / ge),
        "total_area_um2": round(logic_area + mem_area), "total_area_mm2": round((logic_area + mem_area) / 1e6, 3),
        "total_ge": round((logic_area + mem_area) / ge),
        "rom_bits": sum(m["instances"] * m["bits_each"] for m in memories if m["kind"] == "ROM"),
        "ram_bits": sum(m["instances"] * m["bits_each"] for m in memories if m["kind"] == "RAM"),
        "clocks_per_pixel": cpp,
        "clocks_per_pixel_regress": regress_cpp(pathlib.Path(args.regress), name),
        "paper_gates": PAPER_GATES.get(name),
        "timing": timing,
    }
    if timing:
        mpix = timing["fmax_mhz"] / cpp
        res["throughput"] = {"fmax_mhz": timing["fmax_mhz"], "mpixel_s": round(mpix, 2),
                             "realtime_mpixel_s": round(REALTIME_MPIX, 1), "meets_realtime": mpix >= REALTIME_MPIX,
                             "area_time_ge_clocks": round(res["logic_ge"] * cpp),
                             "area_time_total_ge_clocks": round(res["total_ge"] * cpp)}
        # Headline numbers at the top level too (the report's side-by-side summary reads those).
        res["fmax_mhz"] = timing["fmax_mhz"]
        res["mpixel_s"] = res["throughput"]["mpixel_s"]
        res["area_time_ge_clocks"] = res["throughput"]["area_time_ge_clocks"]
        res["worst_path_ns"] = round(timing["period_ns"] - timing["wns_ns"], 3)
        stage_ns = {}
        for s in timing["stages"]:
            stage_ns[s["stage"]] = max(stage_ns.get(s["stage"], 0.0), s["min_period_ns"])
        res["critical_path_ns"] = dict(sorted(stage_ns.items(), key=lambda kv: -kv[1]))
    return res


def markdown(r: dict) -> str:
    ge = r["library"]["ge_um2"]
    md = [f"## Silicon: profile `{r['profile']}`\n",
          f"OSU 0.18 um standard cells (qflow-tech-osu018, typical), Yosys hierarchical synthesis "
          f"({r['seconds'].get('yosys', 0):.0f} s), memories synthesized alone ({r['seconds'].get('memories', 0):.0f} s)"
          + (f", OpenSTA on the flat netlist ({r['seconds'].get('sta', 0):.0f} s)" if r["timing"] else ", no timing run")
          + f". GE = area / NAND2X1 ({ge:g} um^2). Tools: {r['tools']['yosys']}; OpenSTA {r['tools']['opensta']}.\n"]
    t = r.get("throughput")
    md += ["| figure | value |", "|---|---:|",
           f"| logic | {r['logic_ge']:,} GE ({r['logic_area_um2'] / 1e6:.3f} mm^2) |",
           f"| memories (see below) | {r['memory_ge']:,} GE ({r['memory_area_um2'] / 1e6:.3f} mm^2) |",
           f"| **total area** | **{r['total_ge']:,} GE ({r['total_area_mm2']:.3f} mm^2)** |",
           f"| flip-flops | {r['flip_flops']:,} |",
           f"| ROM / RAM bits | {r['rom_bits']:,} / {r['ram_bits']:,} |"]
    fob = r.get("fanout_buffers")
    if fob:
        md.append(f"| fanout buffers (in the logic above, in the blocks holding them) | {fob['instances']:,} {fob['cell']} "
                  f"({fob['ge']:,} GE; {fob['in_netlist']:,} in the hierarchical netlist; nets into >= "
                  f"{fob['min_instances']} sub-module instances; "
                  + ", ".join(f"{b} {n:,}" for b, n in fob["blocks"].items()) + ") |")
    if r.get("paper_gates"):
        md.append(f"| paper's gate count | {r['paper_gates']:,} |")
    if r["logic_ge_cells_lib"] is not None:
        md.append(f"| logic, old basis (cells.lib, generic, not comparable) | {r['logic_ge_cells_lib']:,} GE |")
    cpp_m = r.get("clocks_per_pixel_regress")
    md.append(f"| clocks per pixel | {r['clocks_per_pixel']}"
              + (f" (pst regress: {cpp_m:.3f})" if cpp_m is not None else "") + " |")
    if t:
        w = r["timing"]["worst"]
        md += [f"| Fmax (OpenSTA) | {t['fmax_mhz']:.1f} MHz (worst slack {r['timing']['wns_ns']:+.2f} ns at "
               f"{r['timing']['period_ns']:g} ns) |",
               f"| throughput | {t['mpixel_s']:.2f} Mpixel/s ({'meets' if t['meets_realtime'] else 'misses'} "
               f"640x480 60 Hz depth 2: {t['realtime_mpixel_s']} Mpixel/s) |",
               f"| area-time (logic GE x clocks/pixel) | {t['area_time_ge_clocks']:,} |",
               f"| worst path | {w['stage']}: {w['startpoint']} -> {w['endpoint']} through "
               f"{', '.join(w.get('through', []))}, {w['arrival_ns']:.2f} ns ({w['cells']} cells) |"]
    md.append("")
    md += ["| block | logic GE (OSU018) | area um^2 | flip-flops | GE old basis (cells.lib) | modules (GE in all instances = instances x mean GE each, depth in cells) |",
           "|---|---:|---:|---:|---:|---|"]
    for b in BLOCK_ORDER:
        v = r["blocks"][b]
        mods = ", ".join(f"{m} {e['ge']:,} = {e['instances']} x {e['ge_each']:,} (depth {e['depth']})"
                         for m, e in v["modules"].items())
        old = f"{v['logic_ge_cells_lib']:,}" if v["logic_ge_cells_lib"] is not None else "-"
        md.append(f"| {b} | {v['logic_ge']:,} | {v['area_um2']:,} | {v['flip_flops']:,} | {old} | {mods} |")
    old = f"{r['logic_ge_cells_lib']:,}" if r["logic_ge_cells_lib"] is not None else "-"
    md.append(f"| **total** | **{r['logic_ge']:,}** | **{r['logic_area_um2']:,}** | **{r['flip_flops']:,}** | {old} | |")
    md.append("")
    md += ["Memories (scripts/pstlib/memarea.py): each distinct ROM synthesized alone to OSU018 cells with "
           "one read port and counted once per read port (replication; a 1999 mask ROM would be denser: an "
           "upper bound); delay address to data by OpenSTA (BUFX2-driven address, 0.02 pF load). RAMs: one "
           "SRAM macro per read port, 13.5 um^2 per bit (the 6T cell of GlobalFoundries' published 180 nm "
           "SRAM macros) over an assumed 0.5 array efficiency; built from OSU018 flip-flops instead they "
           "cost the last column (fit to a 256 x 32 RAM synthesized here). The delays are the stand-in "
           "cells' in the design's timing.\n",
           "| memory | kind | instances | words x bits | read / write ports | bits | GE each (all ports) | GE | delay ns | flip-flop RAM GE |",
           "|---|---|---:|---|---|---:|---:|---:|---:|---:|"]
    for m in r["memories"]:
        flop = f"{m['flop_ram_ge']:,}" if m.get("flop_ram_ge") is not None else "-"
        md.append(f"| {m['module']}.{m['memory']} | {m['kind']} | {m['instances']} | {m['size']} x {m['width']} | "
                  f"{m['read_ports']} / {m['write_ports']} | {m['instances'] * m['bits_each']:,} | {m['ge_each']:,} | "
                  f"{m['ge']:,} | {m['delay_ns']:.2f} | {flop} |")
    md.append(f"| **total** | | | | | ROM {r['rom_bits']:,}, RAM {r['ram_bits']:,} | | **{r['memory_ge']:,}** | |")
    md.append("")
    opts = [m for m in r["memories"] if m.get("port_options")]
    if opts:
        md += ["Port options of the many-ported ROMs (the RTL banks the noise unit's hash table "
               "even/odd and its value table by address mod 4: the rows above are the banks; the options "
               "left on a bank are one copy per read port, as built and counted, or its lookups "
               "scheduled over fewer ports):\n",
               "| memory | option | copies | GE per instance | GE all instances | cycles factor | note |",
               "|---|---|---:|---:|---:|---:|---|"]
        for m in opts:
            for o in m["port_options"]:
                md.append(f"| {m['module']}.{m['memory']} | {o['option']} | {o['copies']} | {o['ge']:,} | "
                          f"{o['total_ge']:,} | {o['cycles_factor']} | {o['note']} |")
        md.append("")
    if r["timing"]:
        md += [f"Critical path per stage (OpenSTA, scripts/synth/pst.sdc: {r['timing']['period_ns']:g} ns target; "
               "worst path into each block's registers):\n",
               "| stage (block) | start point | end point | through | arrival ns | slack ns | min period ns | cells |",
               "|---|---|---|---|---:|---:|---:|---:|"]
        for s in sorted(r["timing"]["stages"], key=lambda s: s["slack_ns"]):
            md.append(f"| {s['stage']} | `{s['startpoint']}` | `{s['endpoint']}` | {', '.join(s.get('through', []))} | "
                      f"{s['arrival_ns']:.2f} | {s['slack_ns']:+.2f} | {s['min_period_ns']:.2f} | {s['cells']} |")
        md.append("")
    return "\n".join(md) + "\n"


if __name__ == "__main__":
    sys.exit(main())
