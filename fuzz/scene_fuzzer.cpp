// libFuzzer target for the scene reader (cli/scene.h).
//
// Input: scene TOML text, optionally followed by a NUL and one --set override
// ("material.b1=3", "emitter.0.count=100"). A globular::Error is the expected answer to
// bad input; anything else (a sanitizer report, another exception, a crash) is a bug.
// A scene that parses must also survive the round trip the README promises (its
// resolved scene parses again and resolves to the same text), and its emitters must
// build and emit their first globules (small ones only, so each input stays fast;
// points emitters read files and are left out).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "emitter.h"
#include "errors.h"
#include "globules.h"
#include "reporter.h"
#include "scene.h"

namespace {

[[noreturn]] void roundTripFailed(const std::string& resolved, const std::string& problem) {
    std::fprintf(stderr, "scene_fuzzer: resolved scene does not round-trip: %s\n%s\n",
                 problem.c_str(), resolved.c_str());
    std::abort();
}

constexpr int64_t kMaxFuzzedEmitterCount = 10000;

void emitFirstGlobules(const globular::Scene& scene) {
    for (std::size_t i = 0; i < scene.emitters.size(); ++i) {
        const globular::EmitterSettings& e = scene.emitters[i];
        // Sizes the emitter refuses at once (over 1e8 globules, or not a number) are kept;
        // large sizes it accepts only cost time. A box with count 0 fills its lattice; a
        // spout builds its whole nozzle pattern, ~3.6 (nozzle_radius / spacing)^2 globules.
        const auto large = [](double n) { return n > 1e4 && n <= 1e8; };
        const auto cells = [&](double extent) { return std::floor(extent / e.spacing); };
        const double lattice =
            cells(e.max.x - e.min.x) * cells(e.max.y - e.min.y) * cells(e.max.z - e.min.z);
        const double ratio = e.nozzleRadius / e.spacing;
        if (e.type == "points" || e.count > kMaxFuzzedEmitterCount ||
            (e.type == "box" && e.count == 0 && large(lattice)) ||
            (e.type == "spout" && large(3.63 * ratio * ratio))) {
            continue;
        }
        try {
            const auto emitter = globular::makeEmitter(e, uint64_t(scene.simulation.seed), i, {});
            globular::Globules globules;
            int32_t nextId = 0;
            emitter->emit(e.start, globules, nextId);
        } catch (const globular::Error&) {
            // an unusable combination the emitter names (a spout rate too high, ...)
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::size_t nul = input.find('\0');
    const std::string text = input.substr(0, nul);
    std::vector<std::string> overrides;
    if (nul != std::string::npos) overrides.push_back(input.substr(nul + 1));

    globular::NullReporter reporter;
    std::string resolved;
    try {
        const globular::Scene scene = globular::parseScene(text, "<fuzz>", overrides, reporter);
        resolved = globular::resolvedSceneToml(scene);
    } catch (const globular::Error&) {
        return 0;  // bad input, reported with a message: what the reader should do
    }
    try {
        const globular::Scene again = globular::parseScene(resolved, "<resolved>", {}, reporter);
        const std::string resolvedAgain = globular::resolvedSceneToml(again);
        if (resolvedAgain != resolved) roundTripFailed(resolved, "differs:\n" + resolvedAgain);
        emitFirstGlobules(again);
    } catch (const globular::Error& e) {
        roundTripFailed(resolved, e.what());
    }
    return 0;
}
