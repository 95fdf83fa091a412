#include "integrator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "errors.h"

using namespace globular;

namespace {

/// |x(T) - cos(T)| for x'' = -x, x(0) = 1, v(0) = 0, integrated to T = 1.
double oscillatorError(Integrator& integrator, double dt) {
    Globules g;
    g.add({1, 0, 0}, {0, 0, 0}, 1.0f, 1.0f, 0);
    const int steps = int(std::lround(1.0 / dt));
    for (int s = 0; s < steps; ++s) {
        integrator.step(g, float(dt), [](const Globules& gg, Accelerations& a) {
            a.resize(gg.size());
            a.x[0] = -gg.px[0];
            a.y[0] = a.z[0] = 0;
        });
    }
    return std::abs(double(g.px[0]) - std::cos(1.0));
}

/// Observed order of accuracy from errors at dt and dt/2.
double observedOrder(const std::string& name, double dt) {
    auto coarse = makeIntegrator(name), fine = makeIntegrator(name);
    return std::log2(oscillatorError(*coarse, dt) / oscillatorError(*fine, dt / 2));
}

}  // namespace

TEST(Integrator, ForwardEulerIsFirstOrder) {
    EXPECT_NEAR(observedOrder("forward_euler", 0.02), 1.0, 0.1);
}

TEST(Integrator, SemiImplicitEulerIsFirstOrder) {
    EXPECT_NEAR(observedOrder("semi_implicit_euler", 0.02), 1.0, 0.15);
}

TEST(Integrator, VelocityVerletIsSecondOrder) {
    EXPECT_NEAR(observedOrder("velocity_verlet", 0.1), 2.0, 0.1);
}

TEST(Integrator, ForwardEulerUsesTheOldVelocityForPosition) {
    ForwardEuler euler;
    Globules g;
    g.add({0, 0, 0}, {1, 0, 0}, 1.0f, 1.0f, 0);
    euler.step(g, 0.5f, [](const Globules& gg, Accelerations& a) {
        a.resize(gg.size());
        a.x[0] = 2;
        a.y[0] = a.z[0] = 0;
    });
    EXPECT_FLOAT_EQ(g.px[0], 0.5f);  // x += dt v_old
    EXPECT_FLOAT_EQ(g.vx[0], 2.0f);  // v += dt a
}

TEST(Integrator, UnknownNameIsAnError) {
    EXPECT_THROW(makeIntegrator("runge_kutta"), Error);
}
