// libFuzzer target for the PLY mesh reader (readMeshPly, surface/mesh.h; the PLY reader
// underneath is sim/ply_reader.h).
//
// The reader takes a path, so each input is written to a file under /tmp (one per
// process, reused) and read back. An IoError is the expected answer to a bad file;
// anything else (a sanitizer report, another exception, a crash) is a bug. A mesh that
// reads must be whole: positions in threes, a normal per vertex (read or computed),
// triangles in threes and every triangle index naming a vertex.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "errors.h"
#include "mesh.h"

namespace {

const std::filesystem::path& inputPath() {
    static const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("globular_mesh_fuzz." + std::to_string(getpid()) + ".ply");
    return path;
}

struct RemoveAtExit {
    ~RemoveAtExit() {
        std::error_code ignored;
        std::filesystem::remove(inputPath(), ignored);
    }
} gRemoveAtExit;

[[noreturn]] void inconsistent(const char* what) {
    std::fprintf(stderr, "mesh_fuzzer: readMeshPly returned %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    {
        std::ofstream out(inputPath(), std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
        if (!out) {
            std::perror("mesh_fuzzer: cannot write the input file");
            std::abort();
        }
    }
    try {
        const globular::TriangleMesh mesh = globular::readMeshPly(inputPath());
        if (mesh.positions.size() % 3 != 0) inconsistent("positions not in threes");
        if (mesh.normals.size() != mesh.positions.size()) {
            inconsistent("normals and positions of different lengths");
        }
        if (mesh.triangles.size() % 3 != 0) inconsistent("triangle indices not in threes");
        const std::size_t vertices = mesh.vertexCount();
        for (uint32_t v : mesh.triangles) {
            if (v >= vertices) inconsistent("a triangle index out of range");
        }
    } catch (const globular::Error&) {
    }
    return 0;
}
