#!/usr/bin/env bash
# Installs what globular needs from Debian's packages, only what is missing, then
# configures and builds. Idempotent: a second run installs nothing and rebuilds
# incrementally.
#   scripts/setup.sh            release build in build/
#   BUILD_DIR=x BUILD_TYPE=Debug SANITIZE=ON scripts/setup.sh
#   WITH_PEERS=1 scripts/setup.sh   also what the benchmarks use: the peers (lammps,
#                                   hyperfine, ffmpeg) and jq, time
#   WITH_SLURM=1 scripts/setup.sh   also Debian's Slurm and munge, for the farm test on a
#                                   one-node cluster (scripts/local_slurm.sh; ctest -L slurm)
#   WITH_BLENDER=1 scripts/setup.sh also Debian's blender, for the add-on's headless test
#                                   (ctest -L blender; skipped without it)
set -euo pipefail

packages=(
    build-essential cmake ninja-build pkg-config
    libopenvdb-dev libopenvdb-tools libboost-iostreams-dev libblosc-dev
    libtbb-dev libeigen3-dev libjemalloc-dev
    libosmesa6-dev libegl-dev libegl-mesa0 libpng-dev zlib1g-dev libopenexr-dev openexr
    libtomlplusplus-dev libcli11-dev
    libgtest-dev libgmock-dev libbenchmark-dev
    gnuplot-nox
    python3                     # the Blender add-on's PLY reader test runs under plain python3
    clang libclang-rt-14-dev    # libFuzzer targets (scripts/ci_reliability.sh)
)
if [[ "${WITH_PEERS:-0}" == 1 ]]; then
    packages+=(lammps hyperfine ffmpeg jq time)
fi
if [[ "${WITH_SLURM:-0}" == 1 ]]; then
    packages+=(slurm-wlm munge)
fi
if [[ "${WITH_BLENDER:-0}" == 1 ]]; then
    packages+=(blender)
fi

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' \
        || missing+=("$p")
done
if ((${#missing[@]})); then
    echo "setup: installing ${missing[*]}"
    sudo=""
    [[ $(id -u) == 0 ]] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
        "${missing[@]}"
fi

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -G Ninja \
    -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" \
    -DGLOBULAR_SANITIZE="${SANITIZE:-OFF}" >/dev/null
cmake --build "$build" -j "$(nproc)"
