#include "collider_mesh.h"

#include <cmath>
#include <numbers>

namespace globular {

namespace {

constexpr int kSegments = 48;      // around a circle
constexpr int kRings = 24;         // pole to pole on a sphere
constexpr double kPlaneSide = 20;  // world units

class MeshBuilder {
public:
    explicit MeshBuilder(const Pose& pose) : mPose(pose) {}

    uint32_t vertex(Vec3 local, Vec3 normal) {
        const Vec3 p = mPose.toWorld(local), n = mPose.rotate(normalized(normal));
        for (double c : {p.x, p.y, p.z}) mMesh.positions.push_back(float(c));
        for (double c : {n.x, n.y, n.z}) mMesh.normals.push_back(float(c));
        return uint32_t(mMesh.positions.size() / 3 - 1);
    }
    void triangle(uint32_t a, uint32_t b, uint32_t c) { mMesh.triangles.insert(mMesh.triangles.end(), {a, b, c}); }
    /// A flat quad a b c d, counter-clockwise seen from the side @p normal points to.
    void quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 normal) {
        const uint32_t i = vertex(a, normal), j = vertex(b, normal), k = vertex(c, normal),
                       l = vertex(d, normal);
        triangle(i, j, k);
        triangle(i, k, l);
    }
    /// The side of a cylinder of radius @p r from y0 to y1, facing out (or in).
    void tube(double r, double y0, double y1, bool facingOut) {
        for (int s = 0; s < kSegments; ++s) {
            const Vec3 a = around(s), b = around(s + 1);
            const Vec3 na = facingOut ? a : -1.0 * a, nb = facingOut ? b : -1.0 * b;
            const uint32_t i = vertex(r * a + Vec3{0, y0, 0}, na), j = vertex(r * b + Vec3{0, y0, 0}, nb),
                           k = vertex(r * b + Vec3{0, y1, 0}, nb), l = vertex(r * a + Vec3{0, y1, 0}, na);
            if (facingOut) {
                triangle(i, k, j);
                triangle(i, l, k);
            } else {
                triangle(i, j, k);
                triangle(i, k, l);
            }
        }
    }
    /// A ring (or disc, @p inner = 0) at height @p y between two radii, facing up or down.
    void ring(double inner, double outer, double y, bool up) {
        const Vec3 n{0, up ? 1.0 : -1.0, 0};
        for (int s = 0; s < kSegments; ++s) {
            const Vec3 a = around(s), b = around(s + 1);
            const Vec3 y0{0, y, 0};
            const uint32_t i = vertex(inner * a + y0, n), j = vertex(outer * a + y0, n),
                           k = vertex(outer * b + y0, n), l = vertex(inner * b + y0, n);
            if (up) {
                triangle(i, k, j);
                triangle(i, l, k);
            } else {
                triangle(i, j, k);
                triangle(i, k, l);
            }
        }
    }
    TriangleMesh take() { return std::move(mMesh); }

private:
    static Vec3 around(int s) {
        const double a = 2 * std::numbers::pi * s / kSegments;
        return {std::cos(a), 0, std::sin(a)};
    }
    Pose mPose;
    TriangleMesh mMesh;
};

void box(MeshBuilder& m, Vec3 c, Vec3 h) {
    for (int axis = 0; axis < 3; ++axis) {
        for (double side : {-1.0, 1.0}) {
            // u, v span the face so that u x v points along the outward normal.
            Vec3 n{0, 0, 0}, u{0, 0, 0}, v{0, 0, 0};
            if (axis == 0) n = {side, 0, 0}, u = {0, h.y, 0}, v = {0, 0, h.z};
            if (axis == 1) n = {0, side, 0}, u = {0, 0, h.z}, v = {h.x, 0, 0};
            if (axis == 2) n = {0, 0, side}, u = {h.x, 0, 0}, v = {0, h.y, 0};
            if (side < 0) u = -1.0 * u;
            const Vec3 f = c + Vec3{n.x * h.x, n.y * h.y, n.z * h.z};
            m.quad(f - u - v, f + u - v, f + u + v, f - u + v, n);
        }
    }
}

void sphere(MeshBuilder& m, Vec3 c, double r) {
    std::vector<uint32_t> previous;
    for (int ring = 0; ring <= kRings; ++ring) {
        const double polar = std::numbers::pi * ring / kRings;
        std::vector<uint32_t> current;
        for (int s = 0; s <= kSegments; ++s) {
            const double a = 2 * std::numbers::pi * s / kSegments;
            const Vec3 n{std::sin(polar) * std::cos(a), std::cos(polar), std::sin(polar) * std::sin(a)};
            current.push_back(m.vertex(c + r * n, n));
        }
        if (!previous.empty()) {
            for (int s = 0; s < kSegments; ++s) {
                m.triangle(previous[s], previous[s + 1], current[s + 1]);
                m.triangle(previous[s], current[s + 1], current[s]);
            }
        }
        previous = std::move(current);
    }
}

}  // namespace

TriangleMesh collidersMesh(const std::vector<ColliderSettings>& colliders,
                           const std::vector<ColliderSolid>& solids,
                           const std::vector<Pose>& poses) {
    TriangleMesh all;
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        const TriangleMesh one = colliderMesh(colliders[k], solids[k], poses[k]);
        const auto offset = uint32_t(all.vertexCount());
        all.positions.insert(all.positions.end(), one.positions.begin(), one.positions.end());
        all.normals.insert(all.normals.end(), one.normals.begin(), one.normals.end());
        for (uint32_t index : one.triangles) all.triangles.push_back(offset + index);
    }
    return all;
}

bool drawnSeeThrough(const ColliderSettings& c) {
    return c.inside || c.shape == "cup" || (c.shape == "mesh" && c.thickness > 0);
}

TriangleMesh colliderMesh(const ColliderSettings& c, const ColliderSolid& solid, const Pose& pose) {
    if (solid.shape() == ColliderShape::Mesh) {
        TriangleMesh mesh = solid.mesh();  // in the collider's frame: place it
        for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
            float* p = &mesh.positions[3 * v];
            float* n = &mesh.normals[3 * v];
            const Vec3 w = pose.toWorld({p[0], p[1], p[2]}), m = pose.rotate({n[0], n[1], n[2]});
            p[0] = float(w.x), p[1] = float(w.y), p[2] = float(w.z);
            n[0] = float(m.x), n[1] = float(m.y), n[2] = float(m.z);
        }
        return mesh;
    }
    const bool onBase = c.shape == "cylinder" || c.shape == "cup";
    // A cylinder or cup is built around the centre of its base, then placed there.
    Pose frame = pose;
    if (onBase) frame.translation = pose.toWorld(c.center);
    MeshBuilder m(frame);
    if (c.shape == "plane") {
        const Vec3 n = normalized(c.normal);
        const Vec3 u = normalized(cross(std::abs(n.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0}, n));
        const Vec3 v = cross(n, u);
        const double h = kPlaneSide / 2;
        m.quad(c.center - h * u - h * v, c.center + h * u - h * v, c.center + h * u + h * v,
               c.center - h * u + h * v, n);
    } else if (c.shape == "box") {
        box(m, c.center, 0.5 * c.size);
    } else if (c.shape == "sphere") {
        sphere(m, c.center, c.radius);
    } else {
        m.tube(c.radius, 0, c.height, true);
        m.ring(0, c.radius, 0, false);
        if (c.shape == "cylinder") {
            m.ring(0, c.radius, c.height, true);
        } else {  // cup: the rim, the inner wall and the inside of the bottom
            const double inner = c.radius - c.thickness;
            m.ring(inner, c.radius, c.height, true);
            m.tube(inner, c.thickness, c.height, false);
            m.ring(0, inner, c.thickness, true);
        }
    }
    return m.take();
}

}  // namespace globular
