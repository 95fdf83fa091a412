// libFuzzer target for the PLY globule reader (readGlobulePly, sim/globule_cache.h).
//
// The reader takes a path, so each input is written to a file under /tmp (one per
// process, reused) and read back. An IoError is the expected answer to a bad file;
// anything else (a sanitizer report, another exception, a crash) is a bug. A file that
// reads must give arrays of one length (temperature: or none) and finite temperatures.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "errors.h"
#include "fuzz_input.h"
#include "globule_cache.h"

namespace {

const globular_fuzz::InputFile gInput("globular_ply_fuzz", ".ply");

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    gInput.write(globular_fuzz::bytesOf(data, size));
    try {
        const globular::Globules g = globular::readGlobulePly(gInput.path(), 0.5f);
        const std::size_t n = g.size();
        for (const auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
            if (a->size() != n) std::abort();
        }
        if (g.id.size() != n) std::abort();
        if (!g.temperature.empty() && g.temperature.size() != n) std::abort();
        for (float t : g.temperature) {
            if (!std::isfinite(t)) std::abort();
        }
        for (float m : g.mass) {
            if (!(m > 0) || !std::isfinite(m)) std::abort();
        }
    } catch (const globular::Error&) {
    }
    return 0;
}
