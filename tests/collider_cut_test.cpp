// Cutting colliders out of the liquid (surface/collider_cut.h): a solid's level set against
// its exact phi, and whole frames cut by a box, a thin slab through the interior, a plane,
// a container and a rotated box; determinism across thread counts.
#include "collider_cut.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "errors.h"
#include "grid_compare.h"
#include "mesh_topology.h"
#include "surface_frame.h"
#include "surface_grids.h"

namespace globular {
namespace {

constexpr double kVoxel = 0.1;  // world units, every frame here

Globules globulesAt(const std::vector<Vec3>& centres, float radius = 1.0f) {
    Globules g;
    for (std::size_t i = 0; i < centres.size(); ++i) {
        g.add(centres[i], {0, 0, 0}, radius, 1.0f, int32_t(i));
    }
    return g;
}

/// A @p n^3 block of globules of radius 1, @p spacing apart, centred on the origin.
Globules blockOfGlobules(int n, double spacing = 1.0) {
    std::vector<Vec3> centres;
    const double offset = 0.5 * (n - 1) * spacing;
    for (int x = 0; x < n; ++x) {
        for (int y = 0; y < n; ++y) {
            for (int z = 0; z < n; ++z) {
                centres.push_back(
                    {x * spacing - offset, y * spacing - offset, z * spacing - offset});
            }
        }
    }
    return globulesAt(centres);
}

ColliderSettings box(Vec3 center, Vec3 size, bool inside = false) {
    ColliderSettings c;
    c.shape = "box";
    c.center = center;
    c.size = size;
    c.inside = inside;
    return c;
}

ColliderSettings plane(Vec3 center, Vec3 normal) {
    ColliderSettings c;
    c.shape = "plane";
    c.center = center;
    c.normal = normal;
    return c;
}

/// A pose turning by @p degrees about z, then moving by @p translation.
Pose turnedAboutZ(double degrees, Vec3 translation) {
    const double a = degrees * 3.14159265358979323846 / 180;
    Pose pose;
    pose.rotation[0][0] = std::cos(a), pose.rotation[0][1] = -std::sin(a);
    pose.rotation[1][0] = std::sin(a), pose.rotation[1][1] = std::cos(a);
    pose.translation = translation;
    return pose;
}

SurfaceSettings settings(bool subtract = true) {
    SurfaceSettings s;
    s.voxelSize = kVoxel;
    s.subtractColliders = subtract;
    return s;
}

Vec3 vertex(const TriangleMesh& mesh, std::size_t v) {
    return {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
}

/// Vertices of @p mesh deeper inside @p solid than half a voxel.
std::size_t verticesInside(const TriangleMesh& mesh, const PlacedSolid& solid) {
    std::size_t inside = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        if (solid.sample(vertex(mesh, v)).phi < -0.5 * kVoxel) ++inside;
    }
    return inside;
}

/// The level set's value at the voxel nearest @p world.
float levelSetAt(const SurfaceFrame& frame, Vec3 world) {
    const auto& grid = *frame.grids->surface;
    const auto ijk = grid.transform().worldToIndexNodeCentered({world.x, world.y, world.z});
    return grid.tree().getValue(ijk);
}

void expectSameFrame(const SurfaceFrame& a, const SurfaceFrame& b) {
    EXPECT_EQ(a.mesh.positions, b.mesh.positions);
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
    expectSameGrid(*a.grids->surface, *b.grids->surface);
}

TEST(ColliderCut, SolidLevelSetIsPhiInTheBandAndTheBackgroundBeyond) {
    openvdb::initialize();
    // A liquid that is inside everywhere, so no block is skipped for want of liquid.
    const float background = float(3 * kVoxel);
    openvdb::FloatGrid like(background);
    like.setTransform(openvdb::math::Transform::createLinearTransform(kVoxel));
    like.setGridClass(openvdb::GRID_LEVEL_SET);
    const openvdb::CoordBBox region({-40, -40, -40}, {39, 39, 39});
    like.tree().fill(region, -background, false);

    const ColliderSolid solid(box({0.1, 0, 0}, {5, 3, 2.6}), {}, 0);
    const PlacedSolid placed{&solid, turnedAboutZ(30, {0.05, -0.2, 0.3})};
    const auto grid = solidLevelSet(placed, like, region);
    EXPECT_EQ(grid->background(), background);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);

    auto acc = grid->getConstAccessor();
    std::size_t wrong = 0, band = 0, deep = 0;
    for (auto it = region.begin(); it; ++it) {
        const auto w = grid->transform().indexToWorld(*it);
        const double phi = placed.sample({w.x(), w.y(), w.z()}).phi;
        const float expected = float(std::clamp(phi, -double(background), double(background)));
        const bool inBand = std::abs(phi) < background;
        if (std::abs(acc.getValue(*it) - expected) > 1e-6f || acc.isValueOn(*it) != inBand) {
            ++wrong;
        }
        band += inBand;
        deep += phi <= -background;
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(band, 1000u);
    EXPECT_GT(deep, 1000u);
    // Leaves deep inside the solid are tiles of -background, not leaves; every other tile
    // is the +background outside.
    std::size_t insideTiles = 0, otherTiles = 0;
    for (auto it = grid->cbeginValueOff(); it; ++it) {
        if (!it.isTileValue()) continue;
        if (*it == -background && it.getLevel() == 1) {
            ++insideTiles;
        } else if (*it != background) {
            ++otherTiles;
        }
    }
    EXPECT_GT(insideTiles, 0u);
    EXPECT_EQ(otherTiles, 0u);
}

TEST(ColliderCut, BoxInTheLiquidLeavesNoVertexInsideIt) {
    const Globules blob = blockOfGlobules(3);  // surface about 2.3 from the centre
    // A box from the blob's middle out through its +x face.
    const ColliderSolid solid(box({1.5, 0, 0}, {3, 1.5, 1.5}), {}, 0);
    for (const Pose& pose : {Pose{}, turnedAboutZ(25, {0, 0.3, 0.1})}) {
        const std::vector<PlacedSolid> colliders{{&solid, pose}};
        const PlacedSolid& placed = colliders[0];
        const SurfaceFrame cut = surfaceGlobules(blob, settings(), colliders);
        const SurfaceFrame whole = surfaceGlobules(blob, settings(false), colliders);

        EXPECT_GT(verticesInside(whole.mesh, placed), 100u);  // the surface shows through
        EXPECT_EQ(verticesInside(cut.mesh, placed), 0u);
        // Deep inside the box (7.5 voxels from its walls), where the liquid was.
        const Vec3 deep = pose.toWorld({1.5, 0, 0});
        EXPECT_LT(levelSetAt(whole, deep), 0.0f);
        EXPECT_GT(levelSetAt(cut, deep), 0.0f);
        // Outside the box the liquid is untouched.
        const Vec3 away = pose.toWorld({-1, 0, 0});
        EXPECT_EQ(levelSetAt(cut, away), levelSetAt(whole, away));

        const MeshTopology topo = analyzeMesh(cut.mesh);
        EXPECT_TRUE(topo.watertight());
        EXPECT_EQ(topo.components, 1u);
        EXPECT_LT(topo.signedVolume, analyzeMesh(whole.mesh).signedVolume);
        // The cut face lies on the box: vertices on its wall, not only in front of it.
        std::size_t onWall = 0;
        for (std::size_t v = 0; v < cut.mesh.vertexCount(); ++v) {
            if (std::abs(placed.sample(vertex(cut.mesh, v)).phi) < 0.5 * kVoxel) ++onWall;
        }
        EXPECT_GT(onWall, 100u);
    }
}

TEST(ColliderCut, ThinSlabThroughTheInteriorSplitsTheLiquid) {
    // A 7^3 block: its interior is tiles of the level set, far from the narrow band.
    const Globules blob = blockOfGlobules(7);
    const ColliderSolid slab(box({0.05, 0, 0}, {0.4, 20, 20}), {}, 0);  // 4 voxels thick
    const std::vector<PlacedSolid> colliders{{&slab, Pose{}}};
    const SurfaceFrame cut = surfaceGlobules(blob, settings(), colliders);
    const SurfaceFrame whole = surfaceGlobules(blob, settings(false), colliders);

    EXPECT_EQ(analyzeMesh(whole.mesh).components, 1u);
    EXPECT_GT(verticesInside(whole.mesh, colliders[0]), 100u);
    const MeshTopology topo = analyzeMesh(cut.mesh);
    EXPECT_TRUE(topo.watertight());
    EXPECT_EQ(topo.components, 2u);
    EXPECT_EQ(verticesInside(cut.mesh, colliders[0]), 0u);
    std::size_t left = 0, right = 0;
    for (std::size_t v = 0; v < cut.mesh.vertexCount(); ++v) {
        (vertex(cut.mesh, v).x < 0.05 ? left : right) += 1;
    }
    EXPECT_GT(left, 1000u);
    EXPECT_GT(right, 1000u);
    // The slab's middle, deep in the liquid's interior, is outside the liquid now; a
    // voxel beside the slab is inside it still.
    EXPECT_LT(levelSetAt(whole, {0.05, 0, 0}), 0.0f);
    EXPECT_GT(levelSetAt(cut, {0.05, 0, 0}), 0.0f);
    EXPECT_LT(levelSetAt(cut, {1.0, 0, 0}), 0.0f);
    EXPECT_LT(levelSetAt(cut, {-1.0, 0, 0}), 0.0f);
}

TEST(ColliderCut, PlaneCutsEverythingBelowIt) {
    const Globules blob = blockOfGlobules(3);
    const ColliderSolid ground(plane({0, 0.3, 0}, {0, 1, 0}), {}, 0);  // solid below y = 0.3
    const std::vector<PlacedSolid> colliders{{&ground, Pose{}}};
    const SurfaceFrame cut = surfaceGlobules(blob, settings(), colliders);
    const SurfaceFrame whole = surfaceGlobules(blob, settings(false), colliders);

    EXPECT_GT(verticesInside(whole.mesh, colliders[0]), 1000u);
    ASSERT_GT(cut.mesh.vertexCount(), 0u);
    double lowest = 1e9, highest = -1e9;
    for (std::size_t v = 0; v < cut.mesh.vertexCount(); ++v) {
        lowest = std::min(lowest, vertex(cut.mesh, v).y);
        highest = std::max(highest, vertex(cut.mesh, v).y);
    }
    EXPECT_GE(lowest, 0.3 - 0.5 * kVoxel);
    EXPECT_NEAR(highest, 2.3, 0.2);  // the top is untouched
    EXPECT_TRUE(analyzeMesh(cut.mesh).watertight());
    EXPECT_GT(levelSetAt(cut, {0, -1.5, 0}), 0.0f);
}

TEST(ColliderCut, ContainerSmallerThanTheLiquidKeepsOnlyItsInside) {
    const Globules blob = blockOfGlobules(3);  // the cube [-1, 1]^3 is all liquid
    const ColliderSolid tank(box({0, 0, 0}, {2, 2, 2}, /*inside=*/true), {}, 0);
    const std::vector<PlacedSolid> colliders{{&tank, Pose{}}};
    const SurfaceFrame cut = surfaceGlobules(blob, settings(), colliders);
    const SurfaceFrame whole = surfaceGlobules(blob, settings(false), colliders);

    EXPECT_GT(verticesInside(whole.mesh, colliders[0]), 1000u);
    ASSERT_GT(cut.mesh.vertexCount(), 0u);
    EXPECT_EQ(verticesInside(cut.mesh, colliders[0]), 0u);
    const MeshTopology topo = analyzeMesh(cut.mesh);
    EXPECT_TRUE(topo.watertight());
    EXPECT_EQ(topo.components, 1u);
    // The tank's inside, full, its faces on the walls; the mesher (dual contouring)
    // bevels the 24 units of edge by less than a voxel squared each.
    EXPECT_GT(topo.signedVolume, 8.0 - 24 * kVoxel * kVoxel);
    EXPECT_LT(topo.signedVolume, 8.0);
    Vec3 lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
    for (std::size_t v = 0; v < cut.mesh.vertexCount(); ++v) {
        const Vec3 p = vertex(cut.mesh, v);
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    for (double wall : {lo.x, lo.y, lo.z}) EXPECT_NEAR(wall, -1.0, 1e-3);
    for (double wall : {hi.x, hi.y, hi.z}) EXPECT_NEAR(wall, 1.0, 1e-3);
    EXPECT_LT(levelSetAt(cut, {0, 0, 0}), 0.0f);
    EXPECT_GT(levelSetAt(cut, {1.5, 0, 0}), 0.0f);
    EXPECT_GT(levelSetAt(cut, {1.5, 1.5, 1.5}), 0.0f);
}

TEST(ColliderCut, SolidAwayFromTheLiquidChangesNothing) {
    const Globules blob = blockOfGlobules(3);
    const ColliderSolid far(box({10, 0, 0}, {1, 1, 1}), {}, 0);
    const SurfaceFrame cut = surfaceGlobules(blob, settings(), {{&far, Pose{}}});
    const SurfaceFrame whole = surfaceGlobules(blob, settings());
    expectSameFrame(cut, whole);
}

TEST(ColliderCut, RejectsAPlacedSolidWithoutASolidOrWithANonFinitePose) {
    const Globules blob = blockOfGlobules(2);
    EXPECT_THROW(surfaceGlobules(blob, settings(), {{nullptr, Pose{}}}), Error);
    const ColliderSolid solid(box({0, 0, 0}, {1, 1, 1}), {}, 0);
    Pose bad;
    bad.translation.x = std::nan("");
    EXPECT_THROW(surfaceGlobules(blob, settings(), {{&solid, bad}}), SimulationError);
}

TEST(ColliderCut, SameResultForOneAndTwoThreads) {
    const Globules blob = blockOfGlobules(5);
    const ColliderSolid knife(box({0, 0, 0}, {0.3, 8, 3}), {}, 0);
    const ColliderSolid ground(plane({0, -1.2, 0}, {0, 1, 0}), {}, 0);
    const ColliderSolid tank(box({0, 0, 0}, {4.4, 6, 4.4}, /*inside=*/true), {}, 0);
    const std::vector<PlacedSolid> colliders{
        {&knife, turnedAboutZ(20, {0.3, 0, 0.2})}, {&ground, Pose{}}, {&tank, Pose{}}};
    SurfaceFrame one, two;
    tbb::task_arena(1).execute([&] { one = surfaceGlobules(blob, settings(), colliders); });
    tbb::task_arena(2).execute([&] { two = surfaceGlobules(blob, settings(), colliders); });
    ASSERT_GT(one.mesh.vertexCount(), 0u);
    expectSameFrame(one, two);
    for (const PlacedSolid& c : colliders) EXPECT_EQ(verticesInside(one.mesh, c), 0u);
}

}  // namespace
}  // namespace globular
