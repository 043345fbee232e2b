#!/usr/bin/env bash
# The main job: install dependencies, build, then into out/:
#   1. every scene through the reference model (filtered, unfiltered, filter width, ground truth)
#   2. the RTL regression: every scene through every profile at 512x512, checked bit for bit
#      against the golden model, with the images
#   2b. the seascape fly-in (pst animate, 24 frames at 64x64): webm videos, out/animations/flicker.md
#       (a report section)
#   2c. the filter options (the paper's SAT, the exact box, the trapezoid footprint, bandlimited
#       octaves) against the ground truth: every scene at 64x64 with a 16x16 truth, ten
#       animated sequences (16 frames at 48x48, 8x8 truth; every Rayshade one also through the named
#       profiles' RTL, the subband seascapes through the subband units') -> out/fidelity/fidelity.md
#       (a report section)
#   3. silicon figures of the named profiles (OSU018 area, OpenSTA timing, memories): from the
#      silicon record (scripts/synth/records, pstlib/synth/record.py) while every input of the
#      synthesis is unchanged since the baseline, else the run fails and says what changed;
#      `scripts/run.sh --synth` synthesizes them again (with a quick precision sweep, tens of
#      minutes on 2 cores); Figures 10 and 11
#   4. the figures against scripts/synth/baseline.json (fails on a move > 2 %):
#      out/baseline_check.json, which the report's top line quotes
#   5. out/report.md and out/report.html (the same data; the HTML page has an image viewer per
#      scene and sortable tables, opens from file://), the pages a designer opens first: at the
#      top the regression's and the baseline check's results and where the silicon figures
#      came from (the record, out/synth/source.json, or this run's synthesis)
set -euo pipefail
cd "$(dirname "$0")/.."
SYNTH=0
case "${1:-}" in
  --synth) SYNTH=1 ;;
  "") ;;
  -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d'; exit 0 ;;
  *) echo "error: unknown option '$1' (scripts/run.sh [--synth])" >&2; exit 2 ;;
esac
START=$(date +%s)
scripts/setup.sh
scripts/build.sh --named pst    # every profile the regression below runs
mkdir -p out
# This run's verdicts only: no previous run's baseline check or silicon source in the report.
rm -f out/baseline_check.json out/synth/source.json
TRUTH=${PST_TRUTH:-4}
SIZE=${PST_SIZE:-512}
echo "== reference renders (ground truth ${TRUTH}x${TRUTH})"
for scene in scenes/*.toml; do
  name=$(basename "$scene" .toml)
  ./build/pst render "$scene" -o "out/$name" --truth "$TRUTH" -q
done
echo "== RTL regression at ${SIZE}x${SIZE}"
rc=0
./build/pst regress --size "$SIZE" --profile full --profile full_2clk --profile full_1clk --profile reduced -o out/regress.json \
  --junit out/regress.junit.xml --images out || rc=$?
echo "== animation: seascape fly-in, 24 frames at 64x64 through the reference and full's RTL, flicker vs a 4x4 truth"
./build/pst animate scenes/seascape.toml --frames 24 --size 64 --truth 4 --profile full -o out/anim/seascape -q || rc=1
mkdir -p out/animations
/usr/bin/python3 scripts/flicker.py out/anim/seascape --md out/animations/flicker.md || rc=1
echo "== filter options against the ground truth (scenes 64x64, 16x16 truth; sequences 16 frames 48x48, 8x8 truth)"
VARIANTS=sat,box,trapezoid,sat+footprint,sat+isotropic,trapezoid+footprint
stills=()
for scene in scenes/*.toml; do
  name=$(basename "$scene" .toml)
  ./build/pst render "$scene" --size 64 --truth 16 --variants "$VARIANTS" -o "out/fidelity/$name" -q -j2 || rc=1
  stills+=("out/fidelity/$name")
done
seqs=()
for name in seascape fire marble planet wood_teapot wood_torus moonrise planet_subband seascape_subband \
    seascape_subband_hw; do
  # Every paper scene with a time track through every named profile's RTL (the paper's filter in
  # hardware); the subband basis: also its anisotropic filter (reference) and the subband units' own
  # images (the planet's subband texture is on the sphere, param "sphere": no unit computes it).
  v="$VARIANTS"; hw=(--profile full --profile full_2clk --profile full_1clk --profile reduced)
  case "$name" in *subband*) v="$VARIANTS,sat+anisotropic"; hw=() ;; esac
  [ "$name" = seascape_subband_hw ] && hw=(--profile reduced_subband)
  [ "$name" = seascape_subband ] && hw=(--profile reduced_subband_k8 --profile full_subband_k8)
  ./build/pst animate "scenes/$name.toml" --frames 16 --size 48 --truth 8 --variants "$v" "${hw[@]}" --no-video \
    -o "out/fidelity/anim/$name" -q -j2 || rc=1
  seqs+=("out/fidelity/anim/$name")
done
/usr/bin/python3 scripts/fidelity.py --stills "${stills[@]}" --sequences "${seqs[@]}" \
  --md out/fidelity/fidelity.md --json out/fidelity/fidelity.json > /dev/null || rc=1
if [ "$SYNTH" = 1 ]; then
  echo "== silicon figures (Yosys + OpenSTA), quick precision sweep"
  # full's synthesis and timing (one core) run beside the quick sweep, whose base point is
  # the reduced profile's synthesis (out/synth/reduced.{json,md}).
  /usr/bin/python3 scripts/synth.py full --quiet & full_synth=$!
  /usr/bin/python3 scripts/sweep.py --quick || rc=1
  /usr/bin/python3 scripts/synth.py balanced --quiet || rc=1     # in the baseline too
  /usr/bin/python3 scripts/synth.py full_1clk --quiet || rc=1    # the one-clock full, in the baseline
  /usr/bin/python3 scripts/synth.py full_2clk --quiet || rc=1    # the two-clock full, in the baseline
  wait "$full_synth" || rc=1
  [ -f out/synth/reduced.md ] || /usr/bin/python3 scripts/synth.py reduced --quiet || rc=1
else
  echo "== silicon figures from the record (scripts/run.sh --synth synthesizes them again)"
  /usr/bin/python3 scripts/check_baseline.py --restore --out out || rc=1
fi
echo "== figures"
/usr/bin/python3 scripts/figures.py fig11 --out out || rc=1
/usr/bin/python3 scripts/figures.py fig10 --out out || rc=1
echo "== baseline (scripts/synth/baseline.json)"
/usr/bin/python3 scripts/check_baseline.py --out out --json out/baseline_check.json || rc=1
/usr/bin/python3 scripts/report.py out --md out/report.md --html out/report.html || rc=1
echo "report: out/report.md, out/report.html ($(( $(date +%s) - START )) s)"
exit $rc
