#include "frame_stats.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
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

/// Cluster sizes by brute force over all pairs, largest first, for comparison with the grid.
std::vector<std::size_t> bruteForceClusterSizes(const Globules& g) {
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
    std::vector<std::size_t> sizeOf(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i) ++sizeOf[find(i)];
    std::erase(sizeOf, 0);
    std::sort(sizeOf.rbegin(), sizeOf.rend());
    return sizeOf;
}

std::size_t bruteForceClusters(const Globules& g) { return bruteForceClusterSizes(g).size(); }

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

/// Radii close together (the usual case) take small cells whose globules all overlap;
/// the count and the largest cluster must still be those of every pair. Dense enough
/// that clusters grow long and branch (near percolation), and at a uniform radius, and
/// far from the origin.
TEST(FrameStats, ClustersOfCloseRadiiMatchBruteForce) {
    struct Case {
        float smallest, largest, box;
        double offset;
    };
    for (const Case& c : {Case{0.5f, 0.5f, 12, 0}, Case{0.8f, 1.0f, 22, 0},
                          Case{0.45f, 0.5f, 12, -3000}, Case{0.5f, 0.5f, 6, 0}}) {
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> pos(0, c.box), rad(c.smallest, c.largest);
        Globules g;
        for (int i = 0; i < 2000; ++i) {
            g.add(Vec3{pos(rng) + c.offset, pos(rng), pos(rng) - c.offset}, {}, rad(rng), 1, i);
        }
        const std::vector<std::size_t> expected = bruteForceClusterSizes(g);
        const FrameStats s = computeFrameStats(g, 1, 0);
        EXPECT_EQ(s.clusterCount, expected.size()) << c.smallest << " box " << c.box;
        EXPECT_EQ(s.largestClusterFraction, double(expected.front()) / 2000.0)
            << c.smallest << " box " << c.box;
        // Not a trivial case: several clusters, and the largest of more than a few.
        if (c.box > 6) {
            EXPECT_GT(expected.size(), 20u);
            EXPECT_GT(expected.front(), 20u);
        } else {
            EXPECT_EQ(expected.size(), 1u);  // packed: one cluster
        }
    }
}

/// A cubic lattice a hair wider than the globules is 1000 clusters of one, a hair
/// narrower is one cluster, along the axes and with the lattice turned.
TEST(FrameStats, LatticeJustApartOrJustTouchingIsExact) {
    for (double spacing : {1.001, 0.999}) {
        for (bool turned : {false, true}) {
            Globules g;
            for (int i = 0; i < 1000; ++i) {
                const Vec3 p{spacing * (i % 10), spacing * (i / 10 % 10), spacing * (i / 100)};
                // Turned 45 degrees about y, then 35.26 about x: the lattice's diagonals
                // lie along the axes of the cells.
                const double c1 = std::sqrt(0.5), c2 = std::sqrt(2.0 / 3.0);
                const double s2 = std::sqrt(1.0 / 3.0);
                const Vec3 a{c1 * p.x + c1 * p.z, p.y, -c1 * p.x + c1 * p.z};
                const Vec3 b{a.x, c2 * a.y - s2 * a.z, s2 * a.y + c2 * a.z};
                g.add(turned ? b + Vec3{5, 5, 5} : p, {}, 0.5f, 1, i);
            }
            EXPECT_EQ(computeFrameStats(g, 1, 0).clusterCount, spacing > 1 ? 1000u : 1u)
                << spacing << (turned ? " turned" : "");
        }
    }
}

/// Compact clumps, dense enough that the statistics group globules by small cells (as
/// in a settled pile), side by side across gaps from well apart to overlapping, with a
/// few loose globules between: the count and the largest cluster of every pair.
TEST(FrameStats, DenseClumpsMatchBruteForce) {
    for (float radius : {0.5f, 0.45f}) {
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> in(0, 2.5f), jitter(-0.5f, 0.5f);
        Globules g;
        float x = 0;
        int id = 0;
        for (float gap : {0.6f, 0.95f, 1.0f, 1.05f, 1.5f, 0.8f}) {
            for (int k = 0; k < 300; ++k) {
                g.add({x + in(rng), in(rng), in(rng)}, {}, radius + 0.05f * jitter(rng), 1, id++);
            }
            g.add({x + 2.5 + 0.5 * gap, 6 + jitter(rng), 0}, {}, radius, 1, id++);  // loose
            x += 2.5f + gap;
        }
        const std::vector<std::size_t> expected = bruteForceClusterSizes(g);
        const FrameStats s = computeFrameStats(g, 1, 0);
        EXPECT_EQ(s.clusterCount, expected.size()) << radius;
        EXPECT_EQ(s.largestClusterFraction, double(expected.front()) / double(g.size())) << radius;
        EXPECT_GT(expected.size(), 8u);  // the loose ones and some clumps apart
        EXPECT_GE(expected.front(), 600u);  // and some clumps joined
    }
}

/// Two dense lattices (2-3 globules to a statistics cell, as in a settled pile), their
/// facing globules a hair farther apart than touching or a hair closer: two clusters or
/// one, along the axes and turned.
TEST(FrameStats, DenseLatticesJustApartOrJustTouchingAreExact) {
    for (double gap : {1.001, 0.999}) {
        for (bool turned : {false, true}) {
            Globules g;
            for (int i = 0; i < 1024; ++i) {
                const int k = i % 512;
                const double shift = i < 512 ? 0 : 7 * 0.4 + gap;
                const Vec3 p{0.4 * (k % 8) + shift, 0.4 * (k / 8 % 8), 0.4 * (k / 64)};
                // Turned so that the gap runs along a cell's diagonal, where a cell of
                // the right size just cannot hold both sides of it.
                const Vec3 e1 = Vec3{1, 1, 1} * (1 / std::sqrt(3.0)),
                           e2 = Vec3{1, -1, 0} * (1 / std::sqrt(2.0)),
                           e3 = Vec3{1, 1, -2} * (1 / std::sqrt(6.0));
                const Vec3 t = e1 * p.x + e2 * p.y + e3 * p.z;
                g.add(turned ? t + Vec3{3, 3, 3} : p, {}, 0.5f, 1, i);
            }
            const FrameStats s = computeFrameStats(g, 1, 0);
            EXPECT_EQ(s.clusterCount, gap > 1 ? 2u : 1u) << gap << (turned ? " turned" : "");
            EXPECT_EQ(s.largestClusterFraction, gap > 1 ? 0.5 : 1.0);
        }
    }
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
