#!/bin/sh
# The bandlimit variants' table of scenes/README.md ("Bandlimited octaves: measured"): every
# scene of scenes/ (stills) and six random scenes (scripts/gen_scenes.py --seed 1) at 64 x 64
# against an 8 x 8 ground truth, and the four animated scenes (16 frames, 48 x 48, 8 x 8 truth)
# for flicker; the paper's SAT and the trapezoid, each with every bandlimit variant.
#   scripts/bandlimit_table.sh [PST] [OUT]  -> OUT/bandlimit.md (default build/pst, out/bandlimit)
set -eu
PST=${1:-build/pst}
OUT=${2:-out/bandlimit}
SIZE=64 TRUTH=8
BANDS="footprint isotropic"
variants() {  # KIND[+BANDLIMIT] for both filters; anisotropic on the subband basis only
  v="sat,trapezoid"
  for b in $BANDS ${1:-}; do v="$v,sat+$b,trapezoid+$b"; done
  echo "$v"
}
mkdir -p "$OUT"
/usr/bin/python3 scripts/gen_scenes.py --seed 1 --train 6 --valid 0 --out "$OUT/random" > /dev/null
stills=""
for scene in scenes/*.toml "$OUT"/random/train/*.toml; do
  name=$(basename "$scene" .toml)
  extra=""
  grep -q 'basis *= *"subband"' "$scene" && extra=anisotropic
  "$PST" render "$scene" --size $SIZE --truth $TRUTH --variants "$(variants $extra)" -o "$OUT/$name" -q -j2
  stills="$stills $OUT/$name"
done
seqs=""
for name in seascape fire marble planet; do
  "$PST" animate "scenes/$name.toml" --frames 16 --size 48 --truth $TRUTH --variants "$(variants)" --no-video \
    -o "$OUT/anim/$name" -q -j2
  seqs="$seqs $OUT/anim/$name"
done
# shellcheck disable=SC2086
/usr/bin/python3 scripts/fidelity.py --stills $stills --sequences $seqs --md "$OUT/bandlimit.md" \
  --json "$OUT/bandlimit.json" > /dev/null
echo "$OUT/bandlimit.md"
