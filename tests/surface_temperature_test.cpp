// Temperature and material out of the surface stage: the "temperature" grid (a
// kernel-weighted mean splatted with the field) and the mesh's per-vertex attributes.
#include <gtest/gtest.h>
#include <openvdb/tools/Interpolation.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "mesh.h"
#include "surface_frame.h"
#include "surface_grids.h"
#include "vertex_attributes.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

/// A lattice blob of globules of radius 1, spacing 1.1, centred at @p centre.
void addBlob(Globules& g, Vec3 centre, int side, float temperature, uint8_t material) {
    for (int x = 0; x < side; ++x) {
        for (int y = 0; y < side; ++y) {
            for (int z = 0; z < side; ++z) {
                const Vec3 offset{1.1 * (x - 0.5 * (side - 1)), 1.1 * (y - 0.5 * (side - 1)),
                                  1.1 * (z - 0.5 * (side - 1))};
                g.add(centre + offset, {0, 0, 0}, 1.0f, 1.0f, int32_t(g.size()));
                g.temperature.push_back(temperature);
                g.material.push_back(material);
            }
        }
    }
}

SurfaceSettings coarse() {
    SurfaceSettings s;
    s.voxelsPerRadius = 3;
    return s;
}

TEST(SurfaceTemperature, UniformBlobHasItsTemperatureEverywhereInside) {
    Globules g;
    addBlob(g, {0, 0, 0}, 4, 750.0f, 0);
    const SurfaceFrame frame = surfaceGlobules(g, coarse());
    ASSERT_TRUE(frame.grids->temperature);
    const openvdb::FloatGrid& t = *frame.grids->temperature;
    EXPECT_EQ(t.getName(), "temperature");
    EXPECT_EQ(t.background(), 0.0f);
    EXPECT_GT(t.activeVoxelCount(), 0u);
    for (auto it = t.cbeginValueOn(); it; ++it) {
        ASSERT_NEAR(*it, 750.0f, 750.0f * 1e-5f) << it.getCoord();
    }
    // Inside the liquid everything is defined; far outside nothing is.
    auto acc = t.getConstAccessor();
    EXPECT_TRUE(acc.isValueOn(openvdb::Coord(0, 0, 0)));
    const int far = int(std::ceil(6.0 / frame.voxelSize));
    EXPECT_FALSE(acc.isValueOn(openvdb::Coord(far, 0, 0)));
    // Trilinear samples at the mesh's vertices read no background.
    for (std::size_t v = 0; v < frame.mesh.vertexCount(); v += 7) {
        const openvdb::Vec3d p(frame.mesh.positions[3 * v], frame.mesh.positions[3 * v + 1],
                               frame.mesh.positions[3 * v + 2]);
        ASSERT_NEAR((openvdb::tools::BoxSampler::sample(acc, t.worldToIndex(p))), 750.0f, 0.01f);
    }
}

TEST(SurfaceTemperature, TwoBlobsOfDifferentTemperatureMeetInBetween) {
    Globules g;
    addBlob(g, {-2.2, 0, 0}, 3, 0.0f, 0);
    addBlob(g, {2.2, 0, 0}, 3, 1000.0f, 1);
    const SurfaceFrame frame = surfaceGlobules(g, coarse());
    ASSERT_TRUE(frame.grids->temperature);
    auto acc = frame.grids->temperature->getConstAccessor();
    const auto at = [&](double x) {
        return acc.getValue(openvdb::Coord(int(std::lround(x / frame.voxelSize)), 0, 0));
    };
    // Symmetric blobs: the mean halfway, the blobs' own temperatures at their far sides,
    // and a rise from cold to hot along x.
    EXPECT_NEAR(at(0.0), 500.0f, 1.0f);
    EXPECT_NEAR(at(-3.3), 0.0f, 1e-3f);
    EXPECT_NEAR(at(3.3), 1000.0f, 1e-3f);
    // (A mean of equal values may round a few ulps off them.)
    const float ulps = 1000.0f * 1e-6f;
    float previous = -1;
    for (double x = -3.3; x <= 3.3; x += frame.voxelSize) {
        const float value = at(x);
        EXPECT_GE(value, previous - ulps) << "x = " << x;
        EXPECT_GE(value, -ulps);
        EXPECT_LE(value, 1000.0f + ulps);
        previous = value;
    }
}

TEST(SurfaceTemperature, MeshVerticesCarryTemperatureAndMaterial) {
    Globules g;
    addBlob(g, {-2.2, 0, 0}, 3, 0.0f, 0);
    addBlob(g, {2.2, 0, 0}, 3, 1000.0f, 2);
    const SurfaceFrame frame = surfaceGlobules(g, coarse());
    const TriangleMesh& mesh = frame.mesh;
    ASSERT_GT(mesh.vertexCount(), 0u);
    const VertexAttribute* t = mesh.attribute("temperature");
    const VertexAttribute* m = mesh.attribute("material");
    ASSERT_TRUE(t && m);
    ASSERT_EQ(t->values.size(), mesh.vertexCount());
    ASSERT_EQ(m->values.size(), mesh.vertexCount());
    EXPECT_EQ(m->type, VertexAttribute::Type::Int32);
    int cold = 0, hot = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const double x = mesh.positions[3 * v];
        if (x < -1.5) {  // only the cold blob reaches here
            ++cold;
            EXPECT_FLOAT_EQ(t->values[v], 0.0f);
            EXPECT_EQ(m->values[v], 0.0f);
        } else if (x > 1.5) {
            ++hot;
            EXPECT_NEAR(t->values[v], 1000.0f, 1e-3f);
            EXPECT_EQ(m->values[v], 2.0f);
        } else {
            EXPECT_GE(t->values[v], 0.0f);
            EXPECT_LE(t->values[v], 1000.0f);
            EXPECT_EQ(m->values[v], x < 0 ? 0.0f : 2.0f) << "x = " << x;
        }
    }
    EXPECT_GT(cold, 0);
    EXPECT_GT(hot, 0);

    // Both travel in the PLY mesh and come back.
    const fs::path path = fs::path(testing::TempDir()) /
                          ("surface_temperature_" + std::to_string(::getpid()) + ".ply");
    writeSurfaceMesh(path, mesh, "ply");
    const TriangleMesh back = readMeshPly(path);
    fs::remove(path);
    ASSERT_TRUE(back.attribute("temperature") && back.attribute("material"));
    EXPECT_EQ(back.attribute("temperature")->values, t->values);
    EXPECT_EQ(back.attribute("material")->values, m->values);
}

TEST(SurfaceTemperature, EveryFrameOfSeveralMaterialsCarriesMaterial) {
    Globules g;
    addBlob(g, {0, 0, 0}, 3, 20.0f, 0);  // only material 0 on this frame
    EXPECT_EQ(surfaceGlobules(g, coarse()).mesh.attribute("material"), nullptr);
    const SurfaceFrame frame = surfaceGlobules(g, coarse(), {}, /*severalMaterials=*/true);
    const VertexAttribute* m = frame.mesh.attribute("material");
    ASSERT_NE(m, nullptr);
    for (float v : m->values) EXPECT_EQ(v, 0.0f);
}

TEST(SurfaceTemperature, PlainGlobulesGetNeitherGridNorAttributes) {
    Globules g;
    addBlob(g, {0, 0, 0}, 3, 20.0f, 0);
    g.temperature.clear();
    const SurfaceFrame frame = surfaceGlobules(g, coarse());
    EXPECT_FALSE(frame.grids->temperature);
    // Only the velocity, which every frame carries; material 0 everywhere: left out.
    ASSERT_EQ(frame.mesh.attributes.size(), 3u);
    EXPECT_EQ(frame.mesh.attributes[0].name, "vx");
    EXPECT_EQ(frame.mesh.attribute("temperature"), nullptr);
    EXPECT_EQ(frame.mesh.attribute("material"), nullptr);
}

TEST(SurfaceTemperature, TemperatureGridTravelsInTheSurfaceFile) {
    Globules g;
    addBlob(g, {0, 0, 0}, 3, 300.0f, 0);
    const SurfaceFrame frame = surfaceGlobules(g, coarse());
    const fs::path path = fs::path(testing::TempDir()) /
                          ("surface_temperature_" + std::to_string(::getpid()) + ".vdb");
    writeSurfaceVdb(path, frame);
    const SurfaceGrids back = readSurfaceVdb(path);
    fs::remove(path);
    ASSERT_TRUE(back.temperature);
    EXPECT_EQ(back.temperature->activeVoxelCount(), frame.grids->temperature->activeVoxelCount());
    EXPECT_EQ(back.temperature->getGridClass(), openvdb::GRID_UNKNOWN);
    auto acc = back.temperature->getConstAccessor();
    EXPECT_NEAR(acc.getValue(openvdb::Coord(0, 0, 0)), 300.0f, 1e-3f);
}

}  // namespace
}  // namespace globular
