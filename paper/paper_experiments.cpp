#include "paper_experiments.h"

#include <algorithm>
#include <cmath>

#include "errors.h"

namespace globular {

namespace {

SubjectCriterion crit(Metric metric, Expect expect, double margin, std::string meaning,
                      std::string reference = "", std::string subject = "") {
    SubjectCriterion c;
    c.subject = std::move(subject);
    c.criterion.metric = metric;
    c.criterion.expect = expect;
    c.criterion.margin = margin;
    c.criterion.reference = std::move(reference);
    c.criterion.meaning = std::move(meaning);
    return c;
}

SubjectCriterion near(Metric metric, double target, double tolerance, std::string meaning) {
    SubjectCriterion c = crit(metric, Expect::Near, target, std::move(meaning));
    c.criterion.tolerance = tolerance;
    return c;
}

// "Tighter pour": the falling column contracts more than the best case's (its smallest
// spread is lower). The column starts as the same helix of radius 1, so 5% is a clear
// difference.
SubjectCriterion tighterPour() {
    return crit(Metric::PourSpread, Expect::Less, 0.05, "tighter pour: the column contracts more");
}

SubjectCriterion explodesApart(double margin) {
    SubjectCriterion c = crit(Metric::Spread, Expect::More, margin, "explode apart");
    c.criterion.explosionPasses = true;
    return c;
}

// The note on every "C_r read as a factor" variant.
const char* kFactorNote =
    "variant: C_r, C_d read as factors of (r_i + r_p) that ignore r0 (the paper's \"C_r = r0\" "
    "taken as the factor 1), not the numbers factor x r0 the presets use";

std::vector<Experiment> makeExperiments() {
    std::vector<Experiment> e;

    // ---- Table 4: the best cases, the references of Tables 1-3 -------------------------
    e.push_back({"table4_powder",
                 "Table 4",
                 "Powder: r0 = 1.0, b1 = 2.0, m = 5, n = 3, "
                 "C_r = C_d = r0",
                 "powder.toml",
                 {},
                 kTableFrames,
                 "Natural bounce and spill. No clumps.",
                 "",
                 {crit(Metric::Spread, Expect::More, 0.1, "spills more than the best liquid",
                       "table4_liquid"),
                  crit(Metric::LargestClusterFraction, Expect::Below, 0.5,
                       "no clumps (no overlap cluster holds half the globules)")},
                 ""});
    e.push_back({"table4_solid",
                 "Table 4",
                 "Solid: r0 = 1.0, b1 = 1.0, m = 5, n = 3, "
                 "C_r = C_d = 2 r0",
                 "solid.toml",
                 {},
                 kTableFrames,
                 "Clump together and stabilize.",
                 "",
                 {crit(Metric::LargestClusterFraction, Expect::Above, 0.9,
                       "clump together (one cluster holds > 90%)"),
                  crit(Metric::Settled, Expect::True, 0, "stabilize (comes to rest)"),
                  crit(Metric::Spread, Expect::Less, 0.1, "spills less than the best liquid",
                       "table4_liquid")},
                 ""});
    e.push_back(
        {"table4_liquid",
         "Table 4",
         "Liquid: r0 = 1.0, b1 = 2.0, m = 5, n = 3, "
         "C_r = r0, C_d = 1.5 r0",
         "liquid.toml",
         {},
         kTableFrames,
         "Clump by spill to fill space. Flow.",
         "",
         {crit(Metric::LargestClusterFraction, Expect::Above, 0.9,
               "clump (one cluster holds > 90%)"),
          crit(Metric::Spread, Expect::More, 0.1, "spills more than the solid", "table4_solid"),
          crit(Metric::Spread, Expect::Less, 0.1, "spills less than the powder", "table4_powder")},
         ""});

    // ---- Table 1: powder ------------------------------------------------------------------
    const std::string t1Clump =
        "Solid-like model. Not enough repulsion due to inability to "
        "get close to each other, resulting in clumping.";
    const std::vector<SubjectCriterion> clumps = {
        crit(Metric::Spread, Expect::Less, 0.1, "clumping: spills less than the best case"),
        crit(Metric::Settled, Expect::True, 0, "solid-like: comes to rest")};
    e.push_back({"table1_r0_2",
                 "Table 1",
                 "r0 = 2.0, b1 = 2.0, m = 5, n = 3 (C_r = C_d = 2)",
                 "powder.toml",
                 {"material.r0=2"},
                 kTableFrames,
                 t1Clump,
                 "table4_powder",
                 clumps,
                 "C_r = C_d = r0 as numbers: 2 (the presets' reading)"});
    e.push_back({"table1_r0_2_factor",
                 "Table 1",
                 "r0 = 2.0, b1 = 2.0, m = 5, n = 3 (factor reading: C_r = C_d = 1)",
                 "powder.toml",
                 {"material.r0=2", "material.cr=1", "material.cd=1"},
                 kTableFrames,
                 t1Clump,
                 "table4_powder",
                 clumps,
                 kFactorNote});
    e.push_back({"table1_b1_1",
                 "Table 1",
                 "r0 = 1.0, b1 = 1.0, m = 5, n = 3",
                 "powder.toml",
                 {"material.b1=1"},
                 kTableFrames,
                 "Solid-like model. Strength of radial force diminished, causing globules to "
                 "clump.",
                 "table4_powder",
                 clumps,
                 ""});
    e.push_back(
        {"table1_m7_n5",
         "Table 1",
         "r0 = 1.0, b1 = 2.0, m = 7, n = 5",
         "powder.toml",
         {"material.m=7", "material.n=5"},
         kTableFrames,
         "Explode apart. Globules experience extreme repulsion forces from farther "
         "apart, less attraction.",
         "table4_powder",
         {explodesApart(0.5), crit(Metric::KineticEnergy, Expect::More, 0.5,
                                   "flies apart: more kinetic energy left than the best case")},
         ""});
    e.push_back({"table1_n1",
                 "Table 1",
                 "r0 = 1.0, b1 = 2.0, m = 5, n = 1",
                 "powder.toml",
                 {"material.n=1"},
                 kTableFrames,
                 "Liquid-like model. Globules tighten together as they drop and spill out "
                 "slower than best case.",
                 "table4_powder",
                 {tighterPour(),
                  crit(Metric::SpreadRate, Expect::Less, 0.1, "spills out slower at the end")},
                 ""});

    // ---- Table 2: solid -------------------------------------------------------------------
    const std::string t2Large =
        "Large non-rigid body. Collisions reach equilibrium too "
        "quickly and globules settle on each other's boundaries.";
    const std::vector<SubjectCriterion> large = {
        crit(Metric::Spread, Expect::More, 0.1, "large body: spreads wider"),
        crit(Metric::SettleTime, Expect::Less, 0.1, "reaches equilibrium sooner"),
        crit(Metric::LargestClusterFraction, Expect::Less, 0.1,
             "settle on each other's boundaries: fewer overlaps")};
    e.push_back({"table2_r0_2",
                 "Table 2",
                 "r0 = 2.0, b1 = 1.0, m = 5, n = 3 (C_r = C_d = 4)",
                 "solid.toml",
                 {"material.r0=2"},
                 kTableFrames,
                 t2Large,
                 "table4_solid",
                 large,
                 "C_r = C_d = 2 r0 as numbers: 4 (the presets' reading)"});
    e.push_back({"table2_r0_2_factor",
                 "Table 2",
                 "r0 = 2.0, b1 = 1.0, m = 5, n = 3 (factor reading: C_r = C_d = 2)",
                 "solid.toml",
                 {"material.r0=2", "material.cr=2", "material.cd=2"},
                 kTableFrames,
                 t2Large,
                 "table4_solid",
                 large,
                 "variant: C_r = C_d = 2 read as a factor of (r_i + r_p) that ignores r0"});
    e.push_back({"table2_m7_n5",
                 "Table 2",
                 "r0 = 1.0, b1 = 1.0, m = 7, n = 5",
                 "solid.toml",
                 {"material.m=7", "material.n=5"},
                 kTableFrames,
                 "Globules spread apart to form a disc. Animation begins the same as the best "
                 "case, but spills out by the end.",
                 "table4_solid",
                 {crit(Metric::Spread, Expect::More, 0.25, "spreads apart (disc)"),
                  crit(Metric::Height, Expect::Less, 0.1, "disc: flatter")},
                 ""});
    e.push_back({"table2_m7_n1_5",
                 "Table 2",
                 "r0 = 1.0, b1 = 1.0, m = 7, n = 1.5",
                 "solid.toml",
                 {"material.m=7", "material.n=1.5"},
                 kTableFrames,
                 "Tighter pour, but the model collapses on itself. Due to large radius of "
                 "influence, smaller n increase total attraction.",
                 "table4_solid",
                 {tighterPour(), crit(Metric::Spread, Expect::Less, 0.1,
                                      "collapses on itself: contracts into the middle (sec. 3.3)")},
                 "\"collapse\" is read as in sec. 3.3 (\"spill away or collapse into the "
                 "middle\"): a smaller final spread"});
    e.push_back({"table2_b1_3_n1",
                 "Table 2",
                 "r0 = 1.0, b1 = 3.0, m = 5, n = 1",
                 "solid.toml",
                 {"material.b1=3", "material.n=1"},
                 kTableFrames,
                 "Tighter pour with less collapse. Model is more compressible. It is "
                 "understood increasing b1 has this effect.",
                 "table4_solid",
                 {tighterPour(), crit(Metric::Spread, Expect::More, 0.1,
                                      "less collapse: spreads more than the m = 7, n = 1.5 row",
                                      "table2_m7_n1_5")},
                 ""});

    // ---- Table 3: liquid ------------------------------------------------------------------
    const std::string t3Solid =
        "Solid-like model. Little to no spill. Globules conglomerate "
        "in center.";
    const std::vector<SubjectCriterion> conglomerate = {
        crit(Metric::Spread, Expect::Less, 0.25, "little to no spill"),
        crit(Metric::Height, Expect::More, 0.1, "conglomerate: a taller heap"),
        crit(Metric::Settled, Expect::True, 0, "solid-like: comes to rest")};
    e.push_back({"table3_r0_2",
                 "Table 3",
                 "r0 = 2.0, b1 = 2.0, m = 5, n = 3 (C_r = 2, C_d = 3)",
                 "liquid.toml",
                 {"material.r0=2"},
                 kTableFrames,
                 t3Solid,
                 "table4_liquid",
                 conglomerate,
                 "C_r = r0 = 2, C_d = 1.5 r0 = 3 as numbers (the presets' reading)"});
    e.push_back({"table3_r0_2_factor",
                 "Table 3",
                 "r0 = 2.0, b1 = 2.0, m = 5, n = 3 (factor reading: C_r = 1, C_d = 1.5)",
                 "liquid.toml",
                 {"material.r0=2", "material.cr=1", "material.cd=1.5"},
                 kTableFrames,
                 t3Solid,
                 "table4_liquid",
                 conglomerate,
                 kFactorNote});
    e.push_back({"table3_m7_n5",
                 "Table 3",
                 "r0 = 1.0, b1 = 2.0, m = 7, n = 5",
                 "liquid.toml",
                 {"material.m=7", "material.n=5"},
                 kTableFrames,
                 "Model has more splash. Globules slide past easier.",
                 "table4_liquid",
                 {crit(Metric::Spread, Expect::More, 0.1, "slides past easier: spreads more"),
                  crit(Metric::SpreadRate, Expect::More, 0.1, "still sliding faster at the end")},
                 ""});
    e.push_back({"table3_m7_n1_5",
                 "Table 3",
                 "r0 = 1.0, b1 = 2.0, m = 7, n = 1.5",
                 "liquid.toml",
                 {"material.m=7", "material.n=1.5"},
                 kTableFrames,
                 "Tighter pour, but less spill. The flow ends rather abruptly. The model looks "
                 "like a melted solid.",
                 "table4_liquid",
                 {tighterPour(), crit(Metric::Spread, Expect::Less, 0.1, "less spill"),
                  crit(Metric::SettleTime, Expect::Less, 0.1,
                       "the flow ends abruptly: settles "
                       "sooner")},
                 ""});
    e.push_back({"table3_b1_3_n1",
                 "Table 3",
                 "r0 = 1.0, b1 = 3.0, m = 5, n = 1",
                 "liquid.toml",
                 {"material.b1=3", "material.n=1"},
                 kTableFrames,
                 "Tighter pour with only slightly less spill. Larger spill than < n.",
                 "table4_liquid",
                 {tighterPour(), crit(Metric::Spread, Expect::Less, 0.02, "slightly less spill"),
                  crit(Metric::Spread, Expect::Similar, 0.25, "only slightly (within 25%)"),
                  crit(Metric::Spread, Expect::More, 0.1,
                       "larger spill than the m = 7, n = 1.5 row", "table3_m7_n1_5")},
                 "\"< n\" is read as the row above (smaller n, m = 7, n = 1.5)"});

    // ---- Fig. 7 and unstated defaults of the liquid ---------------------------------------
    e.push_back({"fig7_liquid_viscous",
                 "Fig. 7",
                 "Liquid, C_d = 2 r0 (alpha = 2)",
                 "liquid_viscous.toml",
                 {},
                 kTableFrames,
                 "alpha = 2 results in quite viscous fluid that clumps easily, like ketchup, "
                 "while alpha = 1.5 creates liquid that spills out faster (sec. 2.2.2).",
                 "table4_liquid",
                 {crit(Metric::Spread, Expect::Less, 0.1, "more viscous: spills less"),
                  crit(Metric::SpreadRate, Expect::Less, 0.1, "spills out slower at the end")},
                 ""});
    e.push_back({"defaults_liquid_contact_surface",
                 "Defaults",
                 "Best liquid with ground contact at the globule surface",
                 "liquid.toml",
                 {"ground.contact=surface"},
                 kTableFrames,
                 "(not a claim) The paper's ground acts on the globule centre (half a globule "
                 "sinks); containers would offset it by the radius.",
                 "table4_liquid",
                 {crit(Metric::Spread, Expect::Similar, 0.1,
                       "the spill does not depend on the contact point (within 10%)")},
                 "variant of an unstated default: ground.contact = surface"});

    // ---- Fig. 3 and Fig. 4 ----------------------------------------------------------------
    e.push_back(
        {"fig3_helix",
         "Fig. 3",
         "100 globules, helix formation",
         "helix.toml",
         {},
         0,
         "100 Globules initialized in a helix formation.",
         "",
         {near(Metric::Count, 100, 0, "100 globules"),
          near(Metric::InitialSpread, 1.0, 0.15, "on the unit circle (x-z RMS radius about 1)"),
          crit(Metric::Exploded, Expect::False, 0, "not too close: the start does not explode")},
         ""});
    e.push_back({"fig4_dt0_01",
                 "Fig. 4",
                 "Powder, 200 globules, dt = 0.01",
                 "explode.toml",
                 {},
                 0,
                 "Globules explode away from each other if the timestep is too large: 200 "
                 "globules that should fall as a powder recoil away from each other due to a "
                 "timestep of 0.01.",
                 "table4_powder",
                 {crit(Metric::Exploded, Expect::True, 0, "dt = 0.01 explodes"),
                  crit(Metric::Exploded, Expect::False, 0, "dt = 0.001 stays together", "",
                       "table4_powder")},
                 ""});
    e.push_back(
        {"fig4_dt0_01_unguarded",
         "Fig. 4",
         "Powder, dt = 0.01, explosion guard raised to 1e12 units/s (for the pictures)",
         "explode.toml",
         {"simulation.max_speed=1e12"},
         0,
         "(for the figure) The default guard stops the run at 1000 units/s, before the "
         "globules have visibly moved; raised, the run writes the frames in which they "
         "fly apart.",
         "table4_powder",
         {crit(Metric::Exploded, Expect::True, 0, "dt = 0.01 explodes"), explodesApart(0.5)},
         "variant: simulation.max_speed = 1e12, so frames after the blow-up are written"});
    e.push_back({"fig4_dt0_01_semi_implicit",
                 "Fig. 4",
                 "Powder, dt = 0.01, semi-implicit Euler",
                 "explode.toml",
                 {"simulation.integrator=semi_implicit_euler"},
                 0,
                 "(variant) The paper integrates with forward Euler; a public implementation "
                 "used semi-implicit Euler.",
                 "table4_powder",
                 {crit(Metric::Exploded, Expect::True, 0, "dt = 0.01 explodes")},
                 "variant of the integrator"});
    e.push_back({"fig4_dt0_01_no_ground",
                 "Fig. 4",
                 "Powder, dt = 0.01, no ground",
                 "explode.toml",
                 {"ground.enabled=false"},
                 0,
                 "(variant) Is the explosion between globules, as the paper says, or at the "
                 "ground (k_s = 5000, k_d = 300)?",
                 "table4_powder",
                 {crit(Metric::Exploded, Expect::True, 0, "dt = 0.01 explodes in free fall")},
                 "variant: the same column falling without the ground plane"});
    return e;
}

/// A strip of @p tiles evenly spaced frames of one run, 3 per sheet row.
FigureStrip strip(std::string id, std::string title, std::string claim, std::string run,
                  std::string rowLabel, int tiles, int lastFrame) {
    FigureStrip s;
    s.id = std::move(id);
    s.title = std::move(title);
    s.claim = std::move(claim);
    s.experiments = {run};
    s.rowLabels = {std::move(rowLabel)};
    s.tiles = tiles;
    s.columns = 3;
    s.verdictFrom = std::move(run);
    s.lastFrame = lastFrame;
    return s;
}

std::vector<FigureStrip> makeStrips() {
    // The strips of Figs. 1, 5-7 cover the scenes' own lengths (liquid 6 s = 150 frames,
    // powder and solid 4 s = 100: the pour and the pile it makes); the table runs go on to
    // 10 s.
    const FigureStrip fig1 = strip("fig1_liquid", "Fig. 1: the best liquid (C_d = 1.5 r0)",
                                   "Frames from liquid animation with best results (material "
                                   "constant C_d = 1.5 r0).",
                                   "table4_liquid", "liquid, C_d = 1.5 r0", 6, 150);
    FigureStrip fig3 = strip("fig3_helix", "Fig. 3: the helix formation",
                             "100 Globules initialized in a helix formation.", "fig3_helix",
                             "helix, 100 globules", 3, 0);
    fig3.autoCamera = true;  // the whole column, frame by frame
    // Fig. 4: the column's foot reaches the ground (t = 1 s, frame 26), then the unguarded
    // dt = 0.01 run blows up (frames 32-34), beside the same frames at dt = 0.001. (With the
    // default guard the run stops at frame 29, before anything has visibly moved.)
    FigureStrip fig4 = strip("fig4_explode", "Fig. 4: dt = 0.01 (top) beside dt = 0.001 (bottom)",
                             "200 globules that should fall as a powder recoil away from each "
                             "other due to a timestep of 0.01.",
                             "fig4_dt0_01", "", 4, 0);
    fig4.experiments = {"fig4_dt0_01_unguarded", "table4_powder"};
    fig4.rowLabels = {"powder, dt = 0.01 (explosion guard raised)", "powder, dt = 0.001"};
    fig4.columns = 4;
    fig4.frames = {26, 30, 32, 34};
    // The powder goes on sliding over the frictionless ground after the pour: its strip
    // covers the whole 10 s run, so the spill its verdict measures is in the picture.
    const FigureStrip fig5 =
        strip("fig5_powder", "Fig. 5: the best powder",
              "Frames from powder animation with best results.", "table4_powder", "powder", 6, 0);
    const FigureStrip fig6 =
        strip("fig6_solid", "Fig. 6: the best solid",
              "Frames from solid animation with best results.", "table4_solid", "solid", 6, 100);
    const FigureStrip fig7 = strip("fig7_liquid_viscous", "Fig. 7: the viscous liquid (C_d = 2 r0)",
                                   "Frames from liquid animation with material constant "
                                   "C_d = 2 r0.",
                                   "fig7_liquid_viscous", "liquid, C_d = 2 r0", 6, 150);
    return {fig1, fig3, fig4, fig5, fig6, fig7};
}

}  // namespace

const std::vector<Experiment>& paperExperiments() {
    static const std::vector<Experiment> experiments = makeExperiments();
    return experiments;
}

const std::vector<FigureStrip>& paperFigureStrips() {
    static const std::vector<FigureStrip> strips = makeStrips();
    return strips;
}

const std::vector<std::vector<std::string>>& paperVariantGroups() {
    static const std::vector<std::vector<std::string>> groups = {
        {"table1_r0_2", "table1_r0_2_factor"},
        {"table2_r0_2", "table2_r0_2_factor"},
        {"table3_r0_2", "table3_r0_2_factor"},
        {"table4_liquid", "defaults_liquid_contact_surface"},
        {"fig4_dt0_01", "fig4_dt0_01_unguarded", "fig4_dt0_01_semi_implicit",
         "fig4_dt0_01_no_ground"}};
    return groups;
}

std::vector<std::string> stripRenderOverrides(double scale) {
    const auto pixels = [&](int full) {
        return std::to_string(std::max(16, int(std::lround(full * scale))));
    };
    return {"render.width=" + pixels(640), "render.height=" + pixels(360), "render.mode=spheres",
            "render.contact_sheet=0", "render.checker_size=4"};
}

std::vector<std::string> stripCameraOverrides() {
    return {"camera.auto_frame=false", "camera.position=[0.0, 9.0, 36.0]",
            "camera.target=[0.0, 3.0, 0.0]"};
}

const Experiment& findExperiment(const std::string& id) {
    for (const auto& e : paperExperiments()) {
        if (e.id == id) return e;
    }
    throw Error("no paper experiment named '" + id + "'");
}

}  // namespace globular
