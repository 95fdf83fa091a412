// libFuzzer target for the surface VDB reader (readSurfaceVdb, surface/surface_grids.h).
//
// COVERAGE: the reader checks the file's bytes (layout, checksum) in this process, then
// parses it with OpenVDB in a forked child (core/isolated_parse.h), which sends the grids
// back in OpenVDB's streamed encoding. libFuzzer sees no coverage from the child, so it
// cannot steer mutations through OpenVDB's parser; what it covers and steers is this
// process's side: the byte checks, the decoding of the child's answer, and the handling
// of a child that crashed, failed or timed out. The mutated files still reach OpenVDB:
// the first input byte selects a mode that reseals the checksum after the mutation
// (vdb_fuzz_support.h), and the child's crashes are kept from triggering libFuzzer's
// crash handling there (installChildGuard). To see what a child printed or where it
// crashed, rerun an input with GLOBULAR_CHILD_STDERR=1.
//
// Input: a mode byte (odd: reseal the checksum), then the file. The seeds in
// fuzz/corpus/surface_vdb are '1' (names ending .reseal) or '0', then a surface file
// written by `globular run` (some damaged or cut by hand). An IoError is the expected
// answer to a bad file; anything else (a sanitizer report or a crash in this process,
// another exception) is a bug. A file that reads must give two float grids, "surface" a
// level set and "density", whose trees can be walked.

#include <openvdb/openvdb.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "errors.h"
#include "surface_grids.h"
#include "vdb_fuzz_support.h"

namespace {

const globular_fuzz::InputFile gInput("globular_surface_vdb_fuzz", ".vdb");

using globular_fuzz::verbose;

[[noreturn]] void inconsistent(const char* what) {
    globular_fuzz::inconsistent("surface_vdb_fuzzer", what);
}

/// Walks every active value and every leaf of @p grid in this process, under ASan.
template <typename GridT>
void walk(const GridT& grid) {
    openvdb::Index64 values = 0;
    for (auto it = grid.cbeginValueOn(); it; ++it) values += it.getVoxelCount();
    if (values != grid.activeVoxelCount()) inconsistent("a tree whose active counts disagree");
    openvdb::Index64 leaves = 0;
    for (auto it = grid.tree().cbeginLeaf(); it; ++it) ++leaves;
    if (leaves != grid.tree().leafCount()) inconsistent("a tree whose leaf counts disagree");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    globular_fuzz::installChildGuard();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    gInput.write(globular_fuzz::vdbFile(data, size));
    try {
        const globular::SurfaceGrids grids = globular::readSurfaceVdb(gInput.path());
        if (!grids.surface || !grids.density) inconsistent("a null grid");
        if (grids.surface->getName() != "surface") inconsistent("a surface grid of another name");
        if (grids.density->getName() != "density") inconsistent("a density grid of another name");
        if (grids.surface->getGridClass() != openvdb::GRID_LEVEL_SET) {
            inconsistent("a surface grid that is not a level set");
        }
        walk(*grids.surface);
        walk(*grids.density);
        if (grids.temperature) walk(*grids.temperature);
        if (grids.vel) {
            if (grids.vel->getName() != "vel") inconsistent("a vel grid of another name");
            walk(*grids.vel);
        }
        if (verbose()) {
            std::fprintf(stderr, "surface_vdb_fuzzer: %llu + %llu active voxels\n",
                         static_cast<unsigned long long>(grids.surface->activeVoxelCount()),
                         static_cast<unsigned long long>(grids.density->activeVoxelCount()));
        }
    } catch (const globular::Error& e) {
        if (verbose()) std::fprintf(stderr, "%s\n", e.what());
    }
    return 0;
}
