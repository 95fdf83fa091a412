#include "render_settings.h"

#include <gtest/gtest.h>

#include "errors.h"
#include "settings_schema.h"
#include "surface_look.h"

namespace globular {
namespace {

SettingValue at(SettingValue::Data data, int line = 3) {
    return {std::move(data), {"scene.toml", line, 1}};
}

TEST(RenderSettings, DefaultsAreTheIssuesAndValid) {
    RenderSettings s;
    EXPECT_EQ(s.width, 1280);
    EXPECT_EQ(s.height, 720);
    EXPECT_EQ(s.mode, "spheres");
    EXPECT_EQ(s.colorBy, "constant");
    EXPECT_NO_THROW(s.validate());
    EXPECT_NO_THROW(CameraSettings{}.validate());
    EXPECT_NO_THROW(LightSettings{}.validate());
}

TEST(RenderSettings, KeysBindToFields) {
    RenderSettings s;
    SettingsSection section("render");
    s.describe(section);
    section.assign("width", at(int64_t(64)));
    section.assign("mode", at(std::string("surface")));
    section.assign("color_by", at(std::string("height")));
    section.assign("color", at(std::vector<double>{1, 0.5, 0}));
    section.assign("contact_sheet", at(int64_t(6)));
    section.assign("movie", at(true));
    EXPECT_EQ(s.width, 64);
    EXPECT_EQ(s.mode, "surface");
    EXPECT_EQ(s.colorBy, "height");
    EXPECT_EQ(s.color, (Vec3{1, 0.5, 0}));
    EXPECT_EQ(s.contactSheet, 6);
    EXPECT_TRUE(s.movie);
}

TEST(RenderSettings, RangesAreCheckedOnAssign) {
    RenderSettings s;
    SettingsSection section("render");
    s.describe(section);
    EXPECT_THROW(section.assign("width", at(int64_t(0))), SceneError);
    EXPECT_THROW(section.assign("color", at(std::vector<double>{1.5, 0, 0})), SceneError);
    EXPECT_THROW(section.assign("mode", at(std::string("voxels"))), SceneError);
    EXPECT_THROW(section.assign("colour", at(std::vector<double>{1, 1, 1})), SceneError);
}

TEST(RenderSettings, LightKeysBindAndAreCheckedOnAssign) {
    RenderSettings s;
    SettingsSection section("render");
    s.describe(section);
    section.assign("environment", at(std::string("sky.exr")));
    section.assign("environment_intensity", at(2.5));
    section.assign("shadow_softness", at(4.0));
    section.assign("ambient_occlusion", at(0.5));
    section.assign("occlusion_radius", at(0.25));
    EXPECT_EQ(s.environment, "sky.exr");
    EXPECT_EQ(s.environmentIntensity, 2.5);
    EXPECT_EQ(s.shadowSoftness, 4.0);
    EXPECT_EQ(s.ambientOcclusion, 0.5);
    EXPECT_EQ(s.occlusionRadius, 0.25);
    EXPECT_THROW(section.assign("environment_intensity", at(-1.0)), SceneError);
    EXPECT_THROW(section.assign("shadow_softness", at(17.0)), SceneError);
    EXPECT_THROW(section.assign("ambient_occlusion", at(1.5)), SceneError);
    EXPECT_THROW(section.assign("occlusion_radius", at(-0.1)), SceneError);
    EXPECT_THROW(section.assign("specular", at(1.2)), SceneError);
    // The old sky-light fraction is gone: the environment lights the scene.
    try {
        section.assign("ambient", at(0.3));
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("environment_intensity"), std::string::npos)
            << e.what();
    }
}

TEST(RenderSettings, MaterialRoughnessAndMetallicAreInTheUnitRange) {
    MaterialSettings m;
    SettingsSection section("material");
    m.describe(section);
    section.assign("roughness", at(0.8));
    section.assign("metallic", at(1.0));
    EXPECT_EQ(surfaceLook(m).roughness, 0.8);
    EXPECT_EQ(surfaceLook(m).metallic, 1.0);
    EXPECT_THROW(section.assign("roughness", at(1.5)), SceneError);
    EXPECT_THROW(section.assign("metallic", at(-0.5)), SceneError);
    EXPECT_EQ(SurfaceLook{}.roughness, MaterialSettings{}.roughness);
}

TEST(RenderSettings, ValidateNamesTheKeyAndPlace) {
    RenderSettings s;
    SettingsSection section("render");
    s.describe(section);
    section.assign("samples", at(int64_t(3), 7));
    try {
        s.validate(section);
        FAIL() << "3 samples accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("scene.toml:7:1: [render] key 'samples'"),
                  std::string::npos)
            << e.what();
    }
    s.samples = 4;
    s.mode = "surface";
    s.colorBy = "speed";
    EXPECT_THROW(s.validate(), SceneError);
    s.colorBy = "height";
    s.rampMin = 2;
    s.rampMax = 1;
    try {
        s.validate();
        FAIL() << "ramp_max below ramp_min accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("'ramp_max'"), std::string::npos) << e.what();
    }
}

TEST(RenderSettings, TemperatureRangeMustRiseAndSurfaceModeTakesMaterialAndTemperature) {
    RenderSettings s;
    s.colorBy = "temperature";
    EXPECT_NO_THROW(s.validate());
    s.temperatureLow = 800;
    s.temperatureHigh = 800;
    try {
        s.validate();
        FAIL() << "temperature_high equal to temperature_low accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("[render] key 'temperature_high'"),
                  std::string::npos)
            << e.what();
    }
    s.temperatureHigh = 1500;
    s.mode = "surface";
    EXPECT_NO_THROW(s.validate());
    s.colorBy = "material";
    EXPECT_NO_THROW(s.validate());
    s.colorBy = "speed";
    EXPECT_THROW(s.validate(), SceneError);
}

TEST(CameraSettings, DefaultIsAutomaticAndAGivenCameraIsNot) {
    CameraSettings c;
    EXPECT_TRUE(c.automatic());
    SettingsSection section("camera");
    c.describe(section);
    section.assign("position", at(std::vector<double>{1, 2, 3}));
    EXPECT_FALSE(c.automatic());  // without the scene reader's help
    c.noteGivenKeys(section);
    EXPECT_FALSE(c.autoFrame);  // and the resolved scene says so
    EXPECT_EQ(c.position, (Vec3{1, 2, 3}));
    EXPECT_NO_THROW(c.validate());
}

TEST(CameraSettings, NoteGivenKeysLeavesAnExplicitAutoFrame) {
    CameraSettings c;
    SettingsSection section("camera");
    c.describe(section);
    section.assign("target", at(std::vector<double>{0, 1, 0}));
    section.assign("auto_frame", at(true));
    c.noteGivenKeys(section);
    EXPECT_TRUE(c.autoFrame);
    SettingsSection untouched("camera");
    CameraSettings d;
    d.describe(untouched);
    d.noteGivenKeys(untouched);
    EXPECT_TRUE(d.autoFrame);
}

TEST(CameraSettings, FixedCameraNeedsADirection) {
    CameraSettings c;
    c.autoFrame = false;
    EXPECT_THROW(c.validate(), SceneError);  // position == target == origin
    c.position = {0, 1, 5};
    EXPECT_NO_THROW(c.validate());
    EXPECT_FALSE(c.automatic());
}

TEST(LightSettings, ZeroDirectionIsAnError) {
    LightSettings l;
    SettingsSection section("light[0]");
    l.describe(section);
    section.assign("direction", at(std::vector<double>{0, 0, 0}, 9));
    try {
        l.validate(section);
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("scene.toml:9:1: [light[0]] key 'direction'"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace globular
