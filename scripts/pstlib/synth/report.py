"""The silicon report of one profile: the JSON record (blocks, memories, timing, throughput)
and its Markdown."""
import json
import pathlib

from .. import contract
from ..pstjson import regress_runs
from . import fanout, liberty, sta
from .tools import ABC_CONSTR, ABC_DELAY_PS, ABC_SCRIPT, SDC, tool_version

REALTIME_MPIX = 640 * 480 * 60 * 2 / 1e6   # 640 x 480, 60 Hz, depth complexity 2
PAPER_GATES = {"reduced": 100_000, "full": 1_250_000}
# Path-group key -> pipeline stage it ends in. A group is a top-level instance's registers, keyed
# by its module (sta.stage_groups_tcl), or by instance for the pipeline registers and the top.
STAGE_OF = {
    "u_reg_a": "[A] input register",
    "(top)": "octave stage [A] -> [B] (sequencer, accumulators)",
    "pst_octave_stage": "octave stage [A] -> [B]",
    "u_reg_b": "octave stage [A] -> [B] (into [B])",
    "pst_width_stage": "filter width [B] -> [C]",
    "u_reg_c": "filter width [B] -> [C] (into [C])",
    "pst_colour_stage": "colour-table filter [C] -> [D]",
    "u_reg_d": "colour-table filter [C] -> [D] (into [D])",
}


def clocks_per_pixel(prof: dict) -> int:
    """The pipeline's clocks per pixel (the slowest stage: the contract's clocks_per_pixel
    formula through pstlib.contract.stage_cycles, the docs' cycle table; Profile::cyclesPerPixel
    in the golden model)."""
    return contract.stage_cycles(prof)["pixel"]


def regress_cpp(regress: pathlib.Path, name: str):
    """Measured clocks per pixel of `pst regress` (out/regress.json), max over scenes."""
    if not regress.exists():
        return None
    try:
        runs = [r for r in regress_runs(json.loads(regress.read_text())) if r.get("profile") == name]
    except (ValueError, AttributeError):
        return None
    return max((r["cycles_per_pixel"] for r in runs), default=None)


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


FMAX_BASIS = "pre-layout"
FMAX_LABEL = "pre-layout (typical corner, no wire load)"
# The post-route / pre-layout Fmax ratios of the routed profiles (scripts/pnr.py PROFILE
# --update-derate writes PROFILE's entry): every profile's pre-layout Fmax is also given derated,
# by its own ratio where it was routed, else by the worst ratio of those that were.
DERATE_FILE = SDC.parent / "layout_derate.json"


def derate_entries(doc) -> dict:
    """Profile -> its entry of a layout_derate.json document ({} for None)."""
    if not doc:
        return {}
    return doc.get("profiles") or {}


def derate_for(doc, name: str):
    """The entry PROFILE's Fmax is derated by: its own when it was routed, else the routed
    profile with the worst ratio (the conservative choice); None when nothing was routed. The
    entry's "profile" names where it comes from."""
    entries = derate_entries(doc)
    if name in entries:
        return entries[name]
    return min(entries.values(), key=lambda e: e["ratio"]) if entries else None


def derate_label(entry: dict, name: str) -> str:
    """Where profile NAME's derate comes from, in words."""
    if entry["profile"] == name:
        which = "its critical blocks" if entry.get("critical_blocks_only") else "its blocks"
        return f"worst post-route / pre-layout of {which} placed and routed ({len(entry.get('blocks', []))})"
    return (f"not routed itself: the worst post-route / pre-layout ratio of the routed profiles, "
            f"{entry['profile']}'s blocks")


def layout_derate(name: str):
    """derate_for(scripts/synth/layout_derate.json, NAME)."""
    return derate_for(json.loads(DERATE_FILE.read_text()) if DERATE_FILE.exists() else None, name)


def timing_result(reports: dict, sta_out: str, name=lambda p: p) -> dict:
    """The timing record from the OpenSTA run's reports (sta.sta_script's REPORTS, read) and
    its stdout (path groups, capacitance check): setup per stage and Fmax, hold per stage, the
    hold, max-transition and max-capacitance violations."""
    sdc = SDC.read_text()
    period = sta.sdc_period(sdc)
    groups = sta.parse_groups(sta_out)

    def stage_rows(paths):
        rows = []
        for p in paths:
            g = groups.get(p["group"], {"key": p["group"], "instance": "", "module": ""})
            rows.append({"group": g["key"], "stage": STAGE_OF.get(g["key"], g["key"]),
                         "startpoint": name(p["startpoint"]), "endpoint": name(p["endpoint"]),
                         "arrival_ns": p["arrival"], "slack_ns": p["slack"],
                         "min_period_ns": round(period - p["slack"], 3), "cells": len(p["cells"]),
                         "through": p["through"]})
        return rows

    stages = stage_rows(sta.parse_checks(reports["setup"]))
    holds = stage_rows(sta.parse_checks(reports["hold"]))
    if not stages or not holds:
        raise RuntimeError("OpenSTA reported no setup or no hold path")
    for h in holds:
        h.pop("min_period_ns")
    worst = min(stages, key=lambda s: s["slack_ns"])
    hold_worst = min(holds, key=lambda s: s["slack_ns"])
    hold_viol = sta.parse_hold_violators(reports["hold_violators"])
    trans = sta.parse_transition(reports["transition"])
    cap = sta.parse_capacitance(sta_out)
    if cap["worst"] is None:
        raise RuntimeError("OpenSTA's run printed no capacitance check")
    return {"period_ns": period, "constraints": sta.sdc_constraints(sdc),
            "wns_ns": worst["slack_ns"], "fmax_mhz": round(sta.fmax_mhz(period, worst["slack_ns"]), 1),
            "fmax_basis": FMAX_BASIS, "worst": worst, "stages": stages,
            "hold": {"wns_ns": hold_worst["slack_ns"], "worst": hold_worst, "stages": holds,
                     "violations": len(hold_viol), "violators": hold_viol[:20]},
            "max_transition": {"worst": trans["worst"], "violations": len(trans["violations"]),
                               "violators": trans["violations"][:20]},
            "max_capacitance": {"worst": cap["worst"], "checked": cap["checked"],
                                "violations": len(cap["violations"]), "violators": cap["violations"][:20]}}


def signoff_errors(r: dict) -> list:
    """What fails the sign-off checks of a synthesis record (hold, max transition, max
    capacitance), each naming the worst offender; empty when all pass or no timing ran."""
    t = r.get("timing")
    if not t:
        return []
    if "hold" not in t:
        return ["no sign-off checks in the record (made before they existed: rerun scripts/synth.py)"]
    out = []
    h = t["hold"]
    if h["violations"] or h["wns_ns"] < 0:
        w = h["worst"]
        out.append(f"hold: {h['violations']} endpoints violated, worst slack {w['slack_ns']:+.3f} ns "
                   f"{w['startpoint']} -> {w['endpoint']} ({w['stage']})")
    tr = t["max_transition"]
    if tr["violations"]:
        w = tr["worst"]
        out.append(f"max transition: {tr['violations']} pins, worst {w['pin']} {w['transition_ns']:.3f} ns "
                   f"> {w['limit_ns']:.3f} ns")
    c = t["max_capacitance"]
    if c["violations"]:
        w = c["worst"]     # the driver of least slack: the worst violation
        out.append(f"max capacitance: {c['violations']} drivers, worst {w['pin']} ({w['cell']}) "
                   f"{w['load_pf']:.3f} pF > {w['limit_pf']:.3f} pF")
    return out


def assemble(name, profile, prof, a, a_old, ge, old_ge, memories, timing, times, lib, opts) -> dict:
    """The JSON record of one synthesis (OPTS: the flow's options, for the tools and the regress file)."""
    blocks = {}
    for b in a["blocks"]:
        v = a["blocks"][b]
        blocks[b] = {"area_um2": round(v["area"]), "logic_ge": round(v["area"] / ge), "flip_flops": v["ffs"],
                     "cells": v["cells"],
                     "logic_ge_cells_lib": round(a_old["blocks"][b]["area"] / old_ge) if a_old and b in a_old["blocks"] else None,
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
        "tools": {"yosys": tool_version([opts.yosys, "-V"]), "opensta": tool_version([opts.sta, "-version"])},
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
        "clocks_per_pixel_regress": regress_cpp(pathlib.Path(opts.regress), name),
        "paper_gates": PAPER_GATES.get(name),
        "timing": timing,
    }
    if timing:
        mpix = timing["fmax_mhz"] / cpp
        res["throughput"] = {"fmax_mhz": timing["fmax_mhz"], "fmax_basis": FMAX_BASIS, "mpixel_s": round(mpix, 2),
                             "realtime_mpixel_s": round(REALTIME_MPIX, 1), "meets_realtime": mpix >= REALTIME_MPIX,
                             "area_time_ge_clocks": round(res["logic_ge"] * cpp),
                             "area_time_total_ge_clocks": round(res["total_ge"] * cpp)}
        # Headline numbers at the top level too (the report's side-by-side summary reads those).
        res["fmax_mhz"] = timing["fmax_mhz"]
        res["fmax_basis"] = FMAX_BASIS
        res["fmax_label"] = FMAX_LABEL
        d = layout_derate(res["profile"])
        if d:
            res["fmax_derated_mhz"] = round(timing["fmax_mhz"] * d["ratio"], 1)
            res["fmax_derate"] = d
            res["throughput"]["fmax_derated_mhz"] = res["fmax_derated_mhz"]
            res["throughput"]["mpixel_s_derated"] = round(res["fmax_derated_mhz"] / cpp, 2)
            res["throughput"]["meets_realtime_derated"] = res["fmax_derated_mhz"] / cpp >= REALTIME_MPIX
        res["hold_wns_ns"] = timing["hold"]["wns_ns"]
        res["max_transition_violations"] = timing["max_transition"]["violations"]
        res["max_capacitance_violations"] = timing["max_capacitance"]["violations"]
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
        tm = r["timing"]
        c = tm["constraints"]
        md += [f"| Fmax (OpenSTA), {FMAX_LABEL} | {t['fmax_mhz']:.1f} MHz (worst setup slack {tm['wns_ns']:+.2f} ns at "
               f"{tm['period_ns']:g} ns, clock uncertainty {c['setup_uncertainty_ns']:g} ns) |",
               *([f"| Fmax derated by {r['fmax_derate']['ratio']:.3f} ({derate_label(r['fmax_derate'], r['profile'])}, "
                  f"{r['fmax_derate']['source']}) | {r['fmax_derated_mhz']:.1f} MHz: "
                  f"{t['mpixel_s_derated']:.2f} Mpixel/s ({'meets' if t['meets_realtime_derated'] else 'misses'} "
                  f"{t['realtime_mpixel_s']:.1f}) |"] if r.get("fmax_derated_mhz") else []),
               f"| hold (worst slack, clock uncertainty {c['hold_uncertainty_ns']:g} ns) | {tm['hold']['wns_ns']:+.3f} ns, "
               f"{tm['hold']['violations']:,} violated endpoints |",
               f"| max transition ({c['max_transition_ns']:g} ns) | {tm['max_transition']['violations']:,} violations "
               f"(worst {tm['max_transition']['worst']['transition_ns']:.3f} ns at `{tm['max_transition']['worst']['pin']}`) |",
               f"| max capacitance (liberty, per output pin) | {tm['max_capacitance']['violations']:,} violations of "
               f"{tm['max_capacitance']['checked']:,} drivers (least slack: {tm['max_capacitance']['worst']['load_pf']:.3f} "
               f"of {tm['max_capacitance']['worst']['limit_pf']:.3f} pF at `{tm['max_capacitance']['worst']['pin']}`) |",
               f"| throughput | {t['mpixel_s']:.2f} Mpixel/s ({'meets' if t['meets_realtime'] else 'misses'} "
               f"640x480 60 Hz depth 2: {t['realtime_mpixel_s']} Mpixel/s) |",
               f"| area-time (logic GE x clocks/pixel) | {t['area_time_ge_clocks']:,} |",
               f"| worst path | {w['stage']}: {w['startpoint']} -> {w['endpoint']} through "
               f"{', '.join(w.get('through', []))}, {w['arrival_ns']:.2f} ns ({w['cells']} cells) |"]
    md.append("")
    md += ["| block | logic GE (OSU018) | area um^2 | flip-flops | GE old basis (cells.lib) | modules (GE in all instances = instances x mean GE each, depth in cells) |",
           "|---|---:|---:|---:|---:|---|"]
    for b, v in r["blocks"].items():
        mods = ", ".join(f"{m} {e['ge']:,} = {e['instances']} x {e['ge_each']:,} (depth {e['depth']})"
                         for m, e in v["modules"].items())
        old = f"{v['logic_ge_cells_lib']:,}" if v["logic_ge_cells_lib"] is not None else "-"
        md.append(f"| {b} | {v['logic_ge']:,} | {v['area_um2']:,} | {v['flip_flops']:,} | {old} | {mods} |")
    old = f"{r['logic_ge_cells_lib']:,}" if r["logic_ge_cells_lib"] is not None else "-"
    md.append(f"| **total** | **{r['logic_ge']:,}** | **{r['logic_area_um2']:,}** | **{r['flip_flops']:,}** | {old} | |")
    md.append("")
    md += ["Memories (scripts/pstlib/memarea.py): each distinct ROM synthesized alone to OSU018 cells with "
           "one read port and counted once per read port (replication; a 1999 mask ROM would be denser: an "
           "upper bound); delay address to data by OpenSTA (BUFX2-driven address, 0.02 pF load). RAMs: "
           "what the RTL builds, register files of OSU018 flip-flops with asynchronous reads (fit to a "
           "256 x 32 RAM synthesized here: storage and write port, plus a read multiplexer per port); "
           "the last column is what SRAM macros would cost if the reads were registered (one per read "
           "port, 13.5 um^2 per bit, the 6T cell of GlobalFoundries' published 180 nm SRAM macros, over "
           "an assumed 0.5 array efficiency), not in the total. The delays are the stand-in cells' in "
           "the design's timing.\n",
           "| memory | kind | instances | words x bits | read / write ports | bits | GE each (all ports) | GE | delay ns | SRAM macros GE (registered reads) |",
           "|---|---|---:|---|---|---:|---:|---:|---:|---:|"]
    for m in r["memories"]:
        flop = f"{m['sram_macro_ge']:,}" if m.get("sram_macro_ge") is not None else "-"
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
        c = r["timing"]["constraints"]
        md += [f"Critical path per stage (OpenSTA, {FMAX_LABEL}; scripts/synth/pst.sdc: {c['period_ns']:g} ns target, "
               f"clock uncertainty {c['setup_uncertainty_ns']:g} ns setup / {c['hold_uncertainty_ns']:g} ns hold, "
               f"clock transition {c['clock_transition_ns']:g} ns, input transition {c['input_transition_ns']:g} ns; "
               "worst path into each block's registers):\n",
               "| stage (block) | start point | end point | through | arrival ns | slack ns | min period ns | cells |",
               "|---|---|---|---|---:|---:|---:|---:|"]
        for s in sorted(r["timing"]["stages"], key=lambda s: s["slack_ns"]):
            md.append(f"| {s['stage']} | `{s['startpoint']}` | `{s['endpoint']}` | {', '.join(s.get('through', []))} | "
                      f"{s['arrival_ns']:.2f} | {s['slack_ns']:+.2f} | {s['min_period_ns']:.2f} | {s['cells']} |")
        md.append("")
        md += ["Hold per stage (OpenSTA, shortest path into each block's registers):\n",
               "| stage (block) | start point | end point | arrival ns | slack ns | cells |",
               "|---|---|---|---:|---:|---:|"]
        for s in sorted(r["timing"]["hold"]["stages"], key=lambda s: s["slack_ns"]):
            md.append(f"| {s['stage']} | `{s['startpoint']}` | `{s['endpoint']}` | {s['arrival_ns']:.2f} | "
                      f"{s['slack_ns']:+.3f} | {s['cells']} |")
        md.append("")
    return "\n".join(md) + "\n"
