"""The ground-truth table of the filter options: RMS and PSNR against the N x N ground
truth for the unfiltered image, the paper's filter (the SAT) and each option beyond the paper
(the trapezoid footprint, bandlimited octaves), per scene and per animated sequence, with the
flicker of each sequence and the filter goals, met or missed.

Inputs: `pst render SCENE --truth N --variants sat,...` (report.json: vs_truth of the unfiltered
image and of every variant) and `pst animate SCENE --truth N --variants ...` (flicker.json: per
stream the RMS against the truth per frame and the temporal RMS error per frame)."""
import math
from pathlib import Path

from . import flicker

PAPER = "sat"        # the paper's filter: the summed-area colour table
UNFILTERED = "unfiltered"
RTL = "rtl:"         # a hardware stream's column: rtl:PROFILE (the RTL's own images)
# The reference options a hardware profile computes (the paper's filter; the fade unit, whose exact
# form +isotropic is, for the lattice and worley bases: on the subband basis the reference's
# +isotropic is the subband weights, which no unit computes).
HW_OPTIONS = (PAPER, "sat+isotropic")


class FidelityError(Exception):
    """Malformed or missing input: 'FILE: what is wrong'."""


def psnr(rms):
    """PSNR in dB of an RMS error on [0, 1] images (inf for 0)."""
    return float("inf") if rms <= 0 else 20.0 * math.log10(1.0 / rms)


def load_still(path):
    """A `pst render --truth N --variants ...` report: {scene, size, truth, rms: {stream: rms}}."""
    path, doc = flicker.read_json(path, "report.json", FidelityError)
    if not isinstance(doc, dict) or "vs_truth" not in doc:
        raise FidelityError(f"{path}: vs_truth: missing (rendered without --truth?)")
    variants = doc.get("variants")
    if not isinstance(variants, dict) or PAPER not in variants:
        raise FidelityError(f"{path}: variants: missing the paper's filter '{PAPER}' (pst render --variants {PAPER},...)")
    rms = {UNFILTERED: doc["vs_truth"]["unfiltered"]["rms"]}
    for name, v in variants.items():
        if "vs_truth" not in v:
            raise FidelityError(f"{path}: variants.{name}.vs_truth: missing (rendered without --truth?)")
        rms[name] = v["vs_truth"]["rms"]
    for name, r in rms.items():
        if not isinstance(r, (int, float)) or not math.isfinite(r) or r < 0:
            raise FidelityError(f"{path}: {name}: RMS is not a finite number >= 0")
    return {"scene": Path(doc.get("scene", path.parent.name)).stem, "size": f'{doc["width"]}x{doc["height"]}',
            "truth": doc.get("truth_samples", 0), "title": str(doc.get("title", "")), "rms": rms}


def paper_scene(still):
    """Whether a still is one of the paper's figures (its scene title starts with 'Fig.')."""
    return still.get("title", "").startswith("Fig.")


def hardware_options(still):
    """The still's columns a hardware profile computes: the paper's filter, and on a lattice or
    worley basis the fade unit's exact form (+isotropic); on the subband basis only the paper's
    filter (the subband unit's own still is not in a `pst render --variants` report)."""
    opts = [PAPER]
    if "subband" not in still["scene"]:
        opts += [n for n in HW_OPTIONS if n != PAPER]
    return [n for n in opts if n in still["rms"]]


def _meets(still, n):
    r = still["rms"]
    return r[n] < r[UNFILTERED] and r[n] <= r[PAPER]


def still_goals(stills):
    """The stills goal per paper scene (its best hardware option closer to the truth than
    unfiltered and not worse than the paper's filter) and for one hardware option on every paper
    scene, as (goal, figure, met) tuples."""
    out = []
    paper = [s for s in stills if paper_scene(s)]
    for s in paper:
        r = s["rms"]
        opts = hardware_options(s)
        bn = min(opts, key=lambda n: r[n])
        figs = "; ".join(f"{n} {r[n]:.4f}" for n in opts)
        out.append((f"still {s['scene']}: best hardware option closer to the truth than unfiltered, "
                    "not worse than the paper's",
                    f"unfiltered {r[UNFILTERED]:.4f}; {figs}; best {bn}", _meets(s, bn)))
    if paper:
        # One option for every paper scene: where it is missing (subband scenes) the paper's filter.
        per = [(n, [s["scene"] for s in paper if not _meets(s, n if n in hardware_options(s) else PAPER)])
               for n in HW_OPTIONS]
        ok = [n for n, bad in per if not bad]
        out.append(("every paper scene's still, one hardware option: closer than unfiltered and not worse than the paper's",
                    "; ".join(f"{n}: " + (f"fails {', '.join(bad)}" if bad else "all") for n, bad in per), bool(ok)))
    return out


def sequence_figures(doc):
    """A flicker.json (pstlib.figures.flicker.load) as {scene, frames, size, truth, rms, psnr, flicker}: per
    stream the mean over frames of the RMS against the truth, the PSNR of the whole sequence's RMS
    (sqrt of the mean square over frames) and the flicker."""
    st = doc["streams"]
    names = [UNFILTERED, "filtered"] + flicker.variant_streams(doc)
    # The hardware streams (pst animate --profile) measured against the truth: "rtl:PROFILE".
    hw = {f"{RTL}{n}": n for n, v in st.items() if v.get("hardware") and v.get("rms_vs_truth")}
    rms, ps, fl = {}, {}, {}
    for n in names + list(hw):
        per = st[hw.get(n, n)].get("rms_vs_truth", [])
        rms[n] = sum(per) / len(per) if per else 0.0
        ps[n] = psnr(math.sqrt(sum(v * v for v in per) / len(per))) if per else 0.0
        fl[n] = flicker.sequence_flicker(st[hw.get(n, n)]["temporal_rms"])
    # The paper's filter: the sat variant when given, else the scene's own filter.
    if PAPER not in rms:
        for d in (rms, ps, fl):
            d[PAPER] = d["filtered"]
    for d in (rms, ps, fl):
        d.pop("filtered")
    return {"scene": Path(doc["scene"]).stem, "frames": doc["frames"], "size": f'{doc["width"]}x{doc["height"]}',
            "truth": doc.get("truth_samples", 0), "rms": rms, "psnr": ps, "flicker": fl}


# The options in the order the tables show them (pst's JSON sorts its keys); others follow as seen.
ORDER = ["box", "trapezoid", "sat+footprint", "sat+isotropic", "trapezoid+footprint", "trapezoid+isotropic"]


def columns(rows):
    """Stream columns in order: unfiltered, the paper's filter, then the options (ORDER first)."""
    seen = []
    for r in rows:
        seen += [n for n in r["rms"] if n not in seen and n not in (UNFILTERED, PAPER)]
    return [UNFILTERED, PAPER] + [n for n in ORDER if n in seen] + [n for n in seen if n not in ORDER]


def _cell(rms, paper):
    if rms is None:
        return "-"
    ratio = f", {paper / rms:.2f}x" if paper and rms > 0 else ""
    return f"{rms:.4f} ({psnr(rms):.1f} dB{ratio})"


def goals(stills, seqs):
    """The goals (filter error vs unfiltered, flicker) for the paper's filter and the best
    option, as (goal, figure, met) tuples."""
    out = []
    by = {r["scene"]: r for r in stills}

    def best(r):
        opts = {n: v for n, v in r.items() if n != UNFILTERED}
        return min(opts.items(), key=lambda kv: kv[1])

    if "seascape" in by:
        r = by["seascape"]["rms"]
        ratio = r[UNFILTERED] / r[PAPER]
        bn, bv = best(r)
        out.append(("seascape: filtered error >= 2x lower than unfiltered",
                    f"paper {ratio:.2f}x; best option {bn} {r[UNFILTERED] / bv:.2f}x", max(ratio, r[UNFILTERED] / bv) >= 2))
    if "planet" in by:
        r = by["planet"]["rms"]
        bn, bv = best(r)
        out.append(("planet: filtered error lower than unfiltered",
                    f"paper {r[PAPER]:.4f} vs unfiltered {r[UNFILTERED]:.4f}; best {bn} {bv:.4f}", r[PAPER] < r[UNFILTERED]))
    if stills:
        worst = min(stills, key=lambda s: s["rms"][UNFILTERED] / s["rms"][PAPER])
        wb = min(stills, key=lambda s: s["rms"][UNFILTERED] / best(s["rms"])[1])
        wr = worst["rms"][UNFILTERED] / worst["rms"][PAPER]
        wbr = wb["rms"][UNFILTERED] / best(wb["rms"])[1]
        out.append(("every scene: filtered error >= 1.5x lower than unfiltered",
                    f"paper: worst {worst['scene']} {wr:.2f}x; best option per scene: worst {wb['scene']} {wbr:.2f}x",
                    max(wr, wbr) >= 1.5))
    out += still_goals(stills)
    for s in seqs:
        if s["scene"] == "seascape":
            f = s["flicker"]
            bn, bv = min(((n, v) for n, v in f.items() if n != UNFILTERED), key=lambda kv: kv[1])
            ratio = f[UNFILTERED] / f[PAPER] if f[PAPER] > 0 else float("inf")
            bratio = f[UNFILTERED] / bv if bv > 0 else float("inf")
            out.append(("seascape fly-in: flicker >= 4x lower than unfiltered",
                        f"paper {ratio:.2f}x; best option {bn} {bratio:.2f}x (reference model; the options have no "
                        "hardware unit)", max(ratio, bratio) >= 4))
    # In hardware: the best a hardware profile computes on any seascape fly-in (the RTL's own
    # streams, the paper's filter, the fade's exact form on a lattice basis), each against its
    # sequence's unfiltered stream.
    best_hw = None
    for s in seqs:
        if not s["scene"].startswith("seascape"):
            continue
        f = s["flicker"]
        for n, v in f.items():
            lattice = "subband" not in s["scene"]
            if v > 0 and (n.startswith(RTL) or n == PAPER or (lattice and n in HW_OPTIONS)):
                r = f[UNFILTERED] / v
                if best_hw is None or r > best_hw[0]:
                    best_hw = (r, s["scene"], n)
    if best_hw:
        r, scene, n = best_hw
        out.append(("seascape fly-in in hardware: flicker >= 4x lower than unfiltered",
                    f"best {scene} {n} {r:.2f}x", r >= 4))
    return out


def markdown(stills, seqs):
    """The tables (stills, sequences, flicker) and the goals, as Markdown."""
    lines = []
    if stills:
        cols = columns(stills)
        truth = sorted({s["truth"] for s in stills})
        lines += [f"Stills: RMS error against the ground truth ({', '.join(str(t) for t in truth)} samples per pixel), "
                  "PSNR, and the paper's filter's RMS over the option's (> 1x: better than the paper). "
                  "sat = the paper's summed-area table; box = the exact box of the euclidean width; trapezoid = "
                  "the pixel footprint's shape; +footprint = bandlimited octaves (scenes/README.md); +isotropic = the hardware's bandlimited octaves (the reference's exact form of the RTL's option; on the subband basis the reference's Gaussian subband weights); +anisotropic = the subband basis's anisotropic filter (reference only); rtl:PROFILE = that profile's RTL images (sequences).", "",
                  "| scene | size | " + " | ".join(cols) + " |", "|" + "---|" * (len(cols) + 2)]
        for s in stills:
            paper = s["rms"][PAPER]
            cells = [_cell(s["rms"].get(c), paper if c not in (PAPER,) else None) for c in cols]
            lines.append(f"| {s['scene']} | {s['size']} | " + " | ".join(cells) + " |")
        lines.append("")
    if seqs:
        cols = columns(seqs)
        lines += ["Animated sequences: mean over frames of the RMS error against the truth, the PSNR of the "
                  "sequence's RMS, and the flicker (temporal RMS error against the truth's own frame-to-frame "
                  "change; unfiltered's flicker over the stream's in brackets).", "",
                  "| sequence | frames | size | " + " | ".join(cols) + " |", "|" + "---|" * (len(cols) + 3)]
        for s in seqs:
            cells = []
            for c in cols:
                if c not in s["rms"]:
                    cells.append("-")
                    continue
                fl = s["flicker"][c]
                fr = f" ({s['flicker'][UNFILTERED] / fl:.2f}x)" if c != UNFILTERED and fl > 0 else ""
                cells.append(f"{s['rms'][c]:.4f} ({s['psnr'][c]:.1f} dB); flicker {fl:.4f}{fr}")
            lines.append(f"| {s['scene']} | {s['frames']} | {s['size']} | " + " | ".join(cells) + " |")
        lines.append("")
    gl = goals(stills, seqs)
    if gl:
        lines += ["Goals:", "", "| goal | measured | met |", "|---|---|---|"]
        lines += [f"| {g} | {m} | {'yes' if ok else 'NO'} |" for g, m, ok in gl]
        lines.append("")
    return "\n".join(lines)
