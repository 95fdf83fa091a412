#!/usr/bin/env bash
# Reliability checks that CI runs after the normal test suite (issue 6). Three parts,
# each timed; any crash, sanitizer report, failed test or non-zero exit fails the script.
#   fuzz  builds the libFuzzer targets with clang (fuzz/, ASan+UBSan) in build-fuzz and
#         runs each over its seed corpus for FUZZ_SECONDS (scene, ply, vdb_cache,
#         surface_vdb, mesh, checkpoint, collider_files); crashing inputs are kept in
#         build-fuzz/artifacts/ (add them to fuzz/corpus/ once fixed)
#   asan  builds the whole test suite with GLOBULAR_SANITIZE=ON (gcc, -O1) in build-asan
#         and runs ctest there
#   soak  runs build-asan/globular on scenes/ci/soak.toml: the sim stage (2000 globules,
#         3960 steps), then the surface stage on the last frames, as a second process
#         that reads the caches back
# Environment:
#   PARTS="fuzz asan soak"  the parts to run, in this order
#   FUZZ_SECONDS=60         -max_total_time of each fuzzer
#   FUZZ_BUILD_DIR, ASAN_BUILD_DIR   build directories (build-fuzz, build-asan)
#   CTEST_EXCLUDE=REGEX     tests left out of the sanitizer run (default: none)
#   JOBS=N                  build and ctest parallelism (default: nproc)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
parts=${PARTS:-fuzz asan soak}
fuzz_seconds=${FUZZ_SECONDS:-60}
fuzz_build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
asan_build=${ASAN_BUILD_DIR:-$root/build-asan}
jobs=${JOBS:-$(nproc)}

# Leaks are errors (but those inside third-party libraries listed in
# lsan_suppressions.txt); UBSan stops at the first finding with a stack trace.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/scripts/lsan_suppressions.txt}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

summary=()
started=$SECONDS
# The durations so far, also when a part fails.
report() {
    local status=$?
    echo "ci_reliability: $( ((status == 0)) && echo passed || echo FAILED)" \
        "after $((SECONDS - started)) s"
    ((${#summary[@]})) && printf '  %s\n' "${summary[@]}"
    return $status
}
trap report EXIT
# timed NAME COMMAND...: runs the command, prints and records how long it took.
timed() {
    local name=$1 t0=$SECONDS
    shift
    echo "ci_reliability: == $name"
    "$@"
    local took=$((SECONDS - t0))
    summary+=("$(printf '%-16s %4d s' "$name" "$took")")
    echo "ci_reliability: $name took ${took} s"
}

fuzz_configure_build() {
    cmake -S "$root" -B "$fuzz_build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ \
        -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
        -DGLOBULAR_FUZZ=ON -DGLOBULAR_TESTS=OFF -DGLOBULAR_BENCH=OFF >/dev/null
    cmake --build "$fuzz_build" -j "$jobs" --target scene_fuzzer ply_fuzzer \
        vdb_cache_fuzzer surface_vdb_fuzzer mesh_fuzzer checkpoint_fuzzer collider_files_fuzzer
}

# fuzz_run NAME: new inputs go to a scratch corpus, so fuzz/corpus/ stays as checked in.
# fuzz/NAME.dict is passed when there is one. An artifact written during a run that
# exits 0 fails it too (a reader's child process must not dump crash files).
fuzz_run() {
    local name=$1 scratch stamp
    scratch=$(mktemp -d)
    stamp=$(mktemp)
    mkdir -p "$fuzz_build/artifacts"
    local dict=()
    [[ -f "fuzz/$name.dict" ]] && dict=(-dict="fuzz/$name.dict")
    local status=0
    # A file that makes OpenVDB loop is answered by killing the reader (5 s in the
    # fuzzers, vdb_fuzz_support.h; twice where the helper dies with it): an IoError,
    # the expected answer, in about 20 s. Such a unit is slow, not a finding, so only
    # units past -timeout count (as timeouts); libFuzzer's default of 10 s wrote a
    # slow-unit artifact for one and failed CI.
    "$fuzz_build/fuzz/${name}_fuzzer" -max_total_time="$fuzz_seconds" -timeout=25 \
        -report_slow_units=25 -rss_limit_mb=2048 "${dict[@]}" -print_final_stats=1 \
        -artifact_prefix="$fuzz_build/artifacts/$name-" "$scratch" "fuzz/corpus/$name" \
        >"$fuzz_build/$name.log" 2>&1 || status=$?
    rm -rf "$scratch"
    local artifacts
    artifacts=$(find "$fuzz_build/artifacts" -name "$name-*" -newer "$stamp" -print)
    rm -f "$stamp"
    grep -E '^(stat::number_of_executed_units|stat::new_units_added|Done )' \
        "$fuzz_build/$name.log" || true
    if ((status != 0)); then
        tail -n 60 "$fuzz_build/$name.log"
        echo "ci_reliability: ${name}_fuzzer failed (exit $status); input kept in" \
            "$fuzz_build/artifacts/, log in $fuzz_build/$name.log" >&2
        return 1
    fi
    if [[ -n "$artifacts" ]]; then
        echo "ci_reliability: ${name}_fuzzer exited 0 but wrote artifacts (from a reader's" \
            "child process?); log in $fuzz_build/$name.log:" >&2
        printf '  %s\n' $artifacts >&2
        return 1
    fi
}

asan_configure_build() {
    # -O1 keeps the sanitizer build and run fast enough; -g1 gives line numbers in reports.
    cmake -S "$root" -B "$asan_build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1 -DNDEBUG" \
        -DGLOBULAR_SANITIZE=ON -DGLOBULAR_TESTS=ON -DGLOBULAR_BENCH=OFF >/dev/null
    cmake --build "$asan_build" -j "$jobs"
}

asan_ctest() {
    local exclude=()
    [[ -n "${CTEST_EXCLUDE:-}" ]] && exclude=(-E "$CTEST_EXCLUDE")
    ctest --test-dir "$asan_build" --output-on-failure -j "$jobs" --timeout 1200 \
        "${exclude[@]}"
}

soak() {
    local out status=0
    out=$(mktemp -d)
    local exe="$asan_build/globular" scene="$root/scenes/ci/soak.toml"
    "$exe" run "$scene" --out "$out" --stages sim --quiet || status=$?
    if ((status == 0)); then
        "$exe" run "$scene" --out "$out" --stages surface --frames 98-100 --quiet \
            || status=$?
    fi
    if ((status == 0)); then
        for f in cache/globules.0100.vdb cache/globules.0100.ply surface/surface.0100.vdb \
            mesh/surface.0098.ply mesh/surface.0100.ply; do
            [[ -s "$out/$f" ]] || { echo "ci_reliability: soak did not write $f" >&2; status=1; }
        done
        tail -n 1 "$out/stats.csv"
    fi
    rm -rf "$out"
    if ((status != 0)); then
        echo "ci_reliability: soak run failed (exit $status)" >&2
        return 1
    fi
}

for part in $parts; do
    case $part in
        fuzz)
            timed fuzz-build fuzz_configure_build
            timed fuzz-scene fuzz_run scene
            timed fuzz-ply fuzz_run ply
            timed fuzz-vdb-cache fuzz_run vdb_cache
            timed fuzz-surface-vdb fuzz_run surface_vdb
            timed fuzz-mesh fuzz_run mesh
            timed fuzz-checkpoint fuzz_run checkpoint
            timed fuzz-collider-files fuzz_run collider_files
            ;;
        asan)
            timed asan-build asan_configure_build
            timed asan-ctest asan_ctest
            ;;
        soak)
            [[ -x "$asan_build/globular" ]] || timed asan-build asan_configure_build
            timed soak soak
            ;;
        *)
            echo "ci_reliability: unknown part '$part' (fuzz, asan, soak)" >&2
            exit 2
            ;;
    esac
done

