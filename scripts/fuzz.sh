#!/usr/bin/env bash
# Fuzzes the input parsers (scene, texture block, fragment file, profile, OBJ mesh) with libFuzzer:
# clang 14 with AddressSanitizer + UndefinedBehaviorSanitizer, build tree build-fuzz/
# (-DPST_FUZZ=ON), seed corpus from scenes/ (its .obj meshes too), rtl/configs/ and
# testbench/verify/fuzz/seeds/.
#   scripts/fuzz.sh                    every target, PST_FUZZ_SECONDS (default 60) s each
#   scripts/fuzz.sh scene 600          one target for 600 s
#   PST_FUZZ_RUNS=1000000 scripts/fuzz.sh   a fixed number of executions per target instead
#   PST_FUZZ_KEEP=1 scripts/fuzz.sh    afterwards, merge the inputs that add coverage into the
#                                      kept corpus testbench/verify/fuzz/corpus/<target>/ (libFuzzer -merge=1)
# The scene and texture targets run the check-only parses (checkScene/checkTexture: every check,
# no meshes or colour tables). The growing corpus stays in build-fuzz/corpus/<target>; a crashing
# input is written to build-fuzz/artifacts/<target>/ and the script exits 1. Keep such an input
# as a regression test in testbench/verify/fuzz/regress/<target>/: ctest fuzz_corpus_test replays
# every file of testbench/verify/fuzz/corpus/ and testbench/verify/fuzz/regress/ through the same entry points.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh >/dev/null
SECS=${2:-${PST_FUZZ_SECONDS:-60}}
TARGETS=(scene texture fragments profile obj)
if [ $# -ge 1 ]; then TARGETS=("$1"); fi
B=build-fuzz
if [ ! -f $B/CMakeCache.txt ]; then
  cmake -S . -B $B -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang-14 \
        -DCMAKE_CXX_COMPILER=clang++-14 -DPST_FUZZ=ON >/dev/null
fi
cmake --build $B -j2 --target "${TARGETS[@]/#/fuzz_}"

# Seeds: scene files; each scene's texture tables as texture blocks; profiles; fragments.
mkdir -p $B/seeds/scene $B/seeds/texture $B/seeds/profile $B/seeds/fragments $B/seeds/obj
cp scenes/*.toml $B/seeds/scene/
find scenes -name '*.obj' -exec cp {} $B/seeds/obj/ \;
cp rtl/configs/*.toml sim/test_profiles/*.toml $B/seeds/profile/
cp testbench/verify/fuzz/seeds/fragments/* $B/seeds/fragments/
/usr/bin/python3 - "$B/seeds/texture" scenes/*.toml <<'PY'
import re, sys, pathlib
out = pathlib.Path(sys.argv[1])
for scene in sys.argv[2:]:
    name, lines = None, []
    def flush():
        if name and lines:
            (out / f"{pathlib.Path(scene).stem}_{name}.toml").write_text("".join(lines))
    for line in open(scene):
        m = re.match(r"\s*\[(\[?)textures\.([A-Za-z0-9_]+)(\.octaves)?\]", line)
        if m:
            if m.group(3) is None:
                flush(); name, lines = m.group(2), []
            else:
                lines.append("[[octaves]]\n")
            continue
        if re.match(r"\s*\[", line):
            flush(); name, lines = None, []
            continue
        if name: lines.append(line)
    flush()
PY

rc=0
for t in "${TARGETS[@]}"; do
  mkdir -p $B/corpus/$t $B/artifacts/$t
  extra=()
  for d in testbench/verify/fuzz/corpus/$t testbench/verify/fuzz/regress/$t; do
    if [ -d $d ]; then extra+=($d); fi
  done
  limit=(-max_total_time="$SECS")
  if [ -n "${PST_FUZZ_RUNS:-}" ]; then limit=(-runs="$PST_FUZZ_RUNS"); fi
  echo "fuzz_$t: ${limit[*]}"
  if ! $B/testbench/verify/fuzz/fuzz_$t "${limit[@]}" -rss_limit_mb=2048 -max_len=16384 -timeout=10 \
        -print_final_stats=1 -artifact_prefix=$B/artifacts/$t/ $B/corpus/$t $B/seeds/$t "${extra[@]}" \
        > $B/fuzz_$t.log 2>&1; then
    rc=1
    echo "fuzz_$t: FAILED, see $B/fuzz_$t.log and $B/artifacts/$t/"
    grep -m3 -E "ERROR|runtime error|SUMMARY" $B/fuzz_$t.log || true
  fi
  execs=$(grep -m1 "stat::number_of_executed_units" $B/fuzz_$t.log | awk '{print $2}')
  rate=$(grep -m1 "stat::average_exec_per_sec" $B/fuzz_$t.log | awk '{print $2}')
  echo "fuzz_$t: ${execs:-?} executions (${rate:-?}/s), corpus $(ls $B/corpus/$t | wc -l) files"
  if [ -n "${PST_FUZZ_KEEP:-}" ]; then
    mkdir -p testbench/verify/fuzz/corpus/$t
    $B/testbench/verify/fuzz/fuzz_$t -merge=1 -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
        testbench/verify/fuzz/corpus/$t $B/corpus/$t $B/seeds/$t >> $B/fuzz_$t.log 2>&1 || rc=1
    echo "fuzz_$t: kept corpus $(ls testbench/verify/fuzz/corpus/$t | wc -l) files"
  fi
done
exit $rc
