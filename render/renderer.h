#pragma once
// Draws one frame into an Image: globules as shaded spheres, or a triangle mesh, over a
// ground plane, lit by a key light with a shadow map plus fill lights and sky light,
// multisample anti-aliased, shaded in linear light and encoded to sRGB.
// Offscreen OpenGL through OSMesa (gl_context.h); no GL types in this header.

#include <memory>
#include <vector>

#include "camera.h"
#include "globules.h"
#include "linear_frame.h"
#include "liquid_optics.h"
#include "mesh.h"
#include "mesh_view.h"
#include "png_image.h"
#include "render_settings.h"
#include "scene_extent.h"
#include "surface_look.h"

namespace globular {

/// A solid of the set: a closed mesh wound counter-clockwise seen from outside.
struct Prop {
    TriangleMesh mesh;
    /// Drawn as a cutaway (the walls on the camera's side left out, casting no shadow),
    /// so what it contains shows; otherwise an opaque solid.
    bool seeThrough = false;
};

/// Everything that decides how a frame looks, apart from its globules or mesh.
struct FrameSetup {
    RenderSettings render;  ///< colours, color_by, ground; size and samples are the Renderer's
    ViewCamera camera;
    std::vector<LightSettings> lights;  ///< the first is the key light (shadows); may be empty
    double groundHeight = 0;            ///< world units
    /// The region the whole animation occupies: sizes the shadow map and the ground's fade
    /// so they do not change from frame to frame. Empty: the frame's own extent.
    Bounds3 content;
    /// Values at the ends of the colour ramp (color_by speed or height). Empty: the
    /// frame's own range. (Temperature: always render.temperatureLow and High.)
    ValueRange ramp;
    /// The set around the content (colliders), drawn in a neutral grey.
    std::vector<Prop> props;
    /// sRGB colour of each material, by index (color_by = material; at most 16).
    std::vector<Vec3> materialColors;
    /// Roughness and metallic of each material, by index (at most 16); missing: defaults.
    std::vector<SurfaceLook> materialLooks;
    /// Seconds between frames (1/fps): the interval of the motion pass (renderers made with
    /// passes, spheres only). 0: no motion pass.
    double frameSeconds = 0;
    /// How each material looks as a liquid, by index (drawFluid, and drawMesh with
    /// liquidSurface). Missing entries: the default liquid (liquid_optics.h).
    std::vector<LiquidOptics> materialOptics;
    /// drawMesh draws the mesh as a liquid of material 0's optics (transmission,
    /// absorption by thickness, Fresnel reflection) instead of an opaque surface.
    bool liquidSurface = false;
};

class Renderer {
  public:
    /// Creates the GL resources (and the process's GL context on first use).
    /// @param samples 1 (no anti-aliasing), 2, 4, ... up to what the driver supports.
    /// @param shadowMapSize texels per side of the key light's shadow map.
    /// @param passes also draw the compositing passes (distance and normal) into
    ///        lastFrame(), for EXR output.
    /// @throw Error when the GL context cannot be made or @p samples is unsupported.
    Renderer(int width, int height, int samples, int shadowMapSize = 2048, bool passes = false);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// The draw functions return the frame encoded for display: exposure and tone mapping
    /// of setup.render, sRGB, 8 bits, alpha straight (0 where a transparent background
    /// shows). lastFrame() keeps it linear, with its passes.
    /// Each globule a sphere of its radius. Non-finite globules are skipped.
    /// @throw Error for color_by = temperature when the globules carry none.
    Image drawSpheres(const Globules& globules, const FrameSetup& setup);
    /// The mesh, smooth-shaded with its normals (faceted without); color_by = material or
    /// temperature reads mesh.values (material 0 without).
    /// @throw Error when a triangle index is out of range, or for color_by = temperature
    ///        without mesh.values.
    Image drawMesh(const MeshView& mesh, const FrameSetup& setup);
    /// render.mode = "fluid": the globules of liquid materials (setup.materialOptics) as
    /// one smooth liquid surface in screen space (fluid_pass.h), refracting and reflecting;
    /// those of opaque materials as spheres. Non-finite globules are skipped.
    Image drawFluid(const Globules& globules, const FrameSetup& setup);

    /// As drawSpheres, drawMesh and drawFluid, but the frame is only drawn into
    /// lastFrame(), not encoded: for a caller that encodes it itself (16 bits, or on
    /// another thread after takeFrame).
    void renderSpheres(const Globules& globules, const FrameSetup& setup);
    void renderMesh(const MeshView& mesh, const FrameSetup& setup);
    void renderFluid(const Globules& globules, const FrameSetup& setup);

    /// Exchanges lastFrame() with @p frame: hands the frame drawn last over without a
    /// copy; the next draw reuses @p frame's buffers (any LinearFrame will do).
    void takeFrame(LinearFrame& frame);

    /// Occlusion culling of hidden spheres before drawing (on by default). The image is
    /// the same either way; off is for tests and measurements.
    void setOcclusionCulling(bool on);
    /// The ambient occlusion drawn only where an occluder can darken it (on by default).
    /// The image is the same either way; off is for tests and measurements.
    void setOcclusionRegions(bool on);

    /// The last frame drawn, linear and premultiplied, with the passes when asked for.
    const LinearFrame& lastFrame() const;

    int width() const;
    int height() const;
    int samples() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

/// Checker edge for automatic ground: a round number (1, 2 or 5 times a power of ten)
/// near a sixth of the content's radius, so a few squares span the content.
double automaticCheckerSize(const Bounds3& content);

}  // namespace globular
