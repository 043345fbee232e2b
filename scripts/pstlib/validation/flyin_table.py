"""The fly-in table (scripts/flyins.py): every sequence of flyins.py's training and validation sets
through `pst animate --truth N` with every filter option the reference and the hardware offer, and
per sequence the RMS against the truth and the flicker of each, judged by issue 44's rules.

Per sequence, one `pst animate` run per hardware option group (colour-table filter KIND in
HW_FILTERS x the bandlimit a profile of the basis computes), every profile of the basis that
computes it at once (`--filter KIND --bandlimit B --profile P ... --model rtl|golden`: the
verilated RTL scoreboarded against the golden model, or the golden model alone, the RTL bit for
bit), and one run of the hardware unfiltered (`PROFILE:none`: what the profile's precision alone
does against the truth; shown, not judged). The run of `sat` without bandlimit also carries the
reference's options (`--variants`, REF_VARIANTS). The hardware option of profile P is column
`P:KIND[+B]`; the reference's exact form of each option is the same run's `filtered` stream
(reference model, double), column `ref:KIND[+B]`.
The filter-width cap (issue 44 part 2, docs/HARDWARE.md unit 5): per bandlimit group, the profiles
with the unit (filter.width_cap = "on" in their file) also run `sat` with `--width-cap on`, column
`P:sat[+B]+cap` beside `ref:sat[+B]+cap` (that run's reference stream); the reference's `sat+cap`
is also a variant of the plain `sat` run (REF_VARIANTS), for the bases whose profiles lack the unit.

Figures (pstlib.figures.flicker): RMS = mean over frames of the RMS against the truth; flicker = RMS
over frames of the temporal RMS error against the truth's own frame-to-frame change; "x" =
unfiltered's flicker over the option's.

The reference's exact filter of a basis (REF_EXACT): the exact (double) form of the best
antialiasing its hardware offers: subband, the anisotropic filter (sat+anisotropic); rayshade, the
fade unit's bandlimit (sat+isotropic); perlin2002 and worley (no fade unit), the paper's colour-table
filter (sat). The best reference option of any kind (sat+footprint too) is shown beside it.

Flags (findings, not errors; issue 44 part 2):
- `below4x`: the reference's exact filter is >= 4x less flickery than unfiltered and the best
  hardware option (least flicker) is not;
- `over10`: the best hardware option's flicker is more than 10 % above the reference's exact
  filter's;
- `worse_rms`: a hardware option's RMS against the truth is above unfiltered's."""
import concurrent.futures
import functools
import hashlib
import json
import math
import pathlib
import time
import tomllib

from .. import atomic, procs
from ..paths import ROOT, profile_path
from ..figures import flicker
from . import flyins

HW_FILTERS = ["mip", "mip_linear", "sat"]
HW_NONE = "none"
# The hardware profiles of each basis and the bandlimit each computes (sim/test_profiles/; full,
# reduced: rtl/configs/, the default build's verilated named profiles; parallel_bandlimit is full's
# formats with the fade unit, full_subband_k8 full with the subband unit's filter). A profile with
# the fade unit renders bandlimit off as its base profile, bit for bit.
HW_PROFILES = {
    "rayshade": [("full", "off"), ("reduced", "off"), ("parallel_bandlimit", "isotropic"),
                 ("reduced_bandlimit", "isotropic")],
    "perlin2002": [("reduced_perlin2002", "off")],
    "worley": [("reduced_worley", "off")],
    "subband": [("reduced_subband", "off"), ("reduced_subband_k8", "anisotropic"), ("full_subband_k8", "anisotropic")],
}
REF_EXACT = {"rayshade": "sat+isotropic", "perlin2002": "sat", "worley": "sat", "subband": "sat+anisotropic"}
REF_VARIANTS = {
    "rayshade": ["mip", "mip_linear", "sat+footprint", "sat+isotropic", "sat+cap"],
    "perlin2002": ["mip", "mip_linear", "sat+footprint", "sat+isotropic", "sat+cap"],
    "worley": ["mip", "mip_linear", "sat+footprint", "sat+isotropic", "sat+cap"],
    "subband": ["mip", "mip_linear", "sat+footprint", "sat+isotropic", "sat+anisotropic", "sat+cap"],
}
# The filter-width cap's run suffix (`--width-cap on`; the hardware's filter.width_cap unit).
CAP = "+cap"
GOAL_RATIO = 4.0
# Below this unfiltered flicker a sequence has little aliasing to remove (e.g. a grazing flight
# whose ground is all far off): its ratios are marked "quiet" in the table (not a flag).
QUIET = 0.01
TOLERANCE = 0.10
UNFILTERED = "unfiltered"


# Filter options the hardware refuses (testbench/verify/driver/driver.cpp refusedFilter, the same
# rule; docs/HARDWARE.md unit 6 "Refused combinations"; chosen on the training set): the MIP map
# (nearest or blended) on a ramp colour map (interp linear) on these bases, except a subband unit
# with its anisotropic filter on. A run the rule and the tool disagree on fails (pst exits 2).
REFUSED_MIP_ON_RAMP = ("worley", "subband")


def refused(basis: str, kind: str, bandlimit: str, interp: str) -> bool:
    """Whether the hardware refuses filter KIND (+BANDLIMIT) on a colour map of INTERP for BASIS."""
    return (kind in ("mip", "mip_linear") and interp == "linear" and basis in REFUSED_MIP_ON_RAMP
            and not (basis == "subband" and bandlimit == "anisotropic"))


def option_name(kind: str, bandlimit: str) -> str:
    return kind if bandlimit == "off" else f"{kind}+{bandlimit}"


def _profile_file(p) -> pathlib.Path:
    f = profile_path(p)
    return f if f.exists() else ROOT / "sim" / "test_profiles" / f"{p}.toml"


@functools.lru_cache(maxsize=64)
def has_width_cap(profile: str) -> bool:
    """Whether PROFILE's file builds the filter-width cap (filter.width_cap = "on")."""
    f = _profile_file(profile)
    return f.exists() and tomllib.loads(f.read_text()).get("filter", {}).get("width_cap") == "on"


def runs_of(basis: str, interp: str = "step") -> list:
    """[(run name, filter kind, bandlimit, [profiles], [reference variants])] of a sequence (colour
    map INTERP): a profile whose option is refused (refused()) is left out; a run left without a
    profile or a reference variant is not run."""
    groups = {}
    for prof, bl in HW_PROFILES[basis]:
        groups.setdefault(bl, []).append(prof)
    # The hardware's own unfiltered stream (filter none, no bandlimit): what its precision alone does
    # against the truth; shown, not an option (no best, no flag).
    out = [(HW_NONE, "none", "off", groups["off"], [])] if "off" in groups else []
    for kind in HW_FILTERS:
        for bl, profs in groups.items():
            var = REF_VARIANTS[basis] if (kind, bl) == ("sat", "off") else []
            kept = [] if refused(basis, kind, bl, interp) else profs
            if kept or var:
                out.append((option_name(kind, bl), kind, bl, kept, var))
    # The width cap: sat again with --width-cap on, the group's profiles that have the unit.
    for bl, profs in groups.items():
        capped = [p for p in profs if has_width_cap(p)]
        if capped:
            out.append((option_name("sat", bl) + CAP, "sat", bl, capped, []))
    return out


def refused_options(basis: str, interp: str) -> list:
    """["PROFILE:OPTION"] the hardware refuses on a sequence of BASIS with a colour map of INTERP."""
    groups = {}
    for prof, bl in HW_PROFILES[basis]:
        groups.setdefault(bl, []).append(prof)
    return [f"{p}:{option_name(kind, bl)}" for kind in HW_FILTERS for bl, profs in groups.items() for p in profs
            if refused(basis, kind, bl, interp)]


def animate_cmd(pst, scene, out, kind, bl, profs, variants, frames, size, truth, model, threads, cap=False):
    cmd = [pst, "animate", scene, "--frames", frames, "--size", size, "--truth", truth, "--no-video", "-q",
           "-j", threads, "-o", out, "--filter", kind, "--bandlimit", bl]
    if cap:
        cmd += ["--width-cap", "on"]
    for p in profs:
        cmd += ["--profile", p]
    if profs:
        cmd += ["--model", model]
    if variants:
        cmd += ["--variants", ",".join(variants)]
    return [str(c) for c in cmd]


def _stream_figures(s) -> dict:
    per = s.get("rms_vs_truth") or []
    out = {"rms": sum(per) / len(per) if per else 0.0, "flicker": flicker.sequence_flicker(s["temporal_rms"])}
    if s.get("hardware"):
        out["mismatches"] = int(s.get("mismatches", 0))
    return out


def collect(docs: dict, basis: str, interp: str = "step") -> dict:
    """{option column: {rms, flicker}} of one sequence from its runs' flicker.json documents
    (run name -> document)."""
    out = {}
    for run, _kind, _bl, profs, variants in runs_of(basis, interp):
        d = docs[run]
        st = d["streams"]
        out.setdefault(UNFILTERED, _stream_figures(st["unfiltered"]))
        if run != HW_NONE:            # the none run's filtered stream is the reference unfiltered
            out[f"ref:{run}"] = _stream_figures(st["filtered"])
        for p in profs:
            if p not in st:
                raise KeyError(f"{run}: streams.{p}: missing (hardware stream of profile {p})")
            out[f"{p}:{run}"] = _stream_figures(st[p])
        for v in variants:
            if v not in st:
                raise KeyError(f"{run}: streams.{v}: missing (variant)")
            out.setdefault(f"ref:{v}", _stream_figures(st[v]))
    return out


def judge(figs: dict, basis: str, refused_opts=()) -> dict:
    """The row of one sequence: unfiltered, the reference's exact filter and best option, the best
    hardware option, every hardware option's ratios, and the flags. refused_opts: the hardware
    options refused on it (refused_options(); listed, not judged)."""
    unf = figs[UNFILTERED]

    def ratio(f):
        return unf["flicker"] / f if f > 0 else math.inf

    ref_name = f"ref:{REF_EXACT[basis]}"
    ref = figs[ref_name]
    refs = {n: v for n, v in figs.items() if n.startswith("ref:")}
    ref_best = min(refs, key=lambda n: refs[n]["flicker"])
    own = {n: v for n, v in figs.items() if n.endswith(":" + HW_NONE) and not n.startswith("ref:")}
    hw = {n: v for n, v in figs.items() if n != UNFILTERED and not n.startswith("ref:") and n not in own}
    best = min(hw, key=lambda n: hw[n]["flicker"])
    options = {n: {"rms": v["rms"], "flicker": v["flicker"], "mismatches": v.get("mismatches", 0),
                   "x_unfiltered": ratio(v["flicker"]),
                   "vs_ref": v["flicker"] / ref["flicker"] if ref["flicker"] > 0 else math.inf,
                   "rms_over_unfiltered": v["rms"] / unf["rms"] if unf["rms"] > 0 else math.inf} for n, v in hw.items()}
    worse = sorted(n for n, v in hw.items() if v["rms"] > unf["rms"])
    flags = []
    if ratio(ref["flicker"]) >= GOAL_RATIO and ratio(hw[best]["flicker"]) < GOAL_RATIO:
        flags.append("below4x")
    if hw[best]["flicker"] > (1 + TOLERANCE) * ref["flicker"]:
        flags.append("over10")
    if worse:
        flags.append("worse_rms")
    return {"unfiltered": unf, "ref_exact": {"name": ref_name, **ref, "x_unfiltered": ratio(ref["flicker"])},
            "ref_best": {"name": ref_best, **refs[ref_best], "x_unfiltered": ratio(refs[ref_best]["flicker"])},
            "best_hw": {"name": best, **options[best]}, "hardware": options, "worse_rms": worse, "flags": flags,
            "refused": sorted(refused_opts),
            "quiet": unf["flicker"] < QUIET,
            "hardware_unfiltered": {n: dict(v, x_unfiltered=ratio(v["flicker"])) for n, v in own.items()},
            "reference": {n: dict(v, x_unfiltered=ratio(v["flicker"])) for n, v in refs.items()}}


def _digest(text: str, cmd: list) -> str:
    return hashlib.sha256((text + "\0" + "\0".join(cmd[1:])).encode()).hexdigest()


@functools.lru_cache(maxsize=16)
def _file_sha(path: str, mtime_ns: int, size: int) -> str:
    """A file's SHA-256 (cached per path, modification time and size: the pst binary is hashed once)."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def inputs_key(pst, profiles) -> str:
    """What a run's result depends on besides the scene and the arguments: the pst binary (its
    golden model and verilated RTL) and the text of each PROFILES file (a changed profile or RTL
    must not reuse a stale run)."""
    parts = []
    files = [_profile_file(p) for p in profiles]
    for f in [pathlib.Path(pst)] + files:
        st = f.stat() if f.exists() else None
        parts.append(f"{f.name}:{_file_sha(str(f), st.st_mtime_ns, st.st_size) if st else 'missing'}")
    return "\0".join(parts)


def run_sequence(pst, scene: pathlib.Path, feats: dict, out: pathlib.Path, truth: int, model: str, threads: int,
                 fresh: bool = False) -> dict:
    """Runs (or reuses: same scene text, arguments, pst binary and profile files) every run of one
    sequence; {run: doc}.
    RuntimeError naming the command on a failed run."""
    docs = {}
    text = scene.read_text()
    for run, kind, bl, profs, variants in runs_of(feats["basis"], feats.get("interp", "step")):
        rdir = out / run
        cmd = animate_cmd(pst, scene, rdir, kind, bl, profs, variants, feats["frames"], feats["size"], truth, model,
                          threads, cap=run.endswith(CAP))
        key = _digest(text + "\0" + inputs_key(pst, profs), [c if c != str(rdir) else "OUT" for c in cmd])
        stamp = rdir / "run.sha256"
        if not fresh and stamp.is_file() and stamp.read_text().strip() == key and (rdir / "flicker.json").is_file():
            docs[run] = flicker.load(rdir)
            continue
        rc, so, se = procs.run(cmd)
        if rc != 0:
            raise RuntimeError(f"{' '.join(cmd)}: exit {rc}: {(se or so).strip()[-600:]}")
        docs[run] = flicker.load(rdir)
        atomic.write_text(stamp, key + "\n")
    return docs


def run_split(pst, split: flyins.Split, seed: int, count: int, frames: int, size: int, truth: int, out: pathlib.Path,
              model: str = "rtl", jobs: int = 1, fresh: bool = False, say=print) -> dict:
    """Writes OUT/scenes/, OUT/runs/NAME/RUN/ and returns the split's document (rows per sequence)."""
    manifest = flyins.write(out / "scenes", seed, count, frames, size, split)
    feats = {f["name"]: f for f in manifest["sequences"]}
    threads = max(1, 2 // jobs)
    t0 = time.time()
    rows, errors = {}, []

    def one(name):
        f = feats[name]
        docs = run_sequence(pst, out / "scenes" / f"{name}.toml", f, out / "runs" / name, truth, model, threads, fresh)
        interp = f.get("interp", "step")
        return name, judge(collect(docs, f["basis"], interp), f["basis"], refused_options(f["basis"], interp))

    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as ex:
        for fut in concurrent.futures.as_completed([ex.submit(one, n) for n in feats]):
            try:
                name, row = fut.result()
                rows[name] = row
                say(f"  {split.name} {name} ({feats[name]['basis']}, {feats[name]['path']}): best hardware "
                    f"{row['best_hw']['name']} {row['best_hw']['x_unfiltered']:.2f}x, reference "
                    f"{row['ref_exact']['name']} {row['ref_exact']['x_unfiltered']:.2f}x"
                    f"{'; ' + ', '.join(row['flags']) if row['flags'] else ''} ({time.time() - t0:.0f} s)")
            except (RuntimeError, KeyError, flicker.FlickerError) as e:
                errors.append(str(e))
    return {"split": split.name, "seed": seed, "count": count, "frames": frames, "size": size, "truth": truth,
            "model": model, "wall_s": round(time.time() - t0, 1), "features": feats,
            "rows": dict(sorted(rows.items())), "errors": errors}


def summary(doc: dict) -> dict:
    rows = doc["rows"]
    out = {"sequences": len(rows)}
    for flag in ("below4x", "over10", "worse_rms"):
        out[flag] = sorted(n for n, r in rows.items() if flag in r["flags"])
    out["mismatches"] = sum(o["mismatches"] for r in rows.values() for o in r["hardware"].values())
    out["worse_rms_options"] = sorted({o.split(":", 1)[1] + " (" + o.split(":", 1)[0] + ")"
                                       for r in rows.values() for o in r["worse_rms"]})
    out["refused"] = sum(len(r.get("refused", [])) for r in rows.values())
    return out


def _x(v):
    return "inf" if math.isinf(v) else f"{v:.2f}x"


def _fig(f):
    return f"{f['rms']:.4f} / {f['flicker']:.4f}"


def compact(doc: dict) -> dict:
    """The split's document without the per-option detail: what docs/data/flyins.json records and
    the main table shows (flyins.py --record)."""
    keep = ("split", "seed", "count", "frames", "size", "truth", "model")
    rows = {}
    for n, r in doc["rows"].items():
        f = doc["features"][n]
        rows[n] = {"basis": f["basis"], "path": f["path"], "cmap": f["cmap"], "unfiltered": r["unfiltered"],
                   "ref_exact": r["ref_exact"], "ref_best": r["ref_best"],
                   "best_hw": {k: r["best_hw"][k] for k in ("name", "rms", "flicker", "x_unfiltered", "vs_ref")},
                   "worse_rms": r["worse_rms"], "flags": r["flags"], "quiet": r.get("quiet", False),
                   "refused": r.get("refused", [])}
    return dict({k: doc[k] for k in keep}, rows=rows, summary=summary(doc))


def main_table(c: dict) -> str:
    """The flags line and one row per sequence of a compact document (compact())."""
    s = c["summary"]
    L = [f"Flags: below4x (reference's exact filter >= {GOAL_RATIO:g}x, best hardware option below): "
         f"{len(s['below4x'])} of {s['sequences']} ({', '.join(s['below4x']) or 'none'}); over10 (best hardware "
         f"flicker > {1 + TOLERANCE:.2f} x the reference's exact filter's): {len(s['over10'])} "
         f"({', '.join(s['over10']) or 'none'}); worse_rms (a hardware option's RMS above unfiltered's): "
         f"{len(s['worse_rms'])} ({', '.join(s['worse_rms']) or 'none'}). Refused options (the hardware refuses "
         f"them, docs/HARDWARE.md unit 6; not judged): {s.get('refused', 0)}. Hardware mismatches against the golden "
         f"model: {s['mismatches']}. (quiet: unfiltered flicker below {QUIET:g}, little aliasing to remove; "
         "its ratios are ill-conditioned.)\n",
         "| sequence | basis | path | map | unfiltered | reference's exact filter | best reference option | "
         "best hardware option | hw / ref flicker | hardware options worse than unfiltered (RMS) | refused | flags |",
         "|---|---|---|---|---|---|---|---|---:|---|---|---|"]
    for n, r in c["rows"].items():
        re_, rb, bh = r["ref_exact"], r["ref_best"], r["best_hw"]
        quiet = " (quiet)" if r.get("quiet") else ""
        L.append(f"| {n} | {r['basis']} | {r['path']} | {r['cmap']} | {_fig(r['unfiltered'])}{quiet} | "
                 f"{re_['name'][4:]} {_fig(re_)} ({_x(re_['x_unfiltered'])}) | {rb['name'][4:]} {_fig(rb)} "
                 f"({_x(rb['x_unfiltered'])}) | {bh['name']} {_fig(bh)} ({_x(bh['x_unfiltered'])}) | "
                 f"{bh['vs_ref']:.2f} | {', '.join(r['worse_rms']) or '-'} | {', '.join(r.get('refused', [])) or '-'} | "
                 f"{', '.join(r['flags']) or '-'} |")
    return "\n".join(L) + "\n"


def heading(c: dict) -> str:
    return (f"Fly-ins, {c['split']} set: {c['count']} sequences (seed {c['seed']}), {c['frames']} frames at "
            f"{c['size']} x {c['size']}, {c['truth']} x {c['truth']} truth, hardware through the {c['model']} model")


CELLS = ("Cells: RMS against the truth (mean over frames) / flicker (temporal RMS error against the truth's "
         "frame-to-frame change), and unfiltered's flicker over the option's; hw / ref flicker: the best hardware "
         "option's flicker over the reference's exact filter's.")


def markdown(doc: dict, command: str = "") -> str:
    rows, feats = doc["rows"], doc["features"]
    L = [f"## {heading(doc)}\n"]
    if command:
        L.append(f"`{command}`. {CELLS} Scenes: scripts/pstlib/validation/flyins.py; rules: flyin_table.py.\n")
    L.append(main_table(compact(doc)))
    # Every option per basis: flicker ratio against unfiltered and RMS over unfiltered's.
    for basis in flyins.BASES:
        names = [n for n in rows if feats[n]["basis"] == basis]
        if not names:
            continue
        cols = sorted({c for n in names for c in rows[n]["hardware"]})
        own = sorted({c for n in names for c in rows[n].get("hardware_unfiltered", {})})
        refc = sorted({c for n in names for c in rows[n]["reference"]})
        L.append(f"{basis}: every option, flicker x against unfiltered (RMS over unfiltered's):\n")
        L.append("| sequence | " + " | ".join(refc + own + cols) + " |")
        L.append("|---|" + "---:|" * (len(refc) + len(own) + len(cols)))
        for n in names:
            r = rows[n]
            unf = r["unfiltered"]["rms"]
            cells = []
            for c in refc:
                v = r["reference"].get(c)
                cells.append("-" if v is None else f"{_x(v['x_unfiltered'])} ({v['rms'] / unf:.2f})")
            for c in own:
                v = r.get("hardware_unfiltered", {}).get(c)
                cells.append("-" if v is None else f"{_x(v['x_unfiltered'])} ({v['rms'] / unf:.2f})")
            for c in cols:
                v = r["hardware"].get(c)
                cells.append("-" if v is None else f"{_x(v['x_unfiltered'])} ({v['rms_over_unfiltered']:.2f})")
            L.append(f"| {n} | " + " | ".join(cells) + " |")
        L.append("")
    if doc["errors"]:
        L.append("Errors: " + "; ".join(doc["errors"]) + "\n")
    return "\n".join(L) + "\n"
