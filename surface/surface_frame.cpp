#include "surface_frame.h"

#include <openvdb/io/File.h>
#include <tbb/parallel_invoke.h>

#include "atomic_file.h"
#include "errors.h"
#include "surface_grids.h"

namespace globular {

SurfaceFrame surfaceGlobules(const Globules& globules, const SurfaceSettings& settings) {
    settings.validate();
    openvdb::initialize();

    SurfaceFrame frame;
    frame.voxelSize = resolveVoxelSize(settings, globules);
    openvdb::FloatGrid::Ptr levelSet;
    {
        // Deep inside the liquid the field's exact value is never read: partial sums there.
        const auto field = splatMetaballs(globules, settings.metaballKernel(), settings.influence,
                                          frame.voxelSize, settings.isoValue);
        frame.fieldLeaves = field->tree().leafCount();
        levelSet = fieldToLevelSet(*field, settings.isoValue, settings.bandWidth);
    }  // the field is the largest grid: free it before the level-set steps
    applyFilters(*levelSet, settings.filterChain());
    frame.dropletsRemoved = removeDroplets(levelSet, settings.dropletVolume);

    auto grids = std::make_shared<SurfaceGrids>();
    grids->surface = levelSet;
    // The fog volume and the mesh only read the level set: build them side by side.
    tbb::parallel_invoke([&] { grids->density = levelSetToFog(*levelSet); },
                         [&] { frame.mesh = meshLevelSet(*levelSet, settings.adaptivity); });

    // Provenance for whoever opens the file in a DCC tool.
    for (const auto& grid : {grids->surface, grids->density}) {
        grid->insertMeta("globular_kernel", openvdb::StringMetadata(settings.kernel));
        grid->insertMeta("globular_iso_value", openvdb::FloatMetadata(float(settings.isoValue)));
        grid->insertMeta("globular_influence", openvdb::FloatMetadata(float(settings.influence)));
    }
    frame.grids = grids;
    return frame;
}

void writeSurfaceVdb(const std::filesystem::path& path, const SurfaceFrame& frame) {
    if (!frame.grids || !frame.grids->surface || !frame.grids->density) {
        throw IoError("cannot write " + path.string() + ": the frame has no grids");
    }
    openvdb::initialize();
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        openvdb::GridPtrVec grids{frame.grids->surface, frame.grids->density};
        openvdb::io::File file(temporary.string());
        file.write(grids);
        file.close();
    });
}

void writeSurfaceMesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                      const std::string& format) {
    if (format == "obj") {
        writeMeshObj(path, mesh);
    } else if (format == "ply") {
        writeMeshPly(path, mesh);
    } else {
        throw IoError("cannot write " + path.string() + ": unknown mesh format '" + format + "'");
    }
}

}  // namespace globular
