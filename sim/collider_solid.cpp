#include "collider_solid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "errors.h"
#include "mesh_sdf.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// A capped cylinder of radius @p r from y = @p y0 to @p y1 around the y axis through the
/// origin of @p local: signed distance and outward normal (the exact SDF of the solid).
SurfaceSample cylinderSample(Vec3 local, double r, double y0, double y1) {
    const double radial = std::hypot(local.x, local.z);
    const Vec3 outward = radial > 0 ? Vec3{local.x / radial, 0, local.z / radial} : Vec3{1, 0, 0};
    const double dRadial = radial - r;
    const double mid = 0.5 * (y0 + y1), half = 0.5 * (y1 - y0);
    const double dAxial = std::abs(local.y - mid) - half;
    const Vec3 axial{0, local.y >= mid ? 1.0 : -1.0, 0};
    if (dRadial > 0 && dAxial > 0) {  // beyond a rim: the nearest point is on its circle
        const double d = std::hypot(dRadial, dAxial);
        return {d, normalized(dRadial * outward + dAxial * axial)};
    }
    if (dRadial > dAxial) return {dRadial, outward};
    return {dAxial, axial};
}

SurfaceSample boxSample(Vec3 local, Vec3 half) {
    const double q[3] = {std::abs(local.x) - half.x, std::abs(local.y) - half.y,
                         std::abs(local.z) - half.z};
    const double sign[3] = {local.x >= 0 ? 1.0 : -1.0, local.y >= 0 ? 1.0 : -1.0,
                            local.z >= 0 ? 1.0 : -1.0};
    const double outside[3] = {std::max(q[0], 0.0), std::max(q[1], 0.0), std::max(q[2], 0.0)};
    const double outsideLength = std::sqrt(outside[0] * outside[0] + outside[1] * outside[1] +
                                           outside[2] * outside[2]);
    if (outsideLength > 0) {
        return {outsideLength, Vec3{outside[0] * sign[0], outside[1] * sign[1],
                                    outside[2] * sign[2]} *
                                   (1.0 / outsideLength)};
    }
    const int a = q[0] >= q[1] && q[0] >= q[2] ? 0 : (q[1] >= q[2] ? 1 : 2);
    Vec3 normal{0, 0, 0};
    (a == 0 ? normal.x : a == 1 ? normal.y : normal.z) = sign[a];
    return {q[a], normal};
}

SurfaceSample flipped(SurfaceSample s) { return {-s.phi, -1.0 * s.normal}; }

fs::path meshPathOf(const ColliderSettings& c, const fs::path& sceneDir) {
    return fs::path(c.file).is_absolute() ? fs::path(c.file) : sceneDir / c.file;
}

/// The mesh of @p c in the collider's frame: the file's coordinates scaled, then moved.
TriangleMesh readColliderMesh(const ColliderSettings& c, const fs::path& sceneDir) {
    TriangleMesh mesh;
    try {
        mesh = readMeshFile(meshPathOf(c, sceneDir));
    } catch (const std::exception& e) {
        throw SceneError(e.what());
    }
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        float* p = &mesh.positions[3 * v];
        p[0] = float(p[0] * c.scale + c.center.x);
        p[1] = float(p[1] * c.scale + c.center.y);
        p[2] = float(p[2] * c.scale + c.center.z);
    }
    return mesh;
}

}  // namespace

void checkColliderMesh(const ColliderSettings& c, const fs::path& sceneDir) {
    const TriangleMesh mesh = readColliderMesh(c, sceneDir);
    const std::string path = meshPathOf(c, sceneDir).string();
    if (mesh.empty()) throw SceneError("mesh " + path + " has no triangles");
    if (c.thickness == 0 && !isClosedMesh(mesh)) {
        throw SceneError("mesh " + path +
                         " is not closed (some edge lies on one triangle only): give the "
                         "collider a thickness (a shell around the surface), or close the mesh");
    }
}

ColliderShape colliderShapeNamed(const std::string& name) {
    if (name == "plane") return ColliderShape::Plane;
    if (name == "box") return ColliderShape::Box;
    if (name == "sphere") return ColliderShape::Sphere;
    if (name == "cylinder") return ColliderShape::Cylinder;
    if (name == "cup") return ColliderShape::Cup;
    if (name == "mesh") return ColliderShape::Mesh;
    throw Error("unknown collider shape '" + quoteForMessage(name, 40) + "'");
}

ColliderSolid::ColliderSolid(const ColliderSettings& c, const fs::path& sceneDir, double reach)
    : mShape(colliderShapeNamed(c.shape)),
      mCenter(c.center),
      mSize(c.size),
      mNormal(normalized(c.normal)),
      mRadius(c.radius),
      mHeight(c.height),
      mThickness(c.thickness),
      mScale(c.scale),
      mInside(c.inside) {
    const Vec3 r{mRadius, mRadius, mRadius};
    switch (mShape) {
        case ColliderShape::Plane:
            mBoundsMin = {-kInfinity, -kInfinity, -kInfinity};
            mBoundsMax = {kInfinity, kInfinity, kInfinity};
            break;
        case ColliderShape::Box:
            mBoundsMin = mCenter - 0.5 * mSize;
            mBoundsMax = mCenter + 0.5 * mSize;
            break;
        case ColliderShape::Sphere:
            mBoundsMin = mCenter - r;
            mBoundsMax = mCenter + r;
            break;
        case ColliderShape::Cylinder:
        case ColliderShape::Cup:
            mBoundsMin = mCenter - Vec3{mRadius, 0, mRadius};
            mBoundsMax = mCenter + Vec3{mRadius, mHeight, mRadius};
            break;
        case ColliderShape::Mesh: {
            auto mesh = std::make_shared<TriangleMesh>(readColliderMesh(c, sceneDir));
            Vec3 lo{kInfinity, kInfinity, kInfinity}, hi = -1.0 * lo;
            for (std::size_t v = 0; v < mesh->vertexCount(); ++v) {
                const float* p = &mesh->positions[3 * v];
                lo = {std::min(lo.x, double(p[0])), std::min(lo.y, double(p[1])),
                      std::min(lo.z, double(p[2]))};
                hi = {std::max(hi.x, double(p[0])), std::max(hi.y, double(p[1])),
                      std::max(hi.z, double(p[2]))};
            }
            const Vec3 extent = hi - lo;
            const double longest = std::max({extent.x, extent.y, extent.z, 0.0});
            // Automatic: 1/100 of the mesh, but no finer than the field's reach needs (a
            // band of 64 voxels), and a shell two voxels thick at least (mesh_sdf.h).
            double voxel = std::max(longest / 100, reach / 64);
            if (c.thickness > 0) voxel = std::min(voxel, c.thickness / 2);
            if (c.voxelSize > 0) voxel = c.voxelSize;
            try {
                mSdf = std::make_shared<MeshSdf>(*mesh, voxel, c.thickness, reach,
                                                 meshPathOf(c, sceneDir).string());
            } catch (const SceneError& e) {
                throw SceneError("[[collider]] '" + c.name + "': " + e.what());
            }
            mBoundsMin = mSdf->boundsMin();
            mBoundsMax = mSdf->boundsMax();
            mMesh = std::move(mesh);
            break;
        }
    }
    if (mInside) {
        mBoundsMin = {-kInfinity, -kInfinity, -kInfinity};
        mBoundsMax = {kInfinity, kInfinity, kInfinity};
    }
}

bool ColliderSolid::bounded() const {
    return std::isfinite(mBoundsMin.x) && std::isfinite(mBoundsMax.x);
}

const TriangleMesh& ColliderSolid::mesh() const {
    static const TriangleMesh kEmpty;
    return mMesh ? *mMesh : kEmpty;
}

std::size_t ColliderSolid::memoryBytes() const {
    std::size_t bytes = sizeof *this;
    if (mSdf) bytes += mSdf->memoryBytes();
    if (mMesh) bytes += 4 * (mMesh->positions.size() + mMesh->normals.size() + mMesh->triangles.size());
    return bytes;
}

SurfaceSample ColliderSolid::sampleShape(Vec3 p) const {
    const Vec3 local = p - mCenter;
    switch (mShape) {
        case ColliderShape::Plane:
            return {dot(local, mNormal), mNormal};
        case ColliderShape::Sphere: {
            const double d = length(local);
            return {d - mRadius, d > 0 ? local * (1.0 / d) : Vec3{0, 1, 0}};
        }
        case ColliderShape::Box:
            return boxSample(local, 0.5 * mSize);
        case ColliderShape::Cylinder:
            return cylinderSample(local, mRadius, 0, mHeight);
        case ColliderShape::Cup: {  // the outer cylinder minus the hollow, open at the top
            const SurfaceSample outer = cylinderSample(local, mRadius, 0, mHeight);
            const SurfaceSample hollow = cylinderSample(local, mRadius - mThickness, mThickness,
                                                        mHeight + mRadius + 1);
            // The solid is outer AND NOT hollow: max(phi_outer, -phi_hollow).
            return outer.phi >= -hollow.phi ? outer : flipped(hollow);
        }
        case ColliderShape::Mesh:
            return mSdf->sample(p);  // the mesh is already in the collider's frame
    }
    return {};
}

std::vector<ColliderSolid> ColliderScene::solids() const {
    std::vector<ColliderSolid> solids;
    for (const ColliderSettings& c : colliders) solids.emplace_back(c, sceneDir, reach);
    return solids;
}

SurfaceSample ColliderSolid::sample(Vec3 local) const {
    const SurfaceSample s = sampleShape(local);
    return mInside ? flipped(s) : s;
}

}  // namespace globular
