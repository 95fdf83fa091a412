#include "farm_scripts.h"

#include <algorithm>

#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

std::string stepSummary(const std::string& step) {
    if (step == "sim") return "the simulation (one job; --resume continues a requeued run)";
    if (step == "surface") return "surfacing, one array task per chunk of frames";
    if (step == "plan") return "the render plan, measured once from the whole animation";
    if (step == "render") return "rendering, one array task per chunk of frames";
    return "the contact sheet and the movie";
}

std::string runCommand(const FarmSettings& s, const std::string& stage) {
    std::string line = "exec " + shellQuote(s.program.string()) + " run " +
                       shellQuote(s.scene.string()) + " --out " + shellQuote(s.outDir.string());
    for (const std::string& o : s.overrides) line += " --set " + shellQuote(o);
    line += " --stages " + stage;
    if (stage == "sim") line += " --resume";
    if (stage == "surface" || stage == "render") line += " --frames \"$frames\"";
    return line + " --threads \"${SLURM_CPUS_PER_TASK:-0}\"";
}

}  // namespace

void FarmSettings::validate() const {
    if (chunk < 1) throw SceneError("farm: --chunk must be at least 1 frame");
    if (maxRunning < 0) throw SceneError("farm: --max-running must be at least 1 (0: no limit)");
    if (frames < 1) throw SceneError("farm: the scene has no frames");
    for (const std::string* option : {&partition, &account, &timeLimit}) {
        if (option->find_first_of(" \t\n'\"\\$`") != std::string::npos) {
            throw SceneError("farm: " + quoteForMessage(*option) +
                             ": --partition, --account and --time take no spaces or quotes");
        }
    }
}

std::vector<std::pair<int, int>> farmChunks(int frames, int chunk) {
    std::vector<std::pair<int, int>> chunks;
    for (int first = 1; first <= frames; first += chunk) {
        chunks.push_back({first, std::min(frames, first + chunk - 1)});
    }
    return chunks;
}

std::string farmArraySpec(const FarmSettings& s, const std::vector<int>& tasks) {
    std::string spec;
    if (tasks.empty()) {
        spec = "0-" + std::to_string(farmChunks(s.frames, s.chunk).size() - 1);
    } else {
        for (std::size_t i = 0; i < tasks.size(); ++i) {
            if (i) spec += ',';
            spec += std::to_string(tasks[i]);
        }
    }
    if (s.maxRunning > 0) {
        spec += '%';
        spec += std::to_string(s.maxRunning);
    }
    return spec;
}

std::string farmDependency(const FarmSettings& s, const std::string& step,
                           const std::vector<std::string>& ids) {
    const auto id = [&](const std::string& name) {
        const auto at = std::find(kFarmSteps.begin(), kFarmSteps.end(), name) - kFarmSteps.begin();
        return std::size_t(at) < ids.size() ? ids[std::size_t(at)] : std::string();
    };
    std::vector<std::string> parts;
    const auto after = [&](const std::string& kind, const std::string& name) {
        if (!id(name).empty()) parts.push_back(kind + ":" + id(name));
    };
    if (step == "surface") after("afterok", "sim");
    if (step == "plan") {
        after("afterok", "sim");
        if (s.planAfterSurface) after("afterok", "surface");
    }
    if (step == "render") {
        // Task k draws the frames that surface task k meshed: a chunk starts as soon as
        // its own surfaces are there (and the plan), not when all are.
        after("aftercorr", "surface");
        after("afterok", "plan");
        if (id("surface").empty()) after("afterok", "sim");
    }
    if (step == "finish") {
        after("afterok", "render");
        if (id("render").empty()) after("afterok", "plan");
    }
    std::string text;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        if (i) text += ',';
        text += parts[i];
    }
    return text;
}

std::string farmScript(const FarmSettings& s, const std::string& step,
                       const std::string& dependency, const std::vector<int>& tasks) {
    const bool array = step == "surface" || step == "render";
    const fs::path logs = farmDir(s.outDir) / "logs";
    std::string text = "#!/bin/bash\n# globular farm: " + stepSummary(step) + ".\n# Scene " +
                       s.scene.string() + " into " + s.outDir.string() + ".\n";
    text += "#SBATCH --job-name=globular-" + step + "\n";
    text += "#SBATCH --output=" + (logs / (step + (array ? "-%A_%a.out" : "-%j.out"))).string() +
            "\n";
    if (array) text += "#SBATCH --array=" + farmArraySpec(s, tasks) + "\n";
    if (!dependency.empty()) {
        text += "#SBATCH --dependency=" + dependency + "\n";
        // A task whose dependency failed can never run: drop it rather than wait forever.
        text += "#SBATCH --kill-on-invalid-dep=yes\n";
    }
    if (!s.partition.empty()) text += "#SBATCH --partition=" + s.partition + "\n";
    if (!s.account.empty()) text += "#SBATCH --account=" + s.account + "\n";
    if (!s.timeLimit.empty()) text += "#SBATCH --time=" + s.timeLimit + "\n";
    // A node lost mid-task puts the task back in the queue; every step may run again.
    text += "#SBATCH --requeue\nset -euo pipefail\n";
    if (array) {
        text += "case \"${SLURM_ARRAY_TASK_ID:-}\" in\n";
        const auto chunks = farmChunks(s.frames, s.chunk);
        for (std::size_t k = 0; k < chunks.size(); ++k) {
            text += "    " + std::to_string(k) + ") frames=" + std::to_string(chunks[k].first) +
                    "-" + std::to_string(chunks[k].second) + " ;;\n";
        }
        text += "    *) echo \"globular farm: array task '${SLURM_ARRAY_TASK_ID:-}' has no "
                "frames\" >&2; exit 2 ;;\nesac\n";
    }
    return text + runCommand(s, step) + "\n";
}

fs::path farmDir(const fs::path& outDir) { return outDir / "farm"; }

std::string shellQuote(const std::string& text) {
    if (!text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                "0123456789_-+=./,:@%") == std::string::npos) {
        return text;
    }
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace globular
