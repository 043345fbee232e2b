#!/usr/bin/env bash
# Installs the project's dependencies from Debian's packages, skipping what is present.
# Idempotent; needs root (or sudo) only when something is missing.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config git
  verilator yosys opensta
  libglm-dev libopenimageio-dev openimageio-tools
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-numpy python3-matplotlib python3-openimageio python3-pytest
  python3-markdown chromium         # HTML report (scripts/report.py) and its browser test
  clang-14 libclang-rt-14-dev     # scripts/fuzz.sh: libFuzzer and the sanitizer runtimes
  ffmpeg                            # pst animate: frames -> video (VP9 webm)
  slurm-wlm slurm-client munge      # scripts/search.py --backend slurm; ctest -L slurm (scripts/slurm_local.sh)
  lcov                            # scripts/coverage.sh: genhtml
  gtkwave                         # FST waves (pst render --trace, regress --waves): the viewer, fst2vcd in the tests
  iverilog                        # gate-level simulation of the netlists (scripts/gatelevel.py --simulator iverilog)
  libmetis-dev                     # pst atlas: the multiresolution atlas's partition
  libfftw3-dev libeigen3-dev       # model/subband: spectral noise tiles (FFT), least-squares weights
  z3 python3-z3                    # scripts/mul_proof.py: the multiplier forms' proof (with Yosys's ABC)
  libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri  # pst_multipass: OpenGL ES 3 through EGL without a display (llvmpipe)
)
# scripts/pnr.py (place and route, not part of the test suite): `scripts/setup.sh --pnr` adds
# qflow and its OSU 0.18 um technology (graywolf, qrouter, magic, netgen-lvs come with it) and
# KLayout for the layout pictures.
if [ "${1:-}" = "--pnr" ]; then
  PACKAGES+=(qflow qflow-tech-osu018 klayout tcsh)
fi
# Node.js for the report's browser test (playwright-core): Debian's nodejs/npm unless a node
# (and npm) is already on the PATH (e.g. another distribution's nodejs package, which has npm).
command -v node >/dev/null 2>&1 || PACKAGES+=(nodejs)
command -v npm >/dev/null 2>&1 || PACKAGES+=(npm)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
else
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The browser test's driver (playwright-core, no browser download: it drives /usr/bin/chromium)
# from the checked-in lock file, into scripts/tests/browser/node_modules (ignored by git).
BROWSER_DIR="$(dirname "$0")/tests/browser"
if [ ! -f "$BROWSER_DIR/node_modules/.package-lock.json" ] ||
   ! cmp -s "$BROWSER_DIR/package-lock.json" "$BROWSER_DIR/node_modules/.lock-installed"; then
  echo "setup: npm ci in $BROWSER_DIR"
  (cd "$BROWSER_DIR" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error &&
   cp package-lock.json node_modules/.lock-installed)
fi

# The OSU 0.18 um standard-cell library (scripts/synth.py): Debian's qflow-tech-osu018 depends
# on all of qflow, so its files alone are unpacked into a cache (apt-get download + dpkg-deb).
OSU_LIB=usr/share/qflow/tech/osu018/osu018_stdcells.lib
OSU_DIR="${XDG_CACHE_HOME:-$HOME/.cache}/pst/osu018"
if [ ! -f "/$OSU_LIB" ] && [ ! -f "$OSU_DIR/$OSU_LIB" ]; then
  echo "setup: unpacking qflow-tech-osu018 into $OSU_DIR"
  dl=$(mktemp -d)
  if ! (cd "$dl" && apt-get download -q qflow-tech-osu018 2>/dev/null); then
    $SUDO apt-get update -q
    (cd "$dl" && apt-get download -q qflow-tech-osu018)
  fi
  mkdir -p "$OSU_DIR"
  dpkg-deb -x "$dl"/qflow-tech-osu018_*.deb "$OSU_DIR"
  rm -rf "$dl"
  test -f "$OSU_DIR/$OSU_LIB"
fi
