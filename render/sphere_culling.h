#pragma once
// Internal to render/: occlusion culling of sphere impostors on the CPU, before drawing.
//
// A million globules in a puddle overlap tens of times on screen, and llvmpipe runs the
// ray-casting fragment shader (which writes gl_FragDepth, so no early depth test) for
// every one of them. Most are hidden behind the top layer. Here each sphere becomes a
// ScreenDisc in one view (the camera's or the key light's); a coarse depth grid keeps,
// per cell, the nearest depth up to which some sphere covers every sample of the cell
// (its "core": a square inside the silhouette); a sphere whose nearest point is behind
// that depth in every cell its fragments can touch cannot change the image and is not
// drawn. The test is conservative (cores are inside silhouettes, depths are bounds with
// a margin larger than the depth buffer's resolution), so the drawn frame is identical
// with and without culling; draw order is kept.

#include <cstdint>
#include <vector>

#include "frame_uniforms.h"
#include "globules.h"

namespace globular::detail {

/// A sphere as one view sees it. Positions in pixels (texels) from the bottom left;
/// depths in any measure that grows away from the viewer.
struct ScreenDisc {
    float x = 0, y = 0;  ///< projected centre
    /// Half side of the square around (x, y) that holds every fragment the sphere can
    /// write. +infinity: it may cover anything (kept, never tested); negative: never drawn.
    float half = -1;
    float reach = 0;      ///< radius about (x, y) holding the centres of all pixels it can write
    float nearDepth = 0;  ///< its nearest point, less the depth buffer's resolution
    /// Radius of a circle about (x, y) in which it covers every sample; <= 0: none.
    float coreRadius = 0;
    float coreDepth = 0;  ///< farthest depth it writes inside that circle
};

/// The spheres in the camera's view of @p frame (sprites, multisampled or not), into
/// @p discs (one per globule; its memory is reused from frame to frame).
void cameraDiscs(const Globules& globules, const FrameUniforms& frame,
                 std::vector<ScreenDisc>& discs);

/// The spheres in the key light's orthographic view (the shadow map, @p frame's size).
void lightDiscs(const Globules& globules, const FrameUniforms& frame,
                std::vector<ScreenDisc>& discs);

/// Culls discs in one view; keeps its working memory (a depth grid of the view's size,
/// tens of megabytes for a million discs) from frame to frame.
class OcclusionCuller {
  public:
    /// Sets @p indices to those, ascending, of the discs that may be visible in a
    /// @p width x @p height view: all but those off the view and those behind other
    /// discs' cores everywhere they reach. Deterministic for any thread count.
    void cull(const std::vector<ScreenDisc>& discs, int width, int height,
              std::vector<uint32_t>& indices);

  private:
    struct Core {
        float x, y, radius, depth;
    };
    std::vector<float> mGrid, mBlockFar;
    std::vector<std::size_t> mStart, mNext;
    std::vector<Core> mCores;
    std::vector<uint8_t> mVisible;
};

/// OcclusionCuller::cull with memory of its own.
std::vector<uint32_t> unoccluded(const std::vector<ScreenDisc>& discs, int width, int height);

}  // namespace globular::detail
