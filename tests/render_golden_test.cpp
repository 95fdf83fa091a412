// Small golden images, one per render mode, compared with a tolerance: they catch any
// change to how a frame looks (lighting, shadows, ground, framing, anti-aliasing).
// After an intended change, regenerate and look at them:
//   GLOBULAR_UPDATE_GOLDENS=1 build/tests/renderer_tests --gtest_filter='RenderGolden.*'
// and commit tests/data/render/*.png (docs/render.md).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "camera.h"
#include "png_image.h"
#include "renderer.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 64, kHeight = 48;

/// 36 globules of radius 1 in a small heap beside a short falling column.
Globules heap() {
    Globules g;
    int id = 0;
    for (int ring = 0; ring < 3; ++ring) {
        const int count = ring == 0 ? 1 : 6 * ring;
        for (int k = 0; k < count; ++k) {
            const double a = 2 * std::numbers::pi * k / count;
            g.add({1.6 * ring * std::cos(a), 0.4 + 0.5 * (2 - ring), 1.6 * ring * std::sin(a)},
                  {0, -double(ring), 0}, 1.0f, 1.0f, id++);
        }
    }
    for (int k = 0; k < 17; ++k) {
        g.add({0.3 * std::cos(k), 3.5 + 1.1 * k / 2, 0.3 * std::sin(k)}, {0, -6, 0}, 0.7f, 1.0f,
              id++);
    }
    return g;
}

/// A blobby closed mesh: a sphere of radius 2 with bumps, resting on the ground.
std::vector<float> blobPositions, blobNormals;
std::vector<uint32_t> blobTriangles;
MeshView blob() {
    const int rings = 24, segments = 48;
    blobPositions.clear();
    blobNormals.clear();
    blobTriangles.clear();
    for (int i = 0; i <= rings; ++i) {
        const double theta = std::numbers::pi * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2 * std::numbers::pi * j / segments;
            const Vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta),
                         std::sin(theta) * std::sin(phi)};
            const double r = 2 + 0.25 * std::sin(3 * phi) * std::sin(theta);
            blobPositions.insert(blobPositions.end(),
                                 {float(r * n.x), float(1.8 + r * n.y), float(r * n.z)});
            blobNormals.insert(blobNormals.end(), {float(n.x), float(n.y), float(n.z)});
        }
    }
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments;
            const uint32_t c = a + segments, d = b + segments;
            blobTriangles.insert(blobTriangles.end(), {a, b, c, b, d, c});
        }
    }
    return {blobPositions.data(), blobNormals.data(),       blobPositions.size() / 3,
            blobTriangles.data(), blobTriangles.size() / 3, true};
}

FrameSetup lookFor(const SceneExtent& extent, const std::string& colorBy) {
    FrameSetup s;
    s.render.colorBy = colorBy;
    s.lights = {LightSettings{}};
    s.content = extent.box;
    s.camera = autoFrame(extent, 0, 40, double(kWidth) / kHeight);
    return s;
}

/// Compares @p image with the golden @p name; with GLOBULAR_UPDATE_GOLDENS set, writes it.
void expectMatchesGolden(const Image& image, const std::string& name) {
    const fs::path golden = fs::path(GLOBULAR_SOURCE_DIR) / "tests/data/render" / name;
    if (std::getenv("GLOBULAR_UPDATE_GOLDENS")) {
        writePng(golden, image);
        std::printf("updated %s\n", golden.c_str());
        return;
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing; run with GLOBULAR_UPDATE_GOLDENS=1";
    const Image expected = readPng(golden);
    ASSERT_EQ(image.width, expected.width);
    ASSERT_EQ(image.height, expected.height);
    // Tolerance for rasteriser differences (another Mesa, another CPU's rounding): small
    // everywhere, larger only on a few edge pixels.
    double sum = 0;
    int largest = 0, off = 0;
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        const int d = std::abs(int(image.rgba[i]) - int(expected.rgba[i]));
        sum += d;
        largest = std::max(largest, d);
        off += d > 12;
    }
    const double mean = sum / (image.width * image.height * 3.0);
    const bool ok = mean <= 1.5 && off <= int(0.02 * image.width * image.height * 3);
    if (!ok) {
        const fs::path actual = fs::path(GLOBULAR_BINARY_DIR) / ("actual_" + name);
        writePng(actual, image);
        ADD_FAILURE() << name << " differs from its golden: mean " << mean << ", largest "
                      << largest << ", " << off << " channels off by more than 12; see " << actual;
    }
}

TEST(RenderGolden, Spheres) {
    const Globules g = heap();
    SceneExtent extent;
    extent.addFrame(g);
    Renderer renderer(kWidth, kHeight, 4);
    expectMatchesGolden(renderer.drawSpheres(g, lookFor(extent, "height")), "golden_spheres.png");
}

TEST(RenderGolden, Surface) {
    const MeshView mesh = blob();
    SceneExtent extent;
    extent.addPoints(mesh.positions, mesh.vertexCount);
    Renderer renderer(kWidth, kHeight, 4);
    expectMatchesGolden(renderer.drawMesh(mesh, lookFor(extent, "constant")), "golden_surface.png");
}

TEST(RenderGolden, Fluid) {
    const Globules g = heap();
    SceneExtent extent;
    extent.addFrame(g);
    Renderer renderer(kWidth, kHeight, 4);
    expectMatchesGolden(renderer.drawFluid(g, lookFor(extent, "constant")), "golden_fluid.png");
}

TEST(RenderGolden, LiquidSurface) {
    const MeshView mesh = blob();
    SceneExtent extent;
    extent.addPoints(mesh.positions, mesh.vertexCount);
    FrameSetup s = lookFor(extent, "constant");
    s.liquidSurface = true;
    Renderer renderer(kWidth, kHeight, 4);
    expectMatchesGolden(renderer.drawMesh(mesh, s), "golden_liquid_surface.png");
}

TEST(RenderGolden, DetectsAChange) {
    // The comparison must be able to fail: a different colour mode is not the golden.
    const Globules g = heap();
    SceneExtent extent;
    extent.addFrame(g);
    Renderer renderer(kWidth, kHeight, 4);
    const Image other = renderer.drawSpheres(g, lookFor(extent, "constant"));
    const Image golden =
        readPng(fs::path(GLOBULAR_SOURCE_DIR) / "tests/data/render/golden_spheres.png");
    int off = 0;
    for (std::size_t i = 0; i < other.rgba.size(); ++i) {
        off += std::abs(int(other.rgba[i]) - int(golden.rgba[i])) > 12;
    }
    EXPECT_GT(off, int(0.02 * kWidth * kHeight * 3));
}

}  // namespace
}  // namespace globular
