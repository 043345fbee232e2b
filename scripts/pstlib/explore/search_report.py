"""The search's outputs: every point (points.csv), the Pareto fronts per clocks-per-pixel class
(front.csv, front.md, front.png), with each front point's verdict on the validation set (the
rule of acceptance.py against the class's start) and its RTL check."""
import csv
import io
import pathlib

from ..validation import acceptance
from .. import atomic
from ..power import estimate
from .search import pareto


def fronts(rows: list, classes) -> dict:
    """Class -> the Pareto front (least logic GE against the highest worst training PSNR) of the
    points with clocks per pixel <= the class."""
    return {c: pareto([r for r in rows if r.get("cpp") is not None and r["cpp"] <= c]) for c in classes}


def losses(r: dict, start) -> dict:
    """A front point judged against its class's START result by the rule of acceptance
    (acceptance.py: every validation scene within TOLERANCE_DB of the start's PSNR there): the
    largest loss on one training / validation scene, the validation scene that loses most, and
    valid_pass (None when the start or the point has no validation scores)."""
    if start is None:
        return {}
    out = {"train_loss": acceptance.scene_loss(start.get("train") or {}, r.get("train") or {}, missing=None)}
    if not start.get("valid") or not r.get("valid"):
        return dict(out, valid_loss=None, valid_loss_scene=None, valid_pass=None)
    v = acceptance.judge(start["valid"], r["valid"])
    return dict(out, valid_loss=v["worst_loss"], valid_loss_scene=v["worst_loss_scene"], valid_pass=v["passed"])


def add_energy(rows: list, starts: dict, refs: dict | None = None) -> None:
    """Each row with a logic area gets energy_pj, the estimated energy per pixel (pstlib.power.estimate:
    the measured density of its class's start profile, STARTS class -> profile name, else of the
    measured profile nearest in clocks per pixel), energy_ref (that profile) and ace (area x
    clocks/pixel x energy, GE x clocks x nJ). Without a power record the fields stay empty."""
    refs = estimate.references() if refs is None else refs
    classes = sorted(starts)
    for r in rows:
        if r.get("logic_ge") is None or not r.get("cpp"):
            continue
        c = next((c for c in classes if r["cpp"] <= c), None)
        ref = estimate.nearest(refs, r["cpp"], prefer=starts.get(c, ""))
        if ref is None:
            continue
        pj = estimate.estimate_pj(r["logic_ge"], r["cpp"], ref)
        r.update(energy_pj=round(pj, 1), energy_ref=ref.profile,
                 ace=round(estimate.figure_of_merit(r["logic_ge"], r["cpp"], pj)))


COLUMNS = ["class", "name", "cpp", "logic_ge", "energy_pj", "energy_ref", "ace", "train_worst", "train_mean", "valid_worst", "valid_mean",
           "train_loss", "valid_loss", "valid_loss_scene", "valid_pass", "rtl", "fmax_mhz", "fmax_derated_mhz", "move"]


def _fmt(v):
    if isinstance(v, float):
        return f"{v:.2f}"
    return "" if v is None else str(v)


def front_rows(fr: dict, rtl: dict) -> list:
    out = []
    for c, rows in fr.items():
        for r in rows:
            out.append({"class": c, "name": r["name"], "cpp": r["cpp"], "logic_ge": r["logic_ge"],
                        "energy_pj": r.get("energy_pj"), "energy_ref": r.get("energy_ref"), "ace": r.get("ace"),
                        "train_worst": r.get("train_worst"), "train_mean": r.get("train_mean"),
                        "valid_worst": r.get("valid_worst"), "valid_mean": r.get("valid_mean"),
                        "train_loss": r.get("train_loss"), "valid_loss": r.get("valid_loss"),
                        "valid_loss_scene": r.get("valid_loss_scene"), "valid_pass": r.get("valid_pass"),
                        "rtl": (rtl.get(r["name"]) or {}).get("summary"),
                        "fmax_mhz": r.get("fmax_mhz"), "fmax_derated_mhz": r.get("fmax_derated_mhz"),
                        "move": r.get("move")})
    return out


def write_csv(path: pathlib.Path, rows: list, columns: list) -> None:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=columns, extrasaction="ignore", lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: _fmt(r.get(k)) for k in columns})
    atomic.write_text(path, buf.getvalue())


def markdown(title: str, frows: list, targets: dict, best: dict, stats: dict, max_losses=None) -> str:
    tol = acceptance.TOLERANCE_DB
    L = [f"# {title}\n", "Least logic area (OSU018 GE, per-module synthesis cache) subject to the worst training-scene "
         "PSNR against the double reference and clocks per pixel; every front point judged on the held-out validation "
         f"set by the rule of acceptance (scripts/pstlib/validation/acceptance.py: every validation scene within {tol:g} dB of "
         "the class's start profile there) and checked on the RTL (`pst regress`, 0 mismatches).\n"]
    L.append("| class (clk/px <=) | target PSNR dB | best point | logic GE | worst train dB | worst valid dB |")
    L.append("|---:|---:|---|---:|---:|---:|")
    for c, b in best.items():
        if b:
            L.append(f"| {c} | {targets[c]:g} | `{b['name']}` | {b['logic_ge']:,} | {_fmt(b.get('train_worst'))} | "
                     f"{_fmt(b.get('valid_worst'))} |")
        else:
            L.append(f"| {c} | {targets[c]:g} | (start misses the target) | | | |")
    L.append("")
    if max_losses:
        L.append("Texture by texture (`--max-loss`): every training scene within " +
                 ", ".join(f"{v:g} dB (class {c})" for c, v in max_losses.items()) +
                 " of the class's start profile.\n")
    L.append("Loss columns: the largest loss on one scene against the class's start, training / validation, and "
             f"the validation scene that loses most; rule: pass when every validation scene is within {tol:g} dB.\n")
    L.append("Energy: pJ per pixel estimated from the measured density of the reference profile in brackets "
             "(scripts/pstlib/power/estimate.py; its error on the measured profiles: docs/POWER.md, energy-estimate); "
             "A x C x E: logic GE x clocks per pixel x nJ per pixel, lower is better.\n")
    L.append("| class | point | clk/px | logic GE | energy pJ/px (ref) | A x C x E | train worst / mean dB | "
             "valid worst / mean dB | max loss train / valid dB (scene) | rule | RTL | how reached |")
    L.append("|---:|---|---:|---:|---:|---:|---|---|---|---|---|---|")
    for r in frows:
        rule = {True: "pass", False: "**FAIL**", None: "-"}[r.get("valid_pass")]
        loss = "-" if r.get("train_loss") is None and r.get("valid_loss") is None else \
            f"{_fmt(r.get('train_loss'))} / {_fmt(r.get('valid_loss'))}" + \
            (f" ({r['valid_loss_scene']})" if r.get("valid_loss_scene") else "")
        energy = "-" if r.get("energy_pj") is None else f"{r['energy_pj']:,.0f} ({r['energy_ref']})"
        ace = "-" if r.get("ace") is None else f"{r['ace']:,}"
        L.append(f"| {r['class']} | `{r['name']}` | {r['cpp']} | {r['logic_ge']:,} | {energy} | {ace} | "
                 f"{_fmt(r['train_worst'])} / "
                 f"{_fmt(r['train_mean'])} | {_fmt(r['valid_worst'])} / {_fmt(r['valid_mean'])} | {loss} | {rule} | "
                 f"{r['rtl'] or '-'} | {r['move'] or ''} |")
    L.append("")
    L.append(f"Search: {stats['points']} points evaluated ({stats['synthesized']} synthesized, "
             f"{stats['modules_synthesized']} module syntheses, the rest from the cache) in {stats['wall_s']:.0f} s wall: "
             f"{stats['points_per_hour']:.1f} points per hour. Scenes: {stats['train']} training, {stats['valid']} "
             f"validation (scripts/pstlib/validation/valset.py) at {stats['size']} x {stats['size']}.\n")
    return "\n".join(L) + "\n"


def plot(path: pathlib.Path, rows: list, fr: dict, title: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    pts = [r for r in rows if r.get("logic_ge") is not None and r.get("train_worst") is not None]
    ax.scatter([r["logic_ge"] / 1000 for r in pts], [r["train_worst"] for r in pts], s=10, c="0.7",
               label="evaluated points")
    for c, f in fr.items():
        if not f:
            continue
        ax.step([r["logic_ge"] / 1000 for r in f], [r["train_worst"] for r in f], where="post", marker="o",
                label=f"front, <= {c} clk/px")
        vx = [r["logic_ge"] / 1000 for r in f if r.get("valid_worst") is not None]
        vy = [r["valid_worst"] for r in f if r.get("valid_worst") is not None]
        if vx:
            ax.scatter(vx, vy, marker="x", label=f"validation, <= {c} clk/px")
    xs = [r["logic_ge"] for r in pts]
    if xs and max(xs) > 4 * min(xs):
        ax.set_xscale("log")
    ax.set_xlabel("logic area, thousand GE (OSU018)")
    ax.set_ylabel("worst-scene PSNR vs reference, dB")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    atomic.write_with(path, lambda tmp: fig.savefig(tmp, dpi=110))
    plt.close(fig)
