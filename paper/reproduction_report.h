#pragma once
// What `globular figures` measured, and REPRODUCTION.md / metrics.csv made from it.
// Pure text generation: the records are filled by figures_command.cpp.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "fig2_plot.h"
#include "outcome_metrics.h"
#include "paper_experiments.h"

namespace globular {

/// One experiment's run and its judgement.
struct RunRecord {
    const Experiment* experiment = nullptr;
    std::filesystem::path dir;           ///< DIR/<id>
    std::string scenePath;               ///< as given to runScene
    std::vector<std::string> overrides;  ///< frames, scale and row overrides, in order
    int frames = 0;                      ///< simulation.frames of the run
    std::string command;                 ///< the command line that repeats the run
    bool measured = false;               ///< stats.csv was read
    OutcomeMetrics metrics;
    std::string explosion;  ///< the SimulationError message when the run exploded
    std::string failure;    ///< any other error that stopped the run
    double seconds = 0;     ///< wall time of the sim
    std::vector<CriterionResult> results;
    Verdict verdict = Verdict::NotReproduced;
};

/// One rendered figure.
struct StripRecord {
    const FigureStrip* strip = nullptr;
    std::filesystem::path image;  ///< relative to DIR; empty when missing
    std::vector<int> frames;      ///< frame numbers shown
    std::string message;          ///< why the image is missing
    std::string renderCommand;    ///< the command that rendered one of its frames
    double seconds = 0;           ///< wall time of its renders
};

/// Fig. 2: the plot and the paper's four statements about its curves.
struct Fig2Report {
    Fig2Output output;
    std::vector<ForceCurveSummary> narrow;  ///< C_r = r0 (plotted)
    std::vector<ForceCurveSummary> wide;    ///< C_r = 2 r0 (the solid's window)
    std::vector<std::pair<std::string, CriterionResult>> claims;
    Verdict verdict = Verdict::NotReproduced;
};

struct ReportContext {
    std::filesystem::path outDir;  ///< as the user gave it (commands name it)
    double scale = 1;
    int threads = 0;
    unsigned hardwareThreads = 0;
    double totalSeconds = 0;  ///< wall time of the whole command
    double cpuSeconds = 0;    ///< processor time of the whole command, all threads
    double loadAverage = -1;  ///< the machine's 1-minute load average at the end; < 0: unknown
};

/// @brief REPRODUCTION.md: summary of verdicts, how outcomes are measured, each figure
/// (images linked as figures/NAME.png relative to DIR), Tables 1-4 with the measured
/// metrics beside the best case, the unstated defaults side by side, the commands and
/// the timings.
std::string reproductionMarkdown(const ReportContext& context, const std::vector<RunRecord>& runs,
                                 const std::vector<StripRecord>& strips, const Fig2Report& fig2);

/// metrics.csv: one row per experiment, every metric, its verdict and wall time.
std::string metricsCsv(const std::vector<RunRecord>& runs);

}  // namespace globular
