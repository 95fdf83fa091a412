#pragma once
// A collider's solid in its own frame, ready to sample: the shape resolved from its name
// to an enum (no string compare per globule), the mesh of a mesh collider read and turned
// into a signed distance field once. The simulation, the surface stage (which cuts the
// colliders out of the liquid) and the renderer all sample the same solid.

#include <filesystem>
#include <memory>
#include <vector>

#include "collider.h"
#include "collider_motion.h"
#include "mesh.h"
#include "surface_sample.h"
#include "vec3.h"

namespace globular {

class MeshSdf;

enum class ColliderShape { Plane, Box, Sphere, Cylinder, Cup, Mesh };

class ColliderSolid {
public:
    /// An analytic shape from @p collider's geometry; for a mesh, reads the file (relative
    /// to @p sceneDir) and builds its distance field, exact to @p reach outside the solid.
    /// @throw SceneError naming the collider and the file (missing, unreadable, an open
    ///        mesh without thickness, ...).
    ColliderSolid(const ColliderSettings& collider, const std::filesystem::path& sceneDir,
                  double reach);

    /// phi and N at @p local (the collider's frame): the exact distance for the plane,
    /// box, sphere and cylinder; for the cup the larger of the outer cylinder's and the
    /// (negated) hollow's, exact but near the rim's edge; for a mesh, trilinear in its
    /// field. Where the normal is not unique, one of the candidates. Thread-safe.
    SurfaceSample sample(Vec3 local) const;

    ColliderShape shape() const { return mShape; }
    /// The solid's bounds in its frame (infinite for a plane and for a container).
    Vec3 boundsMin() const { return mBoundsMin; }
    Vec3 boundsMax() const { return mBoundsMax; }
    bool bounded() const;
    /// A mesh collider's triangles in its frame (scaled and moved by center); else empty.
    const TriangleMesh& mesh() const;
    std::size_t memoryBytes() const;

private:
    SurfaceSample sampleShape(Vec3 local) const;

    ColliderShape mShape;
    Vec3 mCenter, mSize, mNormal;
    double mRadius, mHeight, mThickness, mScale;
    bool mInside;
    Vec3 mBoundsMin, mBoundsMax;
    std::shared_ptr<const MeshSdf> mSdf;           ///< shared: solids are copied freely
    std::shared_ptr<const TriangleMesh> mMesh;
};

/// A solid where a frame puts it: world = pose.toWorld(local).
struct PlacedSolid {
    const ColliderSolid* solid = nullptr;
    Pose pose;

    /// phi and N at world point @p p.
    SurfaceSample sample(Vec3 p) const {
        const SurfaceSample s = solid->sample(pose.toLocal(p));
        return {s.phi, pose.rotate(s.normal)};
    }
};

/// The colliders of a scene as the later stages need them: their settings, the folder
/// their mesh files are relative to, and the globules' reach (ColliderSolid).
struct ColliderScene {
    std::vector<ColliderSettings> colliders;
    std::filesystem::path sceneDir;
    double reach = 2;

    /// Each collider's solid. @throw SceneError as ColliderSolid.
    std::vector<ColliderSolid> solids() const;
};

/// Reads a mesh collider's file and checks that it can become a solid (readable, with
/// triangles, closed unless it has a thickness) without building its field: what a scene
/// checks when it is read. @throw SceneError saying what is wrong with the file.
void checkColliderMesh(const ColliderSettings& collider, const std::filesystem::path& sceneDir);

/// The shape named @p name ("plane", ..., "mesh"). @throw Error for an unknown one.
ColliderShape colliderShapeNamed(const std::string& name);

}  // namespace globular
