#!/usr/bin/env bash
# Lints the RTL with Verilator (-Wall, UNOPTFLAT fatal) for every profile, top pst_top.
set -euo pipefail
cd "$(dirname "$0")/.."
status=0
for cfg in rtl/configs/*.toml; do
  name=$(basename "$cfg" .toml)
  mapfile -t params < <(/usr/bin/python3 scripts/profile.py "$cfg" --verilator)
  if ! out=$(verilator --lint-only -Wall -Werror-UNOPTFLAT -Irtl --top-module pst_top \
        +define+PST_ROM_DIR=\"build/rom\" "${params[@]}" rtl/*.sv 2>&1); then
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
