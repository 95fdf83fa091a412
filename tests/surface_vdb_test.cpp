// The OpenVDB side of surfacing: the metaball field's values, the written VDB file as
// OpenVDB and vdb_print see it, and grid determinism across thread counts.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <tbb/task_arena.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <utility>

#include "errors.h"
#include "globule_bins.h"
#include "grid_compare.h"
#include "surface_estimate.h"
#include "surface_frame.h"
#include "surface_grids.h"

namespace globular {
namespace {

namespace fs = std::filesystem;
using openvdb::Coord;

Globules someGlobules(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    Globules g;
    for (int i = 0; i < count; ++i) g.add({u(rng), u(rng), u(rng)}, {0, 0, 0}, 0.8f, 1, i);
    return g;
}

std::string run(const std::string& command) {
    std::string out;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return out;
    std::array<char, 4096> buffer;
    while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe))
        out.append(buffer.data(), n);
    pclose(pipe);
    return out;
}

TEST(MetaballSplat, FieldIsTheKernelSumOverExactlyTheInfluenceSpheres) {
    openvdb::initialize();
    const double h = 0.25;
    Globules g;
    g.add({1.0, 1.0, 1.0}, {0, 0, 0}, 1.0f, 1, 0);  // on voxel (4, 4, 4)
    g.add({2.0, 1.0, 1.0}, {0, 0, 0}, 0.5f, 1, 1);  // on voxel (8, 4, 4), R = 1
    const MetaballKernel kernel{KernelType::Wyvill};
    const auto field = splatMetaballs(g, kernel, 2.0, h);
    auto acc = field->getConstAccessor();
    auto c = [&](double r2, double R) { return kernel.value(float(r2 / (R * R))); };
    // Voxel (4,4,4): 1 from the first, the second is 1.0 away with R = 1: nothing.
    EXPECT_FLOAT_EQ(acc.getValue({4, 4, 4}), 1.0f);
    // Voxel (6,4,4): 0.5 from the first (R = 2), 0.5 from the second (R = 1).
    EXPECT_FLOAT_EQ(acc.getValue({6, 4, 4}), c(0.25, 2.0) + c(0.25, 1.0));
    // Voxel (4,7,5): offsets (0, 0.75, 0.25) from the first only.
    EXPECT_FLOAT_EQ(acc.getValue({4, 7, 5}), c(0.625, 2.0));
    // Just inside and outside the first's influence sphere (8 voxels).
    EXPECT_TRUE(acc.isValueOn({4, 4, -3}));
    EXPECT_FALSE(acc.isValueOn({4, 4, -4}));
    EXPECT_EQ(acc.getValue({4, 4, -4}), 0.0f);
    EXPECT_FALSE(acc.isValueOn({4 + 6, 4 + 6, 4}));  // sqrt(72) > 8

    // Every active voxel lies within some influence sphere, and every leaf is one the
    // memory estimate counted.
    std::size_t outside = 0;
    for (auto it = field->cbeginValueOn(); it; ++it) {
        const auto p = it.getCoord();
        const double d1 = (p.asVec3d() - openvdb::Vec3d(4, 4, 4)).length();
        const double d2 = (p.asVec3d() - openvdb::Vec3d(8, 4, 4)).length();
        if (d1 >= 8 && d2 >= 4) ++outside;
    }
    EXPECT_EQ(outside, 0u);
    const GlobuleBins bins(g, h, 2.0);
    const auto& blocks = bins.candidateBlocks();
    for (auto leaf = field->tree().cbeginLeaf(); leaf; ++leaf) {
        const auto o = leaf->origin();
        EXPECT_TRUE(std::binary_search(blocks.begin(), blocks.end(),
                                       GlobuleBins::pack(o.x() >> 3, o.y() >> 3, o.z() >> 3)));
    }
    SurfaceSettings s;
    s.voxelSize = h;
    EXPECT_GE(estimateSurface(g, s).fieldLeaves, field->tree().leafCount());
}

/// A dense cube of globules, 12 wide (48 voxels at voxel 0.25, so some leaves lie a leaf
/// inside), moving (its velocity is read in the level set's band), offset by @p shift
/// voxels (of 0.25) along each axis: the iso surface crosses the leaves at other places.
Globules movingCube(const int shift[3]) {
    Globules g;
    for (int x = 0; x < 12; ++x) {
        for (int y = 0; y < 12; ++y) {
            for (int z = 0; z < 12; ++z) {
                g.add({x + 0.25 * shift[0], y + 0.25 * shift[1], z + 0.25 * shift[2]},
                      {0.1 * x, -0.2 * y, 0.3 * z + 0.01 * x * y}, 1.0f, 1, 0);
            }
        }
    }
    return g;
}

TEST(MetaballSplat, DeepLeavesMayHoldPartialSumsThatChangeNothingNearTheSurface) {
    openvdb::initialize();
    const int unshifted[3] = {0, 0, 0};
    const Globules g = movingCube(unshifted);
    const MetaballKernel kernel{KernelType::Wyvill};
    const auto exact = splatMetaballs(g, kernel, 2.0, 0.25);
    const auto deep = splatMetaballs(g, kernel, 2.0, 0.25, 0.5);
    // Same leaves; some deep ones hold less (never at or below the iso value), and every
    // voxel within a leaf of one at or below it is exact.
    EXPECT_EQ(exact->tree().leafCount(), deep->tree().leafCount());
    auto acc = exact->getConstAccessor();
    std::size_t partial = 0, wrong = 0;
    for (auto it = deep->cbeginValueOn(); it; ++it) {
        const float e = acc.getValue(it.getCoord());
        if (*it == e) continue;
        ++partial;
        if (!(*it > 0.5f && *it < e)) ++wrong;
        bool nearSurface = false;
        const Coord c = it.getCoord();
        for (int dx = -8; dx <= 8 && !nearSurface; ++dx) {
            for (int dy = -8; dy <= 8 && !nearSurface; ++dy) {
                for (int dz = -8; dz <= 8 && !nearSurface; ++dz) {
                    nearSurface = acc.getValue(c.offsetBy(dx, dy, dz)) <= 0.5f;
                }
            }
        }
        if (nearSurface) ++wrong;
    }
    EXPECT_GT(partial, 512u);
    EXPECT_EQ(wrong, 0u);
    // The level sets are identical.
    expectSameGrid(*fieldToLevelSet(*exact, 0.5, 3.0), *fieldToLevelSet(*deep, 0.5, 3.0));
}

TEST(MetaballSplat, PartialSumsKeepTheirDistanceFromTheSurface) {
    openvdb::initialize();
    const MetaballKernel kernel{KernelType::Wyvill};
    std::size_t partialAt[3] = {0, 0, 0};
    for (int s = 0; s < 8; ++s) {
        const int shift[3] = {s, 3 * s % 8, 5 * s % 8};
        SCOPED_TRACE(s);
        const Globules g = movingCube(shift);
        const std::vector<const std::vector<float>*> velocity{&g.vx, &g.vy, &g.vz};
        const MeanSplat exact = splatMetaballsWithMean(g, velocity, kernel, 2.0, 0.25);
        auto acc = exact.field->getConstAccessor();
        auto meanX = exact.means[0]->getConstAccessor();
        const auto exactLevelSet = fieldToLevelSet(*exact.field, 0.5, 3.0);
        const auto exactVelocity =
            velocityInBand(*exact.means[0], *exact.means[1], *exact.means[2], *exactLevelSet, 0.5);
        for (int d = 0; d < 3; ++d) {
            const int depth = 2 << d;  // 2, 4, 8
            SCOPED_TRACE(depth);
            const MeanSplat deep =
                splatMetaballsWithMean(g, velocity, kernel, 2.0, 0.25, 0.5, depth);
            // Every voxel within depth of one at or below the iso value holds its full sum
            // and means; the others hold more than the iso value.
            std::size_t partial = 0, wrong = 0;
            auto deepMeanX = deep.means[0]->getConstAccessor();
            for (auto it = deep.field->cbeginValueOn(); it; ++it) {
                const Coord c = it.getCoord();
                const bool same =
                    *it == acc.getValue(c) && deepMeanX.getValue(c) == meanX.getValue(c);
                partial += !same;
                if (!same && !(*it > 0.5f)) ++wrong;
                bool nearSurface = false;
                for (int dx = -depth; dx <= depth && !same && !nearSurface; ++dx) {
                    for (int dy = -depth; dy <= depth && !nearSurface; ++dy) {
                        for (int dz = -depth; dz <= depth && !nearSurface; ++dz) {
                            nearSurface = acc.getValue(c.offsetBy(dx, dy, dz)) <= 0.5f;
                        }
                    }
                }
                wrong += nearSurface;
            }
            EXPECT_EQ(wrong, 0u);
            partialAt[d] += partial;
            // The level set and the velocity in its band are identical from a depth of 2
            // and ceil(band width) + 1 on.
            const auto levelSet = fieldToLevelSet(*deep.field, 0.5, 3.0);
            expectSameGrid(*exactLevelSet, *levelSet);
            if (depth < 4) continue;
            const auto vel =
                velocityInBand(*deep.means[0], *deep.means[1], *deep.means[2], *levelSet, 0.5);
            EXPECT_EQ(vel->activeVoxelCount(), exactVelocity->activeVoxelCount());
            std::size_t differ = 0;
            auto other = exactVelocity->getConstAccessor();
            for (auto it = vel->cbeginValueOn(); it; ++it) {
                differ += *it != other.getValue(it.getCoord());
            }
            EXPECT_EQ(differ, 0u);
        }
    }
    // The shallower, the more partial sums.
    EXPECT_GT(partialAt[0], partialAt[1]);
    EXPECT_GT(partialAt[1], partialAt[2]);
    EXPECT_GT(partialAt[2], 0u);
    const int shift[3] = {0, 0, 0};
    EXPECT_THROW(splatMetaballs(movingCube(shift), kernel, 2.0, 0.25, 0.5, 0), Error);
}

/// A lone globule's level set at voxel size @p h with a band @p band voxels wide: every
/// active voxel lies within the band and holds its distance to the sphere of radius 1
/// (Wyvill at iso 0.5, influence 2) to within @p tolerance voxels; every voxel nearer than
/// the band's width less @p margin voxels is active.
void expectLoneGlobuleDistances(double band, double h, double tolerance, double margin) {
    openvdb::initialize();
    Globules g;
    g.add({0.013, -0.021, 0.037}, {0, 0, 0}, 1.0f, 1, 0);  // off the voxel lattice
    const auto field = splatMetaballs(g, MetaballKernel{KernelType::Wyvill}, 2.0, h);
    const auto levelSet = fieldToLevelSet(*field, 0.5, band);
    EXPECT_EQ(levelSet->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_FLOAT_EQ(levelSet->background(), float(band * h));
    const openvdb::Vec3d centre(0.013, -0.021, 0.037);
    double worst = 0;
    std::size_t missing = 0;
    for (auto it = levelSet->cbeginValueOn(); it; ++it) {
        const double exact = (levelSet->indexToWorld(it.getCoord()) - centre).length() - 1.0;
        worst = std::max(worst, std::abs(*it - exact) / h);
        EXPECT_LT(std::abs(*it), band * h);
    }
    EXPECT_LT(worst, tolerance) << "voxels";
    auto acc = levelSet->getConstAccessor();
    const int reach = int(std::ceil(1.0 / h + band)) + 2;
    for (int x = -reach; x <= reach; ++x) {
        for (int y = -reach; y <= reach; ++y) {
            for (int z = -reach; z <= reach; ++z) {
                const Coord ijk(x, y, z);
                const double exact = (levelSet->indexToWorld(ijk) - centre).length() - 1.0;
                if (std::abs(exact) < (band - margin) * h && !acc.isValueOn(ijk)) ++missing;
                // Inactive voxels and tiles carry the sign: negative inside.
                if (std::abs(exact) > 0.2 * h) {
                    EXPECT_EQ(acc.getValue(ijk) < 0, exact < 0);
                }
            }
        }
    }
    EXPECT_EQ(missing, 0u);
}

TEST(FieldToLevelSet, LoneGlobuleGivesItsDistanceWithinTheBand) {
    expectLoneGlobuleDistances(3, 0.1, 0.25, 0.2);
}

// A band wider than a leaf (8 voxels): its layers are looked for two leaves out.
// Closest points carried outward layer by layer drift from the exact distance the
// further they go (up to 1.9 voxels at 9 voxels out on this sphere): hence the
// looser bounds.
TEST(FieldToLevelSet, BandWiderThanALeafKeepsItsVoxels) {
    expectLoneGlobuleDistances(10, 0.05, 2.0, 1.5);
}

TEST(FieldToLevelSet, AgreesWithLevelSetRebuildWithinAVoxel) {
    openvdb::initialize();
    const double h = 0.1;
    const Globules g = someGlobules(40, 7);
    const auto field = splatMetaballs(g, MetaballKernel{KernelType::Wyvill}, 2.0, h);
    const auto direct = fieldToLevelSet(*field, 0.5, 3.0);
    const auto rebuilt = rebuildLevelSet(*field, 0.5, 3.0);
    EXPECT_EQ(direct->background(), rebuilt->background());
    auto acc = direct->getConstAccessor();
    double worst = 0, sum = 0;
    std::size_t compared = 0, signs = 0;
    for (auto it = rebuilt->cbeginValueOn(); it; ++it) {
        const float d = acc.getValue(it.getCoord());
        worst = std::max(worst, double(std::abs(d - *it)) / h);
        sum += std::abs(d - *it) / h;
        ++compared;
        if (std::abs(*it) > 0.5 * h && (d < 0) != (*it < 0)) ++signs;
    }
    ASSERT_GT(compared, 1000u);
    EXPECT_LT(worst, 1.0) << "voxels";
    EXPECT_LT(sum / double(compared), 0.05) << "voxels, mean";
    EXPECT_EQ(signs, 0u);
    // The same voxels are active, but for voxels right at the band's edge.
    const double ratio = double(direct->activeVoxelCount()) / double(rebuilt->activeVoxelCount());
    EXPECT_NEAR(ratio, 1.0, 0.05);
}

TEST(FieldToLevelSet, EmptyFieldGivesAnEmptyLevelSet) {
    openvdb::initialize();
    const auto field = splatMetaballs(Globules{}, MetaballKernel{}, 2.0, 0.1);
    const auto levelSet = fieldToLevelSet(*field, 0.5, 3.0);
    EXPECT_EQ(levelSet->activeVoxelCount(), 0u);
    EXPECT_GT(levelSet->getConstAccessor().getValue({0, 0, 0}), 0.0f);
}

// The mesh's normals read a 3x3x3 window of voxels once per vertex; they must be the
// six BoxSampler samples' central differences, bit for bit, wherever the window lies
// (inside one leaf, across leaves, on a tile).
TEST(MeshLevelSet, NormalsAreTheBoxSamplersCentralDifferencesExactly) {
    openvdb::initialize();
    for (const float halfWidth : {3.0f, 1.5f}) {
        const auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
            7.3f, openvdb::Vec3f(0.37f, -1.21f, 2.05f), 0.25f, halfWidth);
        const TriangleMesh mesh = meshLevelSet(*sphere, 0.0);
        ASSERT_GT(mesh.vertexCount(), 1000u);
        ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
        const auto accessor = sphere->getConstAccessor();
        openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>
            sample(accessor, sphere->transform());
        std::size_t differ = 0;
        for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
            const openvdb::Vec3d p = sphere->transform().worldToIndex(openvdb::Vec3d(
                mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]));
            openvdb::Vec3d g;
            for (int k = 0; k < 3; ++k) {
                openvdb::Vec3d step(0.0);
                step[k] = 0.5;
                g[k] = sample.isSample(p + step) - sample.isSample(p - step);
            }
            for (int k = 0; k < 3; ++k) {
                differ += mesh.normals[3 * v + k] != float(g[k] / g.length());
            }
        }
        EXPECT_EQ(differ, 0u) << "half width " << halfWidth;
    }
}

TEST(SurfaceVdb, FileHoldsTheDocumentedGrids) {
    openvdb::initialize();
    SurfaceSettings s;
    s.voxelSize = 0.1;
    Globules g = someGlobules(30, 11);
    g.add({0, 0, 0}, {0, 0, 0}, 1.0f, 1, 30);  // so the origin is deep inside
    const SurfaceFrame frame = surfaceGlobules(g, s);
    const fs::path path = fs::temp_directory_path() / "globular_surface_vdb_test" / "s.0001.vdb";
    writeSurfaceVdb(path, frame);

    openvdb::io::File file(path.string());
    file.open();
    const auto surface = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("surface"));
    const auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
    file.close();
    ASSERT_TRUE(surface && density);
    EXPECT_EQ(surface->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_EQ(density->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(surface->voxelSize(), openvdb::Vec3d(0.1));
    EXPECT_EQ(density->voxelSize(), openvdb::Vec3d(0.1));
    EXPECT_FLOAT_EQ(surface->background(), 3.0f * 0.1f);  // band_width voxels, world units
    EXPECT_EQ(surface->metaValue<std::string>("globular_kernel"), "wyvill");

    float lo = 1, hi = 0;
    for (auto it = density->cbeginValueAll(); it; ++it) {
        lo = std::min(lo, *it);
        hi = std::max(hi, *it);
    }
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_EQ(hi, 1.0f);  // the interior
    // Inside (deep in the blob) and far outside, both grids agree.
    auto ls = surface->getConstAccessor();
    auto fog = density->getConstAccessor();
    const auto centreIndex = surface->transform().worldToIndexNodeCentered({0, 0, 0});
    EXPECT_LT(ls.getValue(centreIndex), 0.0f);
    EXPECT_EQ(fog.getValue(centreIndex), 1.0f);
    EXPECT_GT(ls.getValue({1000, 0, 0}), 0.0f);
    EXPECT_EQ(fog.getValue({1000, 0, 0}), 0.0f);

    // vdb_print (libopenvdb-tools) opens the file and lists both grids with their classes.
    if (run("command -v vdb_print").empty()) GTEST_SKIP() << "vdb_print not installed";
    const std::string printed = run("vdb_print -l -m " + path.string() + " 2>&1");
    EXPECT_NE(printed.find("surface"), std::string::npos) << printed;
    EXPECT_NE(printed.find("density"), std::string::npos) << printed;
    EXPECT_NE(printed.find("level set"), std::string::npos) << printed;
    EXPECT_NE(printed.find("fog volume"), std::string::npos) << printed;
    EXPECT_NE(printed.find("voxel size: 0.1"), std::string::npos) << printed;
}

TEST(SurfaceVdb, FileStoresTheFogAsHalfFloatsAndTheLevelSetExactly) {
    SurfaceSettings s;
    s.voxelSize = 0.1;
    const SurfaceFrame frame = surfaceGlobules(someGlobules(30, 11), s);
    EXPECT_FALSE(frame.grids->surface->saveFloatAsHalf());
    EXPECT_TRUE(frame.grids->density->saveFloatAsHalf());
    const fs::path path = fs::temp_directory_path() / "globular_surface_vdb_test" / "half.vdb";
    writeSurfaceVdb(path, frame);
    const SurfaceGrids back = readSurfaceVdb(path);
    fs::remove(path);
    ASSERT_TRUE(back.surface && back.density);
    expectSameGrid(*back.surface, *frame.grids->surface);
    // Half floats round to 2^-11 of the value (and below 2^-14 to steps of 2^-24).
    constexpr float kHalfRelative = 1.0f / 2048.0f;
    const auto& written = frame.grids->density;
    const auto& read = back.density;
    EXPECT_EQ(read->activeVoxelCount(), written->activeVoxelCount());
    EXPECT_EQ(read->background(), written->background());
    auto before = written->getConstAccessor();
    std::size_t rounded = 0;
    for (auto it = read->cbeginValueOn(); it; ++it) {
        const float w = before.getValue(it.getCoord());
        ASSERT_NEAR(*it, w, std::abs(w) * kHalfRelative + 6e-8f) << it.getCoord();
        rounded += *it != w;
    }
    EXPECT_GT(rounded, 0u);  // the file really holds halves
}

TEST(SurfaceVdb, GridsAreIdenticalForOneAndTwoThreads) {
    SurfaceSettings s;
    s.voxelSize = 0.1;
    s.filters = "gaussian:1, dilate:1";
    const Globules g = someGlobules(80, 5);
    SurfaceFrame one, two;
    tbb::task_arena(1).execute([&] { one = surfaceGlobules(g, s); });
    tbb::task_arena(2).execute([&] { two = surfaceGlobules(g, s); });
    const auto f1 = splatMetaballs(g, s.metaballKernel(), s.influence, s.voxelSize);
    openvdb::FloatGrid::Ptr f2;
    tbb::task_arena(2).execute(
        [&] { f2 = splatMetaballs(g, s.metaballKernel(), s.influence, s.voxelSize); });
    {
        SCOPED_TRACE("field");
        expectSameGrid(*f1, *f2);
    }
    {
        SCOPED_TRACE("surface");
        expectSameGrid(*one.grids->surface, *two.grids->surface);
    }
    {
        SCOPED_TRACE("density");
        expectSameGrid(*one.grids->density, *two.grids->density);
    }
}

}  // namespace
}  // namespace globular
