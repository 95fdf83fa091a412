// The GL context's two back ends (render/gl_context.h): chosen by name or GLOBULAR_GL,
// and drawing the same frame. Draws through OSMesa and EGL surfaceless (llvmpipe).
#include <gtest/gtest.h>

#include <cstdlib>

#include "errors.h"
#include "gl_context.h"
#include "renderer.h"

namespace globular {
namespace {

/// Sets GLOBULAR_GL for one scope.
struct EnvironmentGl {
    explicit EnvironmentGl(const char* value) { setenv("GLOBULAR_GL", value, 1); }
    ~EnvironmentGl() { unsetenv("GLOBULAR_GL"); }
};

TEST(GlBackend, ChosenBySettingUnlessTheEnvironmentSaysOtherwise) {
    unsetenv("GLOBULAR_GL");
    EXPECT_EQ(chooseGlBackend("osmesa"), GlBackend::OSMesa);
    EXPECT_EQ(chooseGlBackend("egl"), GlBackend::Egl);
    {
        EnvironmentGl env("egl");
        EXPECT_EQ(chooseGlBackend("osmesa"), GlBackend::Egl);
    }
    {
        EnvironmentGl env("vulkan");
        try {
            chooseGlBackend("osmesa");
            FAIL() << "GLOBULAR_GL = vulkan accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("GLOBULAR_GL = \"vulkan\""), std::string::npos)
                << e.what();
        }
    }
    EXPECT_THROW(chooseGlBackend("glx"), Error);
    EXPECT_STREQ(glBackendName(GlBackend::Egl), "egl");
}

/// A small frame with everything the renderer draws: spheres with shadows on the ground.
Image drawWith(GlBackend backend) {
    selectGlBackend(backend);
    Renderer renderer(96, 64, 4, 512);
    Globules g;
    for (int i = 0; i < 5; ++i) g.add({i - 2.0, 1.0 + 0.3 * i, 0.5 * i}, {}, 0.8f, 1, 0);
    FrameSetup s;
    s.camera = {{4, 5, 12}, {0, 1, 0}, 40};
    s.lights = {LightSettings{}};
    return renderer.drawSpheres(g, s);
}

TEST(GlBackend, OsMesaAndEglDrawTheSameFrame) {
    const Image osmesa = drawWith(GlBackend::OSMesa);
    Image egl;
    try {
        egl = drawWith(GlBackend::Egl);
    } catch (const Error& e) {
        // Where EGL cannot run the error must say which back end failed.
        EXPECT_NE(std::string(e.what()).find("\"egl\""), std::string::npos) << e.what();
        selectGlBackend(GlBackend::OSMesa);
        GTEST_SKIP() << e.what();
    }
    const Image again = drawWith(GlBackend::OSMesa);  // switching back works
    selectGlBackend(GlBackend::OSMesa);
    ASSERT_EQ(osmesa.rgba.size(), egl.rgba.size());
    int worst = 0;
    for (std::size_t i = 0; i < osmesa.rgba.size(); ++i) {
        worst = std::max(worst, std::abs(int(osmesa.rgba[i]) - int(egl.rgba[i])));
        worst = std::max(worst, std::abs(int(osmesa.rgba[i]) - int(again.rgba[i])));
    }
    EXPECT_LE(worst, 1);  // the same llvmpipe behind both: identical in practice
    EXPECT_NE(glContextDescription(GlBackend::Egl).find("Core Profile"), std::string::npos);
    selectGlBackend(GlBackend::OSMesa);
}

}  // namespace
}  // namespace globular
