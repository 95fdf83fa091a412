#pragma once
// The render plan: every quantity of a frame that spans the whole animation (the
// automatic camera, the colour ramp's range, the content's bounds that size the shadow
// map and the ground's fade, the contact sheet's frames), resolved once from every
// cached frame and kept in DIR/render_plan.toml. Any later render of any frame range
// reads it, so a split (--frames A-B, a farm's chunks) renders exactly the pixels of one
// run. A fingerprint of the settings and input files it was measured from tells a stale
// plan from a current one.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "camera.h"
#include "scene_extent.h"

namespace globular {

struct RenderJob;

struct RenderPlan {
    int firstFrame = 1;        ///< the animation measured, inclusive
    int lastFrame = 1;         ///< inclusive
    std::string fingerprint;   ///< renderPlanFingerprint of what it was measured from
    std::string mode;          ///< [render] mode: what was measured (caches or meshes)
    std::string colorBy;       ///< [render] color_by the ramp is for
    int width = 0, height = 0; ///< pixels: the aspect the camera was fitted to
    ViewCamera camera;         ///< automatic (fitted) or the scene's [camera]; still
    /// With [camera] follow: the camera of each frame firstFrame..lastFrame; empty: camera
    /// on every frame.
    std::vector<ViewCamera> path;
    bool automaticCamera = false;
    Bounds3 content;           ///< the whole animation's robust box, world units
    ValueRange ramp;           ///< colour ramp ends (speed units/s or height units)
    std::vector<int> sheetFrames;  ///< contact_sheet.png's frames; empty: no sheet

    /// The camera of @p frame: path's, else camera.
    const ViewCamera& cameraFor(int frame) const;
};

/// DIR/render_plan.toml.
std::filesystem::path renderPlanPath(const std::filesystem::path& outDir);

/// A 16-hex-digit fingerprint of everything the plan depends on: the render settings
/// that enter it (mode, color_by, ramp, size, camera, ground, contact sheet, fps,
/// colliders), the animation's range, and the size and modification time of every input
/// file of it (caches or meshes, collider poses). Cheap: it stats, never reads.
std::string renderPlanFingerprint(const RenderJob& job, const std::filesystem::path& outDir,
                                  int firstFrame, int lastFrame);

/// The plan as TOML. Numbers are written in their shortest exact form, so the plan read
/// back holds the very doubles written. @throw Error for a non-finite number.
std::string renderPlanToml(const RenderPlan& plan);

/// Parses renderPlanToml's text. @p source names it in errors.
/// @throw IoError naming @p source and the key when the text is not such a plan.
RenderPlan parseRenderPlan(const std::string& text, const std::string& source);

/// Reads DIR/render_plan.toml. @throw IoError naming the file.
RenderPlan readRenderPlan(const std::filesystem::path& path);

}  // namespace globular
