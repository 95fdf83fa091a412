// libFuzzer target for the PLY globule reader (readGlobulePly, sim/globule_cache.h).
//
// The reader takes a path, so each input is written to a file under /tmp (one per
// process, reused) and read back. An IoError is the expected answer to a bad file;
// anything else (a sanitizer report, another exception, a crash) is a bug. A file that
// reads must give arrays of one length.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "errors.h"
#include "globule_cache.h"

namespace {

const std::filesystem::path& inputPath() {
    static const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("globular_ply_fuzz." + std::to_string(getpid()) + ".ply");
    return path;
}

struct RemoveAtExit {
    ~RemoveAtExit() {
        std::error_code ignored;
        std::filesystem::remove(inputPath(), ignored);
    }
} gRemoveAtExit;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    {
        std::ofstream out(inputPath(), std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
        if (!out) {
            std::perror("ply_fuzzer: cannot write the input file");
            std::abort();
        }
    }
    try {
        const globular::Globules g = globular::readGlobulePly(inputPath(), 0.5f);
        const std::size_t n = g.size();
        for (const auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
            if (a->size() != n) std::abort();
        }
        if (g.id.size() != n) std::abort();
    } catch (const globular::Error&) {
    }
    return 0;
}
