"""The record of a profile placed and routed block by block, its Markdown, and the derate
file every synthesis reads (scripts/synth/layout_derate.json)."""
import datetime
import json
import pathlib
import subprocess

from ..paths import ROOT

TARGET_MHZ = 100.0


def assemble(name: str, synth: dict, blocks: list, synth_seconds: float, seconds: float) -> dict:
    """Per block and for the whole profile: area is the blocks' dies plus the memories (their
    model in the synthesis record); post-route Fmax is the slowest block's; the derate is the
    worst block's post-route / pre-layout ratio, which --update-derate writes for every synthesis
    to apply to its pre-layout Fmax (pstlib/synth/report.py, the one place that applies it; the
    whole design's pre-layout Fmax, the flat netlist with memories where paths cross blocks, is
    recorded here beside it)."""
    post = min(blocks, key=lambda b: b["sta"]["post_route"]["fmax_mhz"])
    derate = min(b["fmax_ratio"] for b in blocks)
    die = sum(b["die_mm2"] for b in blocks)
    mem = synth["memory_area_um2"] / 1e6
    whole_pre = synth.get("fmax_mhz")
    return {
        "profile": name,
        "method": "qflow 1.3.17 per block (graywolf, qrouter stages 1-2, magic DRC/GDS, netgen LVS); "
                  "OpenSTA with qrouter's RC trees as SPEF (both fringe edges); typical corner",
        "blocks": blocks,
        "block_count": len(blocks),
        "die_mm2_blocks": round(die, 4),
        "memory_mm2": round(mem, 4),
        "total_mm2": round(die + mem, 4),
        "logic_cell_mm2": round(sum(b["cell_area_mm2"] for b in blocks), 4),
        "cells": sum(b["cells"] for b in blocks),
        "flip_flops": sum(b["flip_flops"] for b in blocks),
        "wirelength_mm": round(sum(b["wirelength_mm"] for b in blocks), 1),
        "drc_errors": sum(b["drc_errors"] for b in blocks),
        "lvs_match": all(b["lvs_match"] for b in blocks),
        # The routed netlists against the blocks as cut (pstlib/pnr/lec.py), each with its mutant.
        "lec_proven": sum((b.get("lec") or {}).get("routed", {}).get("result") == "proven" for b in blocks),
        "lec_mutants_caught": sum((b.get("lec") or {}).get("mutant", {}).get("result") == "differs" for b in blocks),
        "post_route_fmax_mhz": post["sta"]["post_route"]["fmax_mhz"],
        "post_route_slowest_block": post["block"],
        "post_route_critical_path": post["sta"]["post_route"]["critical_path"],
        "hold_slack_ns": min(b["sta"]["post_route"]["hold_slack_ns"] for b in blocks),
        "max_transition_violations": sum(b["sta"]["post_route"]["max_transition_violations"] for b in blocks),
        "max_capacitance_violations": sum(b["sta"]["post_route"]["max_capacitance_violations"] for b in blocks),
        "fmax_ratio_post_over_pre": derate,
        "whole_design_pre_layout_fmax_mhz": whole_pre,
        "meets_target": post["sta"]["post_route"]["fmax_mhz"] >= TARGET_MHZ,
        "target_mhz": TARGET_MHZ,
        "synthesis": {k: synth.get(k) for k in ("logic_ge", "memory_ge", "total_ge", "total_area_mm2",
                                                "flip_flops", "fmax_mhz", "clocks_per_pixel")},
        "seconds": {"synthesis": synth_seconds, "total": seconds,
                    "blocks": {b["block"]: b["seconds"] for b in blocks}},
    }


def _repaired(b: dict) -> str:
    """How many minimum-area islands the DRC step repaired in the block (pstlib/pnr/islands.py)."""
    f = b.get("drc_islands_repaired")
    if not f or not f.get("drc_before"):
        return ""
    return f" (was {f['drc_before']}: {f['moved']} via moved onto its pin, {f['removed']} removed)"


def _pins(b: dict) -> str:
    """The median distance from a block pin to the nearest cell on its net; for a block whose
    pins were placed from its cells after a placement that did not route (pstlib/pnr/pins.py),
    the figure of that placement beside."""
    d = b.get("median_pin_to_cell_um")
    if d is None:
        return "-"
    tries = b.get("pin_hints") or []
    return f"{d:.0f}" + (f" (pins from cells; was {tries[0]['median_pin_to_cell_um_before']:.0f})" if tries else "")


def _lec(b: dict) -> str:
    """A block's routed-netlist equivalence, in the table: "proven (differs)", or "-" when not run."""
    e = b.get("lec")
    if not e:
        return "-"
    return f"{e['routed']['result']} ({e['mutant']['result']})"


def _assembled_rows(a) -> list:
    """The whole chip timed from its blocks (pstlib/pnr/assembly.py)."""
    if not a:
        return []
    if "error" in a:
        return [f"| whole chip, blocks assembled (post-route) | not timed: {a['error']} |"]
    cp = a["critical_path"]
    pre = (f"; without layout (netlist before layout, no wires): {', '.join(a['blocks_without_layout'])}"
           if a["blocks_without_layout"] else "")
    return [f"| **whole chip, blocks assembled: post-route Fmax** (every block's routed netlist and SPEF "
            f"under its instance, clock propagated through each block's buffers; no wire between blocks{pre}) | "
            f"**{a['fmax_mhz']:.1f} MHz** ({'meets' if a['fmax_mhz'] >= TARGET_MHZ else 'misses'} "
            f"{TARGET_MHZ:.0f} MHz): `{cp['from']}` -> `{cp['to']}` ({cp['arrival_ns']:.2f} ns, {cp['cells']} cells, "
            f"slack {cp['slack_ns']:+.3f} ns) |",
            f"| whole chip: worst hold slack / max-transition / max-capacitance violations | "
            f"{a['hold_slack_ns']:+.3f} ns / {a['max_transition_violations']} / {a['max_capacitance_violations']} |"]


def markdown(r: dict) -> str:
    md = [f"## Place and route: profile `{r['profile']}`\n",
          f"Method: {r['method']}. Each block is timed alone with the SDC's 2 ns input and output "
          "budgets at its pins; pre-layout and post-route are the same (qflow-buffered) netlist without "
          "and with the routed parasitics (post-route: clock propagated through qflow's clock buffers, setup "
          "uncertainty the SDC's jitter only).\n",
          "| figure | value |", "|---|---:|",
          f"| blocks | {r['block_count']} routed"
          + (f"; not finished: {', '.join(r['failed_blocks'])} (below)" if r.get("failed_blocks") else "")
          + (f"; not run (--block): {', '.join(r['skipped_blocks'])}" if r.get("skipped_blocks") else "") + " |",
          f"| die area, sum of the routed blocks | {r['die_mm2_blocks']:.3f} mm^2 (cells {r['logic_cell_mm2']:.3f} mm^2) |",
          f"| memories (synthesis model) | {r['memory_mm2']:.3f} mm^2 |",
          f"| **total** | **{r['total_mm2']:.3f} mm^2** |",
          f"| cells / flip-flops | {r['cells']:,} / {r['flip_flops']:,} |",
          f"| routed wire | {r['wirelength_mm']:,.1f} mm |",
          f"| DRC errors / LVS | {r['drc_errors']} / {'match' if r['lvs_match'] else 'MISMATCH'} |",
          *([f"| routed netlist = block as cut (Yosys miter, ABC dprove) / its mutant caught | "
             f"{r['lec_proven']} of {r['block_count']} proven / {r['lec_mutants_caught']} of {r['block_count']} |"]
            if "lec_proven" in r else []),
          f"| post-route Fmax (slowest block path, each block alone with 2 ns pin budgets) | {r['post_route_fmax_mhz']:.1f} MHz in `{r['post_route_slowest_block']}` "
          f"({'meets' if r['meets_target'] else 'misses'} {r['target_mhz']:.0f} MHz) |",
          f"| worst hold slack / max-transition / max-capacitance violations | {r['hold_slack_ns']:+.3f} ns / "
          f"{r['max_transition_violations']} / {r['max_capacitance_violations']} |",
          *_assembled_rows(r.get("assembled")),
          f"| post-route / pre-layout Fmax (worst block) | {r['fmax_ratio_post_over_pre']:.3f} |",
          f"| whole design: pre-layout (derated in every synthesis record after --update-derate) | "
          f"{r['whole_design_pre_layout_fmax_mhz']} MHz |",
          *([f"| fanout step: synthesis' hand buffers vs blifFanout, whole design pre-layout | "
              f"{r['buffering']['fmax_mhz_hand_fanout']} vs {r['buffering']['fmax_mhz_blif_fanout']} MHz "
              f"({r['buffering']['blif_fanout_buffers']:,} buffers; "
              f"{'within' if r['buffering']['within_2_percent'] else 'NOT within'} 2 %) |"]
            if "fmax_mhz_blif_fanout" in r.get("buffering", {}) else []),
          *([f"| command | `{r['command']}` |"] if r.get("command") else []),
          f"| time | synthesis {r['seconds']['synthesis']:.0f} s, all {r['seconds']['total'] / 60:.1f} min |", "",
          "| block | instance | cells | FF | die um | util (placed at) | wire mm | DRC | LVS | Fmax pre | Fmax post | ratio | "
          "reg-reg post | hold ns | worst path (post) | pin to cell um (median) | place + route min | routed = cut (mutant) |",
          "|---|---|---:|---:|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---|---:|---:|---|"]
    for b in r["blocks"]:
        pre, post = b["sta"]["pre_layout"], b["sta"]["post_route"]
        cp = post["critical_path"]
        s = b["seconds"]
        md.append(f"| {b['block']} | `{b['instance']}` | {b['cells']:,} | {b['flip_flops']:,} | "
                  f"{b['die_um'][0]:.0f} x {b['die_um'][1]:.0f} | {b['utilization']:.2f} ({b['initial_density']:.2f}) | {b['wirelength_mm']:,.1f} | "
                  f"{b['drc_errors']}{_repaired(b)} | {'match' if b['lvs_match'] else 'MISMATCH'} | {pre['fmax_mhz']:.1f} | "
                  f"{post['fmax_mhz']:.1f} | {b['fmax_ratio']:.3f} | {post['reg2reg']['fmax_mhz']:.1f} | "
                  f"{post['hold_slack_ns']:+.3f} | `{cp['from']}` -> `{cp['to']}` ({cp['arrival_ns']:.2f} ns, "
                  f"{cp['cells']} cells) | {_pins(b)} | {(s['place'] + s['route']) / 60:.1f} | {_lec(b)} |")
    for name, f in r.get("failed_blocks", {}).items():
        md.append(f"| {name} | `{f['instance']}` | ({f['cells_synth']:,} cells synthesized) | - | - | - | - | - | - | - | "
                  f"- | - | - | - | not finished: {f['error']} | - | - | - |")
    md.append("")
    md += [f"![{b['block']}]({r['profile']}/{b['png']})" for b in r["blocks"]]
    return "\n".join(md) + "\n"


def write_derate(r: dict, path) -> None:
    """The worst block's post-route / pre-layout ratio, with where it comes from."""
    sha = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                         text=True).stdout.strip() or "unknown"
    slow = next(b for b in r["blocks"] if b["block"] == r["post_route_slowest_block"])
    doc = {"profile": r["profile"], "ratio": r["fmax_ratio_post_over_pre"],
           "blocks": [b["block"] for b in r["blocks"]], "not_routed": sorted([*r.get("failed_blocks", {}), *r.get("skipped_blocks", [])]),
           "source": f"scripts/pnr.py {r['profile']} on {sha}, {datetime.date.today().isoformat()}",
           "worst_ratio_block": min(r["blocks"], key=lambda b: b["fmax_ratio"])["block"],
           "post_route_fmax_mhz": r["post_route_fmax_mhz"], "slowest_block": r["post_route_slowest_block"],
           "slowest_block_pre_layout_fmax_mhz": slow["sta"]["pre_layout"]["fmax_mhz"],
           "block_ratios": {b["block"]: b["fmax_ratio"] for b in r["blocks"]},
           "method": r["method"]}
    a = r.get("assembled") or {}
    if "fmax_mhz" in a:
        # The whole chip timed from its routed blocks (pstlib/pnr/assembly.py).
        doc.update({"assembled_fmax_mhz": a["fmax_mhz"], "assembled_critical_path": a["critical_path"],
                    "assembled_hold_slack_ns": a["hold_slack_ns"],
                    "assembled_blocks_without_layout": a["blocks_without_layout"]})
    # Routed only in part by choice (--block): its critical blocks; its clock after layout is then
    # its pre-layout Fmax derated by their worst ratio, not the slowest routed block's Fmax.
    doc["critical_blocks_only"] = bool(r.get("skipped_blocks"))
    if r.get("command"):
        doc["command"] = r["command"]
    path = pathlib.Path(path)
    old = json.loads(path.read_text()) if path.exists() else {}
    profiles = dict(old.get("profiles") or {})
    profiles[r["profile"]] = doc
    path.write_text(json.dumps({"profiles": dict(sorted(profiles.items()))}, indent=2) + "\n")
