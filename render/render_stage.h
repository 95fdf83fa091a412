#pragma once
// The render stage: every frame of a run's output directory to frames/frame.NNNN.png,
// plus, on request, a contact sheet and movie.mp4. No GL types here.

#include <string>
#include <vector>

#include "collider_solid.h"
#include "liquid_optics.h"
#include "render_plan.h"
#include "render_settings.h"
#include "stage_context.h"
#include "surface_look.h"

namespace globular {

struct RenderJob {
    RenderSettings render;
    CameraSettings camera;
    std::vector<LightSettings> lights;  ///< [[light]]; empty: one default key light
    double groundHeight = 0;            ///< [ground] height, world units
    std::string meshFormat = "ply";     ///< [surface] mesh_format, for mode = surface
    double fps = 25;                    ///< [simulation] fps: the movie's rate by default
    ColliderScene colliders;  ///< [[collider]]: drawn at each frame's pose (collider_poses.h)
    std::vector<Vec3> materialColors;  ///< sRGB by material index, for color_by = material
    std::vector<SurfaceLook> materialLooks;  ///< roughness and metallic by material index
    /// [simulation] frames N: the render plan measures the cached animation, frames 1..N
    /// (or up to the last cached frame), whatever range is drawn. 0: the requested range
    /// is the whole animation.
    int animationFrames = 0;
    /// The liquid look of each material, by index (mode = fluid; mode = surface draws a
    /// liquid when all are liquid). Empty: the surface opaque, the fluid the default liquid.
    std::vector<LiquidOptics> materialOptics = {};
};

/// Renders frames ctx.firstFrame..ctx.lastFrame of ctx.outDir:
///  - takes what spans the animation (the automatic camera, the shadow map's and ground's
///    extent, the colour ramp's range, the contact sheet's frames) from the render plan
///    DIR/render_plan.toml (render_plan.h), measuring it first from every frame of the
///    whole animation when it is missing or stale, so any split draws one run's pixels;
///  - reads cache/globules.NNNN.vdb (mode spheres) or mesh/surface.NNNN.<meshFormat>
///    (mode surface) and writes frames/frame.NNNN.png (8 or 16 bits, render.pngBits) and,
///    with render.exr, frames/frame.NNNN.exr (exr_image.h), reporting
///    progress("render", done, total);
///  - then, once every frame they take is drawn with the plan (this range or earlier
///    ones), contact_sheet.png and movie.mp4 (when render.movie and ffmpeg is on PATH, a
///    warning otherwise).
/// @throw SceneError for invalid settings (naming the key), IoError naming a missing or
///        unreadable input and the stage to run first, Error when OpenGL is unavailable.
void runRenderStage(const RenderJob& job, const StageContext& ctx);

/// The plan step alone: DIR/render_plan.toml measured when missing or stale, else kept.
/// @return the plan. @throw as runRenderStage.
RenderPlan ensureRenderPlan(const RenderJob& job, const StageContext& ctx);

/// contact_sheet.png and movie.mp4 from the frames on disk (a farm's last job).
/// @throw IoError naming the frames that are missing or older than the plan.
void finishRenderStage(const RenderJob& job, const StageContext& ctx);

}  // namespace globular
