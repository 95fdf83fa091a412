#pragma once
// The render stage: every frame of a run's output directory to frames/frame.NNNN.png,
// plus, on request, a contact sheet and movie.mp4. No GL types here.

#include <string>
#include <vector>

#include "collider_solid.h"
#include "render_settings.h"
#include "stage_context.h"

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
};

/// Renders frames ctx.firstFrame..ctx.lastFrame of ctx.outDir:
///  - reads cache/globules.NNNN.vdb (mode spheres) or mesh/surface.NNNN.<meshFormat>
///    (mode surface) of every frame once first, for the automatic camera (when the
///    camera is not given), the shadow map's and ground's extent, and the colour ramp's
///    range, so all of them hold still over the animation;
///  - writes frames/frame.NNNN.png (8 or 16 bits, render.pngBits) and, with render.exr,
///    frames/frame.NNNN.exr (exr_image.h), reporting progress("render", done, total);
///  - contact_sheet.png of render.contactSheet evenly spaced frames when asked;
///  - movie.mp4 when render.movie and ffmpeg is on PATH (a warning otherwise).
/// @throw SceneError for invalid settings (naming the key), IoError naming a missing or
///        unreadable input and the stage to run first, Error when OpenGL is unavailable.
void runRenderStage(const RenderJob& job, const StageContext& ctx);

}  // namespace globular
