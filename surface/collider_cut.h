#pragma once
// Cutting the colliders out of the liquid: liquid = liquid minus solid (a CSG difference of
// level sets), so the surface never shows through a wall. Globule centres stop at a wall,
// but the blobby surface reaches a globule's radius or more beyond them; cutting the solid
// out puts that part of the surface on the wall instead.
//
// THIS HEADER INCLUDES OPENVDB (about a minute of compile time per translation unit on two
// cores): include it only from surface/*.cpp files that need grids and from tests, like
// surface_grids.h. OpenVDB-free callers go through surfaceGlobules (surface_frame.h).

#include <openvdb/openvdb.h>

#include <vector>

#include "collider_solid.h"

namespace globular {

/// The narrow-band level set of @p solid (negative inside it) on the voxels of @p like
/// (its transform and background), over @p region (index space), leaf-aligned: the region
/// is widened to whole 8^3 leaves. Voxels closer to the solid's surface than the
/// background are active with phi (world units); those deeper inside are inactive at
/// -background, whole leaves deep inside as inactive tiles of -background, everything
/// else the +background. Where @p like is an outside tile (no liquid) nothing is built.
/// Parallel over leaves (TBB); the grid is identical for any thread count.
/// Blocks are classified by phi at their centre, which needs phi to be 1-Lipschitz (true
/// of the analytic shapes and of a mesh's distance field).
/// @param like a level set (background > 0, uniform voxels).
openvdb::FloatGrid::Ptr solidLevelSet(const PlacedSolid& solid, const openvdb::FloatGrid& like,
                                      const openvdb::CoordBBox& region);

/// Subtracts every solid of @p solids from @p levelSet (openvdb::tools::csgDifference of
/// each solidLevelSet over the liquid's active bounds grown by its band, clipped to the
/// solid's bounds when it has any). Correct for deep cuts too: a wall through the liquid's
/// interior, not only through its narrow band. The result is a pruned level set with the
/// same transform and background. Identical for any thread count.
/// @param levelSet a narrow-band level set (background > 0), negative inside the liquid.
void subtractColliders(openvdb::FloatGrid& levelSet, const std::vector<PlacedSolid>& solids);

}  // namespace globular
