"""HTML renderer of the report's data (report_data.Report): out/report.html, and the pages of
`pst regress --html` and `pst render --profile ... --html`.

One self-contained file: the viewer's CSS and JS (scripts/viewer/) are inlined and the viewer's
images are data: URIs (a canvas may read the pixels of a data: image from file://, not of a
file:// image, which Chromium treats as cross-origin). Images of the included Markdown files
(figures, sweep plots) are linked relative to the page, as in report.md, unless embed_all.
"""
import base64
import datetime
import html
import json
import pathlib
import re

try:
    import markdown     # Debian's python3-markdown (scripts/setup.sh)
except ImportError:     # report.md does not need it: report.py says what is missing
    markdown = None

from ..paths import ROOT
from . import provenance
from .data import Report, Table, failures_first, gate_summary, regress_table, rel, scene_stem
from .verdicts import verdicts

ASSETS = ROOT / "scripts" / "viewer"
MIME = {".png": "image/png", ".jpg": "image/jpeg", ".jpeg": "image/jpeg", ".gif": "image/gif",
        ".svg": "image/svg+xml", ".webp": "image/webp"}


def esc(s) -> str:
    return html.escape(str(s), quote=True)


def data_uri(path: pathlib.Path) -> str:
    mime = MIME.get(path.suffix.lower(), "application/octet-stream")
    return f"data:{mime};base64," + base64.b64encode(path.read_bytes()).decode("ascii")


def anchor_heading(level: int, anchor: str, title: str) -> str:
    return f'<h{level} id="{esc(anchor)}">{esc(title)}<a class="anchor" href="#{esc(anchor)}">#</a></h{level}>\n'


def table(t: Table, sortable: bool = False, cls: str = "") -> str:
    classes = " ".join(c for c in ("sortable" if sortable else "", cls) if c)
    out = [f'<table class="{classes}">' if classes else "<table>", "<thead><tr>"]
    out += [f"<th>{esc(c)}</th>" for c in t.columns]
    out.append("</tr></thead><tbody>")
    for r, row in enumerate(t.rows):
        failed = r < len(t.failed) and t.failed[r]
        out.append('<tr class="failed">' if failed else "<tr>")
        for c, v in enumerate(row):
            text = esc(t.cell(r, c))
            links = t.links[r].get(t.columns[c]) if r < len(t.links) else None
            if links:
                extra = " ".join(f'<a href="{esc(p)}">{esc(label)}</a>' for label, p in links)
                text = f"{text} {extra}" if text not in ("", "-") else extra
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                out.append(f'<td class="num" data-v="{v!r}">{text}</td>')
            else:
                out.append(f"<td>{text}</td>")
        out.append("</tr>")
    out.append("</tbody></table>\n")
    return "".join(out)


def md_to_html(text: str) -> str:
    """Markdown (python3-markdown, tables) to HTML; a link to an image file (the sweep's plots)
    also shows the image under it."""
    if markdown is None:
        raise RuntimeError("python3-markdown is not installed (scripts/setup.sh installs it)")
    page = markdown.markdown(text, extensions=["tables"], output_format="html")
    return re.sub(r'(<a href="([^"]+\.(?:png|gif|jpe?g|svg|webp))">([^<]*)</a>)',
                  lambda m: f'{m.group(1)}<br><img class="plot" src="{m.group(2)}" alt="{m.group(3)}">', page)


def embed_images(page: str, root: pathlib.Path) -> str:
    """Replaces relative <img src> of files under root by data: URIs."""
    def sub(m):
        src = html.unescape(m.group(2))
        if re.match(r"^[a-z]+:", src) or src.startswith("/"):
            return m.group(0)
        p = root / src
        return f'{m.group(1)}"{data_uri(p)}"' if p.is_file() else m.group(0)
    return re.sub(r'(<img[^>]*?\ssrc=)"([^"]*)"', sub, page)


def viewer(view, root: pathlib.Path) -> str:
    layers = [{"label": l.label, "kind": l.kind, "src": data_uri(l.path)} for l in view.layers]
    # A = the reference, B = the first hardware image.
    b = next((i for i, l in enumerate(view.layers) if l.kind in ("rtl", "golden")), min(1, len(layers) - 1))
    spec = json.dumps({"name": view.name, "layers": layers, "a": 0, "b": b}).replace("</", "<\\/")
    return (f'<div class="pv" id="viewer-{esc(view.name)}" data-scene="{esc(view.name)}">'
            f'<script type="application/json">{spec}</script></div>\n')


def scene_stats(view) -> str:
    if not view.runs:
        return '<p class="scene-stats">Reference render only (no hardware run of this scene).</p>\n'
    parts = []
    for r in failures_first(view.runs):
        v = r.get("vs_reference", {})
        if r.get("model") == "golden":      # no RTL run: no check, no clocks
            parts.append(f'<b>{esc(r["profile"])}</b>: PSNR {v.get("psnr", 0):.2f} dB, '
                         f'{v.get("within_1lsb_percent", 0):.2f}% within 1 LSB')
            continue
        status = "pass" if r.get("passed") else "FAIL"
        parts.append(f'<span class="status-{status.lower()}">{esc(r["profile"])}: {status}</span>, '
                     f'{r.get("mismatches", 0)} mismatches, PSNR {v.get("psnr", 0):.2f} dB, '
                     f'{v.get("within_1lsb_percent", 0):.2f}% within 1 LSB, '
                     f'{r.get("cycles_per_pixel", 0):.3f} clocks/pixel')
    return '<p class="scene-stats">' + "; ".join(parts) + "</p>\n"


def without_images(text: str, paths: set) -> str:
    """The Markdown text without its images whose link is one of `paths`."""
    return re.sub(r"!\[[^\]]*\]\(([^)\s]+)\)[ \t]*", lambda m: "" if m.group(1) in paths else m.group(0), text)


def included(inc, root: pathlib.Path, level: int = 2) -> str:
    """An included file's section: its text; with a viewer, the text without the images the
    viewer shows (its tables above), then the viewer."""
    out = [f'<section id="{esc(inc.anchor)}">', anchor_heading(level, inc.anchor, inc.title)]
    if inc.text is None:
        out.append(f'<p class="missing">({esc(inc.missing)})</p>' if inc.missing else "")
    else:
        text = inc.text
        if inc.view is not None:
            text = without_images(text, {rel(l.path, root) for l in inc.view.layers})
        # The included file's headings go below this section's heading.
        levels = [len(m) for m in re.findall(r"^(#+) ", text, flags=re.M)]
        shift = level + 1 - min(levels) if levels else 0
        text = re.sub(r"^(#+) ", lambda m: "#" * min(6, len(m.group(1)) + shift) + " ", text, flags=re.M)
        out.append('<div class="md">' + md_to_html(text) + "</div>")
    if inc.view is not None:
        out.append(f"<p>{esc(ATLAS_VIEWER_HELP)}</p>" + viewer(inc.view, root))
    out.append("</section>\n")
    return "\n".join(out)


VIEWER_HELP = ("Each viewer: pick images A and B; the toggle button (or key t on the image) flips between "
               "them; 'slider' shows A left of the yellow line and B right of it; zoom with the wheel or "
               "+/- (pixels stay square, unsmoothed), drag to pan; the values of every image under the "
               "cursor are printed below it (8-bit RGB). Difference images: |image - reference| x 8.")
ATLAS_VIEWER_HELP = ("The run's images in the viewer (as the scenes' in Images: A and B, toggle, slider, zoom, "
                     "values under the cursor). Every layer is drawn on the first one's pixel grid: the "
                     "N x N atlas is scaled to the render's size, zoom in to see its texels.")


def verdict_html(v) -> str:
    cls = {True: "status-pass", False: "status-fail"}.get(v.ok, "")
    status = f'<span class="{cls}">{esc(v.status)}</span>' if cls else esc(v.status)
    return (f'<span class="verdict" data-label="{esc(v.label)}" data-status="{esc(v.status)}">{esc(v.label)}: '
            f'{status}{" (" + esc(v.detail) + ")" if v.detail else ""}</span>')


def top(rep: Report) -> str:
    """The main job's verdicts (as report_md.top) and the provenance, with the provenance also
    as JSON (`<script type="application/json" id="provenance">`)."""
    out = []
    if rep.main_job:
        reg, base, silicon = verdicts(rep)
        out.append(f'<div class="verdicts"><p>{verdict_html(reg)} · {verdict_html(base)}</p>')
        if base.items:
            out.append('<ul class="moved">' + "".join(f"<li>{esc(i)}</li>" for i in base.items) + "</ul>")
        out.append(f"<p>{verdict_html(silicon)}</p></div>\n")
    if rep.provenance:
        data = json.dumps(rep.provenance, sort_keys=True).replace("</", "<\\/")
        out.append(f'<p class="provenance">Provenance: {esc(provenance.line(rep.provenance))}</p>\n'
                   f'<script type="application/json" id="provenance">{data}</script>\n')
    return "".join(out)


def render(rep: Report, embed_all: bool = False) -> str:
    css = (ASSETS / "viewer.css").read_text()
    js = (ASSETS / "viewer.js").read_text().replace("</", "<\\/")   # no end tag inside <script>
    nav, body = [], []

    def section(anchor, title, content):
        nav.append(f'<a href="#{esc(anchor)}">{esc(title)}</a>')
        body.append(f'<section id="{esc(anchor)}">' + anchor_heading(2, anchor, title) + content + "</section>\n")

    if rep.regress_ran:
        failed = rep.failed_runs
        status = (f'<p><span class="status-{"fail" if failed else "pass"}">{"FAILED" if failed else "PASSED"}'
                  f"</span>: {len(rep.runs)} runs, {len(failed)} with mismatches against the golden model. "
                  "Error figures: hardware image against the double-precision reference over RGB. Failures "
                  "first; click a column to sort.</p>\n")
        t = regress_table(rep.runs, lambda r: [("view", f"#scene-{scene_stem(r)}")])
        notes = ""
        if rep.notes:
            notes = ("<p>Driver notes (what the hardware does differently from the scene's request):</p><ul>"
                     + "".join(f"<li>{esc(n)}</li>" for n in rep.notes) + "</ul>\n")
        section("regression", rep.runs_title, status + table(t, sortable=True, cls="regress") + notes)
    else:
        section("regression", rep.runs_title, '<p class="missing">(not run)</p>')

    if rep.scenes:
        # Scenes with a failing run first, as in the table.
        views = sorted(rep.scenes, key=lambda v: all(r.get("passed", False) for r in v.runs))
        links = " ".join(f'<a href="#scene-{esc(v.name)}">{esc(v.name)}</a>' for v in views)
        parts = [f"<p>{esc(VIEWER_HELP)}</p>\n<p class=\"scene-links\">Scenes: {links}</p>\n"]
        for v in views:
            parts.append(anchor_heading(3, f"scene-{v.name}", v.name))
            parts.append(scene_stats(v))
            parts.append(viewer(v, rep.root))
        section("images", "Images", "".join(parts))

    if rep.gates:
        summary = gate_summary(rep.gates, rep.root, rep.runs)
        parts = []
        if summary is not None:
            parts.append("<p>The silicon table (the README's rows) of each synthesized profile: "
                         "out/synth/&lt;profile&gt;.json, post-route from out/pnr/&lt;profile&gt;.json when the "
                         "profile was routed ('-': not reported for that profile); the raw JSON in the last row.</p>"
                         + table(summary, cls="gates-summary"))
        parts += [included(g, rep.root, 3) for g in rep.gates]
        section("gates", "Gates and timing", "".join(parts))
    for f in rep.figures:
        nav.append(f'<a href="#{esc(f.anchor)}">{esc(f.title)}</a>')
        body.append(included(f, rep.root))
    if rep.sweeps:
        section("sweeps", "Sweeps", "".join(included(s, rep.root, 3) for s in rep.sweeps))
    for x in rep.extras:
        nav.append(f'<a href="#{esc(x.anchor)}">{esc(x.title)}</a>')
        body.append(included(x, rep.root))
    if rep.references is not None:
        section("references", "Reference renders",
                "<p>Ground truth: n x n jittered, unfiltered samples per pixel. RMS over RGB in [0, 1].</p>"
                + table(rep.references, sortable=True))

    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    prov = ""
    if rep.provenance:
        # The run's provenance as pst recorded it (testbench/tool/reports/provenance.h).
        pv = rep.provenance
        tools = ", ".join(f"{k} {v}" for k, v in (pv.get("tool_versions") or {}).items())
        prov = (f'<div class="provenance" data-schema="{esc(str(pv.get("schema", "")))}">commit '
                f'<code>{esc(str(pv.get("commit", "?")))}</code>; {esc(tools)}; command: '
                f'<code>{esc(" ".join(map(str, pv.get("command_line") or [])))}</code></div>')
    page = f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{esc(rep.title)}</title>
<style>
{css}</style>
</head>
<body>
<header><h1>{esc(rep.title)}</h1><div>{esc(stamp)}{". " + esc(rep.subtitle) if rep.subtitle else ""}</div>{prov}</header>
<nav>{" ".join(nav)}</nav>
<main>
{top(rep)}{"".join(body)}</main>
<script>
{js}</script>
</body>
</html>
"""
    return embed_images(page, rep.root) if embed_all else page
