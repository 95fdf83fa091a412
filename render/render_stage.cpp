#include "render_stage.h"

#include <algorithm>
#include <filesystem>
#include <optional>

#include "camera.h"
#include "collider_mesh.h"
#include "collider_poses.h"
#include "contact_sheet.h"
#include "errors.h"
#include "exr_image.h"
#include "gl_context.h"
#include "frame_paths.h"
#include "globule_cache.h"
#include "mesh_input.h"
#include "movie.h"
#include "render_estimate.h"
#include "renderer.h"
#include "surface_estimate.h"
#include "shaders.h"
#include "tone_map.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

/// frames/frame.NNNN.exr beside frames/frame.NNNN.png.
fs::path frameExrPath(const fs::path& png) {
    fs::path exr = png;
    return exr.replace_extension(".exr");
}

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
    // The surface stage's meshes are closed level sets wound outward (core/mesh.h).
    return {m.positions.data(),
            m.normals.size() == m.positions.size() ? m.normals.data() : nullptr,
            m.vertexCount(),
            m.triangles.data(),
            m.triangleCount(),
            true,
            values && values->values.size() == m.vertexCount() ? values->values.data() : nullptr};
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
                            const StageContext& ctx) {
    SceneExtent extent;
    for (int f = ctx.firstFrame; f <= ctx.lastFrame; ++f) {
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
    }
    return extent;
}

FrameSetup frameSetup(const RenderJob& job, const SceneExtent& extent) {
    FrameSetup setup;
    setup.render = job.render;
    setup.lights = job.lights.empty() ? std::vector<LightSettings>{LightSettings{}} : job.lights;
    setup.groundHeight = job.groundHeight;
    setup.materialColors = job.materialColors;
    setup.frameSeconds = job.fps > 0 ? 1.0 / job.fps : 0;
    const double aspect = double(job.render.width) / double(job.render.height);
    if (job.camera.automatic()) {
        setup.camera = autoFrame(extent, job.groundHeight, job.camera.fov, aspect);
    } else {
        setup.camera = {job.camera.position, job.camera.target, job.camera.fov};
    }
    setup.content = extent.box;
    if (job.render.rampMax > job.render.rampMin) {
        setup.ramp.add(job.render.rampMin, job.render.rampMax);
    } else {
        setup.ramp = job.render.colorBy == "speed" ? extent.speed : extent.height;
        if (setup.ramp.empty) setup.ramp.add(0, 1);  // nothing to colour: any range will do
    }
    return setup;
}

void writeSheet(const RenderJob& job, const StageContext& ctx) {
    const int count = int(job.render.contactSheet);
    const std::vector<int> frames = evenlySpacedFrames(ctx.firstFrame, ctx.lastFrame, count);
    std::vector<fs::path> pngs;
    for (int f : frames) pngs.push_back(framePngPath(ctx.outDir, f));
    const int columns = job.render.contactColumns > 0 ? int(job.render.contactColumns)
                                                      : automaticColumns(int(frames.size()));
    writeContactSheet(pngs, columns, int(job.render.contactTileWidth),
                      ctx.outDir / "contact_sheet.png");
    ctx.report().info("render: wrote " + (ctx.outDir / "contact_sheet.png").string());
}

void writeMovie(const RenderJob& job, const StageContext& ctx) {
    const fs::path ffmpeg = findOnPath("ffmpeg");
    if (ffmpeg.empty()) {
        ctx.report().warn(
            "render: [render] movie = true but ffmpeg is not on PATH; no movie.mp4 "
            "(install ffmpeg, or assemble frames/ yourself)");
        return;
    }
    const double fps = job.render.movieFps > 0 ? job.render.movieFps : job.fps;
    assembleMovie(ffmpeg, ctx.outDir, ctx.firstFrame, ctx.lastFrame, fps);
    ctx.report().info("render: wrote " + (ctx.outDir / "movie.mp4").string());
}

}  // namespace

void runRenderStage(const RenderJob& job, const StageContext& ctx) {
    validate(job, ctx);
    ctx.sweepTemporaries("render");
    const uint64_t available = availableMemoryBytes();
    checkRenderMemory(job.render, 0, available, "the image");
    const long total = ctx.lastFrame - ctx.firstFrame + 1;
    ctx.report().info("render: measuring " + std::to_string(total) + " frame(s) for framing");
    const std::vector<ColliderSolid> solids = job.colliders.solids();
    const FrameSetup setup = frameSetup(job, animationExtent(job, solids, ctx));
    selectGlBackend(chooseGlBackend(job.render.gl));
    Renderer renderer(int(job.render.width), int(job.render.height), int(job.render.samples),
                      int(job.render.shadowMapSize), job.render.exr);
    const ToneMapping tone = ToneMapping::from(job.render.exposure, job.render.toneMapping);
    ctx.report().progress("render", 0, total);
    for (int f = ctx.firstFrame; f <= ctx.lastFrame; ++f) {
        FrameSetup frameSetup = setup;
        frameSetup.props = propsAt(job, solids, ctx, f);
        Image image;
        if (job.render.mode == "surface") {
            const TriangleMesh mesh = readMesh(job, ctx.outDir, f);
            // An empty frame (nothing emitted yet) has nothing to colour.
            checkTemperature(job, mesh.attribute("temperature") || mesh.vertexCount() == 0,
                             meshPath(ctx.outDir, f, job.meshFormat));
            checkRenderMemory(job.render,
                              estimateMeshBytes(mesh.vertexCount(), mesh.triangleCount()),
                              available, "frame " + std::to_string(f));
            image = renderer.drawMesh(viewOf(mesh, job.render.colorBy), frameSetup);
        } else {
            const Globules globules = readCache(ctx.outDir, f);
            checkTemperature(job, !globules.temperature.empty() || globules.empty(),
                             cacheVdbPath(ctx.outDir, f));
            checkRenderMemory(job.render, estimateSphereBytes(globules.size()), available,
                              "frame " + std::to_string(f));
            image = renderer.drawSpheres(globules, frameSetup);
        }
        const fs::path png = framePngPath(ctx.outDir, f);
        if (job.render.pngBits == 16) {
            writePng(png, encode16(renderer.lastFrame(), tone));
        } else {
            writePng(png, image);
        }
        if (job.render.exr) writeExr(frameExrPath(png), renderer.lastFrame());
        ctx.report().progress("render", f - ctx.firstFrame + 1, total);
    }
    if (job.render.contactSheet > 0) writeSheet(job, ctx);
    if (job.render.movie) writeMovie(job, ctx);
}

}  // namespace globular
