"""The report's data: one collection of the main job's outputs under out/ (or of one
`pst regress` / `pst render --profile` run), rendered by md (Markdown) and html (HTML); the
verdicts at its top are verdicts.py's. Nothing here formats for one renderer: tables are lists
of cells, images are paths.
"""
import json
import pathlib
import re
from dataclasses import dataclass, field
from typing import Optional

from . import provenance, silicon_table
from .. import pstjson
from .verdicts import (Verdict, baseline_verdict, regression_verdict, silicon_verdict,  # noqa: F401  (re-exported)
                       verdict_text, verdicts)
from ..synth.report import REALTIME_MPIX

SCHEMA = 1      # of the report (its provenance record says so)


class InputError(Exception):
    """An input file is missing or malformed: `FILE: what is wrong`."""


def load_json(path: pathlib.Path):
    try:
        return json.loads(pathlib.Path(path).read_text())
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}")
    except ValueError as e:
        raise InputError(f"{path}: not JSON: {e}")


@dataclass
class Table:
    """A table both renderers draw: `columns` names, `rows` of cells (str, int, float or None,
    None drawn as '-'), `fmt` per column a format spec for numbers ('' = as is), `links` per
    row a dict column -> list of (label, path relative to the report)."""
    columns: list
    rows: list
    fmt: list = field(default_factory=list)
    links: list = field(default_factory=list)
    failed: list = field(default_factory=list)     # per row: True when the row is a failure

    def cell(self, r: int, c: int) -> str:
        v = self.rows[r][c]
        if v is None:
            return "-"
        f = self.fmt[c] if c < len(self.fmt) else ""
        if f == "auto" and isinstance(v, (int, float)) and not isinstance(v, bool):
            if isinstance(v, int):
                return f"{v:,}"
            return f"{v:,.0f}" if abs(v) >= 1e4 else f"{v:.4g}"
        if f and isinstance(v, (int, float)) and not isinstance(v, bool):
            return format(v, f)
        return str(v)


@dataclass
class Layer:
    """One image of a viewer: `kind` reference | rtl | golden | truth | difference (a scene's
    regression), filtered | unfiltered | width (a reference render), atlas_render | per_pixel |
    scale | atlas (a `pst atlas` run)."""
    label: str
    kind: str
    path: pathlib.Path             # absolute
    profile: str = ""


@dataclass
class SceneView:
    name: str
    layers: list                   # of Layer, reference first
    runs: list                     # the hardware runs (JSON objects) of this scene


@dataclass
class Included:
    """A Markdown file written by another script (synth, figures, sweep): its text with links
    re-based onto the report's folder and its headings demoted below the section's."""
    title: str
    anchor: str
    text: Optional[str]            # None when missing
    missing: str = ""              # what to run to make it
    data: dict = field(default_factory=dict)   # a JSON file beside it, when there is one
    view: Optional[SceneView] = None           # its images in a viewer (report.html), when it has one


@dataclass
class Report:
    title: str
    root: pathlib.Path             # folder the report's relative links start from
    subtitle: str = ""
    runs_title: str = "RTL regression"
    runs: list = field(default_factory=list)   # hardware runs (regress.json entries)
    provenance: dict = field(default_factory=dict)   # regress.json's schema, commit, tool versions, command line
    regress_ran: bool = False
    scenes: list = field(default_factory=list)  # of SceneView
    notes: list = field(default_factory=list)   # driver notes
    gates: list = field(default_factory=list)   # of Included (data: out/synth/<profile>.json)
    figures: list = field(default_factory=list)  # of Included
    sweeps: list = field(default_factory=list)   # of Included
    extras: list = field(default_factory=list)   # of Included (coverage, animations, ...)
    references: Optional[Table] = None           # the reference renders, None when none
    main_job: bool = False                       # the main job's report: the verdicts at its top
    baseline_check: Optional[dict] = None        # out/baseline_check.json, None when not run
    silicon_source: Optional[dict] = None        # out/synth/source.json, None when absent
    provenance: dict = field(default_factory=dict)   # pstlib.report.provenance.collect

    @property
    def failed_runs(self) -> list:
        return [r for r in self.runs if not r.get("passed", False)]


def scene_stem(run: dict) -> str:
    return pathlib.Path(run["scene"]).stem


def rel(path: pathlib.Path, root: pathlib.Path) -> str:
    try:
        return path.resolve().relative_to(root.resolve()).as_posix()
    except ValueError:
        return path.resolve().as_posix()


def failures_first(runs: list) -> list:
    """Failures (most mismatches first), then the rest in their run order."""
    order = {id(r): i for i, r in enumerate(runs)}
    return sorted(runs, key=lambda r: (bool(r.get("passed", False)), -int(r.get("mismatches", 0)), order[id(r)]))


REGRESS_COLUMNS = ["scene", "profile", "result", "pixels", "mismatches", "PSNR dB", "within 1 LSB %",
                   "max LSB", "clocks/pixel", "RTL px/s", "golden px/s", "images"]
REGRESS_FMT = ["", "", "", "d", "d", ".2f", ".2f", ".0f", ".3f", ",.0f", ",.0f", ""]


def regress_table(runs: list, image_links) -> Table:
    """The regression table, failures first. `image_links(run)` gives the row's image links."""
    t = Table(columns=REGRESS_COLUMNS, rows=[], fmt=REGRESS_FMT)
    for r in failures_first(runs):
        v = r.get("vs_reference", {})
        pps = r.get("pixels_per_second", {})
        t.rows.append([scene_stem(r), r.get("profile"), "pass" if r.get("passed") else "FAIL",
                       r.get("pixels_checked"), r.get("mismatches"), v.get("psnr"), v.get("within_1lsb_percent"),
                       v.get("max_lsb"), r.get("cycles_per_pixel"), pps.get("rtl"), pps.get("golden"), ""])
        t.failed.append(not r.get("passed", False))
        t.links.append({"images": image_links(r)})
    return t


def scene_views(runs_dirs: list, truth_dir) -> list:
    """Viewer layers per scene from (run, image folder) pairs: the reference, each profile's
    image, the ground truth (truth_dir(stem)/truth.png when it exists) and each profile's
    difference image."""
    by_scene = {}
    for run, d in runs_dirs:
        by_scene.setdefault(scene_stem(run), []).append((run, pathlib.Path(d)))
    views = []
    for stem, items in by_scene.items():
        layers, diffs, refs = [], [], []
        for run, d in items:
            ref = d / "reference.png"
            if ref.exists() and not any(ref.read_bytes() == r.read_bytes() for r in refs):
                refs.append(ref)
                label = "reference" if not refs[:-1] else f"reference ({run['profile']})"
                layers.append(Layer(label, "reference", ref, run["profile"]))
        for run, d in items:
            model = run.get("model", "rtl")
            img = d / f"{model}.png"
            if img.exists():
                layers.append(Layer(f"{run['profile']} ({model})", model, img, run["profile"]))
            if (d / "difference.png").exists():
                diffs.append(Layer(f"|{run['profile']} - reference| x8", "difference", d / "difference.png",
                                   run["profile"]))
        tdir = truth_dir(stem)
        if tdir is not None and (pathlib.Path(tdir) / "truth.png").exists():
            layers.append(Layer("ground truth", "truth", pathlib.Path(tdir) / "truth.png"))
        layers += diffs
        if layers:
            views.append(SceneView(stem, layers, [r for r, _ in items]))
    return views


def read_included(title: str, anchor: str, path: pathlib.Path, root: pathlib.Path, missing: str,
                  json_path: Optional[pathlib.Path] = None) -> Included:
    data = {}
    if json_path is not None and json_path.exists():
        try:
            data = json.loads(json_path.read_text())
        except (OSError, ValueError):
            data = {}
    if not path.exists():
        return Included(title, anchor, None, missing, data)
    text = path.read_text()
    base = rel(path.parent, root)
    if base not in ("", "."):
        # Relative links and images of the included file start from its own folder.
        text = re.sub(r"\]\((?![a-z]+:|/|#)([^)]+)\)", lambda m: f"]({base}/{m.group(1)})", text)
    text = re.sub(r"^(#+) ", lambda m: "#" + m.group(1) + " ", text, flags=re.M)
    return Included(title, anchor, text, missing, data)


# The images `pst atlas` writes beside atlas.md, in the viewer's order (file, label, kind): the
# textured render first and the per-pixel render second (the viewer's A and B), the atlas last.
ATLAS_LAYERS = [("render_bilinear", "textured, bilinear", "atlas_render"),
                ("per_pixel", "per-pixel render", "per_pixel"),
                ("render_nearest", "textured, nearest", "atlas_render"),
                ("render_trilinear", "textured, trilinear (MIP)", "atlas_render"),
                ("truth", "ground truth", "truth"),
                ("scale", "relative scale (Fig. 7)", "scale"),
                ("atlas", "atlas (reference fill)", "atlas"),
                ("atlas_rtl", "atlas (RTL fill)", "atlas"),
                ("atlas_golden", "atlas (golden-model fill)", "atlas")]


def atlas_view(d: pathlib.Path, data: dict) -> Optional[SceneView]:
    """The viewer of one `pst atlas` run's folder: the images of ATLAS_LAYERS it has (the
    hardware fill named by its profile from atlas.json), None when it has none."""
    profile = (data.get("hardware") or {}).get("profile", "")
    layers = []
    for f, label, kind in ATLAS_LAYERS:
        if (d / f"{f}.png").exists():
            if profile and f in ("atlas_rtl", "atlas_golden"):
                label = label.replace("(", f"({profile} ", 1)
            layers.append(Layer(label, kind, d / f"{f}.png", profile if kind == "atlas" else ""))
    return SceneView(f"atlas-{d.name}", layers, []) if layers else None


def reference_table(root: pathlib.Path) -> Optional[Table]:
    reports = sorted(root.glob("*/report.json"))
    if not reports:
        return None
    t = Table(columns=["scene", "size", "fragments", "render s", "truth s", "RMS filtered vs truth",
                       "RMS unfiltered vs truth", "images"],
              rows=[], fmt=["", "", "d", ".2f", ".2f", ".4f", ".4f", ""])
    for path in reports:
        r = load_json(path)
        name = path.parent.name
        vt = r.get("vs_truth", {})
        sec = r.get("seconds", {})
        t.rows.append([r.get("title", name), f"{r['width']}x{r['height']}", r.get("fragments"),
                       sec.get("total", 0) - sec.get("truth", 0), sec.get("truth"),
                       vt.get("filtered", {}).get("rms"), vt.get("unfiltered", {}).get("rms"), ""])
        t.failed.append(False)
        t.links.append({"images": [(k, f"{name}/{k}.png") for k in ("filtered", "unfiltered", "width", "truth")
                                   if (path.parent / f"{k}.png").exists()]})
    return t


def _optional_json(path: pathlib.Path, what: str) -> Optional[dict]:
    """PATH's object, None when absent; an unreadable file is an error verdict, not a crash."""
    if not path.exists():
        return None
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError) as e:
        return {"status": "error", "source": "unreadable", "messages": [f"error: {path}: {e}"]}
    if not isinstance(data, dict):
        return {"status": "error", "source": "unreadable", "messages": [f"error: {path}: not a {what}"]}
    return data


THROUGHPUT_ROW = re.compile(r"^\| throughput \|.*$", re.M)
# The derated Fmax row's own throughput (": 36.70 Mpixel/s (misses 36.9)"), dropped: the
# throughput row states the one figure.
DERATED_MPIX = re.compile(r": [\d.,]+ Mpixel/s \((?:meets|misses) [\d.]+\)")


def one_throughput(text: str, fig: dict) -> str:
    """A profile's included synthesis Markdown (out/synth/PROFILE.md) with one throughput: the
    silicon table's (pstlib.report.silicon_table.throughput, FIG its normalized profile), labelled with
    its basis, in place of scripts/synth.py's pre-layout and derated figures."""
    tp = silicon_table.throughput(fig)
    if tp is None or text is None:
        return text
    mpix, mhz, basis = tp
    text = DERATED_MPIX.sub("", text)
    row = (f"| throughput, {basis} (the summary's: {mhz:.1f} MHz / {fig['clocks_per_pixel']} clocks per pixel) | "
           f"{mpix:.2f} Mpixel/s ({'meets' if mpix >= REALTIME_MPIX else 'misses'} 640x480 60 Hz depth 2: "
           f"{REALTIME_MPIX:.1f} Mpixel/s) |")
    if THROUGHPUT_ROW.search(text):
        return THROUGHPUT_ROW.sub(lambda m: row, text, count=1)
    return text


def profile_figures(g: Included, root: Optional[pathlib.Path], runs: list) -> dict:
    """The silicon table's normalized profile (silicon_table.from_synth) of a gates section:
    its out/synth JSON, out/pnr/PROFILE.json when routed, the regression's PSNRs."""
    name = g.data.get("profile", g.anchor.split("-", 1)[1])
    pnr_file = root / "pnr" / f"{name}.json" if root else None
    pnr = json.loads(pnr_file.read_text()) if pnr_file and pnr_file.exists() else None
    psnr = {scene_stem(r): r["vs_reference"]["psnr"] for r in runs
            if r.get("profile") == name and (r.get("vs_reference") or {}).get("psnr") is not None}
    power_file = root / "power" / f"{name}.json" if root else None
    power = json.loads(power_file.read_text()).get("summary") if power_file and power_file.exists() else None
    return silicon_table.with_power(silicon_table.from_synth({"profile": name, **g.data}, pnr, psnr or None), power)


def collect(out_dir, argv=None) -> Report:
    """Everything the main job (scripts/run.sh) left under out_dir (ARGV: the command line the
    provenance records, default sys.argv)."""
    root = pathlib.Path(out_dir)
    rep = Report("pst: main job report", root)
    rep.main_job = True
    rep.provenance = provenance.collect(SCHEMA, argv)
    rep.baseline_check = _optional_json(root / "baseline_check.json", "baseline check result")
    rep.silicon_source = _optional_json(root / "synth" / "source.json", "silicon source")
    path = root / "regress.json"
    if path.exists():
        rep.regress_ran = True
        doc = load_json(path)
        rep.runs = pstjson.regress_runs(doc)   # the report's own provenance stays (the commit is the same run's)
        if not isinstance(rep.runs, list) or not all(isinstance(r, dict) and "scene" in r and "profile" in r
                                                      for r in rep.runs):
            raise InputError(f"{path}: expected a list of runs with scene and profile (pst regress -o)")
    runs_dirs = [(r, root / scene_stem(r) / r["profile"]) for r in rep.runs]
    rep.scenes = scene_views(runs_dirs, lambda stem: root / stem)
    # Scenes with a reference render and no hardware run (e.g. a reference-only noise basis).
    have = {v.name for v in rep.scenes}
    for path in sorted(root.glob("*/report.json")):
        d, stem = path.parent, path.parent.name
        kinds = [("filtered", "reference (filtered)"), ("unfiltered", "unfiltered"), ("truth", "ground truth"),
                 ("width", "filter width")]
        layers = [Layer(label, k, d / f"{k}.png") for k, label in kinds if (d / f"{k}.png").exists()]
        if stem not in have and layers:
            rep.scenes.append(SceneView(stem, layers, []))
    rep.notes = sorted({n for r in rep.runs for n in r.get("notes", [])})
    synth = root / "synth"
    # The named profiles (the silicon table's) and any other profile the regression ran (out/synth
    # also holds the sweep's points, <base>_<knob>_<value>.json: those belong to the sweep's section).
    names = list(silicon_table.PROFILES)
    names += sorted({r["profile"] for r in rep.runs} - set(names))
    for name in names:
        g = read_included(f"Gates and timing: {name}", f"gates-{name}", synth / f"{name}.md", root,
                          f"not synthesized: scripts/synth.py {name}", synth / f"{name}.json")
        if g.data and g.text is not None:
            g.text = one_throughput(g.text, profile_figures(g, root, rep.runs))
        rep.gates.append(g)
    figs = root / "figures"
    rep.figures.append(read_included("Figure 11", "fig11", figs / "fig11.md", root,
                                     "not built: scripts/figures.py fig11"))
    rep.figures.append(read_included("Figure 10", "fig10", figs / "fig10.md", root,
                                     "not built: scripts/figures.py fig10"))
    for sweep in sorted((root / "sweep").glob("*/sweep.md")):
        rep.sweeps.append(read_included(f"Precision sweep around {sweep.parent.name}",
                                        f"sweep-{sweep.parent.name}", sweep, root, ""))
    for sweep in sorted((root / "search").glob("*/*.md")):
        rep.sweeps.append(read_included(f"Search: {sweep.parent.name}", f"search-{sweep.parent.name}", sweep,
                                        root, ""))
    # Later outputs (the filter options against the ground truth, animations, coverage) as they
    # appear: their Markdown summaries.
    for kind in ("fidelity", "animations", "coverage"):
        for md in sorted((root / kind).glob("*.md")):
            title = "Filter options against the ground truth" if kind == "fidelity" else f"{kind.capitalize()}: {md.stem}"
            rep.extras.append(read_included(title, f"{kind}-{md.stem}", md, root, ""))
    # `pst atlas SCENE` runs (default folder out/atlas/<scene>): their atlas.md, its images also
    # in a viewer.
    for md in sorted((root / "atlas").glob("*/atlas.md")):
        inc = read_included(f"Texture atlas: {md.parent.name}", f"atlas-{md.parent.name}", md, root, "",
                            md.parent / "atlas.json")
        inc.view = atlas_view(md.parent, inc.data)
        rep.extras.append(inc)
    rep.references = reference_table(root)
    return rep


def final_place(d: pathlib.Path, staged: list) -> pathlib.Path:
    """Where folder D will be once pst's output transaction commits: D under a temporary folder
    TMP of STAGED's (TMP, FINAL) pairs is FINAL/<D relative to TMP>; else D."""
    d = pathlib.Path(d).resolve()
    for tmp, final in staged:
        tmp = pathlib.Path(tmp).resolve()
        if d == tmp or tmp in d.parents:
            return pathlib.Path(final).resolve() / d.relative_to(tmp)
    return d


def collect_runs(runs_dirs: list, root: pathlib.Path, title: str, argv=None, staged=()) -> Report:
    """One `pst regress --html` or `pst render --profile ... --html` run: (run, image folder)
    pairs; the ground truth of a scene is <image folder>/../truth.png when present (the
    layout of `pst render SCENE --truth N` beside `pst render SCENE --profile P`), the image
    folder taken where it will be after the run's output transaction (STAGED: (TMP, FINAL))."""
    rep = Report(title, root)
    rep.provenance = provenance.collect(SCHEMA, argv)
    rep.regress_ran = True
    rep.runs = [r for r, _ in runs_dirs]
    # Only a folder named after the scene: <dir>/<scene>/<profile>/ beside <dir>/<scene>/truth.png.
    dirs = {scene_stem(r): final_place(d, staged).parent for r, d in runs_dirs}
    rep.scenes = scene_views(runs_dirs, lambda stem: dirs[stem] if dirs.get(stem) and dirs[stem].name == stem else None)
    rep.notes = sorted({n for r in rep.runs for n in r.get("notes", [])})
    return rep


# Nested objects of a synthesis JSON that are per-module listings, not headline figures.
NOT_FIGURES = {"blocks", "depth", "seconds", "modules", "count"}


def flatten_figures(data: dict) -> dict:
    """The numbers (and yes/no flags) at the top level of a JSON object and one level down
    ("timing fmax_mhz"), in file order."""
    out = {}
    for k, v in data.items():
        if isinstance(v, bool):
            out[k] = "yes" if v else "no"
        elif isinstance(v, (int, float)):
            out[k] = v
        elif isinstance(v, dict) and k not in NOT_FIGURES:
            for k2, v2 in v.items():
                if isinstance(v2, bool):
                    out[f"{k} {k2}"] = "yes" if v2 else "no"
                elif isinstance(v2, (int, float)):
                    out[f"{k} {k2}"] = v2
    return out


def gate_summary(gates: list, root: Optional[pathlib.Path] = None, runs: list = ()) -> Optional[Table]:
    """The silicon table (pstlib/report/silicon_table.py: docs/HARDWARE.md's rows) of each synthesized
    profile, named profiles first: out/synth/<profile>.json, the post-route Fmax of
    out/pnr/<profile>.json when the profile was placed and routed, the worst paper scene of the
    regression RUNS; the last row links each profile's raw JSON."""
    present = [g for g in gates if g.data]
    if not present:
        return None
    order = {n: i for i, n in enumerate(silicon_table.PROFILES)}
    present.sort(key=lambda g: order.get(g.data.get("profile"), len(order)))
    profiles = [profile_figures(g, root, runs) for g in present]
    t = Table(columns=["figure"] + [p["profile"] for p in profiles], rows=[])
    t.fmt = [""] * (len(profiles) + 1)
    for row in silicon_table.rows(profiles):
        t.rows.append(row)
        t.failed.append(False)
        t.links.append({})
    t.rows.append(["raw figures"] + [""] * len(profiles))
    t.failed.append(False)
    t.links.append({p["profile"]: [(f"synth/{p['profile']}.json", f"synth/{p['profile']}.json")] for p in profiles})
    return t
