#pragma once
// `globular figures`: regenerate every figure and table of the paper and write
// DIR/REPRODUCTION.md, which sets the paper's claims beside the measured numbers with a
// verdict for each (paper_experiments.h lists them; outcome_metrics.h measures them).
//
// DIR after a run:
//   REPRODUCTION.md          the report; images linked relatively (figures/...)
//   metrics.csv              one row per experiment: the measured outcome and verdict
//   figures/*.png            contact sheets of Fig. 1, 3-7; fig2_force.png (gnuplot)
//   figures/fig2_force.csv   the data of Fig. 2 (and fig2_force.gp, its script)
//   <experiment id>/         each run: scene.toml, stats.csv, cache/, frames/ (strips only)

#include <filesystem>
#include <string>
#include <vector>

namespace globular {

class Reporter;

struct FiguresOptions {
    std::filesystem::path outDir = "out/figures";
    /// (0, 1]: 1 is the paper's sizes (200/400 globules, 250-frame table runs, 640x360
    /// frames); smaller shrinks frames, globule counts and pixels (for tests). Verdicts
    /// are only meaningful at 1.
    double scale = 1.0;
    int threads = 0;  ///< 0 = all cores
    /// Where the paper's scenes are; empty: ./scenes/paper when it exists, else the
    /// source tree's scenes/paper (compiled in).
    std::filesystem::path scenesDir;
};

/// The artefacts a run writes under DIR (relative paths), for callers and tests:
/// REPRODUCTION.md, metrics.csv, every figure image and the Fig. 2 CSV.
std::vector<std::filesystem::path> figuresArtefacts();

/// @brief Runs every experiment and figure, and writes DIR/REPRODUCTION.md.
/// A failed render is reported in the report (the strip is missing) and as a warning;
/// an experiment that cannot run (other than by exploding, which is a result) is too.
/// @throw SceneError for bad options; Error at the end when an experiment failed to run
///        or a figure is missing, after the report was written.
void runFigures(const FiguresOptions& options, Reporter& reporter);

}  // namespace globular
