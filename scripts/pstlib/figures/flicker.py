"""Flicker of animated sequences: reads the flicker.json that `pst animate --truth N` writes,
tabulates the temporal RMS error per stream (filtered, unfiltered, each hardware profile, each
`--variants` reference stream) and plots it over time.

The metric (computed by pst, testbench/tool/animate): per frame k >= 1 the RMS over pixels and RGB of
(X_k - X_{k-1}) - (T_k - T_{k-1}), T the ground truth; a sequence's flicker is the RMS of that
over its frames."""
import json
import math
from pathlib import Path

FIXED = ("filtered", "unfiltered")


class FlickerError(Exception):
    """Malformed or missing input: the message is 'FILE: what is wrong'."""


def sequence_flicker(per_frame):
    """RMS over frames of the per-frame temporal RMS errors (0 for an empty list)."""
    vals = list(per_frame)
    if not vals:
        return 0.0
    return math.sqrt(sum(v * v for v in vals) / len(vals))


def validate(doc, where="flicker.json"):
    """Checks the fields this module reads; raises FlickerError naming the first problem."""
    if not isinstance(doc, dict):
        raise FlickerError(f"{where}: expected a JSON object")
    for key in ("scene", "frames", "width", "height", "streams"):
        if key not in doc:
            raise FlickerError(f"{where}: {key}: missing")
    streams = doc["streams"]
    if not isinstance(streams, dict) or not all(s in streams for s in FIXED):
        raise FlickerError(f"{where}: streams: expected filtered and unfiltered")
    for name, s in streams.items():
        t = s.get("temporal_rms") if isinstance(s, dict) else None
        if not isinstance(t, list):
            raise FlickerError(f"{where}: streams.{name}.temporal_rms: missing (rendered without --truth?)")
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in t):
            raise FlickerError(f"{where}: streams.{name}.temporal_rms: expected finite numbers")
    return doc


def read_json(path, name, error):
    """(Path, document) of a JSON file, or of DIR/name when path is a folder; unreadable or
    malformed: error('FILE[:LINE]: what')."""
    path = Path(path)
    if path.is_dir():
        path = path / name
    try:
        return path, json.loads(path.read_text())
    except OSError as e:
        raise error(f"{path}: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise error(f"{path}:{e.lineno}: {e.msg}") from None


def load(path):
    path, doc = read_json(path, "flicker.json", FlickerError)
    return validate(doc, str(path))


def hardware_streams(doc):
    """The hardware profiles' streams (every stream but the fixed two and the variants)."""
    return [n for n, s in doc["streams"].items() if n not in FIXED and not s.get("variant")]


def variant_streams(doc):
    """The reference streams of `pst animate --variants` (a filter option each)."""
    return [n for n, s in doc["streams"].items() if s.get("variant")]


def row(doc):
    """One sequence's figures: flicker per stream, the ratio unfiltered / filtered, mismatches."""
    st = doc["streams"]
    fl = {n: sequence_flicker(s["temporal_rms"]) for n, s in st.items()}
    ratio = fl["unfiltered"] / fl["filtered"] if fl["filtered"] > 0 else float("inf")
    return {
        "scene": Path(doc["scene"]).stem,
        "frames": doc["frames"],
        "size": f'{doc["width"]}x{doc["height"]}',
        "flicker": fl,
        "ratio": ratio,
        "mean_rms": {n: s.get("mean_rms_vs_truth", 0.0) for n, s in st.items()},
        "mismatches": {n: st[n].get("mismatches", 0) for n in hardware_streams(doc)},
    }


def markdown_table(docs):
    """The flicker table of several sequences (one row each), as Markdown."""
    hw, var = [], []
    for d in docs:
        hw += [n for n in hardware_streams(d) if n not in hw]
        var += [n for n in variant_streams(d) if n not in var]
    head = ["sequence", "frames", "size", "filtered", "unfiltered", "unfiltered / filtered"] + \
           [f"{n} (mismatches)" for n in hw] + var
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for d in docs:
        r = row(d)
        cells = [r["scene"], str(r["frames"]), r["size"], f'{r["flicker"]["filtered"]:.4f}',
                 f'{r["flicker"]["unfiltered"]:.4f}', f'{r["ratio"]:.2f}x']
        for n in hw:
            cells.append(f'{r["flicker"][n]:.4f} ({r["mismatches"][n]})' if n in r["flicker"] else "-")
        for n in var:
            cells.append(f'{r["flicker"][n]:.4f}' if n in r["flicker"] else "-")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def plot(doc, out):
    """Temporal RMS error per frame of every stream (and the error against the truth) -> PNG."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    for name, s in doc["streams"].items():
        t = s["temporal_rms"]
        ax.plot(range(1, len(t) + 1), t, label=f"{name} ({sequence_flicker(t):.4f})",
                linestyle="--" if s.get("hardware") else "-")
        r = s.get("rms_vs_truth", [])
        bx.plot(range(len(r)), r, label=name, linestyle="--" if s.get("hardware") else "-")
    ax.set_ylabel("temporal RMS error")
    ax.set_title(f'{Path(doc["scene"]).stem}: flicker against the ground truth '
                 f'({doc["width"]}x{doc["height"]}, {doc.get("truth_samples", "?")} samples/pixel)')
    ax.legend(fontsize=8)
    bx.set_ylabel("RMS error vs truth")
    bx.set_xlabel("frame")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.set_ylim(bottom=0)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)
