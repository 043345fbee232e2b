#!/usr/bin/env bash
# Configures and builds the project into build/ (ccache if present). Used by test.sh and run.sh.
#   scripts/build.sh            everything (the tests included)
#   scripts/build.sh pst ...    only these targets (the main job needs only the `pst` tool)
#   scripts/build.sh --named pst
#                               with every named profile the main job regresses verilated
#                               (full, full_2clk, full_1clk, reduced; the default build has full
#                               and reduced, rtl/CMakeLists.txt PST_PROFILES). The choice stays in
#                               build/'s cache: a later plain build keeps it.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache keyed on paths relative to the checkout, so that another clone of the tree (CI's) hits
# the cache a build of this one filled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
CONFIG=()
if [ "${1:-}" = "--named" ]; then
  CONFIG=("-DPST_PROFILES=full;full_2clk;full_1clk;reduced")
  shift
fi
GEN=()
if command -v ninja >/dev/null 2>&1; then GEN=(-G Ninja); fi
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release "${CONFIG[@]}"
else
  # Re-configure every time (a few seconds): after a pull that adds sources, ninja's own
  # build.ninja regeneration could link a tool (pst_roms) against a stale library first.
  cmake -S . -B build "${CONFIG[@]}" >/dev/null
fi
if [ $# -gt 0 ]; then
  cmake --build build -j"$(nproc)" --target "$@"
else
  cmake --build build -j"$(nproc)"
fi
