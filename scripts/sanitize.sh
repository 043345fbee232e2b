#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (gcc, -DPST_SANITIZE=ON,
# any UB is fatal but misalignment, which stays recoverable so the third-party suppression
# applies) in its own build tree build-asan/, with one small profile verilated (default: the
# test profile serial_short): every C++ test binary (model, golden model, scenes and fragment
# files, the fuzzers' kept inputs, rasterizer, renderer, hardware path with the RTL, random
# regression, golden bounds), then a few renders, a short random regression and bad-input runs
# of the `pst` tool. Third-party findings are suppressed in scripts/sanitize/*.supp (each entry
# says why).
#   scripts/sanitize.sh        (README "Verification" gives the time)
#   PST_SANITIZE_PROFILES=reduced PST_SANITIZE_TEST_PROFILES=all scripts/sanitize.sh   more RTL
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh >/dev/null
B=build-asan
NAMED=${PST_SANITIZE_PROFILES-}
TESTP=${PST_SANITIZE_TEST_PROFILES:-serial_short}
cmake -S . -B $B -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPST_SANITIZE=ON -DPST_SIM_ASSERT=ON "-DPST_PROFILES=${NAMED// /;}" \
      "-DPST_TEST_PROFILES=${TESTP// /;}" >/dev/null
# The RTL runs below use the first verilated profile.
P=$(echo $NAMED ${TESTP/all/serial_short} | awk '{print $1}')
TESTS=(model/model_test model/golden_test testbench/scene_test testbench/fuzz_corpus_test testbench/raster_test
       testbench/render_test testbench/hw_test)
cmake --build $B -j2 --target pst "${TESTS[@]##*/}"

export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions=$PWD/scripts/sanitize/ubsan.supp
export LSAN_OPTIONS=suppressions=$PWD/scripts/sanitize/lsan.supp
export PST_SOURCE_DIR=$PWD
fail=0
run() {  # run NAME EXPECTED_STATUS CMD...: the sanitizers must stay silent and the status match
  local name=$1 want=$2; shift 2
  local log=$B/sanitize_$name.log st=0
  "$@" >"$log" 2>&1 || st=$?
  if grep -qE "ERROR: (Address|Leak)Sanitizer|runtime error:" "$log" || [ "$st" != "$want" ]; then
    echo "FAIL $name (exit $st, expected $want): $log"; grep -m5 -E "ERROR|runtime error|SUMMARY" "$log" || true
    fail=1
  else
    echo "ok   $name"
  fi
}
for t in "${TESTS[@]}"; do run "${t##*/}" 0 $B/$t --gtest_brief=1; done
O=$B/sanitize_out
rm -rf $O && mkdir -p $O
run render_marble 0 $B/pst render scenes/marble.toml --size 32 --truth 2 -q -o $O/marble
run render_rtl_fire 0 $B/pst render scenes/fire.toml --size 32 --profile $P --stall-rate 0.3 --gap-rate 0.2 -q -o $O/fire
run render_rtl_trace 0 $B/pst render scenes/zoneplate.toml --size 16 --profile $P --trace $O/z.fst --trace-end 200 -q -o $O/z
run regress_scenes 0 $B/pst regress --size 16 --profile $P
run regress_random 0 $B/pst regress --random 20000 --seed 9 --profile $P -q
run fragments 0 $B/pst fragments scenes/fire.toml --size 16 -o $O/fire.frag
printf 'quadric = { I = 0.5 }\nfilter = "sat"\ncolormap = { size = 256, wrap = "mod", ramp = [[0, 0, 0, 0, 1], [1, 1, 1, 1, 1]] }\n[[octaves]]\namplitude = 0.5\nscale = 2.0\n' > $O/tex.toml
run eval_reference 0 $B/pst eval -t $O/tex.toml -f $O/fire.frag -o $O/eval.txt
run eval_rtl 0 $B/pst eval -t $O/tex.toml -f $O/fire.frag --model rtl --profile $P -o $O/eval_rtl.txt
# Bad input: exit 2, no sanitizer report.
printf '1 2 3 nan 5 6 7 8 9\n' > $O/bad.frag
printf '[image]\nwidth = "wide"\n' > $O/bad.toml
head -c 100 scenes/fire.toml > $O/truncated.toml
run bad_fragments 2 $B/pst eval -t $O/tex.toml -f $O/bad.frag
run bad_scene 2 $B/pst render $O/bad.toml -q -o $O/bad
run truncated_scene 2 $B/pst render $O/truncated.toml -q -o $O/bad
run bad_profile 2 $B/pst render scenes/fire.toml --profile $O/bad.toml --model golden -q -o $O/bad
if [ $fail -ne 0 ]; then echo "sanitize: FAILED"; exit 1; fi
echo "sanitize: PASSED (ASan + UBSan, no findings)"
