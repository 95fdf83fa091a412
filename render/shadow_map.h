#pragma once
// Internal to render/: the key light's depth map (an orthographic view along the light
// that covers the content), sampled with hardware depth comparison and linear filtering.

#include <cstdint>
#include <vector>

#include "gl_objects.h"

namespace globular::detail {

/// The shadow map's texture unit, its own: passes create their textures on first use
/// (binding and unbinding them on the active unit, 0), and a map kept on unit 0 was then
/// unbound for the first frame a renderer drew (the liquid's glints missing from the first
/// frame of every range).
inline constexpr int kShadowMapUnit = 14;

/// Texels [x0, x1] x [y0, y1] of the map; empty when x1 < x0.
struct TexelRect {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
    bool empty() const { return x1 < x0 || y1 < y0; }
};

class ShadowMap {
  public:
    /// @param maxSize the most texels per side a frame may use
    explicit ShadowMap(int maxSize);
    /// Texels per side for content of @p worldSize (world units across) seen with pixels of
    /// @p pixelWorldSize: about one texel per pixel, as finer detail is never seen and
    /// costs fill (a million globules cover the map many times over), within
    /// [min(512, maxSize), maxSize].
    int sizeFor(double worldSize, double pixelWorldSize) const;
    /// Binds the map, @p size texels per side, as the render target; clears it to the
    /// far plane.
    void beginDrawing(int size);
    /// The texels the casters drawn since beginDrawing() wrote, while the map is still
    /// bound as the target. Reads the map back, so it waits for them to be drawn.
    TexelRect drawnTexels();
    /// Binds the map to kShadowMapUnit for the shading passes; unit 0 is left active.
    void bindForSampling() const;
    int size() const { return mSize; }

  private:
    void allocate(int size);

    int mMaxSize;
    int mSize = 0;
    gl::Texture mDepth;
    gl::Framebuffer mFramebuffer;
    std::vector<uint32_t> mReadBack;
};

}  // namespace globular::detail
