#!/usr/bin/env bash
# Lints the RTL with Verilator (-Wall, every warning fatal) for every profile (rtl/configs/)
# and test profile (sim/test_profiles/), top pst_top. Run by ctest (test rtl_lint).
set -euo pipefail
cd "$(dirname "$0")/.."
status=0
# Every RTL file in rtl/ and its subfolders, the checkers (rtl/sva/) last.
mapfile -t sources < <(find rtl -name '*.sv' -not -path 'rtl/sva/*' | sort; find rtl/sva -name '*.sv' | sort)
for cfg in rtl/configs/*.toml sim/test_profiles/*.toml; do
  name=$(basename "$cfg" .toml)
  mapfile -t params < <(/usr/bin/python3 scripts/profile.py "$cfg" --verilator)
  if ! out=$(verilator --lint-only -Wall -Irtl --top-module pst_top \
        +define+PST_ROM_DIR=\"build/rom\" "${params[@]}" "${sources[@]}" 2>&1); then
    status=1
  fi
  if [ -n "$out" ]; then
    echo "lint [$name]:"
    echo "$out" | head -40
    status=1
  else
    echo "lint [$name]: clean"
  fi
done
exit $status
