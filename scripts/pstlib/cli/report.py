"""The main job's report, and the page of one hardware run.

    /usr/bin/python3 scripts/report.py out                      Markdown report on stdout
    /usr/bin/python3 scripts/report.py out --md out/report.md --html out/report.html
        Collects out/ (regress.json and its images, out/synth/*.json|md, out/figures, out/sweep,
        the reference renders) once (pstlib.report.data) and writes both renderings: report.md
        (tables, links) and report.html (sortable tables, an image viewer per scene, every
        section with an anchor; one file, no network, opens from file://). At the top of both:
        the regression's and the baseline check's results side by side (out/baseline_check.json,
        scripts/check_baseline.py --json; "not run" without it), where the silicon figures came
        from (out/synth/source.json: the record; absent: synthesized in this run) and the
        provenance (pstlib/report/provenance.py: commit, tool versions, command line, schema).

    /usr/bin/python3 scripts/report.py --html FILE --regress JSON [--images DIR]
    /usr/bin/python3 scripts/report.py --html FILE --summary DIR/summary.json [...]
    /usr/bin/python3 scripts/report.py --html FILE --sweep out/sweep/NAME
        The page of one `pst regress` run (images in DIR/<scene>/<profile>/, default: FILE's
        folder) or of `pst render --profile` runs (images beside each summary.json): the table
        and the viewers. `pst regress --html` and `pst render --profile P --html` call this.
        --sweep: a precision sweep's points side by side per scene (golden images), its sweep.md.
        --staged TMP=FINAL (repeatable; pst passes it): the run's files are still in the
        temporary folder TMP of its output transaction and will be in FINAL; the ground truth
        beside an image folder is looked up where the folder will be.

Missing or unreadable input: `error: FILE: what is wrong`, exit status 2, no output file.
"""
import argparse
import os
import pathlib
import sys

from .. import pstjson
from ..report import data as report_data, html as report_html, md as report_md


def write_atomic(path: pathlib.Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(text)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


InputError = report_data.InputError
load_json = report_data.load_json


def md_links(root: pathlib.Path):
    def links(run):
        d = f"{report_data.scene_stem(run)}/{run['profile']}"
        return [(k, f"{d}/{k}.png") for k in ("rtl", "difference") if (root / d / f"{k}.png").exists()]
    return links


def page(args) -> report_data.Report:
    html_path = pathlib.Path(args.html)
    root = html_path.parent if str(html_path.parent) else pathlib.Path(".")
    pairs = []
    prov = {}
    if args.regress:
        doc = load_json(pathlib.Path(args.regress))
        prov = pstjson.of(doc)
        runs = pstjson.regress_runs(doc)
        if not isinstance(runs, list) or not all(isinstance(r, dict) and "scene" in r and "profile" in r
                                                  for r in runs):
            raise InputError(f"{args.regress}: expected a list of runs with scene and profile (pst regress -o)")
        images = pathlib.Path(args.images) if args.images else root
        pairs += [(r, images / report_data.scene_stem(r) / r["profile"]) for r in runs]
    for s in args.summary or []:
        p = pathlib.Path(s)
        run = load_json(p)
        if not isinstance(run, dict) or "scene" not in run or "profile" not in run:
            raise InputError(f"{p}: expected one run with scene and profile (pst render --profile)")
        pairs.append((run, p.parent))
        prov = prov or pstjson.of(run)
    if args.sweep:
        # A sweep's folder (scripts/sweep.py --out): renders/<point>/<scene>/summary.json beside
        # golden.png, reference.png, difference.png; its sweep.md as a section.
        sweep = pathlib.Path(args.sweep)
        found = sorted((sweep / "renders").glob("*/*/summary.json"))
        if not found:
            raise InputError(f"{sweep}: no renders/<point>/<scene>/summary.json (scripts/sweep.py --out)")
        for p in found:
            run = load_json(p)
            if not isinstance(run, dict) or "scene" not in run:
                raise InputError(f"{p}: expected one run with scene (pst render --profile)")
            run["profile"] = p.parent.parent.name          # the sweep point
            pairs.append((run, p.parent))
    title = "pst regress" if args.regress else "precision sweep" if args.sweep else "pst render --profile"
    staged = []
    for st in args.staged or []:
        tmp, sep, final = st.partition("=")
        if not sep or not tmp or not final:
            raise InputError(f"--staged: '{st}' is not TMP=FINAL")
        staged.append((pathlib.Path(tmp), pathlib.Path(final)))
    rep = report_data.collect_runs(pairs, root, title, staged=staged)
    rep.provenance = prov
    rep.subtitle = f"{len(rep.runs)} runs"
    if args.summary:
        rep.runs_title = "Hardware runs"
    if args.sweep:
        sweep = pathlib.Path(args.sweep)
        rep.title = f"precision sweep: {sweep.resolve().name}"
        rep.runs_title = "Sweep points (golden model against the reference)"
        rep.subtitle += " of the golden model (one per sweep point and scene)"
        rep.sweeps.append(report_data.read_included("Sweep table and plots", "sweep", sweep / "sweep.md", root, ""))
    return rep


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", nargs="?", default="out", help="the main job's output folder (default out)")
    ap.add_argument("--md", help="write the Markdown report here (default: stdout unless --html)")
    ap.add_argument("--html", help="write the HTML report (or page) here")
    ap.add_argument("--regress", help="page of one `pst regress -o JSON` run")
    ap.add_argument("--images", help="with --regress: its --images folder (default: the page's folder)")
    ap.add_argument("--summary", action="append", help="page of `pst render --profile` runs (repeatable)")
    ap.add_argument("--staged", action="append", metavar="TMP=FINAL",
                    help="a temporary folder of pst's output transaction and where it will be")
    ap.add_argument("--sweep", help="page of a precision sweep's folder (scripts/sweep.py --out DIR)")
    ap.add_argument("--embed-all", action="store_true", help="also embed the figures' images (one movable file)")
    args = ap.parse_args()
    try:
        if args.regress or args.summary or args.sweep:
            if not args.html:
                raise InputError("--html: a page needs an output file")
            rep = page(args)
            write_atomic(pathlib.Path(args.html), report_html.render(rep, embed_all=args.embed_all))
            return 0
        root = pathlib.Path(args.out)
        if not root.is_dir():
            raise InputError(f"{root}: no such folder (run scripts/run.sh first)")
        # Each sweep with renders also gets its own page (the points side by side), linked below.
        pages = {}
        for sweep_md in sorted((root / "sweep").glob("*/sweep.md")) if args.html else []:
            d = sweep_md.parent
            if any((d / "renders").glob("*/*/summary.json")):
                sub = argparse.Namespace(html=str(d / "index.html"), regress=None, images=None, summary=None, staged=None,
                                         sweep=str(d))
                write_atomic(d / "index.html", report_html.render(page(sub), embed_all=args.embed_all))
                pages[f"sweep-{d.name}"] = f"sweep/{d.name}/index.html"
        rep = report_data.collect(root)
        for inc in rep.sweeps:
            if inc.anchor in pages and inc.text is not None:
                inc.text += (f"\nEvery point's images side by side in the viewer: "
                             f"[{pages[inc.anchor]}]({pages[inc.anchor]})\n")
        rep.subtitle = "Markdown version: report.md"
        text = report_md.render(rep, md_links(root))
        if args.md:
            write_atomic(pathlib.Path(args.md), text)
        elif not args.html:
            sys.stdout.write(text)
        if args.html:
            write_atomic(pathlib.Path(args.html), report_html.render(rep, embed_all=args.embed_all))
        return 0
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except RuntimeError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
