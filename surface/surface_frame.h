#pragma once
// Surfacing one frame as a pure function: globules + settings -> grids + mesh. OpenVDB-free:
// the grids are behind an opaque pointer (their type is in surface_grids.h, which
// includes OpenVDB), so the CLI and the render stage can call this cheaply.
// \see splashsurf (Löschner et al.): surfacing as a pure function, exporters apart.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <vector>

#include "collider_solid.h"
#include "globules.h"
#include "mesh.h"
#include "surface_settings.h"

namespace globular {

struct SurfaceGrids;  // surface_grids.h: the OpenVDB level set and fog volume

struct SurfaceFrame {
    /// "surface" level set, "density" fog, "vel" velocity and, when the globules carry
    /// one, "temperature"
    std::shared_ptr<SurfaceGrids> grids;
    /// The level set's zero crossing; per-vertex velocity (vx vy vz), and temperature
    /// and material when the globules carry them (vertex_attributes.h)
    TriangleMesh mesh;
    double voxelSize = 0;                 ///< world units, as resolved for this frame
    std::size_t fieldLeaves = 0;          ///< 8^3-voxel leaves the metaball field used
    std::size_t dropletsRemoved = 0;      ///< pieces below droplet_volume
};

/// Splats, makes the level set, filters, removes droplets, cuts out the colliders, makes
/// the fog volume, the velocity grid (and the temperature grid) and meshes. Uses TBB inside (limit threads with a tbb::task_arena); the
/// result does not depend on the thread count.
/// @param colliders the solids where the frame puts them; with settings.subtractColliders
///        each is cut out of the liquid (collider_cut.h), so the surface never shows
///        through a wall. The solids must outlive the call.
/// @throw SceneError when @p settings are invalid; SimulationError for a non-finite
///        globule or collider pose; ResourceError for a globule beyond the grid's
///        coordinate range.
/// @param severalMaterials the scene has several: the mesh carries `material` on every
///        frame (vertex_attributes.h).
SurfaceFrame surfaceGlobules(const Globules& globules, const SurfaceSettings& settings,
                             const std::vector<PlacedSolid>& colliders = {},
                             bool severalMaterials = false);

/// Writes the grids "surface", "density", "vel" and (when made) "temperature" of @p frame to one
/// VDB file, atomically.
/// @throw IoError naming @p path.
void writeSurfaceVdb(const std::filesystem::path& path, const SurfaceFrame& frame);

/// Writes the mesh as @p format ("ply" or "obj"), atomically.
/// @throw IoError naming @p path.
void writeSurfaceMesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                      const std::string& format);

}  // namespace globular
