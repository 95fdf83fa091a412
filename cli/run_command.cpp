#include "run_command.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <regex>

#include "atomic_file.h"
#include "default_scene.h"
#include "errors.h"
#include "output_lock.h"
#include "render_stage.h"
#include "reporter.h"
#include "scene.h"
#include "sim_stage.h"
#include "stage_context.h"
#include "state_file.h"
#include "surface_stage.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

// plan: the render plan alone (render makes it too); finish: the contact sheet and movie
// from the frames on disk (render writes them too once its frames complete the set).
const std::vector<std::string> kStages = {"sim", "surface", "plan", "render", "finish"};

struct FrameRange {
    int first = 1, last = 1;
};

FrameRange parseFrames(const std::string& text, int frames) {
    if (text.empty()) return {1, frames};
    std::smatch match;
    static const std::regex pattern(R"(^\s*(\d+)\s*(?:-\s*(\d+)\s*)?$)");
    if (!std::regex_match(text, match, pattern)) {
        throw SceneError("--frames " + quoteForMessage(text) +
                         ": expected A-B or N, e.g. --frames 1-48");
    }
    // Compared as text first: stol would throw on a number past its range.
    const auto number = [&](const std::string& digits) {
        return digits.size() > 9 ? long(1e9) : std::stol(digits);
    };
    const long first = number(match[1]);
    const long last = match[2].matched ? number(match[2]) : first;
    if (first < 1 || last < first || last > frames) {
        throw SceneError("--frames " + quoteForMessage(text) + ": must lie within 1-" + std::to_string(frames) +
                         " (the scene has " + std::to_string(frames) + " frames) with A <= B");
    }
    return {int(first), int(last)};
}

void checkStages(const std::vector<std::string>& stages) {
    if (stages.empty()) {
        throw SceneError("--stages: name at least one of sim,surface,plan,render,finish");
    }
    for (const auto& s : stages) {
        if (std::find(kStages.begin(), kStages.end(), s) == kStages.end()) {
            throw SceneError("--stages: unknown stage '" + s +
                             "' (stages: sim, surface, plan, render, finish)");
        }
    }
}

bool wants(const std::vector<std::string>& stages, const std::string& stage) {
    return std::find(stages.begin(), stages.end(), stage) != stages.end();
}

}  // namespace

const char* defaultSceneText() { return kDefaultSceneToml; }

void runScene(const RunOptions& options, Reporter& reporter) {
    checkStages(options.stages);
    Scene scene = options.scene.empty()
                      ? parseScene(kDefaultSceneToml, "<default scene>", options.overrides, reporter)
                      : loadScene(options.scene, options.overrides, reporter);
    const std::string name =
        options.scene.empty() ? "default" : fs::path(options.scene).stem().string();
    const fs::path outDir = options.outDir.empty() ? fs::path("out") / name : options.outDir;
    const FrameRange range = parseFrames(options.frames, int(scene.simulation.frames));
    if (options.threads < 0) throw SceneError("--threads must be at least 1 (0 = all cores)");

    std::unique_ptr<tbb::global_control> threadLimit;
    if (options.threads > 0) {
        threadLimit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, std::size_t(options.threads));
    }
    ensureWritableDirectory(outDir);
    // A simulation owns the folder; surface and render runs (farm chunks) may share it.
    const OutputLock lock(outDir, wants(options.stages, "sim") ? OutputLock::Mode::Exclusive
                                                                : OutputLock::Mode::Shared);
    const std::string resolved = resolvedSceneToml(scene);

    StageContext ctx{outDir, range.first, range.last, &reporter};
    const auto started = std::chrono::steady_clock::now();
    if (wants(options.stages, "sim")) {
        // The simulation always starts at frame 1: later frames depend on earlier ones.
        writeFileAtomically(outDir / "scene.toml", resolved);
        SimStageOptions simOptions{scene.output, options.resume, fingerprint(resolved)};
        StageContext simCtx = ctx;
        simCtx.firstFrame = 1;
        reporter.info("sim: " + std::to_string(range.last) + " frames into " + outDir.string());
        try {
            runSimStage(scene.simulationSetup(), simOptions, simCtx);
        } catch (const SceneError& e) {  // an emitter's keys, found when it emits
            throw SceneError(quoteForMessage(scene.file.empty() ? "<default scene>"
                                                                : scene.file.string(), 300) +
                             ": " + e.what());
        }
    }
    if (wants(options.stages, "surface")) {
        reporter.info("surface: frames " + std::to_string(range.first) + "-" +
                      std::to_string(range.last));
        runSurfaceStage(scene.surface, ctx, scene.colliderScene(), scene.simulation.fps,
                        !scene.otherMaterials.empty());
    }
    const bool plan = wants(options.stages, "plan"), render = wants(options.stages, "render"),
               finish = wants(options.stages, "finish");
    if (plan || render || finish) {
        std::vector<Vec3> materialColors;
        std::vector<SurfaceLook> materialLooks;
        const std::vector<MaterialSettings> materials = scene.simulationSetup().materials();
        for (std::size_t k = 0; k < materials.size(); ++k) {
            materialColors.push_back(materialColor(materials[k], k));
            materialLooks.push_back(surfaceLook(materials[k]));
        }
        RenderJob job;
        job.render = scene.render;
        job.camera = scene.camera;
        job.lights = scene.lights;
        job.groundHeight = scene.ground.enabled ? scene.ground.height : 0;
        job.meshFormat = scene.surface.meshFormat;
        job.fps = scene.simulation.fps;
        job.colliders = scene.colliderScene();
        job.materialColors = materialColors;
        for (const MaterialSettings& material : materials) {
            job.materialOptics.push_back(liquidOptics(material));
        }
        job.materialLooks = materialLooks;
        // Like the scene's other files, the environment is found beside the scene.
        if (!job.render.environment.empty() &&
            std::filesystem::path(job.render.environment).is_relative()) {
            job.render.environment =
                (scene.directory() / job.render.environment).lexically_normal().string();
        }
        job.animationFrames = int(scene.simulation.frames);
        if (plan) ensureRenderPlan(job, ctx);
        if (render) {
            reporter.info("render: frames " + std::to_string(range.first) + "-" +
                          std::to_string(range.last));
            runRenderStage(job, ctx);
        }
        if (finish) finishRenderStage(job, ctx);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    reporter.info("done in " + std::to_string(seconds) + " s: " + outDir.string());
}

}  // namespace globular
