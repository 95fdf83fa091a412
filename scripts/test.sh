#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (ctest).
#   scripts/test.sh                 release build in build/
#   SANITIZE=ON BUILD_DIR=build-asan scripts/test.sh   the suite under ASan+UBSan
#   WITH_BLENDER=1 scripts/test.sh  also installs Blender and requires its test to run
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/setup.sh"
build=${BUILD_DIR:-$root/build}
# Under the sanitizers, leaks inside third-party libraries (OSMesa) are not ours.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/scripts/lsan_suppressions.txt}
# With WITH_BLENDER=1 the Blender test must run: a missing Blender fails it, not skips it.
[[ "${WITH_BLENDER:-0}" == 1 ]] && export GLOBULAR_REQUIRE_BLENDER=1
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 900
