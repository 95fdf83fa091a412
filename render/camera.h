#pragma once
// The camera a frame is drawn with, and automatic framing of a whole animation.

#include "scene_extent.h"
#include "transform.h"
#include "vec3.h"

#include <vector>

namespace globular {

struct ViewCamera {
    Vec3 position{0, 6, 24};  ///< eye, world units
    Vec3 target{0, 2, 0};     ///< looked-at point, world units
    double fov = 40;          ///< vertical field of view, degrees
};

/// A three-quarter view from slightly above, as in the paper's figures, aimed and placed
/// so that the content (@p extent's samples and extremes, each a sphere of its largest
/// radius, and
/// their feet on the ground at @p groundHeight) is centred in the central 90% of an image
/// of aspect @p aspect (width / height). Without samples it frames the box's corners;
/// an empty extent frames a few units of ground around the origin.
///
/// When @p extent holds frames (SceneExtent::endFrame), it frames the action instead: the
/// window that holds each edge of the frames' boxes in kFramedFraction of the frames, so
/// a moment that reaches far (a tall falling column, a splash) may leave the picture
/// rather than shrink the subject of the rest of the shot. One camera for the whole
/// shot either way.
ViewCamera autoFrame(const SceneExtent& extent, double groundHeight, double fov, double aspect);

/// One camera per entry of extent.frames, for a shot whose subject changes size or place
/// (a tall column that becomes a wide puddle): frame f is framed as autoFrame frames a
/// shot, from the frames within @p window frames of it, and the targets and (log)
/// distances are then averaged over the same window with raised-cosine weights, so the
/// view glides instead of cutting and the subject never shrinks to a speck. The view
/// direction stays autoFrame's. A shot whose frames are all alike gets autoFrame's camera
/// on every frame; a frame with nothing near it in time gets autoFrame's.
std::vector<ViewCamera> followTheAction(const SceneExtent& extent, double groundHeight,
                                        double fov, double aspect, int window);

/// The fraction of the frames whose content each edge of the automatic framing holds.
inline constexpr double kFramedFraction = 0.75;

/// Near and far clip distances (world units) that hold @p content and the ground out to
/// @p groundReach from the content's centre, for a camera at @p eye.
struct DepthRange {
    double zNear = 0.1, zFar = 100;
};
DepthRange depthRange(Vec3 eye, const Bounds3& content, double groundReach);

}  // namespace globular
