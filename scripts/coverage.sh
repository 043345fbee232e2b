#!/usr/bin/env bash
# RTL coverage (not part of scripts/test.sh): verilates every profile with line, toggle and user
# (`cover property`) coverage in its own build tree build-cov/ (-DPST_COVERAGE=ON), runs the
# scene regression (with gaps and stalls) and the constrained-random regression of every
# verilated profile (each RTL model instance writes its counts to $PST_COVERAGE_DIR), merges
# them with verilator_coverage, renders HTML with lcov's genhtml into out/coverage/html/ and
# writes out/coverage/report.md: rtl/ line coverage per file with the lines never hit, every
# functional cover point with its count (the ones never hit first), toggle coverage per file.
#   scripts/coverage.sh              PST_COV_FRAGMENTS (default 100000) random fragments per profile
#   PST_COV_PROFILES="full reduced" scripts/coverage.sh    these named profiles (default: reduced;
#                                    full's instrumented model takes > 50 min to compile on 2 cores)
#   PST_COV_TEST_PROFILES="serial_short reduced_perlin2002"   these test profiles (default:
#                                    serial_short, the serial datapath; "all": every one)
#   PST_COV_KINDS="line user"        Verilator's coverage kinds (default "line toggle user");
#                                    without toggle points full and balanced compile in about
#                                    20 min each on two cores
#   PST_COV_OUT=out/coverage_full    the output folder (default out/coverage)
# The instrumented models' C++ is compiled at -O1 (PST_VERILATED_OPT_FAST): the counts do not
# depend on it, the compile time does.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh >/dev/null
B=build-cov
O=${PST_COV_OUT:-out/coverage}
KINDS=${PST_COV_KINDS:-line toggle user}
N=${PST_COV_FRAGMENTS:-100000}
PROFILES=${PST_COV_PROFILES:-reduced}
TEST_PROFILES=${PST_COV_TEST_PROFILES:-serial_short}
cmake -S . -B $B -G Ninja -DCMAKE_BUILD_TYPE=Release -DPST_COVERAGE=ON "-DPST_PROFILES=${PROFILES// /;}" \
      "-DPST_TEST_PROFILES=${TEST_PROFILES// /;}" \
      "-DPST_COVERAGE_KINDS=${KINDS// /;}" -DPST_VERILATED_OPT_FAST=-O1 >/dev/null
cmake --build $B -j2 --target pst
rm -rf $O && mkdir -p $O/dat
export PST_COVERAGE_DIR=$PWD/$O/dat PST_SOURCE_DIR=$PWD
t0=$(date +%s)
$B/pst regress --size 32 --stall-rate 0.3 --gap-rate 0.2 > $O/regress_scenes.txt
$B/pst regress --size 32 > $O/regress_scenes_nostall.txt
$B/pst regress --random "$N" --seed 1 -q > $O/regress_random.txt
echo "coverage: runs took $(( $(date +%s) - t0 )) s ($(ls $O/dat | wc -l) coverage files)"
verilator_coverage --write $O/merged.dat $O/dat/*.dat
verilator_coverage --write-info $O/merged.info $O/merged.dat
genhtml --quiet --output-directory $O/html --title "pst RTL coverage" $O/merged.info > $O/genhtml.txt 2>&1 || {
  cat $O/genhtml.txt; exit 1; }
# Annotated sources (verilator_coverage marks points below the minimum with %000000).
verilator_coverage --annotate $O/annotated --annotate-min 1 $O/merged.dat > $O/annotate.txt
(cd scripts && /usr/bin/python3 -m pstlib.validation.coverage "../$O/merged.dat" "../$O/report.md")
echo "coverage: $O/report.md, $O/html/index.html, annotated sources in $O/annotated/"
