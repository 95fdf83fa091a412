// The display encoding of linear frames: exposure, the ACES curve, 8- and 16-bit sRGB,
// 16-bit PNG files, and the [render] keys that choose them. No OpenGL.
#include "tone_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "color_ramp.h"
#include "errors.h"
#include "png_image.h"
#include "render_settings.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

TEST(ToneMapping, AcesMapsZeroToZeroRisesMonotonicallyAndStaysBelowOne) {
    EXPECT_EQ(acesFilmic(0.0f), 0.0f);
    EXPECT_EQ(acesFilmic(-1.0f), 0.0f);
    EXPECT_EQ(acesFilmic(std::nanf("")), 0.0f);
    float previous = 0;
    for (float x = 0.001f; x < 7.0f; x += 0.001f) {
        const float y = acesFilmic(x);
        EXPECT_GT(y, previous) << "x = " << x;
        EXPECT_LT(y, 1.0f) << "x = " << x;
        previous = y;
    }
    for (float x : {7.0f, 10.0f, 1e3f, 1e30f, INFINITY}) EXPECT_LE(acesFilmic(x), 1.0f);
    // Filmic, not a clip: mid-grey stays mid-grey-ish, highlights roll off below 1.
    EXPECT_NEAR(acesFilmic(0.18f), 0.27f, 0.02f);
    EXPECT_LT(acesFilmic(1.0f), 0.85f);
}

TEST(ToneMapping, ExposurePlusOneDoublesLinearInput) {
    const ToneMapping plain = ToneMapping::from(0, "none");
    const ToneMapping brighter = ToneMapping::from(1, "none");
    const ToneMapping darker = ToneMapping::from(-2, "none");
    for (float x : {0.0f, 0.01f, 0.2f, 0.45f}) {
        EXPECT_FLOAT_EQ(brighter.apply(x), 2 * plain.apply(x));
        EXPECT_FLOAT_EQ(darker.apply(x), 0.25f * plain.apply(x));
    }
    EXPECT_EQ(brighter.apply(0.6f), 1.0f);  // none clips
    const ToneMapping aces = ToneMapping::from(1, "aces");
    EXPECT_FLOAT_EQ(aces.apply(0.3f), acesFilmic(0.6f));
}

LinearFrame gradientFrame(int width, int height, bool withAlpha) {
    LinearFrame f;
    f.width = width;
    f.height = height;
    f.rgba.resize(std::size_t(width) * height * 4);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0, 1);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            float* p = &f.rgba[(std::size_t(y) * width + x) * 4];
            const float a = withAlpha ? float(x) / float(width - 1) : 1.0f;
            p[0] = a * float(y) / float(height - 1);  // premultiplied
            p[1] = a * unit(random);
            p[2] = a * unit(random) * 1.5f;  // some above 1
            p[3] = a;
        }
    }
    return f;
}

TEST(ToneMapping, EightBitEncodingIsTheSrgbByteOfTheClippedValue) {
    const LinearFrame f = gradientFrame(64, 32, false);
    const Image image = encode8(f, ToneMapping::from(0, "none"));
    for (std::size_t i = 0; i < f.rgba.size(); ++i) {
        const int expected = i % 4 == 3 ? 255 : int(std::lround(255 * linearToSrgb(f.rgba[i])));
        EXPECT_NEAR(image.rgba[i], expected, 1) << "value " << i;
    }
}

TEST(ToneMapping, StraightAlphaUndoesThePremultiplication) {
    LinearFrame f;
    f.width = 2;
    f.height = 1;
    f.rgba = {0.25f, 0.1f, 0.0f, 0.5f, 0.3f, 0.3f, 0.3f, 0.0f};
    const Image image = encode8(f, ToneMapping::from(0, "none"));
    EXPECT_EQ(image.rgba[0], std::lround(255 * linearToSrgb(0.5)));
    EXPECT_EQ(image.rgba[1], std::lround(255 * linearToSrgb(0.2)));
    EXPECT_EQ(image.rgba[3], 128);
    EXPECT_EQ(image.rgba[7], 0);  // nothing there
}

TEST(Png16, ReadsBackWithSixteenBitsAndTheEightBitImageWithinOneLevel) {
    const fs::path dir = fs::temp_directory_path() / "globular_tone_map_test";
    fs::create_directories(dir);
    for (bool withAlpha : {false, true}) {
        const LinearFrame f = gradientFrame(97, 61, withAlpha);
        const ToneMapping tone = ToneMapping::from(0.5, "aces");
        const Image16 deep = encode16(f, tone);
        const Image shallow = encode8(f, tone);
        writePng(dir / "deep.png", deep);
        writePng(dir / "shallow.png", shallow);
        int bits = 0;
        const Image16 back = readPng16(dir / "deep.png", &bits);
        EXPECT_EQ(bits, 16);
        ASSERT_EQ(back.width, 97);
        ASSERT_EQ(back.height, 61);
        EXPECT_EQ(back.rgba, deep.rgba);  // lossless, byte order right
        int shallowBits = 0;
        readPng16(dir / "shallow.png", &shallowBits);
        EXPECT_EQ(shallowBits, 8);
        const Image eight = readPng(dir / "shallow.png");
        int worst = 0;
        for (std::size_t i = 0; i < back.rgba.size(); ++i) {
            if (i % 4 != 3 && back.rgba[i + 3 - i % 4] == 0) continue;  // no colour there
            worst = std::max(worst, int(std::lround(std::abs(back.rgba[i] / 257.0 - eight.rgba[i]))));
        }
        EXPECT_LE(worst, 1) << "alpha " << withAlpha;
        // The 16-bit file is finer: it holds values between the 8-bit levels.
        int between = 0;
        for (uint16_t v : back.rgba) between += v % 257 != 0;
        EXPECT_GT(between, int(back.rgba.size() / 2));
    }
}

TEST(RenderSettings, OutputKeysAreValidatedNamingTheKey) {
    auto message = [](const RenderSettings& s) {
        try {
            s.validate();
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    RenderSettings s;
    EXPECT_EQ(message(s), "");
    EXPECT_EQ(s.pngBits, 8);
    EXPECT_EQ(s.toneMapping, "none");
    EXPECT_FALSE(s.exr);
    EXPECT_FALSE(s.transparent);
    s.pngBits = 12;
    EXPECT_NE(message(s).find("'png_bits' = 12"), std::string::npos) << message(s);
    s = RenderSettings{};
    s.toneMapping = "filmic";
    EXPECT_NE(message(s).find("'tone_mapping' = \"filmic\""), std::string::npos) << message(s);
    s = RenderSettings{};
    s.exposure = std::nan("");
    EXPECT_NE(message(s).find("'exposure'"), std::string::npos) << message(s);
    s.exposure = 40;
    EXPECT_NE(message(s).find("'exposure'"), std::string::npos) << message(s);
    s.exposure = -3;
    s.toneMapping = "aces";
    s.pngBits = 16;
    EXPECT_EQ(message(s), "");
}

}  // namespace
}  // namespace globular
