#pragma once
// Fig. 2 of the paper: the radial (repulsion/attraction) force between two globules
// against their distance, for (m, n) = (5,3), (10,3), (5,1), (5,4). The values come
// from the simulation's own PairForce (sim/pair_force.h), so the plot is the code's
// force, window S_r included. Written as CSV, plotted to PNG with gnuplot when it is
// installed, and summarised (depth and place of the attraction dip, its reach, the
// repulsion near contact) so the paper's statements about the curves can be checked.

#include <filesystem>
#include <string>
#include <vector>

namespace globular {

struct ForceCurveSpec {
    std::string label;  ///< "A", "B", ...
    double m = 5, n = 3;
};

/// The paper's four curves, A-D.
std::vector<ForceCurveSpec> paperForceCurves();

struct Fig2Settings {
    double b1 = 2.0;           ///< radial strength (the best liquid's and powder's)
    double r0 = 1.0;           ///< rest distance, world units
    double radius = 1.0;       ///< each globule's radius, world units
    double cr = 1.0;           ///< radial window C_r as a number (C_r = r0: liquid, powder)
    double minDistance = 0.6;  ///< plotted range, world units
    double maxDistance = 2.2;
    int samples = 321;  ///< distances from min to max inclusive
};

/// The radial force along the line of centres, positive = repulsive, at rest (V = 0).
struct ForceCurve {
    ForceCurveSpec spec;
    std::vector<double> distance;  ///< world units
    std::vector<double> force;     ///< force units (mass 1: acceleration)
};

/// What the paper says about the curves is measured with these.
struct ForceCurveSummary {
    ForceCurveSpec spec;
    double dipForce = 0;        ///< most attractive (negative) force
    double dipDistance = 0;     ///< where it is
    double halfReach = 0;       ///< distance beyond the dip where attraction is back to half
                                ///< the dip (the window end when it never is)
    double attractionArea = 0;  ///< integral of the attractive part (work to pull apart)
    double forceAt08 = 0;       ///< repulsion at D = 0.8 r0 (steepness near contact)
};

/// @brief Samples the code's pair force (PairForce::accumulate) for @p spec.
ForceCurve sampleForceCurve(const ForceCurveSpec& spec, const Fig2Settings& settings);

/// @brief Measures @p spec on a fine grid over (0.5 r0, window end].
ForceCurveSummary summarizeForceCurve(const ForceCurveSpec& spec, const Fig2Settings& settings);

struct Fig2Output {
    std::filesystem::path csv;     ///< always written
    std::filesystem::path script;  ///< the gnuplot script, always written
    std::filesystem::path png;     ///< empty when gnuplot is missing or failed
    std::string message;           ///< why the PNG is missing; empty otherwise
};

/// @brief Writes DIR/fig2_force.csv (distance, then one column per curve) and
/// DIR/fig2_force.gp, and runs gnuplot (std::system) to make DIR/fig2_force.png of
/// @p widthPx x @p heightPx. A missing gnuplot is not an error: the message says so.
/// @throw IoError naming the file when the CSV or script cannot be written.
Fig2Output writeFig2(const std::filesystem::path& dir, const Fig2Settings& settings, int widthPx,
                     int heightPx);

}  // namespace globular
