#pragma once
// The OpenVDB steps of surfacing, one free function each, for surface_frame.cpp and the
// tests. THIS HEADER INCLUDES OPENVDB (about a minute of compile time per translation
// unit on two cores): include it only from surface/*.cpp files that need grids and from
// tests; everything else goes through the OpenVDB-free surface_frame.h.
//
//   globules --splatMetaballs--> field --fieldToLevelSet--> level set --applyFilters-->
//   --removeDroplets--> --subtractColliders (collider_cut.h)-->
//   level set "surface" --levelSetToFog--> fog "density"
//                       --meshLevelSet---> TriangleMesh
//   splatMetaballsWithMean --> means of vx vy vz (and temperature) --keepInside-->
//                              "vel" (velocityGrid) and "temperature"

#include <openvdb/openvdb.h>

#include <cstddef>
#include <filesystem>
#include <limits>
#include <vector>

#include "filter_chain.h"
#include "globule_bins.h"
#include "globules.h"
#include "mesh.h"
#include "metaball_kernel.h"

namespace globular {

/// What a frame's surface VDB holds.
struct SurfaceGrids {
    openvdb::FloatGrid::Ptr surface;  ///< narrow-band level set, class "level set"
    openvdb::FloatGrid::Ptr density;  ///< fog volume in [0, 1], class "fog volume"
    /// Kernel-weighted mean temperature of the globules inside the liquid (and a couple of
    /// voxels beyond its surface), background 0, class "unknown"; null when the globules
    /// carry no temperature.
    openvdb::FloatGrid::Ptr temperature;
    /// Kernel-weighted mean velocity of the globules in the level set's narrow band, out
    /// to two voxels beyond the surface (velocityInBand), background 0, class unknown,
    /// vector type contravariant relative (what Houdini and Blender read as a velocity);
    /// null only in files written before it existed.
    openvdb::Vec3SGrid::Ptr vel;
};

/// Reads the grids "surface", "density" and, when present, "temperature" and "vel" of a file
/// written by writeSurfaceVdb (or any VDB file with float grids of those names,
/// "surface" a level set). OpenVDB parses the file in a child process
/// (isolated_parse.h), so a damaged file is an error, never a crash.
/// @throw IoError naming @p path and what is wrong.
SurfaceGrids readSurfaceVdb(const std::filesystem::path& path);

/// The metaball field: the sum over globules of kernel(r^2 / R^2), R = influence * radius.
/// Only voxels within some globule's influence sphere are active (value > 0); the
/// background is 0. Parallel over leaves, each leaf gathering its globules in a fixed
/// order, so the result is bit-identical for any thread count.
/// @param voxelSize world units, > 0; the transform is linear with voxel centres at
///        integer multiples of it.
/// @param deepAbove with the default (infinity) every voxel holds its full sum. When
///        finite (the iso value), voxels farther than @p exactDepth voxels (Chebyshev) from
///        every voxel at or below it may hold partial sums (still above it): at the default
///        depth, those of leaves whose every voxel, and every voxel of their 26
///        neighbouring leaves, exceeds it. Deep inside a liquid that leaves out about half
///        the sum.
/// @param exactDepth 1 to 8 voxels (a leaf's width: whole leaves). The level set reads the
///        field within 2 voxels of the iso surface's outer side; its narrow band (and the
///        velocity kept there) reaches ceil(band width) + 1.
/// @throw SimulationError / ResourceError from GlobuleBins (non-finite or far globules).
openvdb::FloatGrid::Ptr splatMetaballs(const Globules& globules, const MetaballKernel& kernel,
                                       double influence, double voxelSize,
                                       double deepAbove = std::numeric_limits<double>::infinity(),
                                       int exactDepth = GlobuleBins::kBlockDim);

/// The field of splatMetaballs and, from the same kernel values in the same pass, the
/// kernel-weighted means of per-globule values: sum(w_i value_i) / sum(w_i) at every
/// active voxel of the field, 0 elsewhere. Where splatMetaballs leaves partial sums (see
/// @p deepAbove) the mean is over the nearer globules, still a weighted mean.
struct MeanSplat {
    openvdb::FloatGrid::Ptr field;               ///< as splatMetaballs, named "field"
    std::vector<openvdb::FloatGrid::Ptr> means;  ///< one per value array, named "mean"
};
/// @param values 1 to 4 arrays, each one value per globule (a velocity component, a
///        temperature).
/// @throw Error when an array is not one per globule; as splatMetaballs otherwise.
MeanSplat splatMetaballsWithMean(const Globules& globules,
                                 const std::vector<const std::vector<float>*>& values,
                                 const MetaballKernel& kernel, double influence,
                                 double voxelSize,
                                 double deepAbove = std::numeric_limits<double>::infinity(),
                                 int exactDepth = GlobuleBins::kBlockDim);
/// The same with the globules already binned (@p bins of @p globules at @p voxelSize), so a
/// frame bins its globules once for the splat and the mesh's vertex attributes.
MeanSplat splatMetaballsWithMean(const Globules& globules, const GlobuleBins& bins,
                                 const std::vector<const std::vector<float>*>& values,
                                 const MetaballKernel& kernel, double voxelSize,
                                 double deepAbove = std::numeric_limits<double>::infinity(),
                                 int exactDepth = GlobuleBins::kBlockDim);

/// Deactivates the voxels of @p grid where @p levelSet (same transform) is above
/// @p margin (world units), sets them to the background and prunes what is left empty:
/// @p grid is then defined inside the level set's surface and a margin beyond it.
void keepInside(openvdb::FloatGrid& grid, const openvdb::FloatGrid& levelSet, double margin);

/// The velocity in the level set's narrow band: the vector of three float grids of one
/// leaf layout (splatMetaballsWithMean's means of vx, vy, vz) at the voxels where
/// @p levelSet (same transform) is active and at most @p margin (world units) and the
/// means are active; nothing deeper inside or farther out. Built leaf by leaf in
/// parallel over the band's leaves. Named "vel", background 0, class unknown, vector type
/// VEC_CONTRAVARIANT_RELATIVE (a velocity: Houdini's and Blender's grids), saved as half
/// floats.
openvdb::Vec3SGrid::Ptr velocityInBand(const openvdb::FloatGrid& x, const openvdb::FloatGrid& y,
                                       const openvdb::FloatGrid& z,
                                       const openvdb::FloatGrid& levelSet, double margin);

/// The narrow-band level set (negative inside) of the field's @p isoValue surface,
/// computed directly from the field (band_distance.cpp): sub-voxel distances where the
/// field crosses the iso value, closest points carried outward layer by layer. Voxels
/// closer than @p bandWidth voxels to the surface are active; background
/// bandWidth * voxel size; named "surface", class level set. Bit-identical for any
/// thread count.
/// @param bandWidth half width of the band, voxels.
openvdb::FloatGrid::Ptr fieldToLevelSet(const openvdb::FloatGrid& field, double isoValue,
                                        double bandWidth);

/// The same level set via openvdb::tools::levelSetRebuild (mesh the iso surface, then
/// scan-convert the mesh): exact distances to the polygonised surface, 10-20 times
/// slower. The reference the tests check fieldToLevelSet against, and a benchmark mode.
openvdb::FloatGrid::Ptr rebuildLevelSet(const openvdb::FloatGrid& field, double isoValue,
                                        double bandWidth);

/// Applies @p chain in order (openvdb::tools::LevelSetFilter); amounts in voxels.
void applyFilters(openvdb::FloatGrid& levelSet, const std::vector<FilterStep>& chain);

/// Removes the disconnected pieces of @p levelSet that enclose less than @p minVolume
/// (world units^3).
/// @return the number of pieces removed.
std::size_t removeDroplets(openvdb::FloatGrid::Ptr& levelSet, double minVolume);

/// A fog volume of @p levelSet: 1 inside, 0 outside, a linear ramp across the inner half
/// of the narrow band (openvdb::tools::sdfToFogVolume); named "density".
openvdb::FloatGrid::Ptr levelSetToFog(const openvdb::FloatGrid& levelSet);

/// The zero crossing of @p levelSet as triangles (volumeToMesh quads split along their
/// shorter diagonal), wound outward, with unit normals from the level set's gradient.
/// @param adaptivity in [0, 1]: 0 uniform, higher merges polygons on flat parts.
TriangleMesh meshLevelSet(const openvdb::FloatGrid& levelSet, double adaptivity);

}  // namespace globular
