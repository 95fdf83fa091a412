#pragma once
// What the renderer needs to know about a whole animation before drawing its first
// frame: a box around the content (for automatic framing, the shadow map and the ground
// fade) and the range of speeds and heights (for a colour ramp that does not flicker from
// frame to frame). Robust: non-finite values are skipped, and each frame contributes the
// 0.5 to 99.5 percentiles of its globules widened by a quarter of their span, so the
// real extremes stay in the picture and a few strays far away do not shrink it.

#include <cstddef>
#include <vector>

#include "globules.h"
#include "vec3.h"

namespace globular {

struct Bounds3 {
    Vec3 min{0, 0, 0};
    Vec3 max{0, 0, 0};
    bool empty = true;

    void add(Vec3 point);
    void add(const Bounds3& other);
    Vec3 center() const { return 0.5 * (min + max); }
    double radius() const { return 0.5 * length(max - min); }  ///< of the bounding sphere
};

struct ValueRange {
    double min = 0, max = 0;
    bool empty = true;
    void add(double lo, double hi);
};

struct SceneExtent {
    Bounds3 box;        ///< globule centres, grown by their radius
    ValueRange speed;   ///< units/s
    ValueRange height;  ///< centre y, units
    /// An even sample of the centres inside the robust box (at most kMaxFramingSamples),
    /// for framing the content itself rather than its box...
    std::vector<Vec3> samples;
    /// ... and each frame's extreme centres along x, y and z, kept for every frame, so the
    /// framing reaches the real top of a falling column however sparse the sample.
    std::vector<Vec3> extremes;
    double maxRadius = 0;  ///< robust largest radius, world units
    /// Each frame's robust box (what addFrame and addPoints merged since the last
    /// endFrame; empty for a frame with nothing), in order: automatic framing frames where the content is for most of
    /// the shot rather than everywhere it ever goes.
    std::vector<Bounds3> frames;
    Bounds3 currentFrame;  ///< merged since the last endFrame()

    /// Merges one frame's robust extent.
    void addFrame(const Globules& globules);
    /// Merges a mesh's vertices (@p positions: x, y, z per vertex).
    void addPoints(const float* positions, std::size_t vertexCount);
    /// Closes the current frame: its box joins `frames` (empty when nothing was added, so
    /// `frames` has one entry per frame).
    void endFrame();
};

/// The fraction of each tail that is ignored per frame.
inline constexpr double kOutlierFraction = 0.005;
/// How far beyond those quantiles, as a fraction of their span, values still count.
inline constexpr double kOutlierMargin = 0.25;
inline constexpr std::size_t kSamplesPerFrame = 512;
inline constexpr std::size_t kMaxFramingSamples = 8192;

}  // namespace globular
