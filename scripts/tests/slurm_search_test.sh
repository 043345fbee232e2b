#!/usr/bin/env bash
# ctest slurm_search (label slurm): a one-node SLURM cluster of the test's own processes
# (scripts/slurm_local.sh: munged, slurmctld, slurmd under WORK/cluster, stopped at the end),
# a small search run through it as sbatch job arrays, then the same search on local workers
# with a separate module cache: the points, their scores and gate counts must be equal.
#   scripts/tests/slurm_search_test.sh WORK [PST]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:?usage: slurm_search_test.sh WORK [PST]}
pst=${2:-$root/build/pst}
rm -rf "$work"; mkdir -p "$work"
work=$(cd "$work" && pwd)
"$root/scripts/slurm_local.sh" start "$work/cluster" 2 > "$work/env.sh"
trap '"$root/scripts/slurm_local.sh" stop "$work/cluster"' EXIT
. "$work/env.sh"
# Start: the smallest test profile (one octave, one corner per cycle), so each run synthesizes little.
common=(--classes 22 --psnr 20 --start "22=$root/sim/test_profiles/serial_short.toml" --knobs norm --budget 3 --backtracks 0 --size 16 --train 2 --valid 1
        --rtl 0 --pst "$pst" --rom-dir "$(dirname "$pst")/rom")
t0=$(date +%s)
/usr/bin/python3 "$root/scripts/search.py" "${common[@]}" --backend slurm --out "$work/slurm" \
  --module-cache "$work/modules_slurm"
t1=$(date +%s)
/usr/bin/python3 "$root/scripts/search.py" "${common[@]}" --jobs 2 --out "$work/local" \
  --module-cache "$work/modules_local"
t2=$(date +%s)
ls "$work"/slurm/slurm/*.sh > /dev/null      # the array job scripts were written
/usr/bin/python3 - "$work" <<'PY'
import json, pathlib, sys
w = pathlib.Path(sys.argv[1])
keys = ("train", "valid", "train_worst", "valid_worst", "logic_ge", "cpp", "status")
def load(d):
    return {p.stem: {k: json.loads(p.read_text()).get(k) for k in keys} for p in (w / d / "results").glob("*.json")}
s, l = load("slurm"), load("local")
assert s and s == l, f"slurm and local results differ:\n{s}\n{l}"
assert all(r["status"] == "ok" and r["logic_ge"] for r in s.values()), s
assert (w / "slurm" / "front.csv").read_text() == (w / "local" / "front.csv").read_text()
print(f"slurm_search: {len(s)} points equal on SLURM and local workers")
PY
echo "slurm_search: slurm run $((t1 - t0)) s, local run $((t2 - t1)) s"
