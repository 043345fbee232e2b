#!/usr/bin/env bash
# The test suite: install dependencies, build, run every test through ctest (results also as
# JUnit XML in build/junit.xml).
set -euo pipefail
cd "$(dirname "$0")/.."
# scripts/test.sh --sanitize: the C++ tests and a few runs under ASan + UBSan instead
# (scripts/sanitize.sh, its own build tree build-asan/).
if [ "${1:-}" = "--sanitize" ]; then exec scripts/sanitize.sh; fi
scripts/setup.sh
# --all: every named profile the main job regresses verilated too (full_2clk, full_1clk), with
# their RTL unit tests and random regressions; the default build has full and reduced.
if [ "${1:-}" = "--all" ]; then scripts/build.sh --named; else scripts/build.sh; fi
# JUnit XML of every test for CI servers: build/junit.xml
# The long checks run on their own (docs/TESTING.md): ctest -L formal (the multiplier proof
# whole; the default suite checks its record), -L long (the RTL unit tests' full random
# counts), -L slurm (the SLURM cluster test, minutes of synthesis), -L power (energy per pixel
# against its record), -L lec (the netlist against the RTL) and -L gatelevel (the netlist
# simulated against the golden model), minutes of synthesis each.
# `scripts/test.sh --all` runs them too but slurm.
EXCLUDE="slurm|formal|long|power|lec|gatelevel"
if [ "${1:-}" = "--all" ]; then EXCLUDE="slurm"; fi
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600 -LE "$EXCLUDE" --output-junit "$PWD/build/junit.xml"
