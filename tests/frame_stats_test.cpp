#include "frame_stats.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <functional>
#include <numeric>
#include <random>

#include "errors.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

Globules chain(Globules g, Vec3 start, int count, double spacing, float radius, int32_t firstId) {
    for (int k = 0; k < count; ++k) {
        g.add(start + Vec3{spacing * k, 0, 0}, {}, radius, 1.0f, firstId + k);
    }
    return g;
}

/// Cluster count by brute force over all pairs, for comparison with the grid.
std::size_t bruteForceClusters(const Globules& g) {
    std::vector<std::size_t> parent(g.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<std::size_t(std::size_t)> find = [&](std::size_t x) {
        return parent[x] == x ? x : parent[x] = find(parent[x]);
    };
    for (std::size_t i = 0; i < g.size(); ++i) {
        for (std::size_t j = i + 1; j < g.size(); ++j) {
            const double d = length(g.position(i) - g.position(j));
            if (d < double(g.radius[i]) + g.radius[j]) parent[find(i)] = find(j);
        }
    }
    std::size_t roots = 0;
    for (std::size_t i = 0; i < g.size(); ++i) roots += find(i) == i;
    return roots;
}

TEST(FrameStats, EmptySetIsAllZero) {
    const FrameStats s = computeFrameStats(Globules{}, 4, 0.5);
    EXPECT_EQ(s.frame, 4);
    EXPECT_EQ(s.time, 0.5);
    EXPECT_EQ(s.count, 0u);
    EXPECT_EQ(s.kineticEnergy, 0);
    EXPECT_EQ(s.maxHeight, 0);
    EXPECT_EQ(s.horizontalSpread, 0);
    EXPECT_EQ(s.clusterCount, 0u);
    EXPECT_EQ(s.largestClusterFraction, 0);
}

TEST(FrameStats, KineticEnergyAndMaxSpeed) {
    Globules g;
    g.add({0, 0, 0}, {1, 0, 0}, 1, 1, 0);
    g.add({10, 0, 0}, {0, 3, 4}, 1, 2, 1);
    const FrameStats s = computeFrameStats(g, 1, 0);
    EXPECT_EQ(s.kineticEnergy, 0.5 * 1 * 1 + 0.5 * 2 * 25);
    EXPECT_EQ(s.maxSpeed, 5);
}

TEST(FrameStats, CircleHasKnownCentroidSpreadAndHeight) {
    Globules g;  // radius 2 around (1, *, -3) in x-z, at different heights
    g.add({3, 1, -3}, {}, 0.5f, 1, 0);
    g.add({1, 2, -1}, {}, 0.5f, 1, 1);
    g.add({-1, 3, -3}, {}, 0.5f, 1, 2);
    g.add({1, 6, -5}, {}, 0.5f, 1, 3);
    const FrameStats s = computeFrameStats(g, 1, 0);
    EXPECT_EQ(s.centroid, (Vec3{1, 3, -3}));
    EXPECT_EQ(s.maxHeight, 6);
    EXPECT_DOUBLE_EQ(s.horizontalSpread, 2);
    EXPECT_EQ(s.clusterCount, 4u);
    EXPECT_EQ(s.largestClusterFraction, 0.25);
}

TEST(FrameStats, ThreeSeparatedChainsAreThreeClusters) {
    Globules g = chain({}, {0, 0, 0}, 5, 1.5, 1.0f, 0);
    g = chain(g, {0, 20, 0}, 3, 1.5, 1.0f, 100);
    g = chain(g, {0, 0, 20}, 2, 1.5, 1.0f, 200);
    const FrameStats s = computeFrameStats(g, 1, 0);
    EXPECT_EQ(s.clusterCount, 3u);
    EXPECT_EQ(s.largestClusterFraction, 0.5);
}

TEST(FrameStats, TouchingIsNotOverlapping) {
    const Globules touching = chain({}, {0, 0, 0}, 2, 2.0, 1.0f, 0);
    EXPECT_EQ(computeFrameStats(touching, 1, 0).clusterCount, 2u);
    Globules mixed;  // a small globule bridges two large ones only through overlap
    mixed.add({0, 0, 0}, {}, 2.0f, 1, 0);
    mixed.add({2.5, 0, 0}, {}, 0.75f, 1, 1);
    mixed.add({5, 0, 0}, {}, 2.0f, 1, 2);
    EXPECT_EQ(computeFrameStats(mixed, 1, 0).clusterCount, 1u);
}

TEST(FrameStats, LongChainIsOneCluster) {
    const Globules g = chain({}, {-50, 3, 7}, 200, 1.9, 1.0f, 0);
    const FrameStats s = computeFrameStats(g, 1, 0);
    EXPECT_EQ(s.clusterCount, 1u);
    EXPECT_EQ(s.largestClusterFraction, 1.0);
}

TEST(FrameStats, ClustersMatchBruteForce) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> pos(0, 40), rad(0.2f, 1.2f);
    Globules g;
    for (int i = 0; i < 2000; ++i) g.add({pos(rng), pos(rng), pos(rng)}, {}, rad(rng), 1, i);
    EXPECT_EQ(computeFrameStats(g, 1, 0).clusterCount, bruteForceClusters(g));
}

TEST(FrameStats, NonFinitePositionIsAClusterOfItsOwn) {
    Globules g = chain({}, {0, 0, 0}, 3, 1.0, 1.0f, 0);
    g.add({NAN, 0, 0}, {}, 1.0f, 1, 9);
    const FrameStats s = computeFrameStats(g, 1, 0);
    EXPECT_EQ(s.clusterCount, 2u);
    EXPECT_EQ(s.largestClusterFraction, 0.75);
    EXPECT_TRUE(std::isnan(s.centroid.x));
}

class StatsCsvTest : public testing::Test {
  protected:
    void SetUp() override {
        mPath = fs::path(testing::TempDir()) /
                ("frame_stats_" + std::to_string(::getpid()) + "_" +
                 testing::UnitTest::GetInstance()->current_test_info()->name() + ".csv");
    }
    void TearDown() override { fs::remove(mPath); }
    void write(const std::string& text) { std::ofstream(mPath) << text; }
    fs::path mPath;
};

TEST_F(StatsCsvTest, HeaderNamesEveryColumn) {
    EXPECT_EQ(statsCsvHeader(),
              "frame,time,count,kinetic_energy,max_speed,centroid_x,centroid_y,centroid_z,"
              "max_height,horizontal_spread,cluster_count,largest_cluster_fraction");
}

TEST_F(StatsCsvTest, RowsRoundTrip) {
    Globules g = chain({}, {0.1, 0.2, 0.3}, 5, 1.5, 1.0f, 0);
    g.vx[2] = 1.0f / 3.0f;
    const FrameStats a = computeFrameStats(g, 7, 0.007);
    FrameStats b;
    b.frame = 8;
    b.maxSpeed = INFINITY;
    write(statsCsvHeader() + "\n" + statsCsvRow(a) + "\r\n\n" + statsCsvRow(b) + "\n");
    const std::vector<FrameStats> rows = readStatsCsv(mPath);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].frame, 7);
    EXPECT_EQ(rows[0].time, 0.007);
    EXPECT_EQ(rows[0].count, 5u);
    EXPECT_NEAR(rows[0].kineticEnergy, a.kineticEnergy, 1e-9 * a.kineticEnergy);
    EXPECT_NEAR(rows[0].centroid.x, a.centroid.x, 1e-8);
    EXPECT_EQ(rows[0].clusterCount, 1u);
    EXPECT_EQ(rows[0].largestClusterFraction, 1.0);
    EXPECT_EQ(rows[1].frame, 8);
    EXPECT_EQ(rows[1].maxSpeed, INFINITY);
}

TEST_F(StatsCsvTest, BadRowsNameFileAndLine) {
    const std::string row = statsCsvRow(FrameStats{});
    const auto expectError = [&](const std::string& text, const std::string& where) {
        write(text);
        try {
            readStatsCsv(mPath);
            ADD_FAILURE() << "no IoError for " << text;
        } catch (const IoError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(mPath.string()), std::string::npos) << what;
            EXPECT_NE(what.find(where), std::string::npos) << what;
        }
    };
    expectError(statsCsvHeader() + "\n" + row + "\n1,2,3\n", "line 3");
    expectError(statsCsvHeader() + "\n" + row + "\n" + row + "\nx" + row + "\n", "line 4");
    expectError("frame,time\n", "line 1: missing column count");
    expectError("", "no header");
    fs::remove(mPath);
    EXPECT_THROW(readStatsCsv(mPath), IoError);
}

}  // namespace
}  // namespace globular
