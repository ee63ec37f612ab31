#!/usr/bin/env bash
# Installs everything Cairn needs to build and test, from Debian's packages
# only; with --bench, also the benchmarks' peers (Google Benchmark, Siconos,
# Bullet), which the main job and the tests do not need. Safe to run again: it
# installs only what is missing. Must run as root (or with sudo available) on
# Debian 12.
#   bash scripts/setup.sh          # build + tests
#   bash scripts/setup.sh --bench  # ... and bench/
#   bash scripts/setup.sh --fuzz   # ... and clang with libFuzzer (fuzz/README.md)
#   bash scripts/setup.sh --lint   # ... and clang-tidy-19 (.clang-tidy) and clang-format
set -euo pipefail

bench=0
fuzz=0
lint=0
for arg in "$@"; do
  case "$arg" in
    --bench) bench=1 ;;
    --fuzz) fuzz=1 ;;
    --lint) lint=1 ;;
    *) echo "setup: unknown option $arg (known: --bench, --fuzz, --lint)" >&2; exit 2 ;;
  esac
done

packages=(
  build-essential cmake git pkg-config
  libeigen3-dev          # dense and sparse linear algebra
  nlohmann-json3-dev     # scene and report JSON
  libcli11-dev           # command-line parsing
  libglpk-dev            # the rest-hypothesis linear program (motion in 3-D)
  coinor-libclp-dev      # the static-equilibrium linear program
  libassimp-dev          # mesh parts (OBJ, STL)
  libboost-dev           # Boost.Geometry: clipping coplanar faces of 3-D contacts
  # STEP assemblies (--format step, src/io/step_reader.cpp): OpenCASCADE 7.6's
  # reader and XCAF document, B-rep tools and mesher; TBB, which it links.
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-ocaf-dev libocct-data-exchange-dev libtbb-dev
  libgtest-dev libgmock-dev  # tests
  # `cairn batch` and `cairn plan` across MPI ranks (CAIRN_MPI, docs/batch.md):
  # Debian's OpenMPI, its headers and mpirun.
  libopenmpi-dev openmpi-bin
  # The Python module (python/, docs/python.md) and its tests: Debian's
  # interpreter, numpy, pybind11, pytest, matplotlib (cairn.plot), and venv,
  # pip, setuptools and wheel for `pip install .` offline.
  python3-dev python3-numpy pybind11-dev python3-pytest python3-matplotlib
  python3-venv python3-pip python3-setuptools python3-wheel
  # The result pages (--html, docs/html.md) tested in a real browser:
  # Debian's Chromium, headless, driven by playwright-core from npm (below).
  chromium fonts-dejavu-core
)
if ((bench)); then
  packages+=(
    libbenchmark-dev           # bench/
    libsiconos-numerics-dev    # bench/: Siconos' Lemke, the peer we compare against
    libbullet-dev              # bench/: Bullet, the simulator a user would otherwise threshold
  )
fi

if ((fuzz)); then
  packages+=(
    clang libclang-rt-dev      # fuzz/: libFuzzer, ASan and UBSan for clang
  )
fi

if ((lint)); then
  packages+=(
    clang-tidy-19 clang-format  # .clang-tidy (misc-include-cleaner needs 17+), .clang-format
  )
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: all packages present"
fi

# The browser tests' driver (web/package.json: playwright-core; three.js and
# esbuild, which rebuild web/dist/viewer.js) from the npm registry, at the
# versions of web/package-lock.json. Node.js is the machine's (>= 20), or
# Debian's when there is none.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "setup: installing nodejs npm"
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
fi
web_dir="$(cd "$(dirname "$0")/../web" && pwd)"
if [[ ! -d "$web_dir/node_modules/playwright-core" || "$web_dir/package-lock.json" -nt "$web_dir/node_modules/.package-lock.json" ]]; then
  echo "setup: npm ci in web/"
  (cd "$web_dir" && npm ci --no-audit --no-fund --loglevel=error)
fi
