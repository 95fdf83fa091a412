#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (ctest).
#   scripts/test.sh                 release build in build/
#   SANITIZE=ON BUILD_DIR=build-asan scripts/test.sh   the suite under ASan+UBSan
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/setup.sh"
build=${BUILD_DIR:-$root/build}
# Under the sanitizers, leaks inside third-party libraries (OSMesa) are not ours.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/scripts/lsan_suppressions.txt}
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 900
