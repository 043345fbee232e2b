"""One profile through Yosys (hierarchical synthesis to the cell library), the memories alone,
the cross-hierarchy fanout buffers and OpenSTA: the record scripts/synth.py writes (its
docstring tells the method)."""
import concurrent.futures
import dataclasses
import json
import pathlib
import re
import sys
import tempfile
import time

from .. import contract
from ..paths import CONFIGS, ROOT
from . import blocks, fanout, liberty, memarea, memories, record, report, sta
from .tools import (ABC_CONSTR, OLD_LIB, SDC, map_lines, parse_stat_json, read_lines, run_sta, run_yosys)


class InputError(ValueError):
    """Bad input (no such profile, no ROM images, no cell library): exit status 2."""


@dataclasses.dataclass
class Options:
    out: pathlib.Path = ROOT / "out" / "synth"
    rom_dir: pathlib.Path = ROOT / "build" / "rom"
    regress: pathlib.Path = ROOT / "out" / "regress.json"
    yosys: str = "yosys"
    sta: str = "sta"
    no_sta: bool = False
    old_basis: bool = True      # the cells.lib column (the named profiles only)
    jobs: int = 1
    mem_cache: pathlib.Path = ROOT / "out" / "synth" / "memories"
    keep: bool = False
    reuse: bool = False


def run_command(step, profile, failures=(RuntimeError,)):
    """A command line's run of STEP() for PROFILE: (its result, 0), or (None, exit code) after
    one `error:` line on stderr: 2 for bad input (InputError: nothing written), 1 when the flow
    failed (FAILURES: a tool, a sign-off check)."""
    try:
        return step(), 0
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return None, 2
    except failures as e:
        print(f"error: {profile}: {e}", file=sys.stderr)
        return None, 1


def yosys_script(doc: dict, rom_dir, lib, tmp: pathlib.Path, old_basis: bool) -> str:
    lines = [
        *read_lines(doc, rom_dir, lib),
        "hierarchy -check -top pst_top",
        # Coarse synthesis with memories kept as $mem cells.
        "synth -top pst_top -run :fine",
        # The memories' shapes and contents for the memory table and their own synthesis.
        f"tee -q -o {tmp}/mem.txt select -list t:$mem_v2",
        f"tee -q -a {tmp}/mem.txt dump t:$mem_v2",
        "opt -fast -full",
        # Depth before the flops become library cells: ltp -noff skips the internal $_DFF_P_
        # cells, so a path ends at a register (a library DFF would be walked through).
        *map_lines(lib, tmp, save_generic=True, before_ffs=[f"tee -q -o {tmp}/ltp.txt ltp -noff"]),
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


def add_cells(stat: dict, per_module: dict, cell: str) -> None:
    """Count inserted cells (module name -> number) in Yosys' `stat -json` modules."""
    names = {n.lstrip("\\"): n for n in stat["modules"]}
    for m, k in per_module.items():
        if m not in names:
            raise RuntimeError(f"fanout buffers in {m}: no such module in the statistics")
        cells = stat["modules"][names[m]].setdefault("num_cells_by_type", {})
        cells[cell] = cells.get(cell, 0) + k


def check_inputs(profile, opts: Options) -> tuple:
    """(profile path, validated profile, cell library) or InputError saying what is missing."""
    path = pathlib.Path(profile)
    if not path.exists():
        raise InputError(f"{path}: no such profile")
    try:
        doc = contract.read_profile(path)
    except contract.ProfileError as e:
        raise InputError(str(e)) from None
    if not (pathlib.Path(opts.rom_dir) / "hash4096.memh").exists():
        raise InputError(f"{opts.rom_dir}: no ROM images (build first: cmake --build build --target pst_rom_images)")
    lib = liberty.osu018_lib()
    if lib is None:
        raise InputError("OSU018 liberty not found (run scripts/setup.sh; looked in "
                         + ", ".join(str(p) for p in liberty.osu018_candidates()) + ")")
    return path, doc, lib


def synthesize(profile, opts: Options) -> dict:
    """Synthesizes one profile; writes OUT/NAME.{json,md,ltp.txt,sta.txt,sta_signoff.txt} and returns
    the record (report.signoff_errors tells whether it passes the hold and design-rule checks).
    InputError on bad input, RuntimeError when a tool fails."""
    profile, prof, lib = check_inputs(profile, opts)
    name = profile.stem
    # The old basis is kept for one release for the named profiles only (a sweep point skips it).
    old_basis = opts.old_basis and profile.resolve().parent == CONFIGS.resolve()
    out = pathlib.Path(opts.out)
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
    with tempfile.TemporaryDirectory(prefix=f"pst_synth_{name}_") as t:
        tmp = pathlib.Path(t)
        if opts.keep:
            tmp = out / f"{name}.work"
            tmp.mkdir(exist_ok=True)
        (tmp / "abc.constr").write_text(ABC_CONSTR)
        # A kept netlist is reused only while every input it was made from is unchanged
        # (record.netlist_stale); its digest is written once Yosys has finished.
        changed = record.netlist_stale(tmp, profile, opts.rom_dir) if opts.keep else ["not kept"]
        if opts.reuse and (tmp / "netlist.v").exists() and not changed:
            times["yosys"] = 0.0
        else:
            if opts.reuse and (tmp / "netlist.v").exists():
                print(f"{tmp}: kept netlist out of date ({'; '.join(changed[:3])}"
                      f"{'; ...' if len(changed) > 3 else ''}): synthesizing again", file=sys.stderr)
            made_from = record.netlist_inputs(profile, opts.rom_dir)
            (tmp / record.NETLIST_DIGEST).unlink(missing_ok=True)
            times["yosys"] = run_yosys(yosys_script(prof, opts.rom_dir, lib, tmp, old_basis), tmp, "synth", opts.yosys)
            if opts.keep:
                (tmp / record.NETLIST_DIGEST).write_text(json.dumps(made_from, indent=1, sort_keys=True) + "\n")
        stat = parse_stat_json((tmp / "stat.json").read_text())
        ltp_text = (tmp / "ltp.txt").read_text()
        mems = memarea.parse_memories((tmp / "mem.txt").read_text())
        stat_old = parse_stat_json((tmp / "stat_old.json").read_text()) if old_basis else None
        (out / f"{name}.ltp.txt").write_text(ltp_text)
        netlist = (tmp / "netlist.v").read_text()
        # Fanout buffers across the hierarchy (a back end's repair_design; ABC buffers inside
        # a module only): in the netlist that is timed, counted in the module holding them.
        netlist, fob = fanout.insert_buffers(netlist)
        add_cells(stat, fob, fanout.CELL)

        a = blocks.analyse(stat, ltp_text, areas, ff_cells, mems)
        a_old = blocks.analyse(stat_old, "", old_areas, old_ff, mems) if stat_old else None

        # Memories alone (distinct contents once).
        t0 = time.time()
        distinct = {}
        for m in mems:
            if memarea.is_rom(m):
                distinct.setdefault(memarea.memory_key(m, memories.mem_flow_salt(lib)), m)
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, opts.jobs)) as ex:
            futs = {k: ex.submit(memories.synth_memory, m, lib, pathlib.Path(opts.mem_cache), opts.yosys, opts.sta,
                                 areas, ff_cells) for k, m in distinct.items()}
            mem_syn = {k: f.result() for k, f in futs.items()}
        times["memories"] = time.time() - t0
        mem_rows, mem_index, delays = memories.memory_rows(mems, mem_syn, a["mem_instances"], lib, ge)

        # Static timing.
        timing = None
        if not opts.no_sta:
            (tmp / "standin.lib").write_text(liberty.standin_liberty(
                delays, memories.MEM_SETUP_NS, memories.MEM_LOAD_PF / 8))
            (tmp / "netlist_sta.v").write_text(rename_standins(netlist, mem_index))
            top = a["top"].lstrip("\\")
            files = {k: tmp / f"{k}.txt" for k in ("setup", "hold", "hold_violators", "transition")}
            limits = liberty.max_capacitance(lib_text)
            tcl = sta.sta_script([str(lib), str(tmp / "standin.lib")], str(tmp / "netlist_sta.v"), top,
                                 str(SDC), {k: str(f) for k, f in files.items()}, limits,
                                 limits[f"{sta.sdc_driving_cell(SDC.read_text())}/Y"])
            times["sta"], sta_out = run_sta(tcl, tmp, "sta", opts.sta)
            reports = {k: f.read_text() for k, f in files.items()}
            (out / f"{name}.sta.txt").write_text(reports["setup"])
            (out / f"{name}.sta_signoff.txt").write_text(
                reports["hold"] + reports["hold_violators"] + reports["transition"]
                + "".join(l + "\n" for l in sta_out.splitlines() if l.startswith("max_capacitance")))
            mods = sta.netlist_instances(netlist)
            timing = report.timing_result(reports, sta_out, lambda pt: sta.register_name(pt, mods, top))
    times["total"] = time.time() - t_all

    result = report.assemble(name, profile, prof, a, a_old, ge, old_ge, mem_rows, timing, times, lib, opts)
    result["fanout_buffers"] = report.fanout_summary(fob, a, areas[fanout.CELL], ge)
    (out / f"{name}.json").write_text(json.dumps(result, indent=2) + "\n")
    (out / f"{name}.md").write_text(report.markdown(result))
    return result
