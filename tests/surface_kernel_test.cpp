#include <gtest/gtest.h>

#include <cmath>

#include "errors.h"
#include "metaball_kernel.h"

namespace globular {
namespace {

TEST(MetaballKernel, EveryKernelIsOneAtTheCentreAndZeroAtTheInfluenceRadius) {
    for (auto type : {KernelType::Wyvill, KernelType::Blinn, KernelType::Murakami}) {
        const MetaballKernel k{type, 4.0f};
        EXPECT_FLOAT_EQ(k.value(0.0f), 1.0f);
        EXPECT_NEAR(k.value(0.999999f), 0.0f, 1e-5f);
        EXPECT_EQ(k.value(1.0f), 0.0f);
        EXPECT_EQ(k.value(2.5f), 0.0f);
        // Monotonically falling.
        for (float q = 0.0f; q < 0.99f; q += 0.01f) EXPECT_GT(k.value(q), k.value(q + 0.01f));
    }
}

TEST(MetaballKernel, WyvillSoftObjectIsOneHalfAtHalfTheInfluenceRadius) {
    // C(q) = 1 - 4/9 q^3 + 17/9 q^2 - 22/9 q, and C(1/4) = 1/2 exactly.
    const MetaballKernel k{KernelType::Wyvill};
    EXPECT_FLOAT_EQ(k.value(0.25f), 0.5f);
    EXPECT_NEAR(k.qAtLevel(0.5), 0.25, 1e-12);
    EXPECT_NEAR(k.surfaceFraction(0.5), 0.5, 1e-12);
    // Its factorisation (1 - q)^2 (1 - 4q/9).
    EXPECT_NEAR(k.value(0.6f), 0.16f * (1.0f - 2.4f / 9.0f), 1e-6f);
}

TEST(MetaballKernel, MurakamiIsTheSquareOfOneMinusQ) {
    const MetaballKernel k{KernelType::Murakami};
    EXPECT_FLOAT_EQ(k.value(0.5f), 0.25f);
    EXPECT_NEAR(k.qAtLevel(0.25), 0.5, 1e-12);
}

TEST(MetaballKernel, BlinnIsTheShiftedTruncatedExponential) {
    const MetaballKernel k{KernelType::Blinn, 3.0f};
    const double expected = (std::exp(-1.5) - std::exp(-3.0)) / (1.0 - std::exp(-3.0));
    EXPECT_NEAR(k.value(0.5f), expected, 1e-6);
    EXPECT_NEAR(k.qAtLevel(expected), 0.5, 1e-9);
}

TEST(MetaballKernel, LevelInversionRoundTripsForEveryKernel) {
    for (auto type : {KernelType::Wyvill, KernelType::Blinn, KernelType::Murakami}) {
        const MetaballKernel k{type, 6.0f};
        for (double level : {0.05, 0.3, 0.5, 0.9}) {
            EXPECT_NEAR(k.value(float(k.qAtLevel(level))), level, 2e-6) << int(type);
        }
    }
    EXPECT_THROW(MetaballKernel{}.qAtLevel(1.0), SceneError);
    EXPECT_THROW(MetaballKernel{}.qAtLevel(0.0), SceneError);
}

TEST(MetaballKernel, NamesMapToTypes) {
    EXPECT_EQ(kernelFromName("wyvill"), KernelType::Wyvill);
    EXPECT_EQ(kernelFromName("blinn"), KernelType::Blinn);
    EXPECT_EQ(kernelFromName("murakami"), KernelType::Murakami);
    EXPECT_THROW(kernelFromName("gauss"), SceneError);
}

}  // namespace
}  // namespace globular
