#!/usr/bin/env bash
# The test suite: install dependencies, build, run every test through ctest (results also as
# JUnit XML in build/junit.xml).
set -euo pipefail
cd "$(dirname "$0")/.."
# scripts/test.sh --sanitize: the C++ tests and a few runs under ASan + UBSan instead
# (scripts/sanitize.sh, its own build tree build-asan/).
if [ "${1:-}" = "--sanitize" ]; then exec scripts/sanitize.sh; fi
scripts/setup.sh
scripts/build.sh
# JUnit XML of every test for CI servers: build/junit.xml
# The SLURM cluster test (label slurm, a few minutes of synthesis) runs on its own: ctest -L slurm.
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600 -LE slurm --output-junit "$PWD/build/junit.xml"
