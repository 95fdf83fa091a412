// libFuzzer target for the checkpoint reader (readCheckpoint, sim/state_file.h).
//
// A checkpoint ends with a checksum (FNV-1a, globular::fingerprint, of everything before
// it), which rejects almost every mutation of a real checkpoint before its fields are
// read. So the first input byte selects a mode: odd rewrites the last 8 bytes of the file
// to the checksum of the bytes before them, so mutated fields reach the validation.
//
// Input: a mode byte, then the file, written to a file under /tmp (one per process,
// reused) and read back. The seeds in fuzz/corpus/checkpoint are '1' (names ending
// .reseal) or '0', then a state.bin written by `globular run` (some damaged by hand). An
// IoError is the expected answer to a bad file; anything else (a sanitizer report, another
// exception, a crash) is a bug. A checkpoint that reads must hold a state a run can
// produce, as the reader promises: arrays of one length, integrator state empty or of that
// length, a frame >= 1, time and step count >= 0, finite positions and velocities,
// positive finite radii and masses, ids 0..n-1 each once with next id n, and emitter
// counts (each at most n) that add up to n.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "errors.h"
#include "fuzz_input.h"
#include "state_file.h"

namespace {

const globular_fuzz::InputFile gInput("globular_checkpoint_fuzz", ".bin");

using globular_fuzz::verbose;

[[noreturn]] void inconsistent(const char* what) {
    globular_fuzz::inconsistent("checkpoint_fuzzer", what);
}

void check(const globular::Checkpoint& c) {
    const globular::SimulationState& s = c.state;
    const globular::Globules& g = s.globules;
    const std::size_t n = g.size();
    for (const auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
        if (a->size() != n) inconsistent("arrays of different lengths");
    }
    if (g.id.size() != n) inconsistent("an id array of another length");
    for (const auto* a : {&s.carried.x, &s.carried.y, &s.carried.z}) {
        if (!a->empty() && a->size() != n) inconsistent("integrator state of another length");
    }
    if (c.frame < 1) inconsistent("a frame below 1");
    if (!std::isfinite(s.time) || s.time < 0) inconsistent("a time that is not finite and >= 0");
    if (s.steps < 0) inconsistent("a negative step count");
    if (s.nextId < 0 || std::size_t(s.nextId) != n) inconsistent("a next id other than n");
    std::size_t emitted = 0;
    for (std::size_t e : s.emitted) {
        if (e > n - emitted) inconsistent("emitter counts adding up to more than n");
        emitted += e;
    }
    if (emitted != n) inconsistent("emitter counts not adding up to n");
    std::vector<bool> seen(n, false);
    for (std::size_t i = 0; i < n; ++i) {
        for (float v : {g.px[i], g.py[i], g.pz[i], g.vx[i], g.vy[i], g.vz[i]}) {
            if (!std::isfinite(v)) inconsistent("a non-finite position or velocity");
        }
        if (!(g.radius[i] > 0) || !std::isfinite(g.radius[i])) inconsistent("a bad radius");
        if (!(g.mass[i] > 0) || !std::isfinite(g.mass[i])) inconsistent("a bad mass");
        const int32_t id = g.id[i];
        if (id < 0 || std::size_t(id) >= n) inconsistent("an id out of range");
        if (seen[std::size_t(id)]) inconsistent("two globules with one id");
        seen[std::size_t(id)] = true;
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    globular_fuzz::ModedInput input = globular_fuzz::splitMode(data, size);
    std::string& bytes = input.file;
    if (input.forgeChecksum && bytes.size() >= sizeof(uint64_t)) {
        const std::size_t payload = bytes.size() - sizeof(uint64_t);
        const uint64_t sum = globular::fingerprint(bytes.substr(0, payload));
        std::memcpy(bytes.data() + payload, &sum, sizeof sum);
    }
    gInput.write(bytes);
    try {
        const globular::Checkpoint c = globular::readCheckpoint(gInput.path());
        check(c);
        if (verbose()) {
            std::fprintf(stderr, "checkpoint_fuzzer: frame %d, %zu globules\n", c.frame,
                         c.state.globules.size());
        }
    } catch (const globular::Error& e) {
        if (verbose()) std::fprintf(stderr, "%s\n", e.what());
    }
    return 0;
}
