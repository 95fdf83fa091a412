#include "figures_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <map>
#include <thread>

#include "atomic_file.h"
#include "contact_sheet.h"
#include "errors.h"
#include "fig2_plot.h"
#include "frame_paths.h"
#include "frame_stats.h"
#include "outcome_metrics.h"
#include "paper_experiments.h"
#include "reporter.h"
#include "reproduction_report.h"
#include "run_command.h"
#include "scene.h"

#ifndef GLOBULAR_PAPER_SCENES_DIR
#define GLOBULAR_PAPER_SCENES_DIR "scenes/paper"
#endif

namespace globular {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kSheetWidth = 768;  // pixels: contact sheets stay small enough for docs/

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Passes warnings on, prefixed with the experiment; drops the inner runs' chatter.
class PrefixReporter final : public Reporter {
  public:
    PrefixReporter(Reporter& outer, std::string prefix)
        : mOuter(outer), mPrefix(std::move(prefix)) {}
    void info(std::string_view) override {}
    void warn(std::string_view message) override {
        mOuter.warn(mPrefix + ": " + std::string(message));
    }
    void progress(std::string_view, long, long) override {}

  private:
    Reporter& mOuter;
    std::string mPrefix;
};

std::string joinCommand(const std::string& scene, const fs::path& dir, const std::string& stages,
                        const std::string& frames, const std::vector<std::string>& overrides) {
    std::string text = "globular run scenes/paper/" + scene + " --stages " + stages;
    if (!frames.empty()) text += " --frames " + frames;
    text += " --out " + dir.string();
    for (const auto& o : overrides) {
        const bool plain = o.find_first_of(" []\"'") == std::string::npos;
        text += " --set " + (plain ? o : "'" + o + "'");
    }
    return text;
}

fs::path scenesDirectory(const FiguresOptions& options) {
    if (!options.scenesDir.empty()) return options.scenesDir;
    if (fs::exists("scenes/paper/liquid.toml")) return "scenes/paper";
    return GLOBULAR_PAPER_SCENES_DIR;
}

/// Frames of the run and the overrides that make a row at @p scale.
void planRun(RunRecord& run, const fs::path& scenes, double scale) {
    const Experiment& e = *run.experiment;
    run.scenePath = (scenes / e.scene).string();
    NullReporter quiet;
    const Scene scene = loadScene(run.scenePath, e.overrides, quiet);
    const int sceneFrames = e.frames > 0 ? e.frames : int(scene.simulation.frames);
    run.frames = scale < 1.0 ? std::max(3, int(std::lround(sceneFrames * scale))) : sceneFrames;
    if (e.frames > 0 || run.frames != sceneFrames) {
        run.overrides.push_back("simulation.frames=" + std::to_string(run.frames));
    }
    if (scale < 1.0) {
        for (std::size_t i = 0; i < scene.emitters.size(); ++i) {
            const long count = std::max(8L, std::lround(double(scene.emitters[i].count) * scale));
            run.overrides.push_back("emitter." + std::to_string(i) +
                                    ".count=" + std::to_string(count));
        }
    }
    run.overrides.insert(run.overrides.end(), e.overrides.begin(), e.overrides.end());
}

void runExperiment(RunRecord& run, const FiguresOptions& options, Reporter& reporter) {
    const Experiment& e = *run.experiment;
    std::error_code ignored;
    fs::remove_all(run.dir, ignored);  // our own folder: no stale frames from earlier runs
    RunOptions ro;
    ro.scene = run.scenePath;
    ro.outDir = run.dir;
    ro.stages = {"sim"};
    ro.threads = options.threads;
    ro.overrides = run.overrides;
    PrefixReporter inner(reporter, e.id);
    const auto start = Clock::now();
    try {
        runScene(ro, inner);
    } catch (const SimulationError& error) {
        run.explosion = error.what();
    } catch (const SceneError&) {
        throw;  // a bad experiment definition is a bug, not a result
    } catch (const std::exception& error) {
        run.failure = error.what();
    }
    run.seconds = secondsSince(start);
    const fs::path stats = run.dir / "stats.csv";
    if (run.failure.empty() || fs::exists(stats)) {
        try {
            run.metrics = computeOutcome(readStatsCsv(stats), run.frames);
            run.measured = true;
        } catch (const std::exception& error) {
            if (run.failure.empty()) run.failure = error.what();
        }
    }
}

void judgeAll(std::vector<RunRecord>& runs) {
    std::map<std::string, const RunRecord*> byId;
    for (const auto& r : runs) byId[r.experiment->id] = &r;
    const auto measured = [&](const std::string& id) -> const OutcomeMetrics* {
        const auto it = byId.find(id);
        if (it == byId.end()) throw Error("experiment '" + id + "' is not defined");
        return it->second->measured ? &it->second->metrics : nullptr;
    };
    for (auto& run : runs) {
        for (const auto& sc : run.experiment->criteria) {
            const std::string subjectId = sc.subject.empty() ? run.experiment->id : sc.subject;
            const std::string refId =
                sc.criterion.reference.empty() ? run.experiment->bestCase : sc.criterion.reference;
            const OutcomeMetrics* subject = measured(subjectId);
            const OutcomeMetrics* reference = refId.empty() ? nullptr : measured(refId);
            const bool relative = sc.criterion.expect == Expect::Less ||
                                  sc.criterion.expect == Expect::More ||
                                  sc.criterion.expect == Expect::Similar;
            CriterionResult result;
            if (!subject || (relative && !reference)) {
                result.text = sc.criterion.meaning + ": not measured (a run failed)";
            } else {
                result = judge(sc.criterion, *subject, relative ? reference : nullptr);
                if (subjectId != run.experiment->id) result.text = subjectId + ": " + result.text;
            }
            run.results.push_back(result);
        }
        run.verdict = overallVerdict(run.results);
    }
}

StripRecord renderStrip(const FigureStrip& strip, const std::vector<RunRecord>& runs,
                        const FiguresOptions& options, const fs::path& figuresDir,
                        Reporter& reporter) {
    StripRecord out;
    out.strip = &strip;
    std::vector<const RunRecord*> rows;
    int last = 1 << 30;
    for (const auto& id : strip.experiments) {
        const auto it = std::find_if(runs.begin(), runs.end(),
                                     [&](const RunRecord& r) { return r.experiment->id == id; });
        if (it == runs.end() || !it->measured) {
            out.message = "the run " + id + " did not produce frames";
            return out;
        }
        rows.push_back(&*it);
        last = std::min(last, it->metrics.frames);
    }
    if (strip.lastFrame > 0) {
        const int wanted = std::max(1, int(std::lround(strip.lastFrame * options.scale)));
        last = std::min(last, wanted);
    }
    const int first =
        std::min(last, std::max(1, int(std::lround(strip.firstFrame * options.scale))));
    out.frames = evenlySpacedFrames(first, last, strip.tiles);
    if (!strip.frames.empty()) {
        out.frames.clear();
        for (int f : strip.frames) {
            f = std::clamp(int(std::lround(f * options.scale)), 1, last);
            if (out.frames.empty() || out.frames.back() < f) out.frames.push_back(f);
        }
    }
    std::vector<std::string> look = stripRenderOverrides(options.scale);
    if (!strip.autoCamera) {
        const std::vector<std::string> camera = stripCameraOverrides();
        look.insert(look.end(), camera.begin(), camera.end());
    }
    look.insert(look.end(), strip.look.begin(), strip.look.end());
    std::vector<fs::path> pngs;
    PrefixReporter inner(reporter, strip.id);
    for (const RunRecord* run : rows) {
        std::vector<std::string> overrides = run->overrides;
        overrides.insert(overrides.end(), look.begin(), look.end());
        if (out.renderCommand.empty()) {
            out.renderCommand = joinCommand(run->experiment->scene, run->dir, "render",
                                            std::to_string(out.frames.back()), overrides);
        }
        try {
            // `globular run SCENE --stages render --frames F` with these overrides, per frame.
            for (int frame : out.frames) {
                RunOptions ro;
                ro.scene = run->scenePath;
                ro.outDir = run->dir;
                ro.stages = {"render"};
                ro.frames = std::to_string(frame);
                ro.threads = options.threads;
                ro.overrides = overrides;
                runScene(ro, inner);
                const fs::path png = framePngPath(run->dir, frame);
                if (!fs::exists(png)) throw Error("the render stage wrote no " + png.string());
                pngs.push_back(png);
            }
        } catch (const SceneError&) {
            throw;  // a bad look is a bug in stripRenderOverrides, not a missing figure
        } catch (const std::exception& error) {
            out.message = std::string("rendering failed: ") + error.what();
            return out;
        }
    }
    const int columns = std::max(1, strip.columns);
    // The sheet, gutters included, is at most kSheetWidth wide.
    const int tileWidth =
        std::max(16, int(std::lround((kSheetWidth - (columns + 1) * kContactGutter) / columns *
                                     std::min(1.0, options.scale))));
    const fs::path image = fs::path("figures") / (strip.id + ".png");
    try {
        writeContactSheet(pngs, columns, tileWidth, figuresDir.parent_path() / image);
    } catch (const std::exception& error) {
        out.message = std::string("contact sheet failed: ") + error.what();
        return out;
    }
    out.image = image;
    return out;
}

// ---- Fig. 2 -------------------------------------------------------------------------------

Fig2Report makeFig2(const fs::path& figuresDir, double scale) {
    Fig2Report report;
    Fig2Settings narrow;  // the plotted material: C_r = r0 (powder, liquid)
    Fig2Settings wide = narrow;
    wide.cr = 2.0;  // the solid's window
    const int w = std::max(64, int(std::lround(800 * std::min(1.0, scale))));
    const int h = std::max(48, int(std::lround(500 * std::min(1.0, scale))));
    report.output = writeFig2(figuresDir, narrow, w, h);
    for (const auto& spec : paperForceCurves()) {
        report.narrow.push_back(summarizeForceCurve(spec, narrow));
        report.wide.push_back(summarizeForceCurve(spec, wide));
    }
    // Each statement is checked under both windows; it holds when it holds in both.
    const auto both = [&](const std::function<bool(const std::vector<ForceCurveSummary>&)>& test,
                          const std::string& what) {
        CriterionResult r;
        const bool a = test(report.narrow), b = test(report.wide);
        r.passed = a && b;
        r.text = what + ": C_r = r0 " + (a ? "yes" : "no") + ", C_r = 2 r0 " + (b ? "yes" : "no");
        return r;
    };
    using S = std::vector<ForceCurveSummary>;  // A, B, C, D
    report.claims.push_back(
        {"B: as m increases, the repulsion diverges faster as globules get very close, but the "
         "overall attraction increases",
         both(
             [](const S& s) {
                 return s[1].forceAt08 > s[0].forceAt08 && s[1].dipForce < s[0].dipForce;
             },
             "B's force at D = 0.8 and its dip beyond A's")});
    report.claims.push_back({"C: if n is small, the attraction pulls in from a larger distance",
                             both([](const S& s) { return s[2].halfReach > s[0].halfReach; },
                                  "C's half-dip reach beyond A's")});
    report.claims.push_back(
        {"D: if n is large, globules experience attraction quickly or not at all",
         both(
             [](const S& s) {
                 return s[3].dipForce > s[0].dipForce && s[3].halfReach <= s[0].halfReach;
             },
             "D's dip shallower and no wider than A's")});
    report.claims.push_back(
        {"the difference m - n controls how deep the dip is",
         both(
             [](const S& s) {
                 std::vector<const ForceCurveSummary*> byGap, byDepth;
                 for (const auto& c : s) byGap.push_back(&c), byDepth.push_back(&c);
                 std::sort(byGap.begin(), byGap.end(), [](auto* x, auto* y) {
                     return x->spec.m - x->spec.n < y->spec.m - y->spec.n;
                 });
                 std::sort(byDepth.begin(), byDepth.end(),
                           [](auto* x, auto* y) { return x->dipForce > y->dipForce; });
                 return byGap == byDepth;
             },
             "dip depth ranked as m - n")});
    std::vector<CriterionResult> results;
    for (const auto& c : report.claims) results.push_back(c.second);
    report.verdict = overallVerdict(results);
    return report;
}

}  // namespace

std::vector<fs::path> figuresArtefacts() {
    std::vector<fs::path> out = {"REPRODUCTION.md", "metrics.csv", "figures/fig2_force.csv",
                                 "figures/fig2_force.png"};
    for (const auto& s : paperFigureStrips()) out.push_back(fs::path("figures") / (s.id + ".png"));
    return out;
}

void runFigures(const FiguresOptions& options, Reporter& reporter) {
    if (!(options.scale > 0 && options.scale <= 1)) {
        throw SceneError("--scale must be in (0, 1]: 1 is the paper's sizes");
    }
    if (options.threads < 0) throw SceneError("--threads must be at least 1 (0 = all cores)");
    const auto start = Clock::now();
    const std::clock_t cpuStart = std::clock();
    const fs::path scenes = scenesDirectory(options);
    if (!fs::exists(scenes / "liquid.toml")) {
        throw SceneError("the paper's scenes are not in " + scenes.string() +
                         ": run from the repository root or pass --scenes DIR");
    }
    ensureWritableDirectory(options.outDir);
    const fs::path figuresDir = options.outDir / "figures";
    ensureWritableDirectory(figuresDir);

    reporter.info("figures: Fig. 2 (force curves)");
    const Fig2Report fig2 = makeFig2(figuresDir, options.scale);
    if (!fig2.output.message.empty()) reporter.warn("Fig. 2: " + fig2.output.message);

    std::vector<RunRecord> runs;
    for (const auto& e : paperExperiments()) {
        RunRecord run;
        run.experiment = &e;
        run.dir = options.outDir / e.id;
        planRun(run, scenes, options.scale);
        run.command = joinCommand(e.scene, run.dir, "sim", "", run.overrides);
        runs.push_back(std::move(run));
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
        RunRecord& run = runs[i];
        runExperiment(run, options, reporter);
        std::string line = "figures: [" + std::to_string(i + 1) + "/" +
                           std::to_string(runs.size()) + "] " + run.experiment->id + " " +
                           formatNumber(run.seconds) + " s";
        if (!run.explosion.empty()) line += " (exploded, as a result)";
        reporter.info(line);
        if (!run.failure.empty()) reporter.warn(run.experiment->id + ": " + run.failure);
    }
    judgeAll(runs);

    std::vector<StripRecord> strips;
    for (const auto& strip : paperFigureStrips()) {
        reporter.info("figures: rendering " + strip.id);
        const auto renderStart = Clock::now();
        strips.push_back(renderStrip(strip, runs, options, figuresDir, reporter));
        strips.back().seconds = secondsSince(renderStart);
        if (!strips.back().message.empty()) {
            reporter.warn(strip.id + ": " + strips.back().message);
        }
    }

    ReportContext context;
    context.outDir = options.outDir;
    context.scale = options.scale;
    context.threads = options.threads;
    context.hardwareThreads = std::thread::hardware_concurrency();
    context.totalSeconds = secondsSince(start);
    context.cpuSeconds = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
    double load[1];
    if (getloadavg(load, 1) == 1) context.loadAverage = load[0];
    const double total = context.totalSeconds;
    writeFileAtomically(options.outDir / "metrics.csv", metricsCsv(runs));
    writeFileAtomically(options.outDir / "REPRODUCTION.md",
                        reproductionMarkdown(context, runs, strips, fig2));
    reporter.info("figures: done in " + formatNumber(total) +
                  " s: " + (options.outDir / "REPRODUCTION.md").string());

    std::size_t failed = 0, missing = 0;
    for (const auto& r : runs) failed += !r.failure.empty();
    for (const auto& s : strips) missing += s.image.empty();
    missing += fig2.output.png.empty();
    if (failed || missing) {
        throw Error("figures: " + std::to_string(failed) + " experiment(s) failed to run and " +
                    std::to_string(missing) + " figure(s) are missing; see " +
                    (options.outDir / "REPRODUCTION.md").string());
    }
}

}  // namespace globular
