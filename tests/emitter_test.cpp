#include "emitter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "errors.h"
#include "globule_cache.h"

using namespace globular;

namespace {

Globules emitAll(const EmitterSettings& s, double time = 0) {
    auto emitter = makeEmitter(s, 1, 0, testing::TempDir());
    Globules g;
    int32_t next = 0;
    emitter->emit(time, g, next);
    return g;
}

double minDistance(const Globules& g) {
    double best = 1e30;
    for (std::size_t i = 0; i < g.size(); ++i)
        for (std::size_t j = i + 1; j < g.size(); ++j)
            best = std::min(best, length(g.position(i) - g.position(j)));
    return best;
}

}  // namespace

TEST(Emitter, HelixPlacesFourGroupsWithTheStatedSpacing) {
    EmitterSettings s;
    s.count = 100;
    s.jitter = 0.05;
    const Globules g = emitAll(s);
    ASSERT_EQ(g.size(), 100u);
    for (std::size_t i = 0; i < g.size(); ++i) {
        EXPECT_FLOAT_EQ(g.py[i], float(5.0 + double(i / 4) * 1.1)) << i;
        const double r = std::hypot(g.px[i], g.pz[i]);
        EXPECT_NEAR(r, 1.0, 0.05 * std::sqrt(2.0) + 1e-6) << i;
        EXPECT_EQ(g.id[i], int32_t(i));
    }
    // Groups start a quarter turn apart on the same plane.
    EXPECT_NEAR(std::atan2(g.pz[1], g.px[1]) - std::atan2(g.pz[0], g.px[0]), M_PI / 2, 0.1);
    EXPECT_GT(minDistance(g), 1.0);
}

TEST(Emitter, HelixJitterIsSeeded) {
    EmitterSettings s;
    s.count = 8;
    auto a = makeEmitter(s, 5, 0, "."), b = makeEmitter(s, 5, 0, "."), c = makeEmitter(s, 6, 0, ".");
    Globules ga, gb, gc;
    int32_t n1 = 0, n2 = 0, n3 = 0;
    a->emit(0, ga, n1);
    b->emit(0, gb, n2);
    c->emit(0, gc, n3);
    EXPECT_EQ(ga.px, gb.px);
    EXPECT_NE(ga.px, gc.px);
}

TEST(Emitter, BoxFillsItsLatticeInsideTheBox) {
    EmitterSettings s;
    s.type = "box";
    s.count = 0;
    s.min = {0, 0, 0};
    s.max = {4, 2, 3};
    s.spacing = 1.0;
    s.jitter = 0.1;
    const Globules g = emitAll(s);
    EXPECT_EQ(g.size(), 4u * 2u * 3u);
    for (std::size_t i = 0; i < g.size(); ++i) {
        EXPECT_GT(g.px[i], 0.0f);
        EXPECT_LT(g.px[i], 4.0f);
    }
    s.count = 100;
    EXPECT_THROW(emitAll(s), SceneError);
    s.count = 0;  // fill a box far too large for memory: refused, no overflow
    s.max = {1e12, 1e12, 1e12};
    EXPECT_THROW(emitAll(s), ResourceError);
}

TEST(Emitter, SpoutPoursAtItsRateWithoutOverlap) {
    EmitterSettings s;
    s.type = "spout";
    s.count = 1000;
    s.rate = 30;
    s.speed = 5;
    s.nozzleRadius = 1.0;
    s.spacing = 1.0;
    s.jitter = 0;
    auto emitter = makeEmitter(s, 1, 0, ".");
    Globules g;
    int32_t next = 0;
    for (int step = 0; step <= 1000; ++step) {
        // Move emitted globules with their velocity, as a simulation would.
        for (std::size_t i = 0; i < g.size(); ++i) g.py[i] += 0.001f * g.vy[i];
        emitter->emit(step * 0.001, g, next);
    }
    // One second at 30 /s: 30 globules, give or take one partial layer of 7.
    EXPECT_NEAR(double(g.size()), 30.0, 7.0);
    EXPECT_GT(minDistance(g), 0.85);
    EXPECT_EQ(emitter->emitted(), g.size());
}

TEST(Emitter, SpoutRejectsARateItsNozzleCannotPour) {
    EmitterSettings s;
    s.type = "spout";
    s.rate = 1e6;
    EXPECT_THROW(emitAll(s), SceneError);
}

TEST(Emitter, SpoutSkipToReproducesTheSameStream) {
    EmitterSettings s;
    s.type = "spout";
    s.count = 50;
    auto whole = makeEmitter(s, 3, 0, "."), resumed = makeEmitter(s, 3, 0, ".");
    Globules a, b;
    int32_t na = 0, nb = 0;
    for (int k = 0; k < 5; ++k) whole->emit(k * 0.1, a, na);
    Globules scratch;
    int32_t ns = 0;
    for (int k = 0; k < 3; ++k) resumed->emit(k * 0.1, scratch, ns);
    resumed->skipTo(scratch.size());
    b = scratch;
    nb = ns;
    for (int k = 3; k < 5; ++k) resumed->emit(k * 0.1, b, nb);
    EXPECT_EQ(a.px, b.px);
    EXPECT_EQ(a.id, b.id);
}

TEST(Emitter, PointsReadsAPlyRelativeToTheSceneDirectory) {
    const std::string dir = testing::TempDir();
    Globules cloud;
    cloud.add({1, 2, 3}, {0, -1, 0}, 0.5f, 1.0f, 0);
    cloud.add({4, 5, 6}, {0, 0, 0}, 0.5f, 1.0f, 1);
    writeGlobulePly(std::filesystem::path(dir) / "cloud_emitter_test.ply", cloud);
    EmitterSettings s;
    s.type = "points";
    s.file = "cloud_emitter_test.ply";
    s.offset = {10, 0, 0};
    auto emitter = makeEmitter(s, 1, 0, dir);
    Globules g;
    int32_t next = 0;
    emitter->emit(0, g, next);
    ASSERT_EQ(g.size(), 2u);
    EXPECT_FLOAT_EQ(g.px[0], 11.0f);
    EXPECT_FLOAT_EQ(g.vy[0], -1.0f);
    EXPECT_FLOAT_EQ(g.radius[1], 0.5f);
    s.file = "missing.ply";
    EXPECT_THROW(makeEmitter(s, 1, 0, dir), IoError);
}
