#pragma once
// A rendered frame before it is encoded for display: scene-linear radiance with
// coverage, and on request the passes a compositor uses. Rows top to bottom.

#include <cstddef>
#include <vector>

namespace globular {

struct LinearFrame {
    int width = 0, height = 0;  ///< pixels
    /// Linear radiance, premultiplied by alpha (the OpenEXR convention), 4 floats a pixel.
    /// Alpha is the fraction of the pixel covered; 1 everywhere unless the background is
    /// transparent. Exposure and tone mapping are not applied.
    std::vector<float> rgba;
    /// With passes only (else empty), one value a pixel: the distance from the eye to
    /// the surface seen, world units, averaged over the pixel's covered samples;
    /// kNothing where nothing is drawn.
    std::vector<float> depth;
    /// With passes only, 3 floats a pixel: the world-space unit normal of the surface
    /// seen (averaged over the covered samples, renormalised); 0 where nothing is drawn.
    std::vector<float> normal;
    /// With passes of globules that carry velocities, 2 floats a pixel: how far the surface
    /// seen moves on the screen over the next frame (1/fps at its velocity), pixels, x to
    /// the right and y up; 0 for the ground and the set. Empty otherwise (mesh mode: the
    /// mesh has no velocities).
    std::vector<float> motion;

    /// Depth where nothing is drawn (as Blender writes it).
    static constexpr float kNothing = 1e10f;

    bool hasPasses() const { return !depth.empty(); }
    const float* pixel(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

}  // namespace globular
