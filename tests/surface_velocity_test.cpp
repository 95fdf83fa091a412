// Velocity out of the surface stage: the "vel" grid (a kernel-weighted mean of the
// globules' velocities, splatted with the field) and the mesh's vx vy vz, checked
// against the same mean summed here directly from the kernel.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "mesh.h"
#include "surface_frame.h"
#include "surface_grids.h"
#include "vertex_attributes.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

SurfaceSettings coarse() {
    SurfaceSettings s;
    s.voxelsPerRadius = 3;
    return s;
}

/// A lattice block of globules of radius 1, spacing 1.1, all moving with @p v.
Globules movingBlock(Vec3 v, int side) {
    Globules g;
    for (int x = 0; x < side; ++x) {
        for (int y = 0; y < side; ++y) {
            for (int z = 0; z < side; ++z) {
                g.add({1.1 * x, 1.1 * y, 1.1 * z}, v, 1.0f, 1.0f, int32_t(g.size()));
            }
        }
    }
    return g;
}

/// sum(w v) / sum(w) at world point @p p, w = kernel(r^2 / R^2), R = influence * radius:
/// the definition, summed over every globule.
Vec3 weightedMean(const Globules& g, const SurfaceSettings& s, Vec3 p) {
    const MetaballKernel kernel = s.metaballKernel();
    double sum = 0;
    Vec3 weighted{0, 0, 0};
    for (std::size_t i = 0; i < g.size(); ++i) {
        const Vec3 d = g.position(i) - p;
        const double r = s.influence * g.radius[i];
        const double w = kernel.value(float((d.x * d.x + d.y * d.y + d.z * d.z) / (r * r)));
        sum += w;
        weighted = weighted + g.velocity(i) * w;
    }
    return weighted * (1.0 / sum);
}

const std::vector<float>& valuesOf(const TriangleMesh& mesh, const char* name) {
    const VertexAttribute* a = mesh.attribute(name);
    if (!a) throw std::runtime_error(std::string("no attribute ") + name);
    return a->values;
}

TEST(SurfaceVelocity, BlockMovingTogetherHasItsVelocityEverywhere) {
    const Vec3 v{1.5, -2.0, 0.25};
    const Globules g = movingBlock(v, 4);
    const SurfaceFrame frame = surfaceGlobules(g, coarse());
    ASSERT_TRUE(frame.grids->vel);
    const openvdb::Vec3SGrid& vel = *frame.grids->vel;
    EXPECT_EQ(vel.getName(), "vel");
    EXPECT_EQ(vel.getVectorType(), openvdb::VEC_CONTRAVARIANT_RELATIVE);
    EXPECT_EQ(vel.getGridClass(), openvdb::GRID_UNKNOWN);
    EXPECT_EQ(vel.background(), openvdb::Vec3s(0.0f));
    EXPECT_GT(vel.activeVoxelCount(), 1000u);
    for (auto it = vel.cbeginValueOn(); it; ++it) {
        ASSERT_NEAR((*it)[0], 1.5f, 1e-5f) << it.getCoord();
        ASSERT_NEAR((*it)[1], -2.0f, 1e-5f) << it.getCoord();
        ASSERT_NEAR((*it)[2], 0.25f, 1e-5f) << it.getCoord();
    }
    // Defined in the level set's narrow band out to two voxels beyond the surface: at
    // every band voxel there and nowhere else, so not deep inside (the block's centre,
    // 8 voxels in, where nothing reads it) nor far outside.
    const openvdb::FloatGrid& levelSet = *frame.grids->surface;
    auto band = levelSet.getConstAccessor();
    auto acc = vel.getConstAccessor();
    const float margin = float(2.0 * frame.voxelSize);
    for (auto it = vel.cbeginValueOn(); it; ++it) {
        ASSERT_TRUE(band.isValueOn(it.getCoord())) << it.getCoord();
        ASSERT_LE(band.getValue(it.getCoord()), margin) << it.getCoord();
    }
    std::size_t inBand = 0;
    for (auto it = levelSet.cbeginValueOn(); it; ++it) {
        if (*it > margin) continue;
        ++inBand;
        ASSERT_TRUE(acc.isValueOn(it.getCoord())) << it.getCoord();
    }
    EXPECT_EQ(inBand, vel.activeVoxelCount());
    const int centre = int(std::lround(1.65 / frame.voxelSize));
    EXPECT_LT(band.getValue(openvdb::Coord(centre, centre, centre)), -margin);
    EXPECT_FALSE(acc.isValueOn(openvdb::Coord(centre, centre, centre)));
    EXPECT_FALSE(acc.isValueOn(openvdb::Coord(-int(std::ceil(3.0 / frame.voxelSize)), 0, 0)));

    const auto& vx = valuesOf(frame.mesh, "vx");
    const auto& vy = valuesOf(frame.mesh, "vy");
    const auto& vz = valuesOf(frame.mesh, "vz");
    ASSERT_EQ(vx.size(), frame.mesh.vertexCount());
    for (std::size_t i = 0; i < vx.size(); ++i) {
        ASSERT_NEAR(vx[i], 1.5f, 1e-5f);
        ASSERT_NEAR(vy[i], -2.0f, 1e-5f);
        ASSERT_NEAR(vz[i], 0.25f, 1e-5f);
    }
}

TEST(SurfaceVelocity, TwoVelocitiesGiveTheKernelWeightedMean) {
    Globules g;
    g.add({-0.6, 0, 0}, {2, 0, 0}, 1.0f, 1.0f, 0);
    g.add({0.7, 0.2, 0}, {0, 1, -1}, 1.3f, 1.0f, 1);
    const SurfaceSettings s = coarse();
    const SurfaceFrame frame = surfaceGlobules(g, s);
    ASSERT_TRUE(frame.grids->vel);
    const openvdb::Vec3SGrid& vel = *frame.grids->vel;
    std::size_t mixed = 0;
    for (auto it = vel.cbeginValueOn(); it; ++it) {
        const openvdb::Vec3d p = vel.indexToWorld(it.getCoord());
        const Vec3 expected = weightedMean(g, s, {p.x(), p.y(), p.z()});
        ASSERT_NEAR((*it)[0], expected.x, 1e-4) << it.getCoord();
        ASSERT_NEAR((*it)[1], expected.y, 1e-4) << it.getCoord();
        ASSERT_NEAR((*it)[2], expected.z, 1e-4) << it.getCoord();
        // Where both globules reach, neither velocity alone.
        mixed += expected.x > 0.1 && expected.x < 1.9;
    }
    EXPECT_GT(mixed, 100u);
    // Between the centres the weights are comparable: a true mix, not a pick. (The grid
    // holds the narrow band: the first voxel of it straight above the point between them.)
    auto acc = vel.getConstAccessor();
    int z = 0;
    while (z < 20 && !acc.isValueOn(openvdb::Coord(0, 0, z))) ++z;
    ASSERT_LT(z, 20);
    const openvdb::Vec3s middle = acc.getValue(openvdb::Coord(0, 0, z));
    EXPECT_GT(middle[0], 0.3f);
    EXPECT_LT(middle[0], 1.7f);

    const auto& vx = valuesOf(frame.mesh, "vx");
    const auto& vy = valuesOf(frame.mesh, "vy");
    const auto& vz = valuesOf(frame.mesh, "vz");
    ASSERT_GT(frame.mesh.vertexCount(), 100u);
    for (std::size_t i = 0; i < frame.mesh.vertexCount(); ++i) {
        const Vec3 p{frame.mesh.positions[3 * i], frame.mesh.positions[3 * i + 1],
                     frame.mesh.positions[3 * i + 2]};
        const Vec3 expected = weightedMean(g, s, p);
        ASSERT_NEAR(vx[i], expected.x, 1e-4) << i;
        ASSERT_NEAR(vy[i], expected.y, 1e-4) << i;
        ASSERT_NEAR(vz[i], expected.z, 1e-4) << i;
    }
}

/// The file stores "vel" as half floats: 11 significant bits, so a value read back is
/// within 2^-11 of its magnitude of the value written (round to nearest).
constexpr float kHalfRelative = 1.0f / 2048.0f;

TEST(SurfaceVelocity, VelGridTravelsAsHalfFloatsWithinTheirPrecision) {
    Globules g;
    g.add({-0.6, 0, 0}, {2.1, 0.03, -7.7}, 1.0f, 1.0f, 0);
    g.add({0.7, 0.2, 0}, {0.01, 1.3, -1.9}, 1.3f, 1.0f, 1);
    const SurfaceFrame frame = surfaceGlobules(g, coarse());
    ASSERT_TRUE(frame.grids->vel);
    EXPECT_TRUE(frame.grids->vel->saveFloatAsHalf());
    const fs::path path = fs::path(testing::TempDir()) /
                          ("surface_velocity_half_" + std::to_string(::getpid()) + ".vdb");
    writeSurfaceVdb(path, frame);
    const SurfaceGrids back = readSurfaceVdb(path);
    fs::remove(path);
    ASSERT_TRUE(back.vel);
    ASSERT_EQ(back.vel->activeVoxelCount(), frame.grids->vel->activeVoxelCount());
    auto written = frame.grids->vel->getConstAccessor();
    std::size_t rounded = 0;
    for (auto it = back.vel->cbeginValueOn(); it; ++it) {
        ASSERT_TRUE(written.isValueOn(it.getCoord()));
        const openvdb::Vec3s w = written.getValue(it.getCoord());
        for (int a = 0; a < 3; ++a) {
            // Half floats below 2^-14 are subnormal: a fixed step of 2^-24 there.
            ASSERT_NEAR((*it)[a], w[a], std::abs(w[a]) * kHalfRelative + 6e-8f)
                << it.getCoord() << " axis " << a;
            rounded += (*it)[a] != w[a];
        }
    }
    EXPECT_GT(rounded, 0u);  // really stored as half floats, not full ones
}

TEST(SurfaceVelocity, VelGridAndMeshVelocityTravelInTheFiles) {
    const Vec3 v{0.0, 3.0, -1.0};
    const Globules g = movingBlock(v, 3);
    const SurfaceFrame frame = surfaceGlobules(g, coarse());
    const fs::path dir = fs::path(testing::TempDir()) /
                         ("surface_velocity_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    writeSurfaceVdb(dir / "surface.vdb", frame);
    writeSurfaceMesh(dir / "surface.ply", frame.mesh, "ply");
    const SurfaceGrids back = readSurfaceVdb(dir / "surface.vdb");
    const TriangleMesh mesh = readMeshPly(dir / "surface.ply");
    fs::remove_all(dir);

    EXPECT_EQ(back.surface->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_EQ(back.density->getGridClass(), openvdb::GRID_FOG_VOLUME);
    ASSERT_TRUE(back.vel);
    EXPECT_EQ(back.vel->getName(), "vel");
    EXPECT_EQ(back.vel->getVectorType(), openvdb::VEC_CONTRAVARIANT_RELATIVE);
    EXPECT_EQ(back.vel->activeVoxelCount(), frame.grids->vel->activeVoxelCount());
    for (auto it = back.vel->cbeginValueOn(); it; ++it) {  // half floats in the file
        ASSERT_NEAR((*it)[0], 0.0f, 1e-5f);
        ASSERT_NEAR((*it)[1], 3.0f, 3.0f * kHalfRelative);
        ASSERT_NEAR((*it)[2], -1.0f, 1.0f * kHalfRelative);
    }
    ASSERT_EQ(mesh.vertexCount(), frame.mesh.vertexCount());
    EXPECT_EQ(valuesOf(mesh, "vy"), valuesOf(frame.mesh, "vy"));
    for (float y : valuesOf(mesh, "vy")) ASSERT_NEAR(y, 3.0f, 1e-5f);
}

// Vertices placed by hand, not by the mesher: within one block, some reached by one
// globule only, some by both, one by neither (but near one). Each gets the kernel-weighted
// mean of exactly those that reach it (the block's candidates are filtered by the block's
// box first, which must drop none that reaches a vertex), and the unreached one its
// nearest globule's velocity.
TEST(SurfaceVelocity, HandPlacedVerticesGetTheGlobulesThatReachThem) {
    Globules g;
    g.add({0, 0, 0}, {1, 0, 0}, 1.0f, 1.0f, 0);    // reaches 2 units
    g.add({3.5, 0, 0}, {0, 4, 0}, 1.0f, 1.0f, 1);  // reaches 1.5 to 5.5 on the x axis
    g.add({-9, 0, 0}, {0, 0, 8}, 0.5f, 1.0f, 2);   // reaches -10 to -8: none of the vertices
    const SurfaceSettings s = coarse();
    const MetaballKernel kernel = s.metaballKernel();
    TriangleMesh mesh;
    const std::vector<float> xs = {0.5f, 1.0f, 1.75f, 3.0f, -2.5f};
    for (float x : xs) mesh.positions.insert(mesh.positions.end(), {x, 0.1f, 0.0f});
    CarriedAttributes which;
    which.velocity = true;
    carryGlobuleAttributes(mesh, g, kernel, s.influence, 0.35, which);
    const auto& vx = valuesOf(mesh, "vx");
    const auto& vy = valuesOf(mesh, "vy");
    const auto& vz = valuesOf(mesh, "vz");
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
        const Vec3 expected = weightedMean(g, s, {xs[i], 0.1, 0.0});
        EXPECT_NEAR(vx[i], expected.x, 1e-5) << xs[i];
        EXPECT_NEAR(vy[i], expected.y, 1e-5) << xs[i];
        EXPECT_NEAR(vz[i], expected.z, 1e-5) << xs[i];
    }
    EXPECT_FLOAT_EQ(vx[0], 1.0f);                     // the first globule's alone
    EXPECT_GT(vx[2], 0.05f);                          // both reach 1.75
    EXPECT_GT(vy[2], 0.05f);
    EXPECT_FLOAT_EQ(vy[3], 4.0f);                     // the second's alone
    // -2.5 is 2.5 from the first globule and 6.5 from the third: none reaches it, and the
    // nearest of its block's candidates (the globules binned within one block) is the first.
    EXPECT_FLOAT_EQ(vx[4], 1.0f);
    EXPECT_FLOAT_EQ(vz[4], 0.0f);
}

}  // namespace
}  // namespace globular
