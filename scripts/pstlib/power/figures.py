"""From per-workload power (flow.Power at the SDC clock) and the profile's silicon record to the
figures a designer quotes: mW at the profile's clock, pJ per pixel, mW at the real-time rate,
per block, and the memories' share from the stated model (flow.py, step 4)."""
import math

REALTIME_MPIXEL_S = 36.9     # the paper's real-time rate (the silicon table's, pstlib.synth)
RAM_READS = " and the RAMs' read ports"


def workload_figures(pw, cycles: int, pixels: int, rom_area_um2: float, ram_read_area_um2: float = 0.0) -> dict:
    """One workload: watts at the SDC clock (logic, the memories' model), energy per pixel (pJ).
    ROM_AREA_UM2: the ROMs' cell area (built from the same cells as the logic); RAM_READ_AREA_UM2:
    the RAMs' read multiplexers (memarea.ram_read_area_um2), both at the logic's dynamic density."""
    t = pw.groups["Total"]
    comb = pw.groups["Combinational"]
    density = (comb[0] + comb[1]) / pw.comb_area_um2 if pw.comb_area_um2 else 0.0   # W/um^2 dynamic
    rom_dyn = rom_area_um2 * density
    ram_dyn = ram_read_area_um2 * density
    mem_dyn = rom_dyn + ram_dyn
    window_s = cycles * pw.period_ns * 1e-9
    dyn = t[0] + t[1] + mem_dyn
    leak = t[2]
    return {
        "cycles": cycles, "pixels": pixels,
        "clocks_per_pixel": cycles / pixels if pixels else None,
        "at_sdc_clock_mhz": 1e3 / pw.period_ns,
        "internal_w": t[0], "switching_w": t[1], "leakage_w": leak,
        "memory_model_w": mem_dyn, "rom_model_w": rom_dyn, "ram_model_w": ram_dyn,
        "dynamic_w": dyn,
        "sequential_w": pw.groups["Sequential"][3], "combinational_w": comb[3],
        "pj_per_pixel": (dyn + leak) * window_s / pixels * 1e12 if pixels else None,
        "blocks_w": {k: v[3] for k, v in pw.blocks.items()},
        "traced_bits": pw.traced_bits, "untraced_bits": pw.missing_bits,
        "port_driven_cells": pw.port_driven_cells, "cells": pw.cells,
    }


def profile_figures(rows: dict, record: dict) -> dict:
    """Every workload (name -> workload_figures) and the profile's silicon record -> the summary:
    mean, least and most pJ/pixel over the workloads, mW at the profile's clock (pre-layout Fmax
    and derated when the record has it) and at the real-time rate."""
    ok = {k: r for k, r in rows.items() if r["pj_per_pixel"]}
    if not ok:
        raise ValueError("no workload produced a pixel inside its traced window")
    pj = [r["pj_per_pixel"] for r in ok.values()]
    mean = lambda key: sum(r[key] for r in ok.values()) / len(ok)      # noqa: E731
    sdc_mhz = next(iter(ok.values()))["at_sdc_clock_mhz"]
    dyn, leak = mean("dynamic_w"), mean("leakage_w")
    cpp = record.get("clocks_per_pixel")
    fmax = record.get("fmax_mhz")

    def at(mhz):
        return None if not mhz else (dyn * mhz / sdc_mhz + leak) * 1e3
    e_px = sum(pj) / len(pj)
    out = {
        "workloads": len(ok),
        "pj_per_pixel": e_px, "pj_per_pixel_min": min(pj), "pj_per_pixel_max": max(pj),
        "mw_at_sdc_clock": (dyn + leak) * 1e3, "sdc_clock_mhz": sdc_mhz,
        "fmax_mhz": fmax, "fmax_basis": record.get("fmax_basis"), "mw_at_fmax": at(fmax),
        "fmax_derated_mhz": record.get("fmax_derated_mhz"), "mw_at_fmax_derated": at(record.get("fmax_derated_mhz")),
        "clocks_per_pixel": cpp,
        "leakage_mw": leak * 1e3,
        "memory_model_share": mean("memory_model_w") / (dyn + leak) if dyn + leak else 0.0,
        "ram_model_share": mean("ram_model_w") / (dyn + leak) if dyn + leak and all("ram_model_w" in r for r in ok.values())
        else 0.0,
        "sequential_share": mean("sequential_w") / (dyn + leak) if dyn + leak else 0.0,
    }
    # Real time: the rate needs 36.9 M x clocks/pixel clocks per second; a profile whose Fmax is
    # short of it needs that many copies side by side (each leaking).
    if cpp and fmax:
        need_mhz = REALTIME_MPIXEL_S * cpp
        copies = max(1, math.ceil(need_mhz / fmax - 1e-9))
        out["realtime_copies"] = copies
        # energy per pixel already holds the leakage of the one copy over a pixel's clocks;
        # the extra copies add their leakage over the same second
        dyn_px = e_px * 1e-12 - leak * cpp / (sdc_mhz * 1e6)
        out["mw_at_realtime"] = (dyn_px * REALTIME_MPIXEL_S * 1e6 + copies * leak) * 1e3
    blocks = {}
    for r in ok.values():
        for b, w in r["blocks_w"].items():
            blocks[b] = blocks.get(b, 0.0) + w / len(ok)
    out["blocks_mw_at_sdc_clock"] = {b: w * 1e3 for b, w in sorted(blocks.items(), key=lambda kv: -kv[1])}
    return out


def markdown(name: str, summary: dict, rows: dict, method: str) -> str:
    f = lambda v, d=1: "-" if v is None else f"{v:,.{d}f}"      # noqa: E731
    s = summary
    lines = [f"# Power of {name} (OSU 0.18 um, typical corner, pre-layout)", "",
             "| figure | value |", "|---|---:|",
             f"| energy per pixel, mean of {s['workloads']} workloads | {f(s['pj_per_pixel'], 0)} pJ |",
             f"| energy per pixel, least / most | {f(s['pj_per_pixel_min'], 0)} / {f(s['pj_per_pixel_max'], 0)} pJ |",
             f"| power at {f(s['fmax_mhz'])} MHz ({s['fmax_basis']} Fmax) | {f(s['mw_at_fmax'])} mW |",
             f"| power at {f(s['fmax_derated_mhz'])} MHz (derated Fmax) | {f(s['mw_at_fmax_derated'])} mW |",
             f"| power at {REALTIME_MPIXEL_S} Mpixel/s ({s.get('realtime_copies', '-')} "
             f"cop{'y' if s.get('realtime_copies') == 1 else 'ies'}) | {f(s.get('mw_at_realtime'))} mW |",
             f"| leakage | {f(s['leakage_mw'], 3)} mW |",
             f"| sequential share (flops, their clock pins) | {100 * s['sequential_share']:.0f} % |",
             f"| memories' share (area model: the ROMs{RAM_READS if 'rams_modelled' in s else ''}) | "
             f"{100 * s['memory_model_share']:.0f} % |",
             (f"| of which the RAMs' read ports | {100 * s.get('ram_model_share', 0.0):.0f} % ({s['rams_modelled']}) |"
              if "rams_modelled" in s else
              f"| RAMs (not modelled; --ram-reads models their read ports) | {s.get('rams_not_modelled') or 'none'} |"),
             "", f"Per block, mW at {f(s['sdc_clock_mhz'], 0)} MHz (mean over the workloads):", "",
             "| block | mW |", "|---|---:|"]
    lines += [f"| {b} | {f(w, 2)} |" for b, w in s["blocks_mw_at_sdc_clock"].items()]
    lines += ["", f"Per workload, at {f(s['sdc_clock_mhz'], 0)} MHz:", "",
              "| workload | cycles | pixels | clocks/pixel | internal mW | switching mW | leakage mW | memories mW | pJ/pixel |",
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for k, r in rows.items():
        lines.append(f"| {k} | {r['cycles']} | {r['pixels']} | {f(r['clocks_per_pixel'], 2)} | "
                     f"{f(r['internal_w'] * 1e3)} | {f(r['switching_w'] * 1e3)} | {f(r['leakage_w'] * 1e3, 4)} | "
                     f"{f(r['memory_model_w'] * 1e3)} | {f(r['pj_per_pixel'], 0)} |")
    lines += ["", "Method:", "", method.strip(), ""]
    return "\n".join(lines)
