// `globular figures`: the experiment list is consistent, Fig. 2 is the code's force, and a
// reduced-size run writes every listed artefact and a report that links and judges them.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "errors.h"
#include "fig2_plot.h"
#include "figures_command.h"
#include "frame_stats.h"
#include "paper_experiments.h"
#include "png_image.h"
#include "reporter.h"
#include "scene.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(GLOBULAR_SOURCE_DIR) / "scenes" / "paper";

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

fs::path scratch(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("globular_figures_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(PaperExperiments, EveryRowRunsAPaperSceneWithValidOverrides) {
    std::set<std::string> ids;
    for (const auto& e : paperExperiments()) {
        EXPECT_TRUE(ids.insert(e.id).second) << "duplicate id " << e.id;
        ASSERT_TRUE(fs::exists(kScenes / e.scene)) << e.id << ": " << e.scene;
        NullReporter quiet;
        EXPECT_NO_THROW(loadScene(kScenes / e.scene, e.overrides, quiet)) << e.id;
        EXPECT_FALSE(e.claim.empty()) << e.id;
        EXPECT_FALSE(e.criteria.empty()) << e.id;
    }
    // Every name a row refers to exists.
    for (const auto& e : paperExperiments()) {
        if (!e.bestCase.empty()) {
            EXPECT_TRUE(ids.count(e.bestCase)) << e.id << " -> " << e.bestCase;
        }
        for (const auto& c : e.criteria) {
            if (!c.subject.empty()) {
                EXPECT_TRUE(ids.count(c.subject)) << e.id;
            }
            if (!c.criterion.reference.empty()) {
                EXPECT_TRUE(ids.count(c.criterion.reference)) << e.id;
            }
        }
    }
    for (const auto& s : paperFigureStrips()) {
        EXPECT_TRUE(ids.count(s.verdictFrom)) << s.id;
        EXPECT_EQ(s.experiments.size(), s.rowLabels.size()) << s.id;
        for (const auto& id : s.experiments) EXPECT_TRUE(ids.count(id)) << s.id << " -> " << id;
    }
    for (const auto& group : paperVariantGroups()) {
        for (const auto& id : group) EXPECT_TRUE(ids.count(id)) << id;
    }
    // The paper's tables: 4 rows each in Tables 1-3 (plus the r0 = 2 reading), 3 best cases.
    std::map<std::string, int> perSection;
    for (const auto& e : paperExperiments()) ++perSection[e.section];
    EXPECT_EQ(perSection["Table 1"], 5);
    EXPECT_EQ(perSection["Table 2"], 5);
    EXPECT_EQ(perSection["Table 3"], 5);
    EXPECT_EQ(perSection["Table 4"], 3);
    EXPECT_EQ(findExperiment("table4_liquid").scene, "liquid.toml");
    EXPECT_THROW(findExperiment("nope"), Error);
}

TEST(Fig2, CurvesAreThePairForceAndVanishAtR0) {
    Fig2Settings settings;
    settings.minDistance = 0.5;
    settings.maxDistance = 2.5;
    settings.samples = 201;  // D = 0.5, 0.51, ... includes 1.0 exactly
    for (const auto& spec : paperForceCurves()) {
        const ForceCurve curve = sampleForceCurve(spec, settings);
        ASSERT_EQ(curve.force.size(), 201u);
        EXPECT_NEAR(curve.force[50], 0.0, 1e-5) << spec.label;  // D = r0
        EXPECT_GT(curve.force[20], 0.0) << spec.label;          // D = 0.7: repulsion
        EXPECT_LT(curve.force[70], 0.0) << spec.label;          // D = 1.2: attraction
        EXPECT_EQ(curve.force[200], 0.0) << spec.label;         // beyond the window D = 2
        // D S_r (b1/D^m - b2/D^n) by hand at D = 1.5 (b2 = b1 with r0 = 1).
        const double d = 1.5, sr = 1 - d * d / 4;
        const double expected = d * sr * 2 * (std::pow(d, -spec.m) - std::pow(d, -spec.n));
        EXPECT_NEAR(curve.force[100], expected, 1e-5) << spec.label;
    }
    const ForceCurveSummary a = summarizeForceCurve(paperForceCurves()[0], settings);
    const ForceCurveSummary b = summarizeForceCurve(paperForceCurves()[1], settings);
    EXPECT_LT(b.dipForce, a.dipForce);  // m = 10 attracts more than m = 5
    EXPECT_GT(b.forceAt08, a.forceAt08);
    EXPECT_GT(a.dipDistance, 1.0);
    EXPECT_LT(a.dipDistance, 2.0);
}

TEST(Fig2, WritesCsvScriptAndPlot) {
    const fs::path dir = scratch("fig2");
    const Fig2Output out = writeFig2(dir, Fig2Settings{}, 320, 200);
    const std::string csv = readText(out.csv);
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "distance,force_m5_n3,force_m10_n3,force_m5_n1,force_m5_n4");
    EXPECT_TRUE(fs::exists(out.script));
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
        ASSERT_FALSE(out.png.empty()) << out.message;
        const Image png = readPng(out.png);
        EXPECT_EQ(png.width, 320);
        EXPECT_EQ(png.height, 200);
    } else {
        EXPECT_TRUE(out.png.empty());
        EXPECT_NE(out.message.find("gnuplot"), std::string::npos);
    }
    fs::remove_all(dir);
}

class ReducedFigures : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        sDir = scratch("reduced");
        FiguresOptions options;
        options.outDir = sDir;
        options.scale = 0.04;
        options.threads = 2;
        options.scenesDir = kScenes;
        NullReporter quiet;
        try {
            runFigures(options, quiet);
        } catch (const std::exception& error) {
            sError = error.what();
        }
    }
    static void TearDownTestSuite() {
        if (!::testing::Test::HasFailure()) fs::remove_all(sDir);
    }
    static fs::path sDir;
    static std::string sError;
};

fs::path ReducedFigures::sDir;
std::string ReducedFigures::sError;

TEST_F(ReducedFigures, WritesEveryListedArtefact) {
    EXPECT_EQ(sError, "");
    for (const auto& relative : figuresArtefacts()) {
        EXPECT_TRUE(fs::exists(sDir / relative)) << relative;
    }
    for (const auto& s : paperFigureStrips()) {
        const fs::path image = sDir / "figures" / (s.id + ".png");
        if (!fs::exists(image)) continue;  // reported above
        const Image sheet = readPng(image);
        EXPECT_GT(sheet.width, 0);
        EXPECT_LE(sheet.width, 960) << s.id;
    }
}

TEST_F(ReducedFigures, EveryExperimentRanAndIsMeasured) {
    const std::string metrics = readText(sDir / "metrics.csv");
    for (const auto& e : paperExperiments()) {
        const fs::path stats = sDir / e.id / "stats.csv";
        ASSERT_TRUE(fs::exists(stats)) << e.id;
        EXPECT_FALSE(readStatsCsv(stats).empty()) << e.id;
        EXPECT_NE(metrics.find("\n" + e.id + ","), std::string::npos) << e.id;
        const std::string scene = readText(sDir / e.id / "scene.toml");
        EXPECT_FALSE(scene.empty()) << e.id;
    }
    EXPECT_EQ(metrics.find("not run"), std::string::npos);
}

TEST_F(ReducedFigures, ReportLinksFiguresAndJudgesEveryRow) {
    const std::string md = readText(sDir / "REPRODUCTION.md");
    EXPECT_NE(md.find("## Summary"), std::string::npos);
    EXPECT_NE(md.find("Reduced run (scale 0.04)"), std::string::npos);
    EXPECT_NE(md.find("![Fig. 2](figures/fig2_force.png)"), std::string::npos);
    for (const auto& s : paperFigureStrips()) {
        EXPECT_NE(md.find("](figures/" + s.id + ".png)"), std::string::npos) << s.id;
    }
    for (const auto& e : paperExperiments()) {
        // One command line repeats the row's run.
        EXPECT_NE(md.find("globular run scenes/paper/" + e.scene + " --stages sim --out " +
                          (sDir / e.id).string()),
                  std::string::npos)
            << e.id;
        EXPECT_NE(md.find(e.label), std::string::npos) << e.id;
    }
    for (const char* table : {"## Table 1", "## Table 2", "## Table 3", "## Table 4",
                              "## The paper's unstated defaults", "## Timing"}) {
        EXPECT_NE(md.find(table), std::string::npos) << table;
    }
    EXPECT_EQ(md.find("not measured"), std::string::npos);
}

int runBinary(const std::string& args, std::string* err) {
    const fs::path errFile =
        fs::temp_directory_path() / ("globular_figures_err_" + std::to_string(getpid()) + ".txt");
    const std::string command = std::string(GLOBULAR_EXECUTABLE) + " " + args +
                                " </dev/null >/dev/null 2>" + errFile.string();
    const int raw = std::system(command.c_str());
    *err = readText(errFile);
    fs::remove(errFile);
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

TEST(FiguresCommand, BadScaleIsBadUsage) {
    std::string err;
    EXPECT_EQ(runBinary("figures --scale 2 --out /tmp/globular_figures_unused", &err), 2);
    EXPECT_NE(err.find("--scale"), std::string::npos) << err;
    EXPECT_EQ(runBinary("figures --scenes /nonexistent --out /tmp/globular_figures_unused", &err),
              2);
    EXPECT_NE(err.find("/nonexistent"), std::string::npos) << err;
    FiguresOptions options;
    options.scale = 0;
    NullReporter quiet;
    EXPECT_THROW(runFigures(options, quiet), SceneError);
}

}  // namespace
}  // namespace globular
