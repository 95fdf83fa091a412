// libFuzzer target for the PLY mesh reader (readMeshPly, surface/mesh.h; the PLY reader
// underneath is core/ply_reader.h).
//
// The reader takes a path, so each input is written to a file under /tmp (one per
// process, reused) and read back. An IoError is the expected answer to a bad file;
// anything else (a sanitizer report, another exception, a crash) is a bug. A mesh that
// reads must be whole: positions in threes, a normal per vertex (read or computed),
// triangles in threes and every triangle index naming a vertex.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "errors.h"
#include "fuzz_input.h"
#include "mesh.h"

namespace {

const globular_fuzz::InputFile gInput("globular_mesh_fuzz", ".ply");

using globular_fuzz::verbose;

[[noreturn]] void inconsistent(const char* what) {
    globular_fuzz::inconsistent("mesh_fuzzer", what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    gInput.write(globular_fuzz::bytesOf(data, size));
    try {
        const globular::TriangleMesh mesh = globular::readMeshPly(gInput.path());
        if (mesh.positions.size() % 3 != 0) inconsistent("positions not in threes");
        if (mesh.normals.size() != mesh.positions.size()) {
            inconsistent("normals and positions of different lengths");
        }
        if (mesh.triangles.size() % 3 != 0) inconsistent("triangle indices not in threes");
        const std::size_t vertices = mesh.vertexCount();
        for (uint32_t v : mesh.triangles) {
            if (v >= vertices) inconsistent("a triangle index out of range");
        }
        if (verbose()) {
            std::fprintf(stderr, "mesh_fuzzer: %zu vertices, %zu triangles\n", vertices,
                         mesh.triangleCount());
        }
    } catch (const globular::Error& e) {
        if (verbose()) std::fprintf(stderr, "%s\n", e.what());
    }
    return 0;
}
