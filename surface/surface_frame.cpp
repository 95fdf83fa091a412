#include "surface_frame.h"

#include <openvdb/io/File.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>

#include "collider_cut.h"
#include "errors.h"
#include "surface_grids.h"
#include "vdb_archive.h"
#include "vertex_attributes.h"

namespace globular {

namespace {

/// How deep inside the iso surface (voxels) a frame reads the splat's exact sums: the
/// level set's narrow band and the velocity kept there, ceil(band width) + 1 (splatMetaballs).
/// Filters and the colliders' cut move the surface inwards, and the temperature is kept
/// throughout the inside: then whole leaves, as deep as a leaf of partial sums lies.
int exactDepth(const SurfaceSettings& settings, const std::vector<FilterStep>& filters,
               const std::vector<PlacedSolid>& colliders, const Globules& globules) {
    const bool surfaceMoves =
        !filters.empty() || (settings.subtractColliders && !colliders.empty());
    if (surfaceMoves || !globules.temperature.empty()) return GlobuleBins::kBlockDim;
    return std::min(GlobuleBins::kBlockDim, int(std::ceil(settings.bandWidth)) + 1);
}

}  // namespace

SurfaceFrame surfaceGlobules(const Globules& globules, const SurfaceSettings& settings,
                             const std::vector<PlacedSolid>& colliders, bool severalMaterials) {
    settings.validate();
    openvdb::initialize();

    SurfaceFrame frame;
    frame.voxelSize = resolveVoxelSize(settings, globules);
    const MetaballKernel kernel = settings.metaballKernel();
    openvdb::FloatGrid::Ptr levelSet, temperature;
    std::vector<openvdb::FloatGrid::Ptr> velocity;  // x, y, z
    const std::vector<FilterStep> filters = settings.filterChain();
    // Binned once, for the splat and the mesh's vertex attributes.
    const GlobuleBins bins(globules, frame.voxelSize, settings.influence);
    {
        // Deep inside the liquid the field's exact value is never read: partial sums there
        // (and the velocity and temperature there means over the nearer globules).
        std::vector<const std::vector<float>*> values{&globules.vx, &globules.vy, &globules.vz};
        if (!globules.temperature.empty()) values.push_back(&globules.temperature);
        const int depth = exactDepth(settings, filters, colliders, globules);
        MeanSplat splat = splatMetaballsWithMean(globules, bins, values, kernel, frame.voxelSize,
                                                 settings.isoValue, depth);
        openvdb::FloatGrid::Ptr field = splat.field;
        velocity.assign(splat.means.begin(), splat.means.begin() + 3);
        if (!globules.temperature.empty()) temperature = splat.means[3];
        frame.fieldLeaves = field->tree().leafCount();
        levelSet = fieldToLevelSet(*field, settings.isoValue, settings.bandWidth);
    }  // the field is the largest grid: free it before the level-set steps
    applyFilters(*levelSet, filters);
    frame.dropletsRemoved = removeDroplets(levelSet, settings.dropletVolume);
    // After the filters, which would round the cut's edges off the walls.
    if (settings.subtractColliders && !colliders.empty()) subtractColliders(*levelSet, colliders);

    // The level set stays full floats on disk (its background is band_width voxels
    // exactly, which readers compare against); the fog, velocity and temperature are
    // saved as half floats (half the bytes, within what they are read for).
    auto grids = std::make_shared<SurfaceGrids>();
    grids->surface = levelSet;
    // The fog volume, the velocity, the temperature and the mesh only read the level set:
    // build them side by side.
    tbb::parallel_invoke(
        [&] { grids->density = levelSetToFog(*levelSet); },
        [&] {
            // In the narrow band, out to two voxels beyond the surface, so that a
            // renderer's trilinear lookup at the surface blurs motion with the liquid's
            // velocity; deeper inside nothing reads it (the fog is 1 there).
            grids->vel = velocityInBand(*velocity[0], *velocity[1], *velocity[2], *levelSet,
                                        2.0 * frame.voxelSize);
            velocity.clear();
        },
        [&] {
            if (!temperature) return;
            // Two voxels beyond the surface: trilinear lookups at the surface then read no
            // background.
            keepInside(*temperature, *levelSet, 2.0 * frame.voxelSize);
            temperature->setName("temperature");
            temperature->setGridClass(openvdb::GRID_UNKNOWN);
            // Half floats: rounded to 2^-11 of the value (0.125 degrees below 512).
            temperature->setSaveFloatAsHalf(true);
            grids->temperature = temperature;
        },
        [&] {
            frame.mesh = meshLevelSet(*levelSet, settings.adaptivity);
            carryGlobuleAttributes(frame.mesh, globules, bins, kernel, frame.voxelSize,
                                   attributesOf(globules, severalMaterials));
        });

    // Provenance for whoever opens the file in a DCC tool.
    for (const openvdb::GridBase::Ptr& grid : {openvdb::GridBase::Ptr(grids->surface),
                                              openvdb::GridBase::Ptr(grids->density),
                                              openvdb::GridBase::Ptr(grids->temperature),
                                              openvdb::GridBase::Ptr(grids->vel)}) {
        if (!grid) continue;
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
    openvdb::GridCPtrVec grids{frame.grids->surface, frame.grids->density};
    if (frame.grids->vel) grids.push_back(frame.grids->vel);
    if (frame.grids->temperature) grids.push_back(frame.grids->temperature);
    writeVdbFile(path, grids);
}

namespace {

/// Surface files larger than this are refused before they are read.
constexpr uint64_t kMaxSurfaceFileBytes = uint64_t(16) << 30;

openvdb::FloatGrid::Ptr floatGridNamed(const openvdb::GridPtrVec& grids, const std::string& name) {
    for (const auto& grid : grids) {
        if (grid && grid->getName() == name) {
            auto floatGrid = openvdb::gridPtrCast<openvdb::FloatGrid>(grid);
            if (!floatGrid) {
                throw std::runtime_error("grid '" + name + "' is a " + grid->type() +
                                         ", not a float grid");
            }
            return floatGrid;
        }
    }
    throw std::runtime_error("no grid named '" + name + "'");
}

/// The grid named @p name of type @p GridT, or null when there is none.
/// @throw std::runtime_error when it has another type.
template <typename GridT>
typename GridT::Ptr optionalGrid(const openvdb::GridPtrVec& grids, const std::string& name) {
    for (const auto& grid : grids) {
        if (grid && grid->getName() == name) {
            auto typed = openvdb::gridPtrCast<GridT>(grid);
            if (!typed) {
                throw std::runtime_error("grid '" + name + "' is a " + grid->type() +
                                         ", not a " + GridT::gridType());
            }
            return typed;
        }
    }
    return nullptr;
}

/// Runs in the reader's child process: OpenVDB parses the file there, and what it read
/// goes back to the parent in OpenVDB's own streamed encoding.
std::string parseSurfaceFile(const std::filesystem::path& path) {
    // Here too: the reader helper may have been forked before this program's first read.
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open(/*delayLoad=*/false);
    openvdb::GridPtrVec grids;
    for (const char* name : {"surface", "density"}) {
        if (!file.hasGrid(name)) throw std::runtime_error(std::string("no grid named '") + name + "'");
        grids.push_back(file.readGrid(name));
    }
    if (file.hasGrid("temperature")) grids.push_back(file.readGrid("temperature"));
    if (file.hasGrid("vel")) grids.push_back(file.readGrid("vel"));
    file.close();
    const auto surface = floatGridNamed(grids, "surface");
    if (surface->getGridClass() != openvdb::GRID_LEVEL_SET) {
        throw std::runtime_error("grid 'surface' is not a level set");
    }
    floatGridNamed(grids, "density");
    optionalGrid<openvdb::FloatGrid>(grids, "temperature");
    optionalGrid<openvdb::Vec3SGrid>(grids, "vel");
    return encodeVdb(openvdb::GridCPtrVec(grids.begin(), grids.end()), openvdb::MetaMap(),
                     /*seekable=*/false);
}

}  // namespace

SurfaceGrids readSurfaceVdb(const std::filesystem::path& path) {
    openvdb::initialize();
    const std::string answer =
        parseVdbInChild(path, kMaxSurfaceFileBytes, parseSurfaceFile);
    try {
        const auto grids = decodeStreamedVdb(answer);
        SurfaceGrids read;
        read.surface = floatGridNamed(*grids, "surface");
        read.density = floatGridNamed(*grids, "density");
        read.temperature = optionalGrid<openvdb::FloatGrid>(*grids, "temperature");
        read.vel = optionalGrid<openvdb::Vec3SGrid>(*grids, "vel");
        return read;
    } catch (const std::exception& e) {
        throw IoError("cannot read " + path.string() + ": " + e.what());
    }
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
