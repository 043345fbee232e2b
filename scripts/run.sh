#!/usr/bin/env bash
# The main job: install dependencies, build, render every scene of scenes/ (filtered,
# unfiltered, filter width, ground truth) into out/<scene>/ and write out/report.md.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
mkdir -p out
TRUTH=${PST_TRUTH:-4}
for scene in scenes/*.toml; do
  name=$(basename "$scene" .toml)
  ./build/pst render "$scene" -o "out/$name" --truth "$TRUTH"
done
/usr/bin/python3 scripts/report.py out > out/report.md.tmp && mv out/report.md.tmp out/report.md
echo "report: out/report.md"
