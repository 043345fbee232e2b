#!/usr/bin/env bash
# The test suite: install dependencies, build, run every test through ctest (results also as
# JUnit XML in build/junit.xml).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
# JUnit XML of every test for CI servers: build/junit.xml
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600 --output-junit "$PWD/build/junit.xml"
