#include "reproduction_report.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace globular {

namespace fs = std::filesystem;

namespace {

std::string verdictCell(Verdict v) { return "**" + verdictText(v) + "**"; }

std::string num(double value) { return formatNumber(value); }

/// Pipes would break a Markdown table cell.
std::string cell(std::string text) {
    for (std::size_t at = 0; (at = text.find('|', at)) != std::string::npos; at += 2) {
        text.replace(at, 1, "\\|");
    }
    return text;
}

std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

class Runs {
  public:
    explicit Runs(const std::vector<RunRecord>& runs) {
        for (const auto& r : runs) mById[r.experiment->id] = &r;
    }
    const RunRecord* find(const std::string& id) const {
        const auto it = mById.find(id);
        return it == mById.end() ? nullptr : it->second;
    }

  private:
    std::map<std::string, const RunRecord*> mById;
};

std::string explodedCell(const RunRecord& r) {
    if (!r.measured) return "-";
    if (!r.metrics.exploded) return "no";
    return "**yes** (last frame " + std::to_string(r.metrics.frames) + ")";
}

/// pour spread | spread | spill rate | height | largest cluster | clusters | final KE | settles |
/// exploded
std::string metricCells(const RunRecord& r) {
    if (!r.measured) return "- | - | - | - | - | - | - | - | " + cell(r.failure);
    const OutcomeMetrics& m = r.metrics;
    return num(m.pourSpread) + " | " + num(m.spread) + " | " + num(m.spreadRate) + " | " +
           num(m.height) + " | " + num(m.largestClusterFraction) + " | " +
           std::to_string(m.clusterCount) + " | " + num(m.kineticEnergy) + " | " +
           num(m.settleTime) + " | " + explodedCell(r);
}

const char* kMetricHeader =
    " pour spread | spread | spill rate | height | largest cluster | clusters | final KE | settles "
    "at (s) | "
    "exploded |";
const char* kMetricRule = "---|---|---|---|---|---|---|---|---|";

std::string why(const RunRecord& r) {
    std::string text;
    for (const auto& res : r.results) text += (text.empty() ? "" : "; ") + res.text;
    if (!r.failure.empty()) text += (text.empty() ? "" : "; ") + ("run failed: " + r.failure);
    return text;
}

std::string shortWhy(const RunRecord& r) {
    std::string text;
    for (std::size_t i = 0; i < r.results.size(); ++i) {
        const auto& c = r.experiment->criteria[i].criterion;
        text += (text.empty() ? "" : "; ") + c.meaning + (r.results[i].passed ? " ✓" : " ✗");
    }
    return text;
}

std::string stripImage(const StripRecord& s) {
    if (s.image.empty()) return "*(image missing: " + s.message + ")*\n";
    return "![" + s.strip->title + "](" + s.image.generic_string() + ")\n";
}

void section(std::ostringstream& md, const std::string& title) { md << "\n## " << title << "\n\n"; }

/// @param reference the row shown as the comparison ("best case", "reference"), not judged.
void experimentTable(std::ostringstream& md, const std::vector<const RunRecord*>& rows,
                     bool withClaim, const RunRecord* reference, const std::string& referenceText) {
    md << "| row |" << (withClaim ? " paper: result |" : "") << kMetricHeader << " verdict |\n|---|"
       << (withClaim ? "---|" : "") << kMetricRule << "---|\n";
    for (const RunRecord* r : rows) {
        md << "| " << cell(r->experiment->label) << " |";
        if (withClaim) md << " " << cell(r->experiment->claim) << " |";
        md << " " << metricCells(*r) << " | "
           << (r == reference ? referenceText : verdictCell(r->verdict)) << " |\n";
    }
}

void whyList(std::ostringstream& md, const std::vector<const RunRecord*>& rows) {
    md << "\n";
    for (const RunRecord* r : rows) {
        if (r->results.empty()) continue;
        md << "- *" << r->experiment->label << "*: " << verdictCell(r->verdict) << ". " << why(*r)
           << ".";
        if (!r->experiment->note.empty()) md << " (" << r->experiment->note << ")";
        if (!r->explosion.empty()) md << " The run stopped: `" << firstLine(r->explosion) << "`";
        md << "\n";
    }
}

void commandList(std::ostringstream& md, const std::vector<const RunRecord*>& rows) {
    md << "\n```sh\n";
    for (const RunRecord* r : rows) md << r->command << "\n";
    md << "```\n";
}

std::vector<const RunRecord*> inSection(const std::vector<RunRecord>& runs,
                                        const std::string& name) {
    std::vector<const RunRecord*> out;
    for (const auto& r : runs) {
        if (r.experiment->section == name) out.push_back(&r);
    }
    return out;
}

void fig2Section(std::ostringstream& md, const Fig2Report& fig2) {
    md << "\n### Fig. 2: the radial force against distance\n\n";
    if (fig2.output.png.empty()) {
        md << "*(plot missing: " << fig2.output.message << ")*\n";
    } else {
        md << "![Fig. 2](figures/fig2_force.png)\n";
    }
    md << "\n*Paper:* force distribution for repulsion/attraction with A: (recommended) m = 5, "
          "n = 3; B: m = 10, n = 3; C: m = 5, n = 1; D: m = 5, n = 4. The curves are the "
          "code's own `PairForce::accumulate` at rest (no drag), b1 = 2, r0 = 1, radii 1, "
          "window C_r = r0 (the powder's and liquid's); data in `figures/fig2_force.csv`, "
          "script `figures/fig2_force.gp`. The statements are also checked with the solid's "
          "window C_r = 2 r0.\n\n"
       << "| curve | m | n | dip force | dip at D | half-dip reach | attraction area | force at "
          "D = 0.8 | dip (C_r = 2 r0) | reach (C_r = 2 r0) |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < fig2.narrow.size(); ++i) {
        const auto& a = fig2.narrow[i];
        const auto& b = fig2.wide[i];
        md << "| " << a.spec.label << " | " << num(a.spec.m) << " | " << num(a.spec.n) << " | "
           << num(a.dipForce) << " | " << num(a.dipDistance) << " | " << num(a.halfReach) << " | "
           << num(a.attractionArea) << " | " << num(a.forceAt08) << " | " << num(b.dipForce)
           << " | " << num(b.halfReach) << " |\n";
    }
    md << "\n| the paper says | measured | verdict |\n|---|---|---|\n";
    for (const auto& [claim, result] : fig2.claims) {
        md << "| " << cell(claim) << " | " << cell(result.text) << " | "
           << verdictCell(result.passed ? Verdict::Reproduced : Verdict::NotReproduced) << " |\n";
    }
    md << "\nFig. 2 overall: " << verdictCell(fig2.verdict) << ".\n";
}

std::string frameTimes(const StripRecord& s, const RunRecord* run) {
    std::string text;
    const double perFrame =
        run && run->metrics.frames > 1 ? run->metrics.duration / (run->metrics.frames - 1) : 0;
    for (int f : s.frames) {
        if (!text.empty()) text += ", ";
        text += std::to_string(f);
        if (perFrame > 0) text += " (" + num((f - 1) * perFrame) + " s)";
    }
    return text;
}

}  // namespace

std::string reproductionMarkdown(const ReportContext& ctx, const std::vector<RunRecord>& runs,
                                 const std::vector<StripRecord>& strips, const Fig2Report& fig2) {
    const Runs byId(runs);
    std::ostringstream md;
    md << "# Reproduction report: globular dynamics (Miller & Pearce 1989)\n\n"
       << "<!-- Generated by `globular figures`; regenerate rather than edit. -->\n\n"
       << "Every figure and table row of the paper (`../shared/paper/` beside the repository) "
          "run with this code, its claim beside the measured numbers and a verdict. Generated "
          "by `globular figures --out "
       << ctx.outDir.generic_string() << (ctx.scale < 1 ? " --scale " + num(ctx.scale) : "")
       << "` in **" << num(ctx.totalSeconds) << " s** (" << num(ctx.totalSeconds / 60)
       << " min) of wall time, sims and renders included, " << num(ctx.cpuSeconds)
       << " s of processor time, on " << ctx.hardwareThreads << " hardware threads ("
       << (ctx.threads > 0 ? std::to_string(ctx.threads) + " used" : "all used") << ")";
    if (ctx.loadAverage >= 0) {
        md << " shared with other jobs (load average " << num(ctx.loadAverage) << " at the end)";
    }
    md << ". Each run's files are in `" << ctx.outDir.generic_string()
       << "/<id>/`; `metrics.csv` has every number below. `docs/REPRODUCTION.md` is this file "
          "with `figures/` copied beside it.\n";
    if (ctx.scale < 1) {
        md << "\n> **Reduced run (scale " << num(ctx.scale)
           << ")**: fewer globules, frames and pixels than the paper. The verdicts below are "
              "not meaningful at this size.\n";
    }

    // ---- summary ---------------------------------------------------------------------------
    section(md, "Summary");
    md << "| item | the paper says | verdict | criteria (✓ held, ✗ did not) |\n|---|---|---|---|\n";
    for (const auto& s : strips) {
        const RunRecord* r = byId.find(s.strip->verdictFrom);
        md << "| " << cell(s.strip->title) << " | " << cell(s.strip->claim) << " | "
           << (r ? verdictCell(r->verdict) : "-") << " | " << (r ? cell(shortWhy(*r)) : "")
           << " |\n";
        if (s.strip->id == "fig1_liquid") {
            std::string crit;
            for (const auto& [claim, result] : fig2.claims) {
                crit += (crit.empty() ? "" : "; ") + claim.substr(0, claim.find(':')) +
                        (result.passed ? " ✓" : " ✗");
            }
            md << "| Fig. 2: radial force against distance | the shapes of curves A-D | "
               << verdictCell(fig2.verdict) << " | " << cell(crit) << " |\n";
        }
    }
    for (const auto& r : runs) {
        const std::string& sec = r.experiment->section;
        if (sec.rfind("Table", 0) != 0 && sec != "Defaults" &&
            r.experiment->note.rfind("variant", 0) != 0) {
            continue;
        }
        md << "| " << sec << ": " << cell(r.experiment->label) << " | " << cell(r.experiment->claim)
           << " | " << verdictCell(r.verdict) << " | " << cell(shortWhy(r)) << " |\n";
    }

    // ---- method ----------------------------------------------------------------------------
    section(md, "How the outcomes are measured");
    char settle[64], window[64];
    std::snprintf(settle, sizeof settle, "%g%%", 100 * kSettleFraction);
    std::snprintf(window, sizeof window, "%g%%", 100 * kSpreadRateWindow);
    md << "Each table row is one `globular run` of a paper scene (`scenes/paper/`) with `--set` "
          "overrides, sim stage only, "
       << kTableFrames
       << " frames at 25 fps (10 s: the 400-globule column needs about 5 s to land, so the end "
          "state is a settled pile, not the pour). Metrics come from the run's `stats.csv` "
          "(`paper/outcome_metrics.h`):\n\n"
          "- **spread**: final horizontal spread, the RMS x-z distance of the globules from "
          "their centroid (world units; radius 1). *Spill* is spread.\n"
          "- **pour spread**: the smallest horizontal spread over the run. The helix column "
          "(radius 1) contracts while it falls and the pile then spreads, so this is how tight "
          "the pour got: *tighter pour* is a pour spread more than 5% below the best case's.\n"
          "- **spill rate**: how fast the spread still grows over the last "
       << window
       << " of the run (units/s): powder on the frictionless ground keeps sliding.\n"
          "- **height**: final max height of a globule centre (the ground is y = 0 and contact "
          "is at the centre, so a lone resting globule has height about 0).\n"
          "- **largest cluster** / **clusters**: globules connected when they overlap (centre "
          "distance < r_i + r_j), transitively, at the last frame. With radius 1 and r0 = 1 "
          "resting neighbours sit about 1 apart and overlap, so a pile or even a spilled "
          "monolayer is one cluster: *clumping* is therefore judged by spread and height, and "
          "the cluster metrics only separate runs whose globules rest farther apart than "
          "2 radii (r0 = 2) or fly apart.\n"
          "- **final KE**: kinetic energy at the end (mass 1 per globule).\n"
          "- **settles at**: the first time after which the kinetic energy stays below "
       << settle
       << " of the run's peak (the peak is the pour's impact); *never* when it is still above "
          "at the end.\n"
          "- **exploded**: the run stopped before its last frame (the simulation stops when a "
          "value is not finite or a globule exceeds 1000 units/s) or a value is not finite.\n\n"
          "Each claim is read as one to three criteria, written next to the verdict: *less/more "
          "X* means the value is below/above the reference (the row's best case unless named) "
          "by more than the stated margin. **reproduced**: every criterion holds; **partly**: "
          "some do; **not reproduced**: none does. Margins are set once from the claim's "
          "wording (10% for a plain *more/less*, 25% for *little to no spill* or a *disc*), "
          "not tuned to the results.\n";

    // ---- figures ---------------------------------------------------------------------------
    section(md, "Figures");
    for (const auto& s : strips) {
        const RunRecord* first = byId.find(s.strip->experiments.front());
        const RunRecord* judged = byId.find(s.strip->verdictFrom);
        md << "\n### " << s.strip->title << "\n\n"
           << stripImage(s) << "\n*Paper:* " << s.strip->claim << "\n\n";
        if (!s.frames.empty()) {
            md << "Frames " << frameTimes(s, first);
            if (s.strip->experiments.size() > 1) {
                md << " (rows, top to bottom: ";
                for (std::size_t i = 0; i < s.strip->rowLabels.size(); ++i) {
                    md << (i ? "; " : "") << s.strip->rowLabels[i];
                }
                md << ")";
            }
            md << ". Rendered (spheres, fixed camera) with e.g. `" << s.renderCommand << "`.\n\n";
        }
        if (judged) {
            md << "Verdict";
            if (judged->experiment->section !=
                s.strip->title.substr(0, judged->experiment->section.size())) {
                md << " (shared with " << judged->experiment->section << ": "
                   << judged->experiment->label << ")";
            }
            md << ": " << verdictCell(judged->verdict) << ". " << why(*judged) << ".\n";
        }
        if (s.strip->id == "fig4_explode") {
            std::vector<const RunRecord*> rows = inSection(runs, "Fig. 4");
            const RunRecord* reference = byId.find("table4_powder");
            md << "\n";
            whyList(md, rows);
            if (reference) rows.push_back(reference);
            md << "\n";
            experimentTable(md, rows, false, reference, "reference (dt = 0.001)");
            commandList(md, rows);
        } else if (s.strip->id == "fig3_helix" && first && first->measured) {
            md << "\nFirst frame of *" << first->experiment->label << "*: " << first->metrics.count
               << " globules, x-z RMS radius " << num(first->metrics.initialSpread)
               << ", top globule at y = " << num(first->metrics.initialHeight) << ".\n";
            commandList(md, {first});
        } else if (s.strip->id == "fig7_liquid_viscous") {
            std::vector<const RunRecord*> rows;
            const RunRecord* reference = byId.find("table4_liquid");
            if (reference) rows.push_back(reference);
            if (first) rows.push_back(first);
            md << "\n";
            experimentTable(md, rows, false, reference, "reference (C_d = 1.5 r0)");
            commandList(md, rows);
        }
        if (s.strip->id == "fig1_liquid") fig2Section(md, fig2);
    }

    // ---- tables ----------------------------------------------------------------------------
    const std::vector<std::pair<std::string, std::string>> tables = {
        {"Table 1", "Table 1: powder (best case: r0 = 1, b1 = 2, m = 5, n = 3, C_r = C_d = r0)"},
        {"Table 2", "Table 2: solid (best case: r0 = 1, b1 = 1, m = 5, n = 3, C_r = C_d = 2 r0)"},
        {"Table 3",
         "Table 3: liquid (best case: r0 = 1, b1 = 2, m = 5, n = 3, C_r = r0, C_d = 1.5 r0)"},
        {"Table 4", "Table 4: the best results for all materials"}};
    const std::map<std::string, std::string> bestOf = {
        {"Table 1", "table4_powder"}, {"Table 2", "table4_solid"}, {"Table 3", "table4_liquid"}};
    for (const auto& [name, title] : tables) {
        section(md, title);
        std::vector<const RunRecord*> rows;
        if (bestOf.count(name)) {
            if (const RunRecord* b = byId.find(bestOf.at(name))) rows.push_back(b);
        }
        const auto own = inSection(runs, name);
        rows.insert(rows.end(), own.begin(), own.end());
        const RunRecord* best = bestOf.count(name) ? byId.find(bestOf.at(name)) : nullptr;
        if (best) md << "The first row is the best case every other row is compared with.\n\n";
        experimentTable(md, rows, true, best, "best case");
        if (bestOf.count(name)) rows.erase(rows.begin());
        whyList(md, rows);
        commandList(md, rows);
    }

    // ---- defaults --------------------------------------------------------------------------
    section(md, "The paper's unstated defaults, side by side");
    md << "`../shared/PAPER_NOTES.md` lists what the paper leaves open. Where a reading changes "
          "the outcome, both are run:\n\n"
          "- **C_r, C_d with r0 = 2.** The paper writes *C_r = r0* and multiplies by "
          "(r_i + r_p). The presets take the number (C_r = 2 when r0 = 2); the other reading "
          "keeps the factor (C_r = 1 whatever r0), so the window ends at D = r_i + r_p = 2 = r0 "
          "and the radial force is repulsion only.\n"
          "- **Ground contact** at the globule centre (the paper: half a globule sinks) or at "
          "its surface.\n"
          "- **Integrator** (Fig. 4): the paper's forward Euler or semi-implicit Euler; and "
          "whether Fig. 4's explosion needs the ground.\n\n";
    std::vector<const RunRecord*> side;
    for (const auto& group : paperVariantGroups()) {
        for (const auto& id : group) {
            if (const RunRecord* r = byId.find(id)) side.push_back(r);
        }
    }
    md << "| run | reading |" << kMetricHeader << " verdict |\n|---|---|" << kMetricRule
       << "---|\n";
    for (const RunRecord* r : side) {
        const std::string reading =
            r->experiment->note.empty() ? "paper default" : r->experiment->note;
        md << "| " << cell(r->experiment->section + ": " + r->experiment->label) << " | "
           << cell(reading) << " | " << metricCells(*r) << " | "
           << (r->results.empty() ? "-" : verdictCell(r->verdict)) << " |\n";
    }
    commandList(md, side);

    // ---- timing ----------------------------------------------------------------------------
    section(md, "Timing");
    md << "Whole command: **" << num(ctx.totalSeconds) << " s** wall time, " << num(ctx.cpuSeconds)
       << " s processor time.\n\n"
       << "| run | frames | globules | sim wall time (s) |\n|---|---|---|---|\n";
    for (const auto& r : runs) {
        md << "| " << r.experiment->id << " | " << (r.measured ? r.metrics.frames : 0) << " | "
           << (r.measured ? r.metrics.count : 0) << " | " << num(r.seconds) << " |\n";
    }
    md << "\n| figure | frames rendered | render wall time (s) |\n|---|---|---|\n";
    for (const auto& s : strips) {
        md << "| " << s.strip->id << " | " << s.frames.size() * s.strip->experiments.size() << " | "
           << num(s.seconds) << " |\n";
    }
    return md.str();
}

std::string metricsCsv(const std::vector<RunRecord>& runs) {
    std::ostringstream csv;
    csv << "id,section,frames,expected_frames,count,pour_spread,spread,spread_rate,height,centroid_"
           "height,"
           "largest_cluster_fraction,cluster_count,kinetic_energy,peak_kinetic_energy,"
           "settle_time,exploded,verdict,sim_seconds\n";
    char line[512];
    for (const auto& r : runs) {
        const OutcomeMetrics& m = r.metrics;
        std::snprintf(
            line, sizeof line,
            "%s,%s,%d,%d,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu,%.6g,%.6g,%.6g,%d,%s,%.3f\n",
            r.experiment->id.c_str(), r.experiment->section.c_str(), m.frames, r.frames, m.count,
            m.pourSpread, m.spread, m.spreadRate, m.height, m.centroidHeight,
            m.largestClusterFraction, m.clusterCount, m.kineticEnergy, m.peakKineticEnergy,
            m.settleTime, int(m.exploded), r.measured ? verdictText(r.verdict).c_str() : "not run",
            r.seconds);
        csv << line;
    }
    return csv.str();
}

}  // namespace globular
