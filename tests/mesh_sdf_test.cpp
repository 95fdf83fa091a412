// Mesh colliders' distance fields (sim/mesh_sdf.h): a triangulated sphere and a cube
// against their exact signed distances, an open sheet as a shell, closedness, and the
// errors a bad mesh or grid gets.

#include "mesh_sdf.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "errors.h"

using namespace globular;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A unit icosphere: the icosahedron with each triangle split in four @p levels times,
/// the new vertices pushed onto the sphere. Counter-clockwise seen from outside.
TriangleMesh icosphere(int levels, double radius = 1) {
    const double t = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                           {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                           {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3& p : v) p = normalized(p);
    std::vector<uint32_t> f = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> middle;
        const auto mid = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto it = middle.find(key);
            if (it != middle.end()) return it->second;
            v.push_back(normalized(v[a] + v[b]));
            return middle[key] = uint32_t(v.size() - 1);
        };
        std::vector<uint32_t> g;
        for (std::size_t i = 0; i < f.size(); i += 3) {
            const uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
            const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            g.insert(g.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        f = std::move(g);
    }
    TriangleMesh mesh;
    for (const Vec3& p : v) {
        mesh.positions.insert(mesh.positions.end(),
                              {float(radius * p.x), float(radius * p.y), float(radius * p.z)});
    }
    mesh.triangles = std::move(f);
    return mesh;
}

/// A cube of edge 1 around the origin, 24 vertices (4 per face, as exporters write
/// meshes with per-face normals) so closedness must weld them.
TriangleMesh cube() {
    TriangleMesh mesh;
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign : {-1, 1}) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            const uint32_t first = uint32_t(mesh.vertexCount());
            for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
                float p[3];
                p[axis] = 0.5f * sign;
                p[u] = 0.5f * a;
                p[w] = 0.5f * b * sign;  // mirrored on the negative face: still outward
                mesh.positions.insert(mesh.positions.end(), {p[0], p[1], p[2]});
            }
            mesh.triangles.insert(mesh.triangles.end(),
                                  {first, first + 1, first + 2, first, first + 2, first + 3});
        }
    }
    return mesh;
}

double boxDistance(Vec3 p, double half) {
    const Vec3 q{std::abs(p.x) - half, std::abs(p.y) - half, std::abs(p.z) - half};
    const Vec3 outside{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
    return length(outside) + std::min(std::max({q.x, q.y, q.z}), 0.0);
}

/// A flat square sheet of edge 2 in the plane y = 0, open.
TriangleMesh sheet() {
    TriangleMesh mesh;
    mesh.positions = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    mesh.triangles = {0, 2, 1, 0, 3, 2};
    return mesh;
}

double degreesBetween(Vec3 a, Vec3 b) {
    return std::acos(std::clamp(dot(normalized(a), normalized(b)), -1.0, 1.0)) * 180 / kPi;
}

void expectSceneError(const std::function<void()>& make, const std::string& part) {
    try {
        make();
        ADD_FAILURE() << "no SceneError, expected one containing: " << part;
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("bowl.obj"), std::string::npos) << e.what();
    }
}

}  // namespace

TEST(MeshSdf, SphereMatchesTheExactDistanceInsideNearAndOutside) {
    const double h = 0.05, reach = 0.2;
    const MeshSdf sdf(icosphere(5), h, 0, reach, "sphere.obj");
    EXPECT_EQ(sdf.voxelSize(), h);
    EXPECT_NEAR(sdf.boundsMin().x, -1, 1e-6);
    EXPECT_NEAR(sdf.boundsMax().y, 1, 1e-6);
    EXPECT_GE(sdf.background(), reach);

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    int checked = 0;
    double worstPhi = 0, worstNear = 0, worstAngle = 0;
    while (checked < 5000) {
        const Vec3 p{1.2 * unit(rng), 1.2 * unit(rng), 1.2 * unit(rng)};
        const double r = length(p);
        // Near the centre (the medial point, a cone) trilinear interpolation rounds the
        // tip by up to 0.87 voxel: any grid does.
        if (r < 2 * h || r - 1 > reach) continue;
        ++checked;
        const SurfaceSample s = sdf.sample(p);
        worstPhi = std::max(worstPhi, std::abs(s.phi - (r - 1)));
        EXPECT_NEAR(s.phi, r - 1, 0.5 * h) << p.x << " " << p.y << " " << p.z;
        // Where contacts are (and the field is smooth), much closer.
        if (std::abs(r - 1) < 2 * h) {
            worstNear = std::max(worstNear, std::abs(s.phi - (r - 1)));
            EXPECT_NEAR(s.phi, r - 1, 0.05 * h) << p.x << " " << p.y << " " << p.z;
        }
        // The gradient of a trilinear cell turns by up to about h / (2 r) radians from
        // the exact one (the field's curvature is 1 / r); the mesh's facets add a little.
        // Where phi > reach, N is not computed.
        if (r - 1 < reach - h) {
            const double allowed = 1.5 + h / r * 180 / kPi;
            worstAngle = std::max(worstAngle, degreesBetween(s.normal, p) / allowed);
            EXPECT_LT(degreesBetween(s.normal, p), allowed) << p.x << " " << p.y << " " << p.z;
        }
        EXPECT_NEAR(length(s.normal), 1, 1e-9);
    }
    std::cout << "sphere: worst |phi error| " << worstPhi / h << " voxel (" << worstNear / h
              << " near the surface), worst normal error " << worstAngle
              << " of the allowed angle\n";
    // Deep inside: the whole inside is filled.
    EXPECT_NEAR(sdf.sample({0.3, -0.2, 0.1}).phi, length({0.3, -0.2, 0.1}) - 1, 0.5 * h);
    // Far outside: the background, at least the reach.
    EXPECT_GE(sdf.sample({3, 0, 0}).phi, reach);
    EXPECT_GE(sdf.sample({0, 1e9, 0}).phi, reach);
    EXPECT_GE(sdf.sample({0, 1 + reach + 0.05, 0}).phi, reach);
}

TEST(MeshSdf, CubeMatchesTheBoxDistance) {
    const double h = 0.04, reach = 0.25;
    const MeshSdf sdf(cube(), h, 0, reach, "cube.obj");
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> coord(-0.5 - reach, 0.5 + reach);
    int checked = 0;
    double worst = 0;
    while (checked < 5000) {
        const Vec3 p{coord(rng), coord(rng), coord(rng)};
        const double exact = boxDistance(p, 0.5);
        if (exact > reach) continue;
        ++checked;
        const SurfaceSample s = sdf.sample(p);
        worst = std::max(worst, std::abs(s.phi - exact));
        EXPECT_NEAR(s.phi, exact, 0.5 * h) << p.x << " " << p.y << " " << p.z;
    }
    std::cout << "cube: worst |phi error| " << worst / h << " voxel\n";
    // On a face's middle the normal is the face's.
    EXPECT_LT(degreesBetween(sdf.sample({0.51, 0.1, -0.2}).normal, {1, 0, 0}), 0.1);
    EXPECT_LT(degreesBetween(sdf.sample({0.1, -0.45, 0.2}).normal, {0, -1, 0}), 0.1);
}

TEST(MeshSdf, SamplesAlikeFromParallelLoops) {
    const MeshSdf sdf(icosphere(3), 0.05, 0, 0.1, "sphere.obj");
    std::vector<Vec3> points;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> coord(-1.3, 1.3);
    for (int i = 0; i < 20000; ++i) points.push_back({coord(rng), coord(rng), coord(rng)});
    std::vector<SurfaceSample> parallel(points.size());
    tbb::parallel_for(std::size_t(0), points.size(),
                      [&](std::size_t i) { parallel[i] = sdf.sample(points[i]); });
    for (std::size_t i = 0; i < points.size(); ++i) {
        const SurfaceSample s = sdf.sample(points[i]);
        ASSERT_EQ(s.phi, parallel[i].phi);
        ASSERT_EQ(s.normal, parallel[i].normal);
    }
}

TEST(IsClosedMesh, SphereAndWeldedCubeAreClosedAndLoseItWithATriangle) {
    TriangleMesh sphere = icosphere(2);
    EXPECT_TRUE(isClosedMesh(sphere));
    EXPECT_TRUE(isClosedMesh(cube()));
    sphere.triangles.resize(sphere.triangles.size() - 3);
    EXPECT_FALSE(isClosedMesh(sphere));
    EXPECT_FALSE(isClosedMesh(sheet()));
    // A fin: a third triangle on an edge of a closed mesh.
    TriangleMesh fin = icosphere(1);
    fin.positions.insert(fin.positions.end(), {5, 5, 5});
    fin.triangles.insert(fin.triangles.end(),
                         {fin.triangles[0], fin.triangles[1], uint32_t(fin.vertexCount() - 1)});
    EXPECT_FALSE(isClosedMesh(fin));
}

TEST(MeshSdf, OpenMeshNeedsAThicknessAndThenIsAShell) {
    TriangleMesh open = icosphere(3);
    open.triangles.resize(open.triangles.size() - 3);
    expectSceneError([&] { MeshSdf(open, 0.05, 0, 0.1, "bowl.obj"); },
                     "is not closed (3 edges lie on one triangle only): give the collider a "
                     "thickness");

    const double h = 0.025, thickness = 0.2, reach = 0.15;
    const MeshSdf shell(sheet(), h, thickness, reach, "sheet.obj");
    EXPECT_NEAR(shell.boundsMin().y, -0.1, 1e-9);
    EXPECT_NEAR(shell.boundsMax().y, 0.1, 1e-9);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> inside(-0.9, 0.9);
    for (int i = 0; i < 1000; ++i) {
        const double x = inside(rng), z = inside(rng);
        // On the sheet: half the thickness deep (the kink of |d| is where trilinear
        // interpolation is worst, up to half a voxel).
        EXPECT_NEAR(shell.sample({x, 0, z}).phi, -thickness / 2, 0.5 * h) << x << " " << z;
        // Above and below it, the distance to the shell's faces and their normals.
        const double y = 0.8 * reach * inside(rng);
        const SurfaceSample s = shell.sample({x, y, z});
        EXPECT_NEAR(s.phi, std::abs(y) - thickness / 2, 0.01 * h) << x << " " << y << " " << z;
        if (std::abs(y) > h) {
            EXPECT_LT(degreesBetween(s.normal, {0, y, 0}), 0.1) << x << " " << y << " " << z;
        }
    }
    // Past the rim, the distance to the rounded edge of the shell.
    EXPECT_NEAR(shell.sample({1.15, 0, 0}).phi, 0.15 - thickness / 2, 0.5 * h);
    EXPECT_GE(shell.sample({0, 2, 0}).phi, reach);
    EXPECT_GT(shell.memoryBytes(), 0u);
}

TEST(MeshSdf, BowlFileIsAnOpenCapThatWorksAsAShell) {
    const std::filesystem::path path =
        std::filesystem::path(GLOBULAR_SOURCE_DIR) / "scenes/effectors/bowl.obj";
    const TriangleMesh bowl = readMeshFile(path);
    EXPECT_FALSE(isClosedMesh(bowl));                      // the rim is open
    const double h = 0.024, thickness = 0.1, reach = 0.1;  // h: 1/100 of its width
    const MeshSdf shell(bowl, h, thickness, reach, path.string());
    EXPECT_NEAR(shell.boundsMin().y, -thickness / 2, 1e-6);       // the pole, at the origin
    EXPECT_NEAR(shell.boundsMax().y, 0.9 + thickness / 2, 1e-4);  // the rim
    EXPECT_NEAR(shell.boundsMax().x, std::sqrt(1.2 * 1.2 - 0.3 * 0.3) + thickness / 2, 1e-3);
    // Against the sphere the cap is cut from (radius 1.2 around (0, 1.2, 0)): its facets
    // lie up to 0.003 inside it.
    const Vec3 center{0, 1.2, 0};
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(-1, 1), offset(-0.12, 0.12);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 d = normalized({unit(rng), -std::abs(unit(rng)) - 0.5, unit(rng)});
        const Vec3 p = center + (1.2 + offset(rng)) * d;
        const double exact = std::abs(length(p - center) - 1.2) - thickness / 2;
        const SurfaceSample s = shell.sample(p);
        EXPECT_NEAR(s.phi, exact, 0.004 + (exact < -thickness / 4 ? 0.5 * h : 0.05 * h))
            << p.x << " " << p.y << " " << p.z;
        if (exact > 0.5 * h && exact < reach) {
            // Out of the bowl's inner or outer face; its facets (edges about 0.15 long)
            // turn up to about 4 degrees from the sphere's radius.
            const Vec3 out = length(p - center) < 1.2 ? center - p : p - center;
            EXPECT_LT(degreesBetween(s.normal, out), 5.0) << p.x << " " << p.y << " " << p.z;
        }
    }
}

TEST(MeshSdf, BadMeshesAndGridsAreSceneErrors) {
    expectSceneError([] { MeshSdf(TriangleMesh{}, 0.05, 0, 0.1, "bowl.obj"); }, "has no triangles");
    TriangleMesh nan = cube();
    nan.positions[4] = std::numeric_limits<float>::quiet_NaN();
    expectSceneError([&] { MeshSdf(nan, 0.05, 0, 0.1, "bowl.obj"); }, "vertex 2 is not finite");
    TriangleMesh inf = cube();
    inf.positions[0] = std::numeric_limits<float>::infinity();
    expectSceneError([&] { MeshSdf(inf, 0.05, 0, 0.1, "bowl.obj"); }, "vertex 1 is not finite");
    TriangleMesh badIndex = cube();
    badIndex.triangles[5] = 24;
    expectSceneError([&] { MeshSdf(badIndex, 0.05, 0, 0.1, "bowl.obj"); }, "names vertex 24 of 24");
    TriangleMesh flat = sheet();
    for (std::size_t i = 0; i < flat.positions.size(); i += 3) flat.positions[i] = 0;
    expectSceneError([&] { MeshSdf(flat, 0.05, 0.2, 0.1, "bowl.obj"); }, "has no area");
    expectSceneError([] { MeshSdf(cube(), 0, 0, 0.1, "bowl.obj"); }, "voxel_size 0");
    expectSceneError([] { MeshSdf(cube(), 0.05, -1, 0.1, "bowl.obj"); }, "thickness -1");
    expectSceneError([] { MeshSdf(cube(), 0.05, 0.06, 0.1, "bowl.obj"); }, "less than two voxels");
    expectSceneError([] { MeshSdf(cube(), 1e-4, 0, 0.1, "bowl.obj"); }, "give a larger voxel_size");
    TriangleMesh far = cube();
    for (std::size_t i = 0; i < far.positions.size(); i += 3) far.positions[i] += 1e7f;
    expectSceneError([&] { MeshSdf(far, 0.005, 0, 0.1, "bowl.obj"); }, "give a larger voxel_size");
}
