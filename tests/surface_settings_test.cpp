#include "surface_settings.h"

#include <gtest/gtest.h>

#include <string>

#include "errors.h"
#include "filter_chain.h"
#include "settings_schema.h"

namespace globular {
namespace {

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

TEST(FilterChain, ParsesStepsInOrderWithDefaultAmounts) {
    const auto chain =
        parseFilterChain(" gaussian:2, dilate:1.5 ,erode, mean_curvature:3,laplacian");
    const std::vector<FilterStep> expected{{FilterKind::Gaussian, 2},
                                           {FilterKind::Dilate, 1.5},
                                           {FilterKind::Erode, 1},
                                           {FilterKind::MeanCurvature, 3},
                                           {FilterKind::Laplacian, 1}};
    EXPECT_EQ(chain, expected);
    EXPECT_EQ(parseFilterChain(formatFilterChain(chain)), chain);
    EXPECT_TRUE(parseFilterChain("").empty());
    EXPECT_TRUE(parseFilterChain("   ").empty());
}

TEST(FilterChain, RejectsBadStepsWithAReason) {
    EXPECT_NE(errorOf([] { parseFilterChain("gausian:2"); }).find("did you mean 'gaussian'"),
              std::string::npos);
    EXPECT_NE(errorOf([] { parseFilterChain("gaussian:1.5"); }).find("integer"), std::string::npos);
    EXPECT_NE(errorOf([] { parseFilterChain("gaussian:0"); }).find("[1, 8]"), std::string::npos);
    EXPECT_NE(errorOf([] { parseFilterChain("dilate:0"); }).find("(0, 64]"), std::string::npos);
    EXPECT_NE(errorOf([] { parseFilterChain("dilate:x"); }).find("not a number"),
              std::string::npos);
    EXPECT_NE(errorOf([] { parseFilterChain("dilate:"); }).find("not a number"), std::string::npos);
    EXPECT_NE(errorOf([] { parseFilterChain("erode:1,,dilate:1"); }).find("step 2 is empty"),
              std::string::npos);
    EXPECT_NE(errorOf([] { parseFilterChain("erode:1,"); }).find("step 2 is empty"),
              std::string::npos);
}

TEST(SurfaceSettings, DescribeBindsEveryKeyWithRanges) {
    SurfaceSettings settings;
    SettingsSection section("surface");
    settings.describe(section);
    const std::vector<std::string> keys{
        "voxel_size",       "voxels_per_radius",  "kernel",     "influence",
        "iso_value",        "blinn_sharpness",    "band_width", "filters",
        "droplet_volume",   "subtract_colliders", "adaptivity", "mesh_format",
        "frames_in_flight", "memory_limit_gib"};
    EXPECT_EQ(section.keys(), keys);

    section.assign("voxel_size", {0.05, {"scene.toml", 3, 1}});
    section.assign("kernel", {std::string("murakami"), {"scene.toml", 4, 1}});
    section.assign("frames_in_flight", {int64_t(2), {"scene.toml", 5, 1}});
    EXPECT_TRUE(settings.subtractColliders);  // on by default
    section.assign("subtract_colliders", {false, {"scene.toml", 6, 1}});
    EXPECT_EQ(settings.voxelSize, 0.05);
    EXPECT_EQ(settings.kernel, "murakami");
    EXPECT_EQ(settings.framesInFlight, 2);
    EXPECT_FALSE(settings.subtractColliders);

    EXPECT_THROW(section.assign("iso_value", {1.0, {"scene.toml", 6, 1}}), SceneError);
    EXPECT_THROW(section.assign("voxel_size", {-1.0, {"scene.toml", 6, 1}}), SceneError);
    EXPECT_THROW(section.assign("mesh_format", {std::string("stl"), {"scene.toml", 6, 1}}),
                 SceneError);
    EXPECT_THROW(section.assign("kernal", {std::string("wyvill"), {"scene.toml", 6, 1}}),
                 SceneError);
}

TEST(SurfaceSettings, DefaultsAreValidAndPutALoneGlobuleSurfaceAtItsRadius) {
    const SurfaceSettings settings;
    EXPECT_NO_THROW(settings.validate());
    EXPECT_NEAR(settings.loneSurfaceRadius(1.0), 1.0, 1e-9);
    EXPECT_NEAR(settings.loneSurfaceRadius(0.25), 0.25, 1e-9);
}

TEST(SurfaceSettings, ValidateNamesTheKey) {
    SurfaceSettings s;
    s.filters = "gaussian:2, blur:3";
    EXPECT_NE(errorOf([&] { s.validate(); }).find("[surface] key 'filters'"), std::string::npos);

    s = SurfaceSettings{};
    s.filters = "gaussian:4";  // wider than the default band of 3 voxels
    const std::string wide = errorOf([&] { s.validate(); });
    EXPECT_NE(wide.find("'filters'"), std::string::npos);
    EXPECT_NE(wide.find("band_width"), std::string::npos);
    s.bandWidth = 4;
    EXPECT_NO_THROW(s.validate());

    s = SurfaceSettings{};
    s.kernel = "cubic";
    EXPECT_NE(errorOf([&] { s.validate(); }).find("'kernel'"), std::string::npos);
    s = SurfaceSettings{};
    s.isoValue = 0;
    EXPECT_NE(errorOf([&] { s.validate(); }).find("'iso_value'"), std::string::npos);
    s = SurfaceSettings{};
    s.meshFormat = "stl";
    EXPECT_NE(errorOf([&] { s.validate(); }).find("'mesh_format'"), std::string::npos);
}

TEST(SurfaceSettings, AutoVoxelSizeIsTheMedianRadiusOverVoxelsPerRadius) {
    Globules g;
    for (float r : {1.0f, 0.5f, 4.0f, 1.0f, 0.0f}) g.add({0, 0, 0}, {0, 0, 0}, r, 1, 0);
    SurfaceSettings s;
    EXPECT_DOUBLE_EQ(resolveVoxelSize(s, g), 0.25);  // median of 0.5 1 1 4 (0 ignored)
    s.voxelsPerRadius = 8;
    EXPECT_DOUBLE_EQ(resolveVoxelSize(s, g), 0.125);
    s.voxelSize = 0.3;
    EXPECT_DOUBLE_EQ(resolveVoxelSize(s, g), 0.3);
    EXPECT_DOUBLE_EQ(resolveVoxelSize(SurfaceSettings{}, Globules{}), 0.25);
}

}  // namespace
}  // namespace globular
