// The table metrics of `globular figures` on hand-built globule sets and stats rows whose
// answers are known: a spread, a number of clusters, a settle time, an explosion; and the
// verdict rules that compare a row with its best case.

#include "outcome_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "errors.h"
#include "frame_stats.h"

namespace globular {
namespace {

/// A row measured from @p g at @p frame (25 fps), as the sim stage writes it.
FrameStats row(const Globules& g, int frame) {
    return computeFrameStats(g, frame, (frame - 1) / 25.0);
}

/// A row with only the fields the settle and spill rules read.
FrameStats synthetic(int frame, double kineticEnergy, double spread = 1.0) {
    FrameStats s;
    s.frame = frame;
    s.time = (frame - 1) / 25.0;
    s.count = 10;
    s.kineticEnergy = kineticEnergy;
    s.horizontalSpread = spread;
    return s;
}

TEST(OutcomeMetrics, KnownSpreadHeightAndClusters) {
    // Four resting globules on a circle of radius 3 around (5, *, -2): the x-z RMS
    // distance from the centroid is exactly 3; none overlaps (2 radii apart or more).
    Globules g;
    g.add({8, 0, -2}, {}, 1, 1, 0);
    g.add({2, 0, -2}, {}, 1, 1, 1);
    g.add({5, 0.5, 1}, {}, 1, 1, 2);
    g.add({5, 2.5, -5}, {}, 1, 1, 3);
    const OutcomeMetrics m = computeOutcome({row(g, 1), row(g, 2)}, 2);
    EXPECT_NEAR(m.spread, 3.0, 1e-6);
    EXPECT_NEAR(m.initialSpread, 3.0, 1e-6);
    EXPECT_NEAR(m.height, 2.5, 1e-6);
    EXPECT_NEAR(m.centroidHeight, 0.75, 1e-6);
    EXPECT_EQ(m.clusterCount, 4u);
    EXPECT_DOUBLE_EQ(m.largestClusterFraction, 0.25);
    EXPECT_EQ(m.count, 4u);
    EXPECT_FALSE(m.exploded);
    EXPECT_DOUBLE_EQ(m.kineticEnergy, 0.0);
}

TEST(OutcomeMetrics, OverlappingChainsAreClusters) {
    // Two chains of overlapping globules (1.5 apart, radius 1) far from each other, and a
    // lone globule: three clusters, the largest holding 4 of 8.
    Globules g;
    for (int k = 0; k < 4; ++k) g.add({1.5 * k, 0, 0}, {}, 1, 1, k);
    for (int k = 0; k < 3; ++k) g.add({1.5 * k, 0, 20}, {}, 1, 1, 10 + k);
    g.add({-20, 0, 0}, {}, 1, 1, 99);
    const OutcomeMetrics m = computeOutcome({row(g, 1)}, 1);
    EXPECT_EQ(m.clusterCount, 3u);
    EXPECT_DOUBLE_EQ(m.largestClusterFraction, 0.5);
}

TEST(OutcomeMetrics, FinalRowDecidesAndKineticEnergyIsMeasured) {
    Globules before, after;
    before.add({0, 10, 0}, {0, -3, 0}, 1, 2, 0);  // 0.5 * 2 * 9 = 9
    after.add({0, 0, 0}, {1, 0, 0}, 1, 2, 0);     // 0.5 * 2 * 1 = 1
    const OutcomeMetrics m = computeOutcome({row(before, 1), row(after, 2)}, 2);
    EXPECT_DOUBLE_EQ(m.kineticEnergy, 1.0);
    EXPECT_DOUBLE_EQ(m.peakKineticEnergy, 9.0);
    EXPECT_NEAR(m.initialHeight, 10.0, 1e-6);
    EXPECT_NEAR(m.height, 0.0, 1e-6);
}

TEST(OutcomeMetrics, SettleTimeIsWhenEnergyStaysBelowTheFraction) {
    // Peak 1000: the threshold is 1. Frame 4 dips below, frame 5 rises above, from frame 6
    // on it stays below: settled at frame 6's time.
    const std::vector<FrameStats> rows = {synthetic(1, 10),  synthetic(2, 1000), synthetic(3, 50),
                                          synthetic(4, 0.5), synthetic(5, 2),    synthetic(6, 0.9),
                                          synthetic(7, 0.2), synthetic(8, 0.999)};
    const OutcomeMetrics m = computeOutcome(rows, 8);
    ASSERT_TRUE(m.settled());
    EXPECT_DOUBLE_EQ(m.settleTime, 5 / 25.0);
    EXPECT_EQ(kSettleFraction, 1e-3);
}

TEST(OutcomeMetrics, NeverSettledWhenTheEndIsAboveTheThreshold) {
    const OutcomeMetrics m =
        computeOutcome({synthetic(1, 1000), synthetic(2, 0.1), synthetic(3, 5)}, 3);
    EXPECT_FALSE(m.settled());
    EXPECT_TRUE(std::isinf(m.settleTime));
    EXPECT_TRUE(std::isinf(metricValue(m, Metric::SettleTime)));
    EXPECT_EQ(metricValue(m, Metric::Settled), 0.0);
}

TEST(OutcomeMetrics, SpillRateOverTheLastTenthOfTheRun) {
    // Spread grows 2 units/s throughout: the rate is 2 whatever the window.
    std::vector<FrameStats> rows;
    for (int f = 1; f <= 101; ++f) rows.push_back(synthetic(f, 1, 2.0 * (f - 1) / 25.0));
    EXPECT_NEAR(computeOutcome(rows, 101).spreadRate, 2.0, 1e-9);
    // Still for the first 90%, then 5 units/s: only the end counts.
    rows.clear();
    for (int f = 1; f <= 101; ++f) {
        const double t = (f - 1) / 25.0;
        rows.push_back(synthetic(f, 1, t < 3.6 ? 1.0 : 1.0 + 5.0 * (t - 3.6)));
    }
    EXPECT_NEAR(computeOutcome(rows, 101).spreadRate, 5.0, 1e-9);
}

TEST(OutcomeMetrics, PourSpreadIsTheTightestTheColumnGot) {
    const OutcomeMetrics m = computeOutcome(
        {synthetic(1, 1, 1.0), synthetic(2, 1, 0.8), synthetic(3, 1, 0.7), synthetic(4, 1, 3.0)},
        4);
    EXPECT_DOUBLE_EQ(m.pourSpread, 0.7);
    EXPECT_DOUBLE_EQ(m.spread, 3.0);
    EXPECT_DOUBLE_EQ(metricValue(m, Metric::PourSpread), 0.7);
}

TEST(OutcomeMetrics, ExplodedWhenTheRunStopsEarlyOrValuesAreNotFinite) {
    const std::vector<FrameStats> early = {synthetic(1, 1), synthetic(2, 5e5)};
    EXPECT_TRUE(computeOutcome(early, 100).exploded);
    EXPECT_FALSE(computeOutcome(early, 2).exploded);
    EXPECT_EQ(computeOutcome(early, 100).frames, 2);

    std::vector<FrameStats> nan = {synthetic(1, 1), synthetic(2, 1), synthetic(3, 1)};
    nan[1].kineticEnergy = std::numeric_limits<double>::quiet_NaN();
    const OutcomeMetrics m = computeOutcome(nan, 3);
    EXPECT_TRUE(m.exploded);
    EXPECT_FALSE(m.settled());
    EXPECT_THROW(computeOutcome({}, 1), Error);
}

OutcomeMetrics withSpread(double spread) {
    OutcomeMetrics m;
    m.spread = spread;
    return m;
}

Criterion criterion(Metric metric, Expect expect, double margin) {
    Criterion c;
    c.metric = metric;
    c.expect = expect;
    c.margin = margin;
    c.meaning = "claim";
    return c;
}

TEST(OutcomeVerdict, LessAndMoreNeedTheMargin) {
    const OutcomeMetrics best = withSpread(10);
    const Criterion less = criterion(Metric::Spread, Expect::Less, 0.1);
    EXPECT_TRUE(judge(less, withSpread(8.9), &best).passed);
    EXPECT_FALSE(judge(less, withSpread(9.5), &best).passed);  // less, but within 10%
    const Criterion more = criterion(Metric::Spread, Expect::More, 0.1);
    EXPECT_TRUE(judge(more, withSpread(11.5), &best).passed);
    EXPECT_FALSE(judge(more, withSpread(10.5), &best).passed);
    const Criterion similar = criterion(Metric::Spread, Expect::Similar, 0.1);
    EXPECT_TRUE(judge(similar, withSpread(10.9), &best).passed);
    EXPECT_FALSE(judge(similar, withSpread(11.1), &best).passed);
    EXPECT_THROW(judge(less, withSpread(1), nullptr), Error);

    const CriterionResult r = judge(less, withSpread(8), &best);
    EXPECT_NE(r.text.find("spread 8 vs 10 (-20%)"), std::string::npos) << r.text;
    EXPECT_NE(r.text.find("claim: yes"), std::string::npos) << r.text;
}

TEST(OutcomeVerdict, AbsoluteBoundsBooleansAndExplosions) {
    OutcomeMetrics m = withSpread(3);
    m.count = 100;
    m.largestClusterFraction = 0.95;
    EXPECT_TRUE(
        judge(criterion(Metric::LargestClusterFraction, Expect::Above, 0.9), m, nullptr).passed);
    EXPECT_FALSE(
        judge(criterion(Metric::LargestClusterFraction, Expect::Below, 0.5), m, nullptr).passed);
    Criterion count = criterion(Metric::Count, Expect::Near, 100);
    EXPECT_TRUE(judge(count, m, nullptr).passed);
    count.margin = 101;
    EXPECT_FALSE(judge(count, m, nullptr).passed);
    count.tolerance = 1;
    EXPECT_TRUE(judge(count, m, nullptr).passed);

    EXPECT_TRUE(judge(criterion(Metric::Exploded, Expect::False, 0), m, nullptr).passed);
    EXPECT_THROW(judge(criterion(Metric::Spread, Expect::True, 0), m, nullptr), Error);
    m.exploded = true;
    EXPECT_TRUE(judge(criterion(Metric::Exploded, Expect::True, 0), m, nullptr).passed);

    // "Explode apart": a run that exploded passes a spread criterion it could not measure.
    const OutcomeMetrics best = withSpread(10);
    Criterion apart = criterion(Metric::Spread, Expect::More, 0.5);
    EXPECT_FALSE(judge(apart, m, &best).passed);
    apart.explosionPasses = true;
    EXPECT_TRUE(judge(apart, m, &best).passed);
    m.exploded = false;
    EXPECT_FALSE(judge(apart, m, &best).passed);
}

TEST(OutcomeVerdict, NotSettledCountsAsSlowest) {
    OutcomeMetrics never;  // settleTime is infinity
    OutcomeMetrics quick;
    quick.settleTime = 2;
    const Criterion sooner = criterion(Metric::SettleTime, Expect::Less, 0.1);
    EXPECT_TRUE(judge(sooner, quick, &never).passed);  // settling at all is sooner
    EXPECT_FALSE(judge(sooner, never, &quick).passed);
    EXPECT_TRUE(judge(criterion(Metric::SettleTime, Expect::More, 0.1), never, &quick).passed);
}

TEST(OutcomeVerdict, AllSomeOrNone) {
    CriterionResult yes{true, ""}, no{false, ""};
    EXPECT_EQ(overallVerdict({yes, yes}), Verdict::Reproduced);
    EXPECT_EQ(overallVerdict({yes, no}), Verdict::Partly);
    EXPECT_EQ(overallVerdict({no, no}), Verdict::NotReproduced);
    EXPECT_EQ(overallVerdict({}), Verdict::NotReproduced);
    EXPECT_EQ(verdictText(Verdict::Partly), "partly");
}

TEST(OutcomeVerdict, NumbersForTables) {
    EXPECT_EQ(formatNumber(3), "3");
    EXPECT_EQ(formatNumber(3.14159), "3.14");
    EXPECT_EQ(formatNumber(1234567.0), "1.23e+06");
    EXPECT_EQ(formatNumber(std::numeric_limits<double>::infinity()), "never");
    EXPECT_EQ(formatNumber(std::numeric_limits<double>::quiet_NaN()), "-");
}

}  // namespace
}  // namespace globular
