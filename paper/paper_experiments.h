#pragma once
// The paper's experiments as data: every table row and figure of Miller & Pearce (as
// re-implemented in ../shared/paper/) with the scene it runs, the --set overrides that
// make the row, the paper's words, and the measurable criteria its verdict is judged by
// (outcome_metrics.h). `globular figures` runs them; docs/REPRODUCTION.md reports them.

#include <string>
#include <vector>

#include "outcome_metrics.h"

namespace globular {

/// Frames of a table row's run: 10 s at 25 fps, so the 400-globule pour (about 5 s to
/// land) has time to settle and "final" means the end state, not the pour.
inline constexpr int kTableFrames = 250;

/// A criterion measured on a run other than the row itself (Fig. 4's dt = 0.001 side).
struct SubjectCriterion {
    std::string subject;  ///< experiment measured; empty: this row
    Criterion criterion;
};

struct Experiment {
    std::string id;                      ///< output folder name and key, e.g. "table1_r0_2"
    std::string section;                 ///< "Table 1", "Table 4", "Fig. 4", ...
    std::string label;                   ///< the row's values as the paper writes them
    std::string scene;                   ///< file in scenes/paper/
    std::vector<std::string> overrides;  ///< --set KEY=VALUE making this row
    int frames = kTableFrames;           ///< simulation.frames; 0 = the scene's own
    std::string claim;                   ///< the paper's words for this row
    std::string bestCase;                ///< default reference of the criteria; empty = none
    std::vector<SubjectCriterion> criteria;
    std::string note;  ///< what the variant tests, when it is one
};

/// A figure made of rendered frames (a contact sheet of evenly spaced frames).
struct FigureStrip {
    std::string id;     ///< image name, "fig1_liquid"
    std::string title;  ///< "Fig. 1: ..."
    std::string claim;  ///< the paper's caption or text
    /// Experiments shown, one sheet row each at the same frame numbers (Fig. 4: two).
    std::vector<std::string> experiments;
    std::vector<std::string> rowLabels;  ///< one per experiment, for the report
    int tiles = 6;                       ///< frames per experiment
    int columns = 3;  ///< tiles per sheet row (a multiple of tiles keeps rows apart)
    /// Experiment whose verdict the figure shares (its criteria judge the figure).
    std::string verdictFrom;
    int firstFrame = 1;             ///< frames shown are evenly spaced over [firstFrame, lastFrame]
    int lastFrame = 0;              ///< 0: the last frame every run of the strip wrote
    std::vector<int> frames;        ///< explicit frames instead (scaled like the run's length)
    bool autoCamera = false;        ///< frame each frame automatically, not the fixed camera
    std::vector<std::string> look;  ///< further --set overrides of the render
};

/// Every experiment, in report order: Table 4's best cases first (the references).
const std::vector<Experiment>& paperExperiments();

/// The rendered figures (Fig. 1, 3, 4, 5, 6, 7); Fig. 2 is a plot (fig2_plot.h).
const std::vector<FigureStrip>& paperFigureStrips();

/// Runs to set side by side in the report: a paper default (first) and its variants
/// (the r0 = 2 readings of C_r, the ground contact, Fig. 4's integrator and ground).
const std::vector<std::vector<std::string>>& paperVariantGroups();

/// Render settings of the strips, as --set overrides (size, spheres, fixed ground checker).
/// @param scale shrinks the image (reduced sizes for tests).
std::vector<std::string> stripRenderOverrides(double scale);

/// The fixed camera of the strips: low, looking at the pile, the pour entering from above.
std::vector<std::string> stripCameraOverrides();

/// @return the experiment with @p id. @throw Error when there is none.
const Experiment& findExperiment(const std::string& id);

}  // namespace globular
