// Surfacing whole frames through the OpenVDB-free API: shapes, topology, filters,
// determinism. Grids themselves are checked in surface_vdb_test.cpp.
#include "surface_frame.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <random>

#include "errors.h"
#include "mesh_topology.h"

namespace globular {
namespace {

constexpr double kPi = 3.14159265358979323846;

Globules globulesAt(const std::vector<Vec3>& centres, float radius = 1.0f) {
    Globules g;
    for (std::size_t i = 0; i < centres.size(); ++i) {
        g.add(centres[i], {0, 0, 0}, radius, 1.0f, int32_t(i));
    }
    return g;
}

/// A lumpy blob of @p count globules, fixed seed.
Globules blob(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    std::vector<Vec3> centres;
    for (int i = 0; i < count; ++i) centres.push_back({u(rng), 0.6 * u(rng), u(rng)});
    return globulesAt(centres);
}

double meanDistance(const TriangleMesh& mesh, Vec3 centre) {
    double sum = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        sum += length(
            Vec3{mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]} -
            centre);
    }
    return sum / double(mesh.vertexCount());
}

TEST(SurfaceFrame, LoneGlobuleIsAClosedSphereAtTheKernelsIsoRadius) {
    const Vec3 centre{0.33, -0.21, 0.07};  // off the voxel lattice on purpose
    for (const char* kernel : {"wyvill", "blinn", "murakami"}) {
        SurfaceSettings s;
        s.kernel = kernel;
        s.voxelSize = 0.1;
        const double expected = s.loneSurfaceRadius(1.0);
        const SurfaceFrame frame = surfaceGlobules(globulesAt({centre}), s);
        const MeshTopology topo = analyzeMesh(frame.mesh);
        SCOPED_TRACE(kernel);
        EXPECT_TRUE(topo.watertight());
        EXPECT_EQ(topo.components, 1u);
        EXPECT_EQ(topo.eulerCharacteristic(frame.mesh.triangleCount()), 2);  // a sphere
        EXPECT_NEAR(meanDistance(frame.mesh, centre), expected, s.voxelSize);
        EXPECT_NEAR(topo.signedVolume, 4.0 / 3.0 * kPi * std::pow(expected, 3),
                    0.03 * 4.0 / 3.0 * kPi * std::pow(expected, 3));
    }
    // The defaults put the Wyvill surface exactly at the radius; in practice much closer
    // than a voxel.
    SurfaceSettings s;
    s.voxelSize = 0.1;
    const SurfaceFrame frame = surfaceGlobules(globulesAt({centre}), s);
    EXPECT_NEAR(meanDistance(frame.mesh, centre), 1.0, 0.2 * s.voxelSize);
}

TEST(SurfaceFrame, TwoGlobulesBridgeOnlyWhenCloserThanTheMergeDistance) {
    // Two Wyvill globules of radius 1 (R = 2) join when the field at the midpoint,
    // 2 C(q), reaches 0.5: C(q) = 1/4 at q = 0.44219, so at d = 2 R sqrt(q) = 2.65990.
    SurfaceSettings s;
    s.voxelSize = 0.1;
    const double merge = 2.0 * 2.0 * std::sqrt(0.4421915851);
    auto pieces = [&](double d) {
        const SurfaceFrame f = surfaceGlobules(globulesAt({{-d / 2, 0, 0}, {d / 2, 0, 0}}), s);
        const MeshTopology topo = analyzeMesh(f.mesh);
        EXPECT_TRUE(topo.watertight()) << d;
        return topo.components;
    };
    EXPECT_EQ(pieces(6.0), 2u);           // fields do not even overlap
    EXPECT_EQ(pieces(merge + 0.25), 2u);  // overlapping fields, still apart
    EXPECT_EQ(pieces(merge - 0.25), 1u);  // a bridge
    EXPECT_EQ(pieces(1.0), 1u);           // one blob

    // The bridge crosses the midplane: vertices lie on it, around the axis.
    const SurfaceFrame bridge =
        surfaceGlobules(globulesAt({{-(merge - 0.25) / 2, 0, 0}, {(merge - 0.25) / 2, 0, 0}}), s);
    int onMidplane = 0;
    for (std::size_t v = 0; v < bridge.mesh.vertexCount(); ++v) {
        if (std::abs(bridge.mesh.positions[3 * v]) < s.voxelSize) ++onMidplane;
    }
    EXPECT_GT(onMidplane, 8);
}

TEST(SurfaceFrame, BlobMeshIsManifoldWithOutwardNormals) {
    for (double adaptivity : {0.0, 0.01, 0.5}) {
        SurfaceSettings s;
        s.voxelSize = 0.1;
        s.adaptivity = adaptivity;
        const SurfaceFrame frame = surfaceGlobules(blob(40, 7), s);
        const MeshTopology topo = analyzeMesh(frame.mesh);
        SCOPED_TRACE(adaptivity);
        EXPECT_EQ(topo.nonManifoldEdges, 0u);
        EXPECT_EQ(topo.boundaryEdges, 0u);
        EXPECT_EQ(topo.misorientedEdges, 0u);
        EXPECT_EQ(topo.normalsAgainstWinding, 0u);
        EXPECT_GT(topo.signedVolume, 0.0);  // faces wound outward
        ASSERT_EQ(frame.mesh.normals.size(), frame.mesh.positions.size());
        for (std::size_t i = 0; i < frame.mesh.normals.size(); i += 3) {
            const float* n = &frame.mesh.normals[i];
            ASSERT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-5f);
        }
    }
}

// The pour's setting (scenes/bench/pour_1e5.toml): a slight adaptivity merges the flat
// parts' triangles but keeps the surface where the uniform mesh has it.
TEST(SurfaceFrame, SlightAdaptivityMergesFlatPartsAndKeepsTheVolume) {
    std::vector<Vec3> puddle;  // one layer of touching globules: a flat top and bottom
    for (int i = 0; i < 12; ++i) {
        for (int k = 0; k < 12; ++k) puddle.push_back({1.5 * i, 0, 1.5 * k});
    }
    SurfaceSettings s;
    s.voxelSize = 0.25;
    const SurfaceFrame uniform = surfaceGlobules(globulesAt(puddle), s);
    s.adaptivity = 0.01;
    const SurfaceFrame merged = surfaceGlobules(globulesAt(puddle), s);
    const MeshTopology a = analyzeMesh(uniform.mesh), b = analyzeMesh(merged.mesh);
    EXPECT_LT(merged.mesh.triangleCount(), uniform.mesh.triangleCount() * 3 / 4);
    EXPECT_EQ(b.boundaryEdges, 0u);
    EXPECT_EQ(b.nonManifoldEdges, 0u);
    EXPECT_NEAR(b.signedVolume, a.signedVolume, 0.01 * a.signedVolume);
    EXPECT_NEAR(b.area, a.area, 0.01 * a.area);
}

TEST(SurfaceFrame, DilateAndErodeMoveTheSurfaceByTheirVoxels) {
    const Vec3 centre{0.05, 0.05, 0.05};
    SurfaceSettings s;
    s.voxelSize = 0.1;
    const double plain = meanDistance(surfaceGlobules(globulesAt({centre}), s).mesh, centre);
    s.filters = "dilate:2";
    const double dilated = meanDistance(surfaceGlobules(globulesAt({centre}), s).mesh, centre);
    s.filters = "erode:3";
    const double eroded = meanDistance(surfaceGlobules(globulesAt({centre}), s).mesh, centre);
    EXPECT_NEAR(dilated - plain, 0.2, 0.03);
    EXPECT_NEAR(plain - eroded, 0.3, 0.03);
    // Smoothing a sphere hardly moves it, and the chain runs in order.
    s.filters = "gaussian:1, mean_curvature:2, laplacian:1, dilate:1, erode:1";
    const SurfaceFrame smoothed = surfaceGlobules(globulesAt({centre}), s);
    EXPECT_NEAR(meanDistance(smoothed.mesh, centre), plain, 0.05);
    EXPECT_TRUE(analyzeMesh(smoothed.mesh).watertight());
}

TEST(SurfaceFrame, DropletsBelowTheVolumeAreRemoved) {
    // A blob of three globules and, far away, a small lone droplet of radius 0.3.
    Globules g = globulesAt({{0, 0, 0}, {0.8, 0, 0}, {0, 0.8, 0}});
    g.add({6, 0, 0}, {0, 0, 0}, 0.3f, 1, 99);
    SurfaceSettings s;
    s.voxelSize = 0.075;  // 4 voxels across the droplet's radius
    EXPECT_EQ(analyzeMesh(surfaceGlobules(g, s).mesh).components, 2u);
    s.dropletVolume = 0.5;  // the droplet holds 4/3 pi 0.3^3 = 0.113
    const SurfaceFrame frame = surfaceGlobules(g, s);
    EXPECT_EQ(frame.dropletsRemoved, 1u);
    const MeshTopology topo = analyzeMesh(frame.mesh);
    EXPECT_EQ(topo.components, 1u);
    for (std::size_t v = 0; v < frame.mesh.vertexCount(); ++v) {
        ASSERT_LT(frame.mesh.positions[3 * v], 4.0f);
    }
}

TEST(SurfaceFrame, NonFiniteGlobuleIsRefusedByName) {
    Globules g = globulesAt({{0, 0, 0}});
    g.add({std::nan(""), 0, 0}, {0, 0, 0}, 1.0f, 1, 42);
    try {
        surfaceGlobules(g, SurfaceSettings{});
        FAIL() << "expected SimulationError";
    } catch (const SimulationError& e) {
        EXPECT_NE(std::string(e.what()).find("globule id 42"), std::string::npos) << e.what();
    }
}

TEST(SurfaceFrame, EmptyFrameGivesEmptyMesh) {
    const SurfaceFrame frame = surfaceGlobules(Globules{}, SurfaceSettings{});
    EXPECT_TRUE(frame.mesh.empty());
    EXPECT_EQ(frame.fieldLeaves, 0u);
}

TEST(SurfaceFrame, SameResultForOneAndTwoThreads) {
    SurfaceSettings s;
    s.voxelSize = 0.1;
    s.filters = "gaussian:1";
    const Globules g = blob(60, 3);
    SurfaceFrame one, two;
    tbb::task_arena(1).execute([&] { one = surfaceGlobules(g, s); });
    tbb::task_arena(2).execute([&] { two = surfaceGlobules(g, s); });
    ASSERT_GT(one.mesh.triangleCount(), 1000u);
    EXPECT_EQ(one.fieldLeaves, two.fieldLeaves);
    EXPECT_EQ(one.mesh.positions, two.mesh.positions);
    EXPECT_EQ(one.mesh.normals, two.mesh.normals);
    EXPECT_EQ(one.mesh.triangles, two.mesh.triangles);
}

}  // namespace
}  // namespace globular
