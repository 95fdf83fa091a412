// The environment's CPU side (render/environment.h) against analytic integrals: the
// spherical-harmonic irradiance, the GGX pre-filtered cube map, and the OpenEXR reader on
// good and damaged files.

#include "environment.h"

#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <string>

#include "errors.h"

namespace globular {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

LatLongImage imageOf(const std::function<double(Vec3)>& radiance, int width = 256,
                     int height = 128) {
    LatLongImage image{width, height, std::vector<float>(std::size_t(3) * width * height)};
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            const double l = radiance(latLongDirection((i + 0.5) / width, (j + 0.5) / height));
            for (int c = 0; c < 3; ++c) image.rgb[3 * (std::size_t(j) * width + i) + c] = float(l);
        }
    }
    return image;
}

const Vec3 kNormals[] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {0.48, 0.6, 0.64},
                         {-0.36, -0.48, 0.8}};

TEST(Environment, LatLongDirectionsAreUnitAndRoundTrip) {
    EXPECT_NEAR(latLongDirection(0.5, 0).y, 1, 1e-12);          // top row: up
    EXPECT_NEAR(latLongDirection(0.5, 0.5).z, -1, 1e-12);       // middle: along -z
    EXPECT_NEAR(latLongDirection(0.75, 0.5).x, 1, 1e-12);       // three quarters: +x
    const LatLongImage ramp = imageOf([](Vec3 d) { return 2 + d.x + 0.5 * d.y - 0.25 * d.z; });
    for (Vec3 n : kNormals) {
        EXPECT_NEAR(ramp.sample(n).x, 2 + n.x + 0.5 * n.y - 0.25 * n.z, 0.01);
    }
}

// Irradiance E(n) = integral of L(w) max(n.w, 0) dw: a constant L gives pi L.
TEST(Environment, IrradianceOfAConstantSkyIsPiTimesItsRadiance) {
    const IrradianceSH sh = irradianceSH(imageOf([](Vec3) { return 0.7; }));
    for (Vec3 n : kNormals) EXPECT_NEAR(evaluateIrradiance(sh, n).x, kPi * 0.7, 1e-3);
}

// A linear L = 1 + a.w gives E(n) = pi + (2 pi / 3) a.n (the clamped cosine's first band).
TEST(Environment, IrradianceOfALinearSkyIsExact) {
    const Vec3 a{0.2, 0.5, -0.3};
    const IrradianceSH sh = irradianceSH(imageOf([&](Vec3 d) { return 1 + dot(a, d); }));
    for (Vec3 n : kNormals) {
        EXPECT_NEAR(evaluateIrradiance(sh, n).y, kPi + 2 * kPi / 3 * dot(a, n), 2e-3);
    }
}

// L = z^2 (bands 0 and 2): E(n) = pi / 3 + (pi / 12)(3 n_z^2 - 1); at n = +z, pi / 2.
TEST(Environment, IrradianceOfAQuadraticSkyIsExact) {
    const IrradianceSH sh = irradianceSH(imageOf([](Vec3 d) { return d.z * d.z; }));
    for (Vec3 n : kNormals) {
        EXPECT_NEAR(evaluateIrradiance(sh, n).z, kPi / 3 + kPi / 12 * (3 * n.z * n.z - 1), 2e-3);
    }
    EXPECT_NEAR(evaluateIrradiance(sh, {0, 0, 1}).x, kPi / 2, 2e-3);
}

// Pre-filtering averages: a uniform environment stays the same at every roughness.
TEST(Environment, PrefilteredUniformSkyKeepsItsRadianceAtEveryRoughness) {
    const PrefilteredCube cube = prefilterGgx(imageOf([](Vec3) { return 1.5; }), 32, 5, 32);
    ASSERT_EQ(cube.levelCount(), 5);
    EXPECT_EQ(cube.sizeOf(4), 2);
    for (int l = 0; l < cube.levelCount(); ++l) {
        for (Vec3 n : kNormals) EXPECT_NEAR(cube.sample(n, l).x, 1.5, 1e-4) << "level " << l;
    }
}

// Level 0 is the mirror image; the rough levels match a brute-force GGX integral of the
// same lobe (many samples, no mip chain), for a sky with a bright glow.
TEST(Environment, PrefilteredLevelsMatchTheGgxLobeIntegral) {
    SkyLook look;
    const LatLongImage sky = proceduralSky(look, 512, 256);
    const PrefilteredCube cube = prefilterGgx(sky, 128, 5, 64);
    for (Vec3 n : kNormals) {
        const Vec3 mirror = cube.sample(n, 0), expected = sky.sample(n);
        EXPECT_NEAR(mirror.z, expected.z, 0.02 * expected.z + 1e-3);
        for (int l = 1; l < cube.levelCount(); ++l) {
            const double roughness = double(l) / (cube.levelCount() - 1);
            const Vec3 want = ggxReference(sky, n, roughness, 8192), got = cube.sample(n, l);
            EXPECT_NEAR(got.x, want.x, 0.05 * want.x + 2e-3) << "roughness " << roughness;
            EXPECT_NEAR(got.z, want.z, 0.05 * want.z + 2e-3) << "roughness " << roughness;
        }
    }
}

// The procedural sky: the zenith and horizon colours where they belong, the floor below,
// the glow towards the sun.
TEST(Environment, ProceduralSkyHasItsZenithHorizonGroundAndGlow) {
    SkyLook look;
    look.sunToward = normalized({1, 1, 0});
    const LatLongImage sky = proceduralSky(look, 512, 256);
    EXPECT_NEAR(sky.sample({0, -1, 0}).x, look.ground.x, 1e-3);
    EXPECT_NEAR(sky.sample({-0.05, 1, 0}).z, look.zenith.z, 0.05);
    EXPECT_GT(sky.sample(look.sunToward).x, sky.sample({-1, 1, 0}).x + 0.8 * look.sunGlow.x);
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "globular_environment_test";
    fs::create_directories(dir);
    return dir / name;
}

void writeExr(const fs::path& path, int width, int height, const std::vector<float>& rgb,
              bool withBlue = true) {
    Imf::Header header(width, height);
    Imf::FrameBuffer buffer;
    const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < (withBlue ? 3 : 2); ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        buffer.insert(names[c], Imf::Slice(Imf::FLOAT, (char*)(rgb.data() + c), 3 * sizeof(float),
                                           3 * sizeof(float) * width));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(buffer);
    file.writePixels(height);
}

TEST(Environment, ReadsALatLongExr) {
    std::vector<float> rgb(8 * 4 * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = float(i % 7) * 0.5f;
    const fs::path path = scratch("ok.exr");
    writeExr(path, 8, 4, rgb);
    const LatLongImage image = readLatLongExr(path);
    ASSERT_EQ(image.width, 8);
    ASSERT_EQ(image.height, 4);
    EXPECT_EQ(image.rgb, rgb);
}

/// The message of the IoError readLatLongExr throws for @p path, or "" when none.
std::string readError(const fs::path& path) {
    try {
        readLatLongExr(path);
    } catch (const IoError& e) {
        return e.what();
    }
    return "";
}

TEST(Environment, MissingOrDamagedFilesAreErrorsNamingTheFile) {
    const fs::path missing = scratch("missing.exr");
    fs::remove(missing);
    EXPECT_NE(readError(missing).find("missing.exr"), std::string::npos);

    const fs::path text = scratch("text.exr");
    std::ofstream(text) << "not an image";
    EXPECT_NE(readError(text).find("text.exr"), std::string::npos);

    // A good file cut short.
    std::vector<float> rgb(64 * 32 * 3, 1.0f);
    const fs::path cut = scratch("cut.exr");
    writeExr(cut, 64, 32, rgb);
    fs::resize_file(cut, fs::file_size(cut) / 2);
    EXPECT_NE(readError(cut).find("cut.exr"), std::string::npos);

    const fs::path noBlue = scratch("no_blue.exr");
    writeExr(noBlue, 64, 32, rgb, false);
    EXPECT_NE(readError(noBlue).find("no B channel"), std::string::npos);

    rgb[5] = std::numeric_limits<float>::infinity();
    const fs::path infinite = scratch("infinite.exr");
    writeExr(infinite, 64, 32, rgb);
    EXPECT_NE(readError(infinite).find("infinite.exr"), std::string::npos);
    EXPECT_NE(readError(infinite).find("non-finite"), std::string::npos);
}

// Lossy compression leaves tiny negatives around black: they read as 0.
TEST(Environment, NegativeRadianceReadsAsZero) {
    std::vector<float> rgb(8 * 4 * 3, 0.5f);
    rgb[4] = -1e-4f;
    const fs::path path = scratch("negative.exr");
    writeExr(path, 8, 4, rgb);
    const LatLongImage image = readLatLongExr(path);
    EXPECT_EQ(image.rgb[4], 0.0f);
    EXPECT_EQ(image.rgb[5], 0.5f);
}

}  // namespace
}  // namespace globular
