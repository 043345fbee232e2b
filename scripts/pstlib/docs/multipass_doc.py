"""The multipass noise's tables (docs/MULTIPASS.md sections multipass-quality and
multipass-proposals) from docs/data/multipass.json, which build/pst_multipass_study writes
(testbench/gpu/multipass_study.cpp; every number there is measured by that tool, none typed)."""
import json
from pathlib import Path

SOURCE = Path("docs/data/multipass.json")
NAMES = {"sgi": "SGI (4), linear", "sgi_scurve": "SGI (4), SCURVE", "rc": "register combiners (5)"}


def load(root: Path) -> dict:
    path = root / SOURCE
    if not path.exists():
        raise ValueError(f"{SOURCE}: missing (build/pst_multipass_study --out {SOURCE})")
    return json.loads(path.read_text())


def _need(d: dict, key: str, where: str):
    if key not in d:
        raise ValueError(f"{SOURCE}: {where}.{key}: missing")
    return d[key]


def quality_markdown(root: Path) -> str:
    d = load(root)
    q = _need(d, "quality", "")
    L = [f"Measured by `pst_multipass_study` on {d['renderer']} ({d['gl_version']}), "
         f"{d['quality_samples']:,} random coordinates (bytes s, t, r; seed {d['seed']}), b = 8. "
         "Noise values in [0, 1]; LSB = 1/255. *vs Figure 3*: the passes against Figure 3 evaluated in double "
         "on the variant's own lattice values (what 8 bits and b_f cost). Rayshade: model/noise.h, value corners, "
         "the variant's interpolation, at the same points; the chip: the golden model (profile `balanced`, noise "
         "interp as the variant, corner value). The lattice values of the multipass noise are a different random "
         "field from Rayshade's hashed one, so pointwise RMS vs Rayshade measures two unrelated fields; the "
         "distributions compare (KS: the Kolmogorov-Smirnov distance of the value distributions; excess "
         "kurtosis: uniform -1.2, Gaussian 0).", "",
         "| variant | b_f | draws | GL pixels differing from the CPU model | RMS / max vs Figure 3 (LSB) | "
         "mean | std | excess kurtosis | KS vs Rayshade | pointwise RMS vs Rayshade |",
         "|---|---:|---:|---:|---|---:|---:|---:|---:|---:|"]
    for e in q:
        n = e["noise"]
        L.append(f"| {NAMES.get(e['variant'], e['variant'])} | {e['b_f']} | {e['draws']} | "
                 f"{e['gl_pixels_differing_from_cpu_model']} | {e['rms_vs_ideal_lsb']:.2f} / {e['max_vs_ideal_lsb']:.2f} | "
                 f"{n['mean']:.3f} | {n['stddev']:.3f} | {n['excess_kurtosis']:+.2f} | {e['ks_vs_rayshade']:.3f} | "
                 f"{e['rms_pointwise_vs_rayshade']:.3f} |")
    L += ["", "The references at the same points (per b_f: the sample grid is the byte grid / 2^b_f):", "",
          "| interpolation | b_f | Rayshade mean / std / excess kurtosis | chip mean / std / excess kurtosis | "
          "chip vs Rayshade RMS (LSB) | KS chip vs Rayshade |",
          "|---|---:|---|---|---:|---:|"]
    for e in q:
        if e["variant"] == "rc":
            continue
        r, c = e["rayshade"], e["chip"]
        L.append(f"| {'SCURVE' if e['variant'] == 'sgi_scurve' else 'linear'} | {e['b_f']} | "
                 f"{r['mean']:.3f} / {r['stddev']:.3f} / {r['excess_kurtosis']:+.2f} | "
                 f"{c['mean']:.3f} / {c['stddev']:.3f} / {c['excess_kurtosis']:+.2f} | "
                 f"{e['rms_chip_vs_rayshade'] * 255:.3f} | {e['ks_chip_vs_rayshade']:.4f} |")
    L += ["", "Lattice correlation (the paper's Figures 6 and 11), over the whole 2^b_i cube of lattice values: "
          "*neighbour* the correlation of the values at (i, j, k) and the next point along one axis, *shared* at "
          "points sharing two coordinates (stride about half the lattice), before the final randomization (SGI: "
          "sran + tran + rran, Figure 6; register combiners: tex_corrnan, Figure 11 (a)) and after it (SGI: nran "
          "of the sum; register combiners: tex_corrnanran, Figure 11 (b)); Rayshade's hashed lattice beside them.",
          "",
          "| variant | b_f | before: neighbour / shared / excess kurtosis | after: neighbour / shared / std / "
          "excess kurtosis | Rayshade: neighbour / shared / excess kurtosis |",
          "|---|---:|---|---|---|"]
    for e in q:
        if e["variant"] == "sgi_scurve":
            continue
        b, a, r = e["lattice_before_final"], e["lattice"], e["lattice_rayshade"]
        L.append(f"| {NAMES.get(e['variant'], e['variant'])} | {e['b_f']} | "
                 f"{b['neighbour']:+.3f} / {b['shared_two_coords']:+.3f} / {b['excess_kurtosis']:+.2f} | "
                 f"{a['neighbour']:+.3f} / {a['shared_two_coords']:+.3f} / {a['stddev']:.3f} / {a['excess_kurtosis']:+.2f} | "
                 f"{r['neighbour']:+.3f} / {r['shared_two_coords']:+.3f} / {r['excess_kurtosis']:+.2f} |")
    return "\n".join(L) + "\n"


def proposals_markdown(root: Path) -> str:
    d = load(root)
    p = d.get("proposals")
    if not p:
        return "Not measured yet (pst_multipass_study writes `proposals`).\n"
    L = [f"Measured by `pst_multipass_study` on {d['renderer']} ({d['gl_version']}), on a 2-core machine shared "
         f"with other builds (1-minute load average {p['load_average_1min_start']:.1f} at the start, "
         f"{p['load_average_1min_end']:.1f} at the end): times are the **minimum** over {p['frames']} frames of "
         "the passes alone (glFinish to glFinish), and still noisy. Error vs Rayshade is pointwise only where the "
         "lattice is Rayshade's own (the integer-hash rows); elsewhere it is the distance to Figure 3 in double on "
         "the variant's lattice.", "",
         "| configuration | target | size | b_f | draws | ms / frame (min) | ms / draw | GL pixels differing from its "
         "model | RMS vs Figure 3 (1/255) | RMS vs Rayshade (1/255) |",
         "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]

    def num(v, fmt):
        if v is None:
            return "-"
        if fmt == ".4f" and 0 < abs(v) < 1e-3:
            return format(v, ".1e")
        return format(v, fmt)

    for r in p["rows"]:
        diff = num(r.get('gl_pixels_differing'), 'd')
        if r.get("gl_max_difference_lsb_of_b"):
            diff += f" (at most {r['gl_max_difference_lsb_of_b']} LSB of b bits)"
        L.append(f"| {r['name']} | {r['target']} | {r['size']} | {r['b_f']} | {r['draws']} | "
                 f"{num(r.get('ms_min'), '.2f')} | {num(r.get('ms_per_draw'), '.3f')} | {diff} | "
                 f"{num(r.get('rms_vs_ideal_lsb'), '.4f')} | {num(r.get('rms_vs_rayshade_lsb'), '.4f')} |")
    # The cost of glCopyTexSubImage2D per draw: the copy rows against their render-to-texture rows.
    rtt = {(r["name"].split(",")[0], r["size"]): r for r in p["rows"] if r["name"].endswith("render to texture")}
    cp = [r for r in p["rows"] if r["name"].endswith("glCopyTexSubImage2D per draw")]
    if cp:
        L += ["", "glCopyTexSubImage2D (the paper's savetex, section 6.2) against render to texture, per draw "
              "(difference of the two rows' minimum frame times / draws):", "",
              "| variant | size | render to texture ms / draw | with a copy ms / draw | the copy's cost ms / draw |",
              "|---|---:|---:|---:|---:|"]
        for r in cp:
            base = rtt.get((r["name"].split(",")[0], r["size"]))
            if base:
                L.append(f"| {r['name'].split(',')[0]} | {r['size']} | {base['ms_per_draw']:.3f} | {r['ms_per_draw']:.3f} | "
                         f"{(r['ms_min'] - base['ms_min']) / r['draws']:+.3f} |")
    iso = p.get("isolated", [])
    if iso:
        L += ["", f"The same two operations timed in isolation (the minimum over {p['frames']} repetitions of a batch, "
              "per operation): one glCopyTexSubImage2D of a whole RGBA8 image from the framebuffer texture into a "
              "texture, and one PixelTransfer draw (scale, bias, no map) rendered to a texture:", "",
              "| size | glCopyTexSubImage2D ms | one pass drawn ms | copy / draw |", "|---:|---:|---:|---:|"]
        for r in iso:
            L.append(f"| {r['size']} | {r['copy_ms']:.3f} | {r['draw_ms']:.3f} | {r['copy_ms'] / r['draw_ms']:.2f} |")
    notes = p.get("notes", [])
    if notes:
        L += [""] + [f"- {n}" for n in notes]
    return "\n".join(L) + "\n"
