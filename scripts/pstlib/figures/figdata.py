"""What the figures share: the paper's figure numbers, the regression summary (regress.json) and
its numbers as the captions print them, the error for missing inputs."""
import json
import sys
from pathlib import Path

from ..pstjson import regress_runs

REGRESS_CMD = "build/pst regress --size 512 -o {out}/regress.json --images {out}"
BUILD_CMD = "cmake --build build --target pst -j2"

# The paper's figures, in its order; other scenes follow alphabetically.
PAPER_FIGURE = {
    "wood_teapot": "Fig. 1", "marble": "Fig. 2", "seascape": "Fig. 3", "fire": "Fig. 4",
    "planet": "Fig. 5", "moonrise": "Fig. 6", "zoneplate": "Fig. 8", "wood_torus": "Fig. 9",
    "precision": "Fig. 10",
}
PAPER_ORDER = list(PAPER_FIGURE)

class InputMissing(Exception):
    """An input file is missing or unusable: exit status 2."""


def progress(msg):
    print(f"figures: {msg}", file=sys.stderr, flush=True)


def rel(p):
    try:
        return str(Path(p).resolve().relative_to(Path.cwd()))
    except ValueError:
        return str(p)



def scene_order(name):
    return (PAPER_ORDER.index(name) if name in PAPER_ORDER else len(PAPER_ORDER), name)


def load_regress(path):
    if not path.exists():
        raise InputMissing(f"{rel(path)} is missing: run `{REGRESS_CMD.format(out=rel(path.parent))}` first")
    try:
        entries = regress_runs(json.loads(path.read_text()))
    except (OSError, json.JSONDecodeError) as e:
        raise InputMissing(f"{rel(path)}: not a regression summary ({e}): run "
                           f"`{REGRESS_CMD.format(out=rel(path.parent))}` again")
    if not isinstance(entries, list):
        raise InputMissing(f"{rel(path)}: expected a list of runs")
    runs = {}
    for e in entries:
        try:
            runs[(Path(e["scene"]).stem, e["profile"])] = e
        except (KeyError, TypeError):
            raise InputMissing(f"{rel(path)}: an entry without 'scene' and 'profile'")
    return runs


def fmt_db(e):
    if e is None:
        return "n/a"
    p = e.get("vs_reference", {}).get("psnr")
    return "n/a" if p is None else ("inf" if p == float("inf") else f"{p:.2f}")


def fmt_pct(e):
    if e is None:
        return "n/a"
    p = e.get("vs_reference", {}).get("within_1lsb_percent")
    return "n/a" if p is None else f"{p:.2f}"


def gates_label(out: Path, profile: str, paper: str) -> str:
    """", 98.3k GE (paper 100k)" from out/synth/<profile>.json when synthesized, else
    " (paper: 100k gates)": the label never claims a count that was not measured."""
    try:
        ge = json.loads((out / "synth" / f"{profile}.json").read_text())["logic_ge"]
        text = f"{ge / 1e6:.2f}M" if ge >= 1e6 else f"{ge / 1e3:.1f}k"
        return f", {text} GE (paper {paper})"
    except (OSError, ValueError, KeyError, TypeError):
        return f" (paper: {paper} gates)"


