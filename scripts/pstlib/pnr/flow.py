"""A profile placed and routed block by block (scripts/pnr.py; the method is in its docstring).

synthesis (pstlib.synth, netlists kept) -> the flattened netlist cut into blocks
(partition.py) -> each block through qflow (qflow.py) -> its routed parasitics as SPEF
(spef.py) -> OpenSTA before and after layout (timing.py) -> die, utilization, wirelength and
a PNG (layout.py) -> OUT/PROFILE.json and .md (report.py). Beside it, the whole profile
buffered by blifFanout instead of the synthesis' fanout step, timed (buffering.py).
"""
import concurrent.futures
import dataclasses
import hashlib
import json
import pathlib
import time

from ..paths import ROOT
from ..synth import flow as synth_flow, liberty, sta as synth_sta
from ..synth.tools import SDC, run_sta, run_yosys
from . import assembly, blif, buffering, layout, lec, partition, pins, qflow, report, spef, timing

STANDIN = "PST_MEMRD*"    # the memory read stand-ins: macros, outside every block
LEC_TIMEOUT = 1800.0      # seconds ABC may take on one block's routed netlist


@dataclasses.dataclass
class Options:
    out: pathlib.Path = ROOT / "out" / "pnr"
    rom_dir: pathlib.Path = ROOT / "build" / "rom"
    jobs: int = 1
    limit: int = partition.LIMIT
    only: tuple = ()          # block names to run (all when empty)
    resume: bool = False      # keep the synthesis and the finished qflow steps of a previous run
    groups: dict = dataclasses.field(default_factory=dict)   # named blocks: name -> instance paths
    whole: bool = True        # also time the whole chip (assembly) and check the fanout step (buffering)


def _digest(path: pathlib.Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def cut(work: pathlib.Path, netlist: pathlib.Path, libs: list, top: str, limit: int, groups: dict = None,
        resume: bool = False, only: tuple = ()) -> dict:
    """Block name -> its mapped netlist WORK/blocks/blk_NAME.v (and the cell counts). GROUPS
    (name -> instance paths) are blocks made first of several instances (partition.claim). ONLY:
    the blocks whose netlists are written (all when empty; then also the top level that connects
    them, for the assembly): Yosys splitting all of full's 773k cells at once needs over 22 GB.
    With RESUME, the cell list and the cut of the same netlist (by content) are reused
    (WORK/blocks/cut.json: listing full takes Yosys some 5 minutes)."""
    blocks_dir = work / "blocks"
    blocks_dir.mkdir(parents=True, exist_ok=True)
    key = {"netlist": _digest(netlist), "limit": limit, "groups": groups or {}, "only": sorted(only)}
    done = blocks_dir / "cut.json"
    listed = blocks_dir / "cells.key"
    if resume and done.exists():
        prev = json.loads(done.read_text())
        if prev["key"] == key and all(pathlib.Path(b["netlist"]).exists() for b in prev["blocks"].values()
                                      if not only or b["name"] in only):
            return {k: {**b, "netlist": pathlib.Path(b["netlist"])} for k, b in prev["blocks"].items()}
    done.unlink(missing_ok=True)
    if not (resume and listed.exists() and listed.read_text().strip() == key["netlist"]
            and (blocks_dir / "cells.txt").exists()):
        listed.unlink(missing_ok=True)
        run_yosys(partition.list_script(libs, netlist, top, blocks_dir / "cells.txt"), blocks_dir, "list")
        listed.write_text(key["netlist"] + "\n")
    raw = [l.strip() for l in (blocks_dir / "cells.txt").read_text().splitlines() if l.strip()]
    cells = [c.split("/", 1)[1] for c in raw]
    # The memory stand-ins (one per read bit, 393 in reduced) are in this list and so in the
    # cell counts the cut is chosen by; the split script leaves them out of every block by type.
    named, cells = partition.claim(cells, groups or {})
    paths = partition.choose(cells, limit)
    parts = partition.assign(cells, paths)
    clash = set(named) & set(parts)
    if clash:
        raise ValueError(f"--group {sorted(clash)[0]}: the cut already has a block of that name")
    parts.update(named)
    sel = {}
    for name, members in parts.items():
        f = blocks_dir / f"{name}.sel"
        f.write_text("".join(f"{top}/{c}\n" for c in members))
        sel[name] = f
    unknown = set(only) - set(sel)
    if unknown:
        raise ValueError(f"--block {sorted(unknown)}: no such block (blocks: {', '.join(sorted(sel))})")
    run_yosys(partition.split_script(libs, netlist, top, {k: v for k, v in sel.items() if not only or k in only},
                                     blocks_dir, STANDIN, assembly=not only), blocks_dir, "split")
    by_path = {partition.block_name(p): p for p in paths}
    by_path.update({name: "+".join(ps) for name, ps in (groups or {}).items()})
    blocks = {name: {"name": name, "netlist": blocks_dir / f"blk_{name}.v", "instance": by_path.get(name, "(top glue)"),
                     "cells_synth": len(members)} for name, members in parts.items()}
    done.write_text(json.dumps({"key": key, "blocks": {k: {**b, "netlist": str(b["netlist"])} for k, b in blocks.items()}},
                               indent=1) + "\n")
    return blocks


def run_block(name: str, info: dict, work: pathlib.Path, lib: pathlib.Path, out: pathlib.Path,
              resume: bool = False) -> dict:
    """One block through qflow, extraction and timing; its record."""
    module = f"blk_{name}"
    p = qflow.setup(work / "qflow" / name, module, info["netlist"], lib, resume)
    times = qflow.run_steps(p, resume)
    density = times.pop("density")
    # Parasitics and timing.
    t0 = time.time()
    # The netlist as placed, written from the BLIF graywolf placed (pstlib/pnr/blif.py): qflow's
    # blif2Verilog garbles the port names of the large blocks and merges ports whose names
    # hold a bus index inside a path (g_ch[0].sn_d[1] -> g_ch[0]).
    # qflow's placement step reassigns each flip-flop to its nearest clock buffer and writes the
    # netlist it placed as NAME_anno.blif (the routed DEF's connections); NAME.blif keeps the
    # assignment before placement.
    placed = p.synthesis / f"{module}_anno.blif"
    routed_v = blif.to_verilog((placed if placed.exists() else p.synthesis / f"{module}.blif").read_text())
    sta_v = p.path / "sta.v"
    sta_v.write_text(timing.without_fill(routed_v))
    spef_text, unmatched = spef.to_spef((p.layout / f"{module}.rc").read_text(), spef.netlist_pins(routed_v),
                                        module, spef.port_directions(routed_v), spef.EDGE_FACTOR)
    if unmatched:
        raise RuntimeError(f"{module}: {len(unmatched)} routed nets not in the netlist (first {unmatched[0]})")
    (p.path / f"{module}.spef").write_text(spef_text)
    period = synth_sta.sdc_period(SDC.read_text())
    runs = {}
    for tag, sp, prop in (("pre_layout", None, False), ("post_route", p.path / f"{module}.spef", True),
                          ("post_route_pins", p.path / f"{module}.spef", False)):
        _, stdout = run_sta(timing.script(lib, sta_v, module, SDC, sp, str(p.path / tag), prop), p.path, tag)
        runs[tag] = timing.summary({k: (p.path / f"{tag}.{k}").read_text() for k in timing.REPORTS}, stdout, period)
    sta = {"pre_layout": timing.combine(runs["pre_layout"], runs["pre_layout"]),
           "post_route": timing.combine(runs["post_route"], runs["post_route_pins"])}
    times["extract_and_sta"] = round(time.time() - t0, 1)
    # The routed netlist against the block as cut (pstlib/pnr/lec.py), and a mutant of it.
    t0 = time.time()
    gold_v = p.path / "gold.v"
    gold_v.write_text(blif.to_verilog(info["netlist"].with_suffix(".blif").read_text()))
    equiv = {"routed": lec.check(lib, gold_v, sta_v, module, p.path / "lec", LEC_TIMEOUT),
             "mutant": lec.check(lib, gold_v, sta_v, module, p.path / "lec", LEC_TIMEOUT, mutate=True)}
    times["lec"] = round(time.time() - t0, 1)
    fig = layout.def_figures((p.layout / f"{module}.def").read_text(),
                             layout.lef_sizes(qflow.LEF.read_text()))
    png = out / f"{name}.png"
    layout.png(p.layout / f"{module}.gds", png)
    for ext in ("def", "gds"):
        (out / f"{name}.{ext}").write_bytes((p.layout / f"{module}.{ext}").read_bytes())
    (out / f"{name}.spef").write_text(spef_text)
    checks = qflow.results(p)
    hinted = p.log / "pins.json"
    return {"block": name, "instance": info["instance"], "cells_synth": info["cells_synth"], **fig, **checks,
            "initial_density": density,
            "pin_hints": json.loads(hinted.read_text()) if hinted.exists() else None,
            "median_pin_to_cell_um": round(pins.pin_distance_um((p.layout / f"{module}.def").read_text()), 1),
            "lec": equiv, "sta": sta, **ratios(sta),
            "seconds": times, "png": png.name}


def ratios(sta: dict) -> dict:
    """A block's post-route / pre-layout Fmax ratio: of its critical path (register or pin,
    `fmax_ratio_combined`) and of its worst register-to-register path (`fmax_ratio_reg2reg`);
    the block's ratio is the worse of the two. A pin path is timed on the SDC's 2 ns budgets
    before and after routing alike, so where one is critical before layout (a block cut across a
    stage) its ratio says little about the wires; the register path's does."""
    pre, post = sta["pre_layout"], sta["post_route"]
    combined = round(post["fmax_mhz"] / pre["fmax_mhz"], 3)
    reg = round(post["reg2reg"]["fmax_mhz"] / pre["reg2reg"]["fmax_mhz"], 3)
    return {"fmax_ratio": min(combined, reg), "fmax_ratio_combined": combined, "fmax_ratio_reg2reg": reg}


def buffered_netlist(name: str, info: dict, work: pathlib.Path, lib: pathlib.Path) -> pathlib.Path:
    """A block without a layout as qflow buffers it before placement (its clock and fanout
    trees from blifFanout: the netlist the assembled timing uses for it, without wires); the
    block's own netlist when qflow fails on it."""
    module = f"blk_{name}"
    try:
        p = qflow.setup(work / "qflow" / name, module, info["netlist"], lib, resume=True)
        if not (p.log / "synthesize.done").exists():
            qflow.synthesize(p)
        return p.synthesis / f"{module}.blif"
    except qflow.FlowError:
        return work / "blocks" / f"{module}.blif"


def place_and_route(profile, opts: Options) -> dict:
    """The whole profile: synthesis, cut, every block, the record OUT/NAME.json (and .md)."""
    profile = pathlib.Path(profile)
    so = synth_flow.Options(out=pathlib.Path(opts.out) / profile.stem / "work" / "synth", rom_dir=opts.rom_dir,
                            keep=True, old_basis=False, reuse=opts.resume,
                            mem_cache=ROOT / "out" / "synth" / "memories")
    synth_flow.check_inputs(profile, so)      # bad input before anything is written
    if not qflow.available():
        raise synth_flow.InputError("qflow with the OSU018 technology is not installed (scripts/setup.sh --pnr)")
    name = profile.stem
    out = pathlib.Path(opts.out) / name
    work = out / "work"
    work.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    synth = synth_flow.synthesize(profile, so)
    t_synth = time.time() - t0
    lib = liberty.osu018_lib()
    swork = work / "synth" / f"{name}.work"
    try:
        blocks = cut(work, swork / "netlist.v", [lib, swork / "standin.lib"], "pst_top",
                     opts.limit, opts.groups, opts.resume, opts.only if not opts.whole else ())
    except ValueError as e:
        raise synth_flow.InputError(str(e)) from None
    buf = (buffering.compare(work / "buffering", swork / "netlist_sta.v", [lib, swork / "standin.lib"], "pst_top",
                             synth["fmax_mhz"]) if opts.whole else {"skipped": "--blocks-only"})
    # Largest blocks first: with N jobs the long ones overlap instead of finishing last.
    todo = sorted((k for k in blocks if not opts.only or k in opts.only), key=lambda k: -blocks[k]["cells_synth"])
    unknown = set(opts.only) - set(blocks)
    if unknown:
        raise synth_flow.InputError(f"--block {sorted(unknown)}: no such block (blocks: {', '.join(sorted(blocks))})")
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, opts.jobs)) as ex:
        futs = {k: ex.submit(run_block, k, blocks[k], work, lib, out, opts.resume) for k in todo}
        recs, failed = [], {}
        for k in todo:
            try:
                recs.append(futs[k].result())
            except (qflow.FlowError, RuntimeError, ValueError) as e:
                # A block that does not finish is reported, the others are kept.
                failed[k] = {"instance": blocks[k]["instance"], "cells_synth": blocks[k]["cells_synth"],
                             "error": str(e).splitlines()[0]}
    if not recs:
        raise RuntimeError("no block finished: " + "; ".join(f"{k}: {v['error']}" for k, v in failed.items()))
    # The whole chip timed from its blocks' routed netlists and parasitics; a block without a
    # layout (not finished, or not run) from its netlist before layout.
    t_asm = time.time()
    routed = {r["block"]: (work / "qflow" / r["block"] / "sta.v", work / "qflow" / r["block"] / f"blk_{r['block']}.spef")
              for r in recs}
    try:
        if not opts.whole:
            raise RuntimeError("not timed (--blocks-only)")
        unrouted = {k: buffered_netlist(k, blocks[k], work, lib) for k in blocks if k not in routed}
        assembled = assembly.time_design(work / "assembly", work / "blocks" / partition.ASSEMBLY_BLIF, routed,
                                         unrouted, [lib, swork / "standin.lib"], SDC)
    except (RuntimeError, ValueError, OSError) as e:
        assembled = {"error": str(e).splitlines()[0]}
    assembled["seconds_total"] = round(time.time() - t_asm, 1)
    result = report.assemble(name, synth, recs, round(t_synth, 1), round(time.time() - t0, 1))
    result["assembled"] = assembled
    result["buffering"] = buf
    result["failed_blocks"] = failed
    result["skipped_blocks"] = sorted(set(blocks) - set(todo))      # left out with --block
    result["groups"] = opts.groups
    result["command"] = " ".join(["scripts/pnr.py", name, *(f"--group {k}={'+'.join(v)}" for k, v in opts.groups.items()),
                                  *(f"--block {b}" for b in opts.only), *([] if opts.whole else ["--blocks-only"]),
                                  *([f"--limit {opts.limit}"] if opts.limit != partition.LIMIT else [])])
    (out.parent / f"{name}.json").write_text(json.dumps(result, indent=2) + "\n")
    (out.parent / f"{name}.md").write_text(report.markdown(result))
    return result
