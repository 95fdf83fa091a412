// libFuzzer target for the VDB globule cache reader (readGlobuleVdb, sim/globule_cache.h).
//
// COVERAGE: the reader checks the file's bytes (layout, checksum) in this process, then
// parses it with OpenVDB in a forked child (core/isolated_parse.h). libFuzzer sees no
// coverage from the child, so it cannot steer mutations through OpenVDB's parser; what
// it covers and steers is this process's side: the byte checks, the decoding of the
// child's answer, and the handling of a child that crashed, failed or timed out. The
// mutated files still reach OpenVDB: the first input byte selects a mode that reseals
// the checksum after the mutation (vdb_fuzz_support.h), and the child's crashes are
// kept from triggering libFuzzer's crash handling there (installChildGuard). To see
// what a child printed or where it crashed, rerun an input with GLOBULAR_CHILD_STDERR=1.
//
// Input: a mode byte (odd: reseal the checksum), then the file. The seeds in
// fuzz/corpus/vdb_cache are '1' (names ending .reseal) or '0', then a cache written by
// `globular run` (some damaged or cut by hand). An IoError is the expected answer to a bad
// file; anything else (a sanitizer report or a crash in this process, another exception)
// is a bug. A cache that reads must give arrays of one length (temperature: or none),
// finite temperatures, positive finite masses, globules ordered by id (as the header
// promises).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "errors.h"
#include "globule_cache.h"
#include "vdb_fuzz_support.h"

namespace {

const globular_fuzz::InputFile gInput("globular_vdb_cache_fuzz", ".vdb");

using globular_fuzz::verbose;

[[noreturn]] void inconsistent(const char* what) {
    globular_fuzz::inconsistent("vdb_cache_fuzzer", what);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    globular_fuzz::installChildGuard();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    gInput.write(globular_fuzz::vdbFile(data, size));
    try {
        globular::CacheInfo info;
        const globular::Globules g = globular::readGlobuleVdb(gInput.path(), &info);
        const std::size_t n = g.size();
        for (const auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
            if (a->size() != n) inconsistent("arrays of different lengths");
        }
        if (g.id.size() != n) inconsistent("an id array of another length");
        if (!g.temperature.empty() && g.temperature.size() != n) {
            inconsistent("a temperature array of another length");
        }
        for (float t : g.temperature) {
            if (!std::isfinite(t)) inconsistent("a non-finite temperature");
        }
        for (std::size_t i = 0; i < n; ++i) {
            if (!(g.mass[i] > 0) || !std::isfinite(g.mass[i])) {
                inconsistent("a mass that is not positive and finite");
            }
            if (i > 0 && g.id[i - 1] > g.id[i]) inconsistent("globules not ordered by id");
        }
        if (verbose()) {
            std::fprintf(stderr, "vdb_cache_fuzzer: %zu globules, frame %d\n", n, info.frame);
        }
    } catch (const globular::Error& e) {
        if (verbose()) std::fprintf(stderr, "%s\n", e.what());
    }
    return 0;
}
