#include "outcome_metrics.h"

#include <cmath>
#include <cstdio>

#include "errors.h"

namespace globular {

namespace {

bool finiteRow(const FrameStats& row) {
    return std::isfinite(row.kineticEnergy) && std::isfinite(row.maxSpeed) &&
           std::isfinite(row.maxHeight) && std::isfinite(row.horizontalSpread) &&
           std::isfinite(row.centroid.x) && std::isfinite(row.centroid.y) &&
           std::isfinite(row.centroid.z);
}

bool isBoolean(Metric metric) { return metric == Metric::Settled || metric == Metric::Exploded; }

std::string percent(double value, double reference) {
    if (reference == 0 || !std::isfinite(value) || !std::isfinite(reference)) return "";
    char text[32];
    std::snprintf(text, sizeof text, " (%+.0f%%)", 100.0 * (value / reference - 1.0));
    return text;
}

}  // namespace

OutcomeMetrics computeOutcome(const std::vector<FrameStats>& rows, int expectedFrames) {
    if (rows.empty()) throw Error("computeOutcome: the run has no stats rows");
    OutcomeMetrics out;
    const FrameStats& first = rows.front();
    const FrameStats& last = rows.back();
    out.frames = last.frame;
    out.expectedFrames = expectedFrames;
    out.duration = last.time;
    out.count = last.count;
    out.initialSpread = first.horizontalSpread;
    out.initialHeight = first.maxHeight;
    out.spread = last.horizontalSpread;
    out.height = last.maxHeight;
    out.centroidHeight = last.centroid.y;
    out.largestClusterFraction = last.largestClusterFraction;
    out.clusterCount = last.clusterCount;
    out.kineticEnergy = last.kineticEnergy;

    bool finite = true;
    out.pourSpread = first.horizontalSpread;
    for (const FrameStats& row : rows) {
        if (row.horizontalSpread < out.pourSpread) out.pourSpread = row.horizontalSpread;
        finite = finite && finiteRow(row);
        if (std::isfinite(row.kineticEnergy) && row.kineticEnergy > out.peakKineticEnergy) {
            out.peakKineticEnergy = row.kineticEnergy;
        }
    }
    out.exploded = !finite || last.frame < expectedFrames;

    // Settled from the first row after which every row stays below the threshold.
    if (!out.exploded) {
        const double threshold = kSettleFraction * out.peakKineticEnergy;
        std::size_t since = rows.size();
        for (std::size_t i = rows.size(); i-- > 0;) {
            if (!(rows[i].kineticEnergy < threshold)) break;
            since = i;
        }
        if (since < rows.size()) out.settleTime = rows[since].time;
    }

    // Spill rate over the run's last kSpreadRateWindow of time.
    const double windowStart = last.time - kSpreadRateWindow * (last.time - first.time);
    std::size_t from = rows.size() - 1;
    while (from > 0 && rows[from - 1].time >= windowStart) --from;
    if (from == rows.size() - 1 && from > 0) --from;  // at least two rows apart
    if (last.time > rows[from].time) {
        out.spreadRate =
            (last.horizontalSpread - rows[from].horizontalSpread) / (last.time - rows[from].time);
    }
    return out;
}

double metricValue(const OutcomeMetrics& m, Metric metric) {
    switch (metric) {
        case Metric::Spread:
            return m.spread;
        case Metric::SpreadRate:
            return m.spreadRate;
        case Metric::PourSpread:
            return m.pourSpread;
        case Metric::Height:
            return m.height;
        case Metric::InitialSpread:
            return m.initialSpread;
        case Metric::InitialHeight:
            return m.initialHeight;
        case Metric::LargestClusterFraction:
            return m.largestClusterFraction;
        case Metric::ClusterCount:
            return double(m.clusterCount);
        case Metric::KineticEnergy:
            return m.kineticEnergy;
        case Metric::SettleTime:
            return m.settleTime;
        case Metric::Settled:
            return m.settled() ? 1.0 : 0.0;
        case Metric::Exploded:
            return m.exploded ? 1.0 : 0.0;
        case Metric::Count:
            return double(m.count);
    }
    return 0;
}

std::string metricName(Metric metric) {
    switch (metric) {
        case Metric::Spread:
            return "spread";
        case Metric::SpreadRate:
            return "spill rate";
        case Metric::PourSpread:
            return "pour spread";
        case Metric::Height:
            return "height";
        case Metric::InitialSpread:
            return "initial spread";
        case Metric::InitialHeight:
            return "initial height";
        case Metric::LargestClusterFraction:
            return "largest cluster";
        case Metric::ClusterCount:
            return "clusters";
        case Metric::KineticEnergy:
            return "final KE";
        case Metric::SettleTime:
            return "settle time";
        case Metric::Settled:
            return "settled";
        case Metric::Exploded:
            return "exploded";
        case Metric::Count:
            return "globules";
    }
    return "?";
}

CriterionResult judge(const Criterion& c, const OutcomeMetrics& value,
                      const OutcomeMetrics* reference) {
    const double v = metricValue(value, c.metric);
    const std::string name = metricName(c.metric);
    CriterionResult result;
    std::string comparison;
    switch (c.expect) {
        case Expect::Less:
        case Expect::More:
        case Expect::Similar: {
            if (!reference) throw Error("criterion '" + c.meaning + "' needs a reference run");
            const double r = metricValue(*reference, c.metric);
            if (c.expect == Expect::Less) {
                result.passed = v < r * (1.0 - c.margin);
            } else if (c.expect == Expect::More) {
                result.passed = v > r * (1.0 + c.margin);
            } else {
                result.passed = std::fabs(v - r) <= c.margin * std::fabs(r);
            }
            const std::string op = c.expect == Expect::Less   ? "< "
                                   : c.expect == Expect::More ? "> "
                                                              : "within ";
            const std::string bound =
                c.expect == Expect::Similar
                    ? formatNumber(100 * c.margin) + "% of"
                    : formatNumber(c.expect == Expect::Less ? 1 - c.margin : 1 + c.margin) + " x";
            comparison = name + " " + formatNumber(v) + " vs " + formatNumber(r) + percent(v, r) +
                         " [" + op + bound + " ref]";
            break;
        }
        case Expect::Below:
            result.passed = v < c.margin;
            comparison = name + " " + formatNumber(v) + " [< " + formatNumber(c.margin) + "]";
            break;
        case Expect::Above:
            result.passed = v > c.margin;
            comparison = name + " " + formatNumber(v) + " [> " + formatNumber(c.margin) + "]";
            break;
        case Expect::Near:
            result.passed = std::fabs(v - c.margin) <= c.tolerance;
            comparison = name + " " + formatNumber(v) + " [" + formatNumber(c.margin) + " +- " +
                         formatNumber(c.tolerance) + "]";
            break;
        case Expect::True:
        case Expect::False: {
            if (!isBoolean(c.metric))
                throw Error("criterion '" + c.meaning + "': " + name + " is not a yes/no metric");
            const bool set = v != 0;
            result.passed = c.expect == Expect::True ? set : !set;
            comparison = name + " " + (set ? "yes" : "no");
            break;
        }
    }
    if (!result.passed && c.explosionPasses && value.exploded) {
        result.passed = true;
        comparison += ", but the run exploded";
    }
    result.text = comparison + ": " + c.meaning + ": " + (result.passed ? "yes" : "no");
    return result;
}

Verdict overallVerdict(const std::vector<CriterionResult>& results) {
    std::size_t passed = 0;
    for (const auto& r : results) passed += r.passed;
    if (results.empty() || passed == 0) return Verdict::NotReproduced;
    return passed == results.size() ? Verdict::Reproduced : Verdict::Partly;
}

std::string verdictText(Verdict verdict) {
    switch (verdict) {
        case Verdict::Reproduced:
            return "reproduced";
        case Verdict::Partly:
            return "partly";
        case Verdict::NotReproduced:
            return "not reproduced";
    }
    return "?";
}

std::string formatNumber(double value) {
    if (std::isnan(value)) return "-";
    if (std::isinf(value)) return value > 0 ? "never" : "-inf";
    char text[32];
    const double magnitude = std::fabs(value);
    if (value == std::floor(value) && magnitude < 1e6) {
        std::snprintf(text, sizeof text, "%.0f", value);
    } else if (magnitude >= 1e5 || magnitude < 1e-3) {
        std::snprintf(text, sizeof text, "%.2e", value);
    } else {
        std::snprintf(text, sizeof text, "%.3g", value);
    }
    return text;
}

}  // namespace globular
