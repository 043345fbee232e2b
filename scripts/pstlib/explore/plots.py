"""The sweep's plots (matplotlib, Agg): gates against PSNR, one plot per knob. The data of each
plot is prepared by a function of its own (tested without drawing)."""
import pathlib

from .sweep import KNOBS

COLOURS_EXTRA = ["#000000", "#a0522d", "#4b0082", "#808000"]
MARKERS = ["o", "s", "^", "v", "D", "P", "X", "<", ">", "h", "p", "*", "8"]


def ge_psnr_series(rows: list, knobs: list, which: str):
    """Per knob with any point to show: (knob, [(value, k GE, PSNR)]); and how many rendered
    points lack a gate count or that PSNR."""
    series, missing = [], 0
    for k in knobs:
        pts = [r for r in rows if r["knob"] == k and r["status"] == "ok"]
        good = [r for r in pts if r["logic_ge"] is not None and r[which] is not None]
        missing += len(pts) - len(good)
        if good:
            series.append((k, [(r["value"], r["logic_ge"] / 1000, r[which]) for r in good]))
    return series, missing


def log_x(rows: list, base: dict) -> bool:
    """A log GE axis when the gate counts span more than a factor of 4."""
    xs = [r["logic_ge"] for r in rows if r["logic_ge"]] + ([base["logic_ge"]] if base["logic_ge"] else [])
    return bool(xs) and max(xs) / min(xs) > 4


def knob_points(rows: list, base: dict, knob: str):
    """One knob's rendered points and the base (with the base's value), in value order (the knob's
    own order for names), their x positions, and whether the values are numbers."""
    bv = base["base_value"].get(knob)
    allp = [r for r in rows if r["knob"] == knob and r["status"] == "ok"]
    allp += [dict(base, value=bv)] if bv is not None else []
    numeric = all(isinstance(r["value"], int) for r in allp)
    if numeric:
        allp.sort(key=lambda r: r["value"])
        return allp, [r["value"] for r in allp], True
    order = KNOBS[knob][1]
    allp.sort(key=lambda r: order.index(r["value"]) if r["value"] in order else 99)
    return allp, list(range(len(allp))), False


def psnr_span(ys: list, least: float = 3.0):
    """Y limits that show at least LEAST dB (a flat line stays flat), None when the data span more."""
    if not ys or max(ys) - min(ys) >= least:
        return None
    mid = (max(ys) + min(ys)) / 2
    return mid - least / 2 - 0.25, mid + least / 2 + 0.25


def ge_limits(gy: list):
    """Y limits of the GE axis: at least 5 % of the value (no magnified noise), 5 % margins."""
    lo, hi = min(gy), max(gy)
    pad = max(0.05 * hi - (hi - lo), 0) / 2
    return lo - pad - 0.05 * (hi - lo), hi + pad + 0.05 * (hi - lo)


def plot_all(out: pathlib.Path, rows: list, base: dict, knobs: list, title: str) -> list:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colours = list(plt.get_cmap("tab10").colors) + COLOURS_EXTRA
    made = [plot_ge_psnr(plt, out, rows, base, knobs, title, which, label, colours)
            for which, label in (("psnr_ref", "reference"), ("psnr_truth", "truth"))]
    kdir = out / "knobs"
    kdir.mkdir(exist_ok=True)
    for k in knobs:
        path = plot_knob(plt, kdir, rows, base, k, title)
        if path:
            made.append(path)
    return made


def plot_ge_psnr(plt, out, rows, base, knobs, title, which, label, colours):
    fig, ax = plt.subplots(figsize=(10, 6), dpi=110)
    series, missing = ge_psnr_series(rows, knobs, which)
    for k, pts in series:
        i = knobs.index(k)
        xs, ys = [p[1] for p in pts], [p[2] for p in pts]
        ax.scatter(xs, ys, s=42, marker=MARKERS[i % len(MARKERS)], color=colours[i % len(colours)],
                   label=k, zorder=3, edgecolors="black", linewidths=0.4)
        for v, x, y in pts:
            ax.annotate(str(v), (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7, color="#333333")
    if base["logic_ge"] is not None and base[which] is not None:
        ax.scatter([base["logic_ge"] / 1000], [base[which]], s=260, marker="*", color="gold",
                   edgecolors="black", linewidths=1.0, zorder=4, label=f"base ({base['name']})")
        ax.axhline(base[which], color="gray", lw=0.8, ls=":", zorder=1)
        ax.axhline(base[which] - 1, color="gray", lw=0.6, ls="--", zorder=1)
        ax.annotate("base - 1 dB", (ax.get_xlim()[0], base[which] - 1), textcoords="offset points",
                    xytext=(4, -10), fontsize=7, color="gray")
    if log_x(rows, base):
        ax.set_xscale("log")
    ax.set_xlabel("logic (k gate equivalents, NAND2; ROM/RAM not included)")
    ax.set_ylabel(f"mean PSNR vs {label} (dB)")
    note = f"  ({missing} points without synthesis not shown)" if missing else ""
    ax.set_title(f"{title}: gates against PSNR vs {label}{note}", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    path = out / f"ge_vs_psnr_{label}.png"
    fig.savefig(path)
    plt.close(fig)
    return path


def plot_knob(plt, kdir, rows, base, k, title):
    bv = base["base_value"].get(k)
    allp, xs, numeric = knob_points(rows, base, k)
    if not allp:
        return None
    fig, ax = plt.subplots(figsize=(5.2, 3.4), dpi=110)

    def nan(v):
        return float("nan") if v is None else v
    ax.plot(xs, [nan(r["psnr_ref"]) for r in allp], "o-", color="tab:blue", label="PSNR vs reference")
    ax.plot(xs, [nan(r["psnr_truth"]) for r in allp], "s--", color="tab:green", label="PSNR vs truth")
    for r, x in zip(allp, xs):
        if r["value"] == bv:
            ax.axvline(x, color="gold", lw=6, alpha=0.35, zorder=0)
    ax.set_xlabel(f"{k}" + (" (bits)" if numeric and k not in ("octaves",) else ""))
    ax.set_ylabel("mean PSNR (dB)")
    span = psnr_span([v for r in allp for v in (r["psnr_ref"], r["psnr_truth"]) if v is not None])
    if span:
        ax.set_ylim(*span)
    if not numeric:
        ax.set_xticks(xs)
        ax.set_xticklabels([str(r["value"]) for r in allp], fontsize=8)
    ax.grid(True, alpha=0.3)
    ges = [r["logic_ge"] for r in allp]
    lines, labels = ax.get_legend_handles_labels()
    if any(g is not None for g in ges):
        ax2 = ax.twinx()
        gx = [x for x, g in zip(xs, ges) if g is not None]
        gy = [g / 1000 for g in ges if g is not None]
        ax2.plot(gx, gy, "^:", color="tab:red", label="logic GE")
        ax2.set_ylim(*ge_limits(gy))
        roms = [r["rom_bits"] for r in allp if r["logic_ge"] is not None]
        if len(set(roms)) > 1:
            for x, g, rb in zip(gx, gy, roms):
                ax2.annotate(f"ROM {rb / 1000:.1f}k bits", (x, g), textcoords="offset points", xytext=(0, 6),
                             fontsize=7, color="tab:red", ha="center")
        ax2.set_ylabel("logic (k GE)", color="tab:red")
        ax2.tick_params(axis="y", colors="tab:red")
        l2, lb2 = ax2.get_legend_handles_labels()
        lines, labels = lines + l2, labels + lb2
    ax.legend(lines, labels, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3, frameon=False)
    ax.set_title(f"{title}: {k} (base = {bv}, shaded)", fontsize=9)
    path = kdir / f"{k}.png"
    fig.savefig(path, bbox_inches="tight")
    plt.close(fig)
    return path
