#include "render_stage.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "camera.h"
#include "collider_mesh.h"
#include "atomic_file.h"
#include "collider_poses.h"
#include "contact_sheet.h"
#include "errors.h"
#include "exr_image.h"
#include "frame_writer.h"
#include "gl_context.h"
#include "frame_paths.h"
#include "globule_cache.h"
#include "mesh_input.h"
#include "movie.h"
#include "render_estimate.h"
#include "render_plan.h"
#include "renderer.h"
#include "surface_estimate.h"
#include "shaders.h"
#include "tone_map.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

Globules readCache(const fs::path& outDir, int frame) {
    const fs::path path = cacheVdbPath(outDir, frame);
    if (!fs::exists(path)) {
        throw IoError("missing globule cache " + path.string() + " for frame " +
                      std::to_string(frame) +
                      ": run the sim stage first (globular run SCENE --stages sim)");
    }
    return readGlobuleVdb(path);
}

TriangleMesh readMesh(const RenderJob& job, const fs::path& outDir, int frame) {
    return readSurfaceMesh(meshPath(outDir, frame, job.meshFormat), job.meshFormat);
}

/// The mesh and, for color_by = material or temperature, its attribute of that name.
MeshView viewOf(const TriangleMesh& m, const std::string& colorBy) {
    const VertexAttribute* values =
        colorBy == "material" || colorBy == "temperature" ? m.attribute(colorBy) : nullptr;
    const VertexAttribute* materials = m.attribute("material");  // roughness and metallic
    auto perVertex = [&](const char* name) -> const float* {
        const VertexAttribute* a = m.attribute(name);
        return a && a->values.size() == m.vertexCount() ? a->values.data() : nullptr;
    };
    // The surface stage's meshes are closed level sets wound outward (core/mesh.h).
    return {m.positions.data(),
            m.normals.size() == m.positions.size() ? m.normals.data() : nullptr,
            m.vertexCount(),
            m.triangles.data(),
            m.triangleCount(),
            true,
            values && values->values.size() == m.vertexCount() ? values->values.data() : nullptr,
            materials && materials->values.size() == m.vertexCount() ? materials->values.data()
                                                                     : nullptr,
            perVertex("vx"),  // the velocity, for motion blur
            perVertex("vy"),
            perVertex("vz")};
}

/// color_by = temperature needs temperatures: a scene without [thermal] has none.
/// @throw SceneError naming the file that lacks them.
void checkTemperature(const RenderJob& job, bool present, const fs::path& file) {
    if (job.render.colorBy != "temperature" || present) return;
    throw SceneError("[render] key 'color_by' = \"temperature\": " + file.string() +
                     " carries no temperature (the scene has no [thermal] section" +
                     (job.render.mode == "surface"
                          ? ", or the mesh was written as obj or before temperature existed)"
                          : ")"));
}

void validate(const RenderJob& job, const StageContext& ctx) {
    job.render.validate();
    job.camera.validate();
    for (const LightSettings& light : job.lights) light.validate();
    if (job.lights.size() > std::size_t(shaders::kMaxLights)) {
        throw SceneError("[[light]]: " + std::to_string(job.lights.size()) +
                         " lights given, at most " + std::to_string(shaders::kMaxLights));
    }
    if (job.meshFormat != "ply" && job.meshFormat != "obj") {
        throw SceneError("[surface] key 'mesh_format' = \"" + job.meshFormat +
                         "\": the render stage reads ply or obj");
    }
    if (ctx.firstFrame < 1 || ctx.lastFrame < ctx.firstFrame) {
        throw SceneError("render stage: frame range " + std::to_string(ctx.firstFrame) + "-" +
                         std::to_string(ctx.lastFrame) + " is empty or starts before frame 1");
    }
}

/// The colliders on frame @p frame, where the sim stage left them.
std::vector<Prop> propsAt(const RenderJob& job, const std::vector<ColliderSolid>& solids,
                          const StageContext& ctx, int frame) {
    std::vector<Prop> props;
    const std::vector<ColliderSettings>& colliders = job.colliders.colliders;
    const std::vector<Pose> poses = colliderPosesOnFrame(colliders, ctx.outDir, frame, job.fps);
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        props.push_back({colliderMesh(colliders[k], solids[k], poses[k]),
                         drawnSeeThrough(colliders[k])});
    }
    return props;
}

/// Reads every frame once: what the whole animation occupies, the set's solids on every
/// frame included (but planes, which have no edge to frame).
SceneExtent animationExtent(const RenderJob& job, const std::vector<ColliderSolid>& solids,
                            const StageContext& ctx, int firstFrame, int lastFrame) {
    SceneExtent extent;
    for (int f = firstFrame; f <= lastFrame; ++f) {
        const std::vector<Prop> props = propsAt(job, solids, ctx, f);
        for (std::size_t k = 0; k < props.size(); ++k) {
            if (solids[k].shape() == ColliderShape::Plane) continue;
            extent.addPoints(props[k].mesh.positions.data(), props[k].mesh.vertexCount());
        }
        if (job.render.mode == "surface") {
            const TriangleMesh mesh = readMesh(job, ctx.outDir, f);
            extent.addPoints(mesh.positions.data(), mesh.vertexCount());
        } else {
            extent.addFrame(readCache(ctx.outDir, f));
        }
        extent.endFrame();
    }
    return extent;
}

/// What the whole animation shares, measured from all its frames.
RenderPlan measurePlan(const RenderJob& job, const std::vector<ColliderSolid>& solids,
                       const StageContext& ctx, int firstFrame, int lastFrame) {
    const SceneExtent extent = animationExtent(job, solids, ctx, firstFrame, lastFrame);
    RenderPlan plan;
    plan.firstFrame = firstFrame;
    plan.lastFrame = lastFrame;
    plan.mode = job.render.mode;
    plan.colorBy = job.render.colorBy;
    plan.width = int(job.render.width);
    plan.height = int(job.render.height);
    plan.automaticCamera = job.camera.automatic();
    const double aspect = double(job.render.width) / double(job.render.height);
    if (plan.automaticCamera) {
        plan.camera = autoFrame(extent, job.groundHeight, job.camera.fov, aspect);
        if (job.camera.follow) {
            const int window = std::max(1, int(std::lround(job.camera.followSeconds * job.fps)));
            plan.path = followTheAction(extent, job.groundHeight, job.camera.fov, aspect, window);
        }
    } else {
        plan.camera = {job.camera.position, job.camera.target, job.camera.fov};
    }
    plan.content = extent.box;
    if (job.render.rampMax > job.render.rampMin) {
        plan.ramp.add(job.render.rampMin, job.render.rampMax);
    } else {
        plan.ramp = job.render.colorBy == "speed" ? extent.speed : extent.height;
        if (plan.ramp.empty) plan.ramp.add(0, 1);  // nothing to colour: any range will do
    }
    if (job.render.contactSheet > 0) {
        plan.sheetFrames = evenlySpacedFrames(firstFrame, lastFrame, int(job.render.contactSheet));
    }
    return plan;
}

FrameSetup frameSetup(const RenderJob& job, const RenderPlan& plan) {
    FrameSetup setup;
    setup.render = job.render;
    setup.lights = job.lights.empty() ? std::vector<LightSettings>{LightSettings{}} : job.lights;
    setup.groundHeight = job.groundHeight;
    setup.materialColors = job.materialColors;
    setup.materialLooks = job.materialLooks;
    setup.materialOptics = job.materialOptics;
    // A mesh has one look: liquid when every material is one, and when no colour codes a
    // value (color_by height, material or temperature keep the opaque, coloured surface,
    // so the values read).
    setup.liquidSurface = job.render.mode == "surface" && job.render.colorBy == "constant" &&
                          !job.materialOptics.empty() &&
                          std::all_of(job.materialOptics.begin(), job.materialOptics.end(),
                                      [](const LiquidOptics& o) { return o.liquid; });
    setup.frameSeconds = job.fps > 0 ? 1.0 / job.fps : 0;
    setup.camera = plan.camera;
    setup.content = plan.content;
    setup.ramp = plan.ramp;
    return setup;
}

/// The frames of the animation whose PNG is missing or older than the plan (so drawn
/// with another one, or none), for the contact sheet and movie.
std::vector<int> framesNotDrawnWith(const std::vector<int>& frames, const fs::path& outDir) {
    std::error_code error;
    const auto planTime = fs::last_write_time(renderPlanPath(outDir), error);
    std::vector<int> missing;
    for (int f : frames) {
        const auto time = fs::last_write_time(framePngPath(outDir, f), error);
        if (error || time < planTime) missing.push_back(f);
    }
    return missing;
}

std::string frameList(const std::vector<int>& frames) {
    std::string text;
    for (std::size_t i = 0; i < frames.size() && i < 10; ++i) {
        text += (i ? ", " : "") + std::to_string(frames[i]);
    }
    if (frames.size() > 10) text += " and " + std::to_string(frames.size() - 10) + " more";
    return text;
}

void writeSheet(const RenderJob& job, const RenderPlan& plan, const StageContext& ctx) {
    std::vector<fs::path> pngs;
    for (int f : plan.sheetFrames) pngs.push_back(framePngPath(ctx.outDir, f));
    const int columns = job.render.contactColumns > 0
                            ? int(job.render.contactColumns)
                            : automaticColumns(int(plan.sheetFrames.size()));
    writeContactSheet(pngs, columns, int(job.render.contactTileWidth),
                      ctx.outDir / "contact_sheet.png");
    ctx.report().info("render: wrote " + (ctx.outDir / "contact_sheet.png").string());
}

void writeMovie(const RenderJob& job, const RenderPlan& plan, const StageContext& ctx) {
    const fs::path ffmpeg = findOnPath("ffmpeg");
    if (ffmpeg.empty()) {
        ctx.report().warn(
            "render: [render] movie = true but ffmpeg is not on PATH; no movie.mp4 "
            "(install ffmpeg, or assemble frames/ yourself)");
        return;
    }
    const double fps = job.render.movieFps > 0 ? job.render.movieFps : job.fps;
    assembleMovie(ffmpeg, ctx.outDir, plan.firstFrame, plan.lastFrame, fps);
    ctx.report().info("render: wrote " + (ctx.outDir / "movie.mp4").string());
}

std::vector<int> moviePlusSheetFrames(const RenderJob& job, const RenderPlan& plan) {
    std::vector<int> frames;
    if (job.render.movie) {
        for (int f = plan.firstFrame; f <= plan.lastFrame; ++f) frames.push_back(f);
    } else {
        frames = plan.sheetFrames;
    }
    return frames;
}

/// The contact sheet and movie, when every frame they take was drawn with @p plan.
/// @return the frames still missing (nothing written then).
std::vector<int> finish(const RenderJob& job, const RenderPlan& plan, const StageContext& ctx) {
    if (plan.sheetFrames.empty() && !job.render.movie) return {};
    const std::vector<int> missing = framesNotDrawnWith(moviePlusSheetFrames(job, plan), ctx.outDir);
    if (!missing.empty()) return missing;
    if (!plan.sheetFrames.empty()) writeSheet(job, plan, ctx);
    if (job.render.movie) writeMovie(job, plan, ctx);
    return {};
}

/// The animation the plan spans: the cached one, frames 1 to the last of an unbroken run
/// of caches (all job.animationFrames once the simulation ran to the end; fewer after
/// `run --frames 1-B`, which simulates to B), and never short of the requested range.
/// job.animationFrames = 0: the requested range.
std::pair<int, int> animationRange(const RenderJob& job, const StageContext& ctx) {
    if (job.animationFrames <= 0) return {ctx.firstFrame, ctx.lastFrame};
    if (ctx.lastFrame > job.animationFrames) {
        throw SceneError("render stage: frame range " + std::to_string(ctx.firstFrame) + "-" +
                         std::to_string(ctx.lastFrame) + " goes past the animation's " +
                         std::to_string(job.animationFrames) + " frames");
    }
    int cached = 0;
    while (cached < job.animationFrames && fs::exists(cacheVdbPath(ctx.outDir, cached + 1))) {
        ++cached;
    }
    return {1, std::max(cached, ctx.lastFrame)};
}

RenderPlan ensurePlan(const RenderJob& job, const std::vector<ColliderSolid>& solids,
                      const StageContext& ctx) {
    const auto [first, last] = animationRange(job, ctx);
    const fs::path path = renderPlanPath(ctx.outDir);
    const std::string print = renderPlanFingerprint(job, ctx.outDir, first, last);
    std::optional<RenderPlan> old;
    if (fs::exists(path)) {
        try {
            old = readRenderPlan(path);
            if (old->fingerprint == print && old->firstFrame == first && old->lastFrame == last) {
                ctx.report().info("render: using " + path.string());
                return *old;
            }
            ctx.report().info("render: " + path.string() +
                              " was measured from other settings or caches; measuring again");
        } catch (const IoError& e) {
            ctx.report().warn(std::string(e.what()) + "; measuring again");
        }
    }
    ctx.report().info("render: measuring frames " + std::to_string(first) + "-" +
                      std::to_string(last) + " for the render plan");
    RenderPlan plan = measurePlan(job, solids, ctx, first, last);
    plan.fingerprint = print;
    const std::string text = renderPlanToml(plan);
    std::error_code error;
    const auto oldTime = fs::last_write_time(path, error);
    writeFileAtomically(path, text);
    ctx.report().info("render: wrote " + path.string());
    if (old && !error) {
        // Inputs rewritten with the same content (a requeued surface task) measure the
        // same plan: frames drawn with the old one stay current for the contact sheet.
        old->fingerprint = print;
        if (renderPlanToml(*old) == text) fs::last_write_time(path, oldTime, error);
    }
    // Draw with the values as read back, exactly what a later split will read.
    return parseRenderPlan(text, path.string());
}

}  // namespace

void runRenderStage(const RenderJob& job, const StageContext& ctx) {
    validate(job, ctx);
    ctx.sweepTemporaries("render");
    const uint64_t available = availableMemoryBytes();
    checkRenderMemory(job.render, 0, available, "the image");
    const long total = ctx.lastFrame - ctx.firstFrame + 1;
    const std::vector<ColliderSolid> solids = job.colliders.solids();
    const RenderPlan plan = ensurePlan(job, solids, ctx);
    const FrameSetup setup = frameSetup(job, plan);
    selectGlBackend(chooseGlBackend(job.render.gl));
    Renderer renderer(int(job.render.width), int(job.render.height), int(job.render.samples),
                      int(job.render.shadowMapSize), job.render.exr);
    const ToneMapping tone = ToneMapping::from(job.render.exposure, job.render.toneMapping);
    ctx.report().progress("render", 0, total);
    FrameWriter writer(tone, int(job.render.pngBits), job.render.exr);
    LinearFrame drawn;
    for (int f = ctx.firstFrame; f <= ctx.lastFrame; ++f) {
        FrameSetup frameSetup = setup;
        frameSetup.props = propsAt(job, solids, ctx, f);
        frameSetup.camera = plan.cameraFor(f);
        if (job.render.mode == "surface") {
            const TriangleMesh mesh = readMesh(job, ctx.outDir, f);
            // An empty frame (nothing emitted yet) has nothing to colour.
            checkTemperature(job, mesh.attribute("temperature") || mesh.vertexCount() == 0,
                             meshPath(ctx.outDir, f, job.meshFormat));
            checkRenderMemory(job.render,
                              estimateMeshBytes(mesh.vertexCount(), mesh.triangleCount()),
                              available, "frame " + std::to_string(f));
            renderer.renderMesh(viewOf(mesh, job.render.colorBy), frameSetup);
        } else {
            const Globules globules = readCache(ctx.outDir, f);
            checkTemperature(job, !globules.temperature.empty() || globules.empty(),
                             cacheVdbPath(ctx.outDir, f));
            checkRenderMemory(job.render, estimateSphereBytes(globules.size()), available,
                              "frame " + std::to_string(f));
            if (job.render.mode == "fluid") {
                renderer.renderFluid(globules, frameSetup);
            } else {
                renderer.renderSpheres(globules, frameSetup);
            }
        }
        renderer.takeFrame(drawn);
        // Frame f is encoded and written while frame f + 1 is drawn; its progress is
        // reported once it is on disk.
        writer.write(drawn, framePngPath(ctx.outDir, f));
        if (f > ctx.firstFrame) ctx.report().progress("render", f - ctx.firstFrame, total);
    }
    writer.finish();
    ctx.report().progress("render", total, total);
    const std::vector<int> missing = finish(job, plan, ctx);
    if (!missing.empty()) {
        ctx.report().info("render: contact sheet and movie wait for frame(s) " +
                          frameList(missing) + " (the render that draws the last of them "
                          "writes them, or --stages finish)");
    }
}

RenderPlan ensureRenderPlan(const RenderJob& job, const StageContext& ctx) {
    validate(job, ctx);
    ctx.sweepTemporaries("render");
    return ensurePlan(job, job.colliders.solids(), ctx);
}

void finishRenderStage(const RenderJob& job, const StageContext& ctx) {
    validate(job, ctx);
    const RenderPlan plan = ensurePlan(job, job.colliders.solids(), ctx);
    const std::vector<int> missing = finish(job, plan, ctx);
    if (!missing.empty()) {
        throw IoError("contact sheet and movie: frame(s) " + frameList(missing) + " of " +
                      ctx.outDir.string() + " are missing or older than " +
                      renderPlanPath(ctx.outDir).string() +
                      ": render them first (globular run SCENE --stages render --frames A-B)");
    }
}


}  // namespace globular
