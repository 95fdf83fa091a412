#include "color_ramp.h"

#include <gtest/gtest.h>

namespace globular {
namespace {

TEST(ColorRamp, SrgbCurveKnownValues) {
    EXPECT_DOUBLE_EQ(srgbToLinear(0.0), 0.0);
    EXPECT_DOUBLE_EQ(srgbToLinear(1.0), 1.0);
    EXPECT_NEAR(srgbToLinear(0.5), 0.214041, 1e-6);
    EXPECT_NEAR(srgbToLinear(0.04045), 0.04045 / 12.92, 1e-12);
    EXPECT_NEAR(linearToSrgb(0.214041), 0.5, 1e-6);
    EXPECT_DOUBLE_EQ(linearToSrgb(2.0), 1.0);
    EXPECT_DOUBLE_EQ(linearToSrgb(-1.0), 0.0);
    for (double c = 0; c <= 1; c += 0.01) EXPECT_NEAR(linearToSrgb(srgbToLinear(c)), c, 1e-12);
}

TEST(ColorRamp, EndsAndMiddleAreStops) {
    const auto& stops = rampStops();
    EXPECT_EQ(rampColor(0), stops.front());
    EXPECT_EQ(rampColor(1), stops.back());
    EXPECT_EQ(rampColor(0.5), stops[5]);
    EXPECT_EQ(rampColor(-3), stops.front());
    EXPECT_EQ(rampColor(7), stops.back());
}

TEST(ColorRamp, InterpolatesBetweenStops) {
    const auto& stops = rampStops();
    const Vec3 c = rampColor(0.05);
    EXPECT_NEAR(c.x, 0.5 * (stops[0].x + stops[1].x), 1e-12);
    EXPECT_NEAR(c.y, 0.5 * (stops[0].y + stops[1].y), 1e-12);
}

TEST(ColorRamp, LightnessRisesMonotonically) {
    // A ramp that reads without a legend: brighter means more.
    double previous = -1;
    for (double t = 0; t <= 1.0001; t += 0.05) {
        const Vec3 c = srgbToLinear(rampColor(t));
        const double luminance = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
        EXPECT_GT(luminance, previous) << "t = " << t;
        previous = luminance;
    }
}

TEST(ColorRamp, BlackbodyRunsFromBlackThroughRedAndYellowToWhite) {
    EXPECT_EQ(blackbodyColor(0), (Vec3{0, 0, 0}));
    EXPECT_EQ(blackbodyColor(1), (Vec3{1, 1, 1}));
    EXPECT_EQ(blackbodyColor(-50), blackbodyColor(0));
    EXPECT_EQ(blackbodyColor(50), blackbodyColor(1));
    const Vec3 red = blackbodyColor(0.4), orange = blackbodyColor(0.6),
               yellow = blackbodyColor(0.85);
    EXPECT_GT(red.x, 2 * red.y);  // red: little green or blue
    EXPECT_GT(red.x, 2 * red.z);
    EXPECT_GT(orange.y, orange.z);  // orange: green rising, blue low
    EXPECT_GT(orange.x, orange.y);
    EXPECT_GT(yellow.y, 0.7);  // yellow: red and green high, blue low
    EXPECT_LT(yellow.z, 0.5 * yellow.y);
}

TEST(ColorRamp, BlackbodyLuminanceRisesMonotonically) {
    // Hotter is always brighter, also between the stops (interpolated in sRGB).
    double previous = -1;
    for (int k = 0; k <= 1000; ++k) {
        const Vec3 c = srgbToLinear(blackbodyColor(k / 1000.0));
        const double luminance = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
        EXPECT_GT(luminance, previous) << "t = " << k / 1000.0;
        previous = luminance;
    }
    EXPECT_NEAR(previous, 1.0, 1e-12);
}

}  // namespace
}  // namespace globular
