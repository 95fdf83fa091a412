#pragma once
// Internal to render/: the pixels the ambient occlusion (occlusion_pass.h) can darken.
// Only what is drawn before it and is not the ground occludes: the ground is a plane and
// every tap of a pixel's hemisphere lies above it, so a pixel whose taps all land on the
// ground or the background keeps its colour. A tap reaches a bounded distance on the
// screen, so the pass need only cover the occluders' tiles of the screen, each widened
// by the reach at its depth: llvmpipe shades every pixel a draw covers, whatever the
// shader discards.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "frame_uniforms.h"
#include "globules.h"

namespace globular::detail {

/// Pixels [x0, x1] x [y0, y1], OpenGL window coordinates (y up).
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};

class OcclusionRegion {
  public:
    /// Square tiles of this many pixels a side.
    static constexpr int kTile = 16;

    /// No occluder yet, for the frame @p f and an occlusion of @p radius world units.
    OcclusionRegion(const FrameUniforms& f, double radius);

    /// Adds the triangles (three indices into @p positions, x y z per vertex) as occluders.
    void addTriangles(const float* positions, std::size_t vertexCount, const uint32_t* triangles,
                      std::size_t triangleCount);
    /// Adds the globules' spheres as occluders.
    void addSpheres(const Globules& globules);
    /// Every pixel may be darkened (an occluder this class cannot bound: the add* members
    /// call it for one at or behind the near plane, or not finite).
    void addEverything() { mWhole = true; }

    bool whole() const { return mWhole; }
    /// Where the pass must run (unless whole()): runs of tiles along each row of tiles,
    /// clipped to the frame; none when nothing occludes.
    std::vector<PixelRect> rects() const;

  private:
    /// Records an occluder covering ndc [x0, x1] x [y0, y1] at view depths >= @p depth.
    void addFootprint(double x0, double x1, double y0, double y1, double depth);

    const FrameUniforms& mFrame;
    double mRadius;
    double mExtent[2];            ///< the image's half width and height at unit distance
    int mTiles[2];                ///< across, up
    std::vector<float> mNearest;  ///< per tile, the least occluder depth in it (or +inf)
    bool mWhole = false;
};

}  // namespace globular::detail
