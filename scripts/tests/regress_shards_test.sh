#!/usr/bin/env bash
# ctest regress_shards_local / regress_shards_slurm (label slurm): scripts/regress.py on the real
# pst, one shard of a random regression deliberately killed while it runs.
#   scripts/tests/regress_shards_test.sh WORK PST PROFILE local|slurm
# local: --jobs 2; the killed shard's pst gets SIGKILL (its pid from the shard's .pid file).
# slurm: a one-node cluster of the test's own processes (scripts/slurm_local.sh, stopped at the
#   end); the killed shard's array task is cancelled with scancel.
# Both: the launcher re-runs that shard alone, and the merged result must equal one process's
# run of the same fragments (fragments, textures, 0 mismatches), with the killed shard run twice.
# local also: an RTL assertion in one shard (--inject-assert) merges as the first failure with
# the fragment, the checker's name and a replay command that fails again alone; and scene shards.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:?usage: regress_shards_test.sh WORK PST PROFILE local|slurm}
pst=${2:?}; profile=${3:?}; mode=${4:?}
rm -rf "$work"; mkdir -p "$work"
work=$(cd "$work" && pwd)
py=/usr/bin/python3
n=40000; seed=11
t0=$(date +%s)
backend=(--jobs 2)
if [ "$mode" = slurm ]; then
  "$root/scripts/slurm_local.sh" start "$work/cluster" 2 > "$work/env.sh"
  trap '"$root/scripts/slurm_local.sh" stop "$work/cluster"' EXIT
  . "$work/env.sh"
  backend=(--backend slurm)
fi

# 1. The sharded run, one shard killed while it runs.
out="$work/random"
"$py" "$root/scripts/regress.py" --random $n --seed $seed --chunk 6000 --profile "$profile" "${backend[@]}" \
  --pst "$pst" --out "$out" > "$work/launcher.log" 2>&1 &
launcher=$!
killed=""
for _ in $(seq 3000); do
  pidf=$(ls "$out"/shards/*.pid 2>/dev/null | head -1 || true)
  if [ -n "$pidf" ]; then
    killed=$(basename "$pidf" .pid)
    if [ "$mode" = slurm ]; then
      batch=$(ls -t "$out"/slurm/*.names | head -1)
      idx=$(($(grep -n -x "$killed" "$batch" | cut -d: -f1) - 1))
      job=$(squeue -h -o '%F' | head -1)
      scancel "${job}_${idx}"
    else
      kill -9 "$(cat "$pidf")"
    fi
    break
  fi
  sleep 0.02
done
rc=0; wait $launcher || rc=$?
cat "$work/launcher.log"
[ -n "$killed" ] || { echo "no shard was seen running"; exit 1; }
[ $rc -eq 0 ] || { echo "launcher exited $rc"; exit 1; }
grep -q "re-running 1 shard(s) without a result, alone: $killed" "$work/launcher.log"
if [ "$mode" = slurm ]; then
  [ "$(ls "$out"/slurm/*.names | wc -l)" -eq 2 ]       # the first array and the re-run of one shard
  [ "$(cat "$(ls -t "$out"/slurm/*.names | head -1)")" = "$killed" ]
fi

# One process over the same fragments.
"$pst" regress --random $n --seed $seed --profile "$profile" -q -o "$work/single.json" > /dev/null
"$py" - "$out/merged.json" "$work/single.json" "$killed" <<'PY'
import json, sys
m, single, killed = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))["runs"][0], sys.argv[3]
assert m["passed"] and m["complete"], m["missing"]
assert m["shards"][killed]["attempts"] == 2, m["shards"][killed]
assert all(s["attempts"] == 1 for k, s in m["shards"].items() if k != killed), m["shards"]
frags = sum(r["fragments"] for r in m["runs"])
texs = sum(r["textures"] for r in m["runs"])
assert (frags, texs) == (single["fragments"], single["textures"]), (frags, texs, single)
assert sum(r["mismatches"] for r in m["runs"]) == 0 and len(m["shards"]) >= 3
print(f"merged: {len(m['shards'])} shards, {frags} fragments, {texs} textures = one process; {killed} killed and re-run")
PY
t1=$(date +%s)
echo "regress_shards ($mode): killed-shard run $((t1 - t0)) s"
[ "$mode" = slurm ] && exit 0

# 2. An RTL assertion in one shard: a failed result like a mismatch, merged and replayed.
rc=0
"$py" "$root/scripts/regress.py" --random $n --seed $seed --chunk 6000 --profile "$profile" --jobs 2 \
  --pst-arg=--inject-assert=25000 --pst "$pst" --out "$work/assert" > "$work/assert.log" 2>&1 || rc=$?
cat "$work/assert.log"
[ $rc -eq 1 ] || { echo "expected exit 1, got $rc"; exit 1; }
replay=$("$py" - "$work/assert/merged.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
f = m["first_failure"]
assert m["complete"] and not m["passed"] and f["kind"] == "assertion", f
shard = next(s for s in m["runs"] if s["shard"] == f["shard"])
assert shard["first_fragment"] <= f["fragment"] <= 25000 and f["seed"] == 11, (f, shard)
assert "RegWriteOnlyWhenIdle" in f["assertion"] and "--inject-assert 25000" in f["replay"], f
assert len(m["failed_shards"]) == 1 and sum(r["passed"] for r in m["runs"]) == len(m["runs"]) - 1
print(f["replay"])
PY
)
grep -q "<failure message=\"RTL assertion at cycle" "$work/assert/merged.xml"
rc=0; $replay > "$work/replay.log" 2>&1 || rc=$?
[ $rc -eq 1 ] && grep -q "RegWriteOnlyWhenIdle" "$work/replay.log" && grep -q "first RTL assertion: seed $seed" "$work/replay.log" ||
  { cat "$work/replay.log"; echo "the replay did not fail the same way (exit $rc)"; exit 1; }

# 3. Scene shards.
"$py" "$root/scripts/regress.py" "$root/scenes/fire.toml" "$root/scenes/marble.toml" --size 16 --profile "$profile" \
  --jobs 2 --pst "$pst" --out "$work/scenes" | tee "$work/scenes.log"
grep -q "PASSED: 2 shards, 0 failed, 0 without a result, 2 runs" "$work/scenes.log"
rc=0
"$py" "$root/scripts/regress.py" "$root/scenes/fire.toml" "$root/scenes/marble.toml" --size 16 --profile "$profile" \
  --jobs 2 --pst-arg=--inject-assert=40 --pst "$pst" --out "$work/scenes_assert" > "$work/scenes_assert.log" 2>&1 || rc=$?
[ $rc -eq 1 ] || { cat "$work/scenes_assert.log"; echo "expected exit 1, got $rc"; exit 1; }
"$py" - "$work/scenes_assert/merged.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
f = m["first_failure"]
assert m["complete"] and f["kind"] == "assertion" and f["scene"].endswith("fire.toml"), f
assert "RegWriteOnlyWhenIdle" in f["assertion"] and f["replay"].endswith("--inject-assert 40"), f
assert [r["assertion"] is not None for r in m["runs"]] == [True, True]
PY
echo "regress_shards (local): all $(($(date +%s) - t0)) s"
