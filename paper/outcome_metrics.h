#pragma once
// The outcome of one run, measured from its stats.csv rows, and the rules that turn a
// paper's claim ("more spill than the best case", "explodes apart", "collapses") into a
// verdict. Pure functions: no files, no simulation, so each rule is testable by hand.
//
// What the paper's words are measured with (`globular figures`, docs/REPRODUCTION.md):
//   spill, spread, disc .......... final horizontal spread (RMS x-z distance from the
//                                  centroid) and how fast it still grows at the end
//   tighter pour ................. the smallest horizontal spread over the run: the helix
//                                  column contracts while it falls, before the pile spreads
//   height, collapse, disc ....... final max height of a globule centre
//   clumping ..................... largest cluster fraction and cluster count (globules
//                                  connected when they overlap, distance < r_i + r_j); with
//                                  radius 1 and r0 = 1 resting neighbours overlap, so a
//                                  spilled monolayer is still one cluster: spread decides
//   settles, stabilises .......... time to settle (below)
//   explodes ..................... the run stopped early (the simulation's explosion check)
//                                  or a value is not finite

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "frame_stats.h"

namespace globular {

/// A run counts as settled from the first frame after which its kinetic energy stays
/// below this fraction of the run's peak kinetic energy (the peak is the pour's impact,
/// so this reads "moves with less than 0.1% of the energy it landed with").
inline constexpr double kSettleFraction = 1e-3;

/// The spill rate is measured over this last fraction of the run's duration.
inline constexpr double kSpreadRateWindow = 0.1;

struct OutcomeMetrics {
    int frames = 0;                     ///< rows measured (the last frame written)
    int expectedFrames = 0;             ///< frames the scene asked for
    double duration = 0;                ///< time of the last row, seconds
    std::size_t count = 0;              ///< globules in the last row
    double initialSpread = 0;           ///< horizontal spread of the first row, units
    double initialHeight = 0;           ///< max height of the first row, units
    double spread = 0;                  ///< final horizontal spread, units
    double pourSpread = 0;              ///< smallest horizontal spread over the run, units
    double spreadRate = 0;              ///< d(spread)/dt over the last kSpreadRateWindow, units/s
    double height = 0;                  ///< final max height of a globule centre, units
    double centroidHeight = 0;          ///< final centroid y, units
    double largestClusterFraction = 0;  ///< final, 0..1
    std::size_t clusterCount = 0;       ///< final
    double kineticEnergy = 0;           ///< final, sum of 0.5 m v^2
    double peakKineticEnergy = 0;       ///< largest over the run
    /// Time to settle, seconds (kSettleFraction); infinity when the run never settled.
    double settleTime = std::numeric_limits<double>::infinity();
    bool exploded = false;  ///< stopped before expectedFrames, or non-finite values

    bool settled() const { return settleTime != std::numeric_limits<double>::infinity(); }
};

/// @brief Measures a run from its stats rows (in frame order).
/// @param expectedFrames the frames the scene asked for: fewer rows mean the simulation
///        stopped early, which only an explosion does.
/// @throw Error when @p rows is empty.
OutcomeMetrics computeOutcome(const std::vector<FrameStats>& rows, int expectedFrames);

/// The quantities a criterion can compare.
enum class Metric {
    Spread,                  ///< final horizontal spread
    SpreadRate,              ///< spill speed at the end
    PourSpread,              ///< smallest spread over the run (how tight the pour got)
    Height,                  ///< final max height
    InitialSpread,           ///< horizontal spread of the first frame
    InitialHeight,           ///< max height of the first frame
    LargestClusterFraction,  ///< final
    ClusterCount,            ///< final
    KineticEnergy,           ///< final
    SettleTime,              ///< infinity when not settled
    Settled,                 ///< boolean
    Exploded,                ///< boolean
    Count,                   ///< globules
};

/// How the measured value must relate to the reference run's (or to a number).
enum class Expect {
    Less,     ///< value < reference * (1 - margin)
    More,     ///< value > reference * (1 + margin)
    Similar,  ///< |value - reference| <= margin * |reference|
    Below,    ///< value < margin (an absolute bound; no reference)
    Above,    ///< value > margin (an absolute bound; no reference)
    Near,     ///< |value - target| <= tolerance (absolute; target = margin, tolerance below)
    True,     ///< boolean metric set
    False,    ///< boolean metric clear
};

/// One measurable reading of a claim, e.g. {Spread, Less, 0.1, "", "less spill"}.
struct Criterion {
    Metric metric = Metric::Spread;
    Expect expect = Expect::Less;
    double margin = 0.1;    ///< relative for Less/More/Similar, absolute for Below/Above/Near
    std::string reference;  ///< experiment compared with; empty: the row's best case
    std::string meaning;    ///< the claim's words this stands for ("less spill")
    /// An exploded run passes (for "explode apart": a numerical explosion is the
    /// extreme of flying apart).
    bool explosionPasses = false;
    double tolerance = 0;  ///< for Near
};

struct CriterionResult {
    bool passed = false;
    std::string text;  ///< "spread 3.10 vs 4.20 (-26%): less spill: yes"
};

enum class Verdict { Reproduced, Partly, NotReproduced };

/// The metric's value; booleans as 0/1, infinity for a run that never settled.
double metricValue(const OutcomeMetrics& metrics, Metric metric);
/// Short name for tables: "spread", "settle time", ...
std::string metricName(Metric metric);

/// @brief Judges one criterion. @p reference may be null for Below/Above/Near/True/False.
/// @throw Error when a relative criterion has no reference.
CriterionResult judge(const Criterion& criterion, const OutcomeMetrics& value,
                      const OutcomeMetrics* reference);

/// Every criterion passed: Reproduced; some: Partly; none (or no criteria): NotReproduced.
Verdict overallVerdict(const std::vector<CriterionResult>& results);

std::string verdictText(Verdict verdict);  ///< "reproduced", "partly", "not reproduced"

/// A number for a Markdown table: 3 significant digits, "inf" / "-" as needed.
std::string formatNumber(double value);

}  // namespace globular
