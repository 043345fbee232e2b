"""Simulation speed per verilated profile: the RTL's cycles/s and pixels/s and the golden
model's pixels/s of the same run, and their ratio, on a fixed scene and a fixed random stream.

    scripts/bench.py [--profile P ...] [--scene scenes/marble.toml] [--size 256]
                     [--random 20000] [--seed 1] [--pst build/pst] [--out out/bench]

One core per run (runs one after another). Writes OUT/bench.json and OUT/bench.md and prints
the table. A benchmark, not a test: the numbers depend on the machine and its load."""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

from .. import atomic
from ..report import bench
from ..paths import ROOT
from ..pstjson import regress_runs


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--profile", action="append", default=[], help="verilated profile (default: every one)")
    ap.add_argument("--scene", default=str(ROOT / "scenes" / "marble.toml"))
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--random", type=int, default=20000, help="random fragments per profile (0: none)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    ap.add_argument("--out", default=str(ROOT / "out" / "bench"))
    a = ap.parse_args(argv)
    if not pathlib.Path(a.pst).is_file():
        print(f"error: --pst: {a.pst} not found (scripts/build.sh pst)", file=sys.stderr)
        return 2
    if not 1 <= a.size <= 4096 or a.random < 0:
        print("error: --size in [1, 4096], --random >= 0", file=sys.stderr)
        return 2
    profiles = a.profile
    if not profiles:
        r = subprocess.run([a.pst, "regress", "--random", "1", "--list"], capture_output=True, text=True)
        profiles = bench.verilated_profiles(r.stdout)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        js = pathlib.Path(tmp) / "r.json"
        for p in profiles:
            runs = [([a.scene, "--size", str(a.size)], bench.scene_row)]
            if a.random:
                runs.append((["--random", str(a.random), "--seed", str(a.seed)], bench.random_row))
            for args, row in runs:
                r = subprocess.run([a.pst, "regress", *args, "--profile", p, "-q", "-o", str(js)],
                                   capture_output=True, text=True)
                if r.returncode != 0:
                    print(f"error: {p}: pst regress {' '.join(args)} exited {r.returncode}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}",
                          file=sys.stderr)
                    return 1
                recs = regress_runs(json.loads(js.read_text()))
                if not recs:   # the profile does not run this scene (another noise basis): skipped
                    print(f"| {p} | {' '.join(args)} | skipped: pst regress ran nothing |", flush=True)
                    continue
                rows.append(row(recs[0]))
                print(bench.table(rows[-1:]).splitlines()[-1], flush=True)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    atomic.write_text(out / "bench.json", json.dumps(rows, indent=1) + "\n")
    atomic.write_text(out / "bench.md", bench.table(rows))
    print()
    print(bench.table(rows), end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
