#include "pair_force.h"

#include <gtest/gtest.h>

#include <cmath>

#include "material.h"

using namespace globular;

namespace {

MaterialSettings powder() {
    MaterialSettings m;
    m.preset = "powder";
    return m;
}

/// Force on a globule at (d, 0, 0) from one at the origin, both radius 1.
float forceX(const PairForce& pair, float d, float vx = 0) {
    float f[3] = {0, 0, 0};
    pair.accumulate(d, 0, 0, vx, 0, 0, 2.0f, f);
    return f[0];
}

}  // namespace

TEST(PairForce, B2FromEquation3) {
    MaterialSettings m;
    m.r0 = 2.0;
    m.b1 = 3.0;
    const PairForce pair = PairForce::fromMaterial(m);
    EXPECT_FLOAT_EQ(pair.b2, float(3.0 * std::pow(2.0, 3.0 - 5.0)));
}

TEST(PairForce, PresetsSetWindowsAsNumbers) {
    MaterialSettings m;
    m.r0 = 2.0;
    m.preset = "powder";
    EXPECT_DOUBLE_EQ(m.resolvedCr(), 2.0);
    EXPECT_DOUBLE_EQ(m.resolvedCd(), 2.0);
    m.preset = "liquid";
    m.alpha = 1.5;
    EXPECT_DOUBLE_EQ(m.resolvedCr(), 2.0);
    EXPECT_DOUBLE_EQ(m.resolvedCd(), 3.0);
    m.preset = "solid";
    EXPECT_DOUBLE_EQ(m.resolvedCr(), 4.0);
    EXPECT_DOUBLE_EQ(m.resolvedCd(), 4.0);
    m.cr = 1.25;  // explicit numbers win over the preset
    EXPECT_DOUBLE_EQ(m.resolvedCr(), 1.25);
}

TEST(PairForce, VanishesAtRestDistance) {
    const PairForce pair = PairForce::fromMaterial(powder());
    EXPECT_NEAR(forceX(pair, 1.0f), 0.0f, 1e-6f);
}

TEST(PairForce, RepelsBelowRestDistanceWithHandComputedMagnitude) {
    // D = 0.5: b1/D^5 - b2/D^3 = 64 - 16 = 48; S_r = 1 - 0.25/4; |f| = D S_r 48.
    const PairForce pair = PairForce::fromMaterial(powder());
    EXPECT_NEAR(forceX(pair, 0.5f), 0.5f * 0.9375f * 48.0f, 1e-4f);
    EXPECT_GT(forceX(pair, 0.5f), 0.0f);  // pushes away from the other globule
}

TEST(PairForce, AttractsAboveRestDistanceWithHandComputedMagnitude) {
    // D = 1.5: 2/1.5^5 - 2/1.5^3 = -0.329218; S_r = 1 - 2.25/4 = 0.4375.
    const PairForce pair = PairForce::fromMaterial(powder());
    const double expected = 1.5 * 0.4375 * (2 / std::pow(1.5, 5) - 2 / std::pow(1.5, 3));
    EXPECT_NEAR(forceX(pair, 1.5f), expected, 1e-6);
    EXPECT_LT(forceX(pair, 1.5f), 0.0f);
}

TEST(PairForce, WindowsAreZeroAtAndBeyondTheirCutoffs) {
    const PairForce pair = PairForce::fromMaterial(powder());  // C_r = C_d = 1: cutoff 2
    EXPECT_EQ(forceX(pair, 2.0f, 5.0f), 0.0f);
    EXPECT_EQ(forceX(pair, 2.5f, 5.0f), 0.0f);
    EXPECT_NE(forceX(pair, 1.99f, 5.0f), 0.0f);
}

TEST(PairForce, DragDampsApproachAlongTheLineOfCentres) {
    MaterialSettings m;  // liquid, C_d = 1.5: drag window 3, radial zero at D = r0 = 1
    const PairForce pair = PairForce::fromMaterial(m);
    // Separating at 1 unit/s at D = 1: f = -S_d (V.P)/D^2 P = -(1 - 1/9) along x.
    EXPECT_NEAR(forceX(pair, 1.0f, 1.0f), -8.0f / 9.0f, 1e-5f);
    // Beyond the radial window (D = 2.5 > 2) only drag acts: S_d = 1 - 6.25/9.
    EXPECT_NEAR(forceX(pair, 2.5f, -1.0f), (1 - 6.25f / 9) * 1.0f, 1e-5f);
    // Motion across the line of centres is not damped.
    float f[3] = {0, 0, 0};
    pair.accumulate(1.0f, 0, 0, 0, 3.0f, 0, 2.0f, f);
    EXPECT_NEAR(f[1], 0.0f, 1e-7f);
}

TEST(PairForce, CoincidentGlobulesGiveNoNaN) {
    const PairForce pair = PairForce::fromMaterial(powder());
    float f[3] = {0, 0, 0};
    pair.accumulate(0, 0, 0, 1, 2, 3, 2.0f, f);
    EXPECT_EQ(f[0], 0.0f);
    EXPECT_EQ(f[1], 0.0f);
    float g[3] = {0, 0, 0};
    pair.accumulate(1e-20f, 0, 0, 0, 0, 0, 2.0f, g);
    EXPECT_TRUE(std::isfinite(g[0]));
}

TEST(PairForce, NonIntegerExponentsMatchPow) {
    MaterialSettings m = powder();
    m.m = 7;
    m.n = 1.5;
    const PairForce pair = PairForce::fromMaterial(m);
    EXPECT_FALSE(pair.integerExponents);
    const double d = 0.8, b2 = 2 * std::pow(1.0, 1.5 - 7);
    const double expected = d * (1 - d * d / 4) * (2 / std::pow(d, 7) - b2 / std::pow(d, 1.5));
    EXPECT_NEAR(forceX(pair, float(d)), expected, 1e-4 * std::abs(expected));
}
