#!/usr/bin/env bash
# Verilates pst_top of named profiles into OUT/NAME (C++ only, not compiled), with the regression
# flavour's options (rtl/CMakeLists.txt pst_verilate: no assertions, tracing compiled in) and
# paths relative to the tree, so that two trees' outputs compare byte for byte: the proof that an
# RTL change behind a profile key that is off elaborates every named profile to the same hardware.
#   scripts/vl_snapshot.sh [--trace] OUT [PROFILE...]   (default: full full_2clk full_1clk reduced balanced)
# Without --trace the model carries no trace code: a parameter added to a module (declared in
# the trace even when it changes nothing) does not show; with --trace it does.
#   diff -r OUT_BEFORE OUT_AFTER                 (nothing printed: the same hardware)
set -euo pipefail
trace=()
if [ "${1:-}" = "--trace" ]; then trace=(--trace-fst); shift; fi
out=$(realpath -m "$1"); shift
cd "$(dirname "$0")/../rtl"
profiles=("$@")
[ ${#profiles[@]} -gt 0 ] || profiles=(full full_2clk full_1clk reduced balanced)
srcs=$(find . -name '*.sv' -not -path './sva/*' | sort)
dirs=$(find . -name '*.sv' -not -path './sva/*' -printf '-y %h\n' | sort -u)
for p in "${profiles[@]}"; do
  mapfile -t gp < <(/usr/bin/python3 ../scripts/profile.py "configs/$p.toml" --verilator)
  rm -rf "$out/$p"; mkdir -p "$out/$p"
  # shellcheck disable=SC2086
  verilator_bin --cc --Mdir "$out/$p" --prefix "Vpst_top_$p" --top-module pst_top "${gp[@]}" \
    "${trace[@]}" -Werror-UNOPTFLAT -Wno-fatal -O3 --x-assign fast --x-initial fast -I. $dirs \
    +define+PST_ROM_DIR=\"rom\" $srcs >"$out/$p.log" 2>&1 || { cat "$out/$p.log"; exit 1; }
  rm -f "$out/$p"/*.d "$out/$p"/*__ver.d "$out/$p"/*__verFiles.dat
  echo "$p: $(ls "$out/$p" | wc -l) files, $(cat "$out/$p"/* | wc -c) bytes"
done
