#pragma once
// A triangle mesh as a collider's solid: an OpenVDB signed distance field built once from
// the mesh and sampled (trilinear) per globule per step.
//   thickness 0   the solid is the inside of a closed mesh; the grid fills the whole
//                 inside, so phi and N are right deep inside too
//                 (openvdb::tools::meshToVolume, interior band to infinity)
//   thickness t   the solid is a shell t thick around the surface: unsigned distance
//                 minus t/2, for open meshes (a bowl) or closed ones
// Outside the solid phi is exact up to `reach` (plus two voxels); beyond that it is the
// grid's background, a constant >= reach.
// OpenVDB headers stay inside mesh_sdf.cpp: this header is cheap to include.

#include <cstddef>
#include <memory>
#include <string>

#include "mesh.h"
#include "surface_sample.h"
#include "vec3.h"

namespace globular {

/// Whether every edge of @p mesh is shared by exactly two triangles (a closed, watertight
/// surface). Vertices at the same position count as one (exporters split vertices along
/// seams and sharp edges); triangles with a repeated vertex index are ignored.
bool isClosedMesh(const TriangleMesh& mesh);

/// The signed distance field of a mesh collider's solid, in mesh coordinates.
/// Immutable after construction; sample() is thread-safe.
class MeshSdf {
  public:
    /// @brief Builds the field: a one-off cost, on two cores about 1.5 s for a closed
    /// mesh 100 voxels across (its inside is filled), 0.15 s for bowl.obj's shell at 50
    /// voxels across; grows with the voxel count (voxelSize^-3 for a closed mesh).
    /// @param mesh       triangles in mesh coordinates, world units
    /// @param voxelSize  grid spacing, world units (> 0). phi is within about half a voxel
    ///                   of the exact distance (trilinear interpolation; sharp edges and the
    ///                   middle of a shell are where it is worst).
    /// @param thickness  0: @p mesh must be closed; the solid is its inside. > 0: the solid
    ///                   is a shell of this total thickness around the surface, world units;
    ///                   at least two voxels (a thinner shell could leak).
    /// @param reach      how far outside the solid phi must be exact, world units (>= 0):
    ///                   the contact reach, e.g. the largest globule radius. The exterior
    ///                   band covers reach + 2 voxels.
    /// @param name       how messages name the mesh (its file path).
    /// @throw SceneError naming @p name: an empty mesh, a vertex index out of range, a
    ///        non-finite vertex, a mesh without area, an open mesh with thickness 0, a
    ///        voxel size, thickness or reach that is not finite or out of range, a grid
    ///        that would exceed kMaxVoxels voxels in its bounding box, or a mesh more than
    ///        1e9 voxels from its origin.
    MeshSdf(const TriangleMesh& mesh, double voxelSize, double thickness, double reach,
            const std::string& name);
    ~MeshSdf();
    MeshSdf(MeshSdf&&) noexcept;
    MeshSdf& operator=(MeshSdf&&) noexcept;
    MeshSdf(const MeshSdf&) = delete;
    MeshSdf& operator=(const MeshSdf&) = delete;

    /// Largest grid the constructor builds, in voxels of the solid's padded bounding box
    /// (about 1.1 GB of floats if all of them were stored).
    static constexpr double kMaxVoxels = 2e8;

    /// @brief phi and N at @p local (mesh coordinates, world units).
    /// phi is the trilinear interpolation of the grid; N the normalised gradient of the
    /// same trilinear cell (exact for a plane; continuous across a cell's faces only up
    /// to O(voxel) for curved surfaces). Where phi > reach (beyond the contact reach)
    /// N is not computed and is (0, 1, 0); far outside phi is the background, a constant
    /// >= reach. Thread-safe: no shared mutable state.
    SurfaceSample sample(Vec3 local) const;

    /// The solid's bounding box in mesh coordinates: the mesh's, grown by thickness / 2.
    Vec3 boundsMin() const { return mBoundsMin; }
    Vec3 boundsMax() const { return mBoundsMax; }
    double voxelSize() const { return mVoxelSize; }
    /// The value of phi far outside the solid (>= reach), world units.
    double background() const;
    /// The grid's memory, bytes.
    std::size_t memoryBytes() const;

  private:
    struct Grid;  // the distance field as sample() reads it (mesh_sdf.cpp)
    std::unique_ptr<Grid> mGrid;
    double mVoxelSize = 0;  // world units
    Vec3 mBoundsMin, mBoundsMax;
};

}  // namespace globular
