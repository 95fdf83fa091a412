#pragma once
// OpenEXR frames for compositing (Debian's OpenEXR library): scene-linear, with alpha and
// the passes a compositor uses. Channels, all of the full image:
//   R G B A      half   linear radiance, premultiplied by A (coverage), no exposure and no
//                       tone mapping
//   Z            float  distance from the eye to the surface seen, world units (Euclidean,
//                       not along the view axis); 1e10 where nothing is drawn
//   N.x N.y N.z  half   world-space unit normal of the surface seen; 0 where nothing is
//                       drawn
//   forward.u    half   screen-space motion of the surface seen over the next frame (its
//   forward.v           velocity times 1/fps), pixels, u to the right and v up (Nuke's
//                       forward motion layer); 0 for the ground and colliders. Sphere mode
//                       only: a surface mesh carries no velocities, so mesh frames have none
// Z and N are written when the frame carries passes (LinearFrame::hasPasses()), forward
// when it carries motion. ZIP
// compression, scanlines, top row first.

#include <filesystem>

#include "linear_frame.h"

namespace globular {

/// Writes @p frame atomically (a temporary renamed into place).
/// @throw IoError naming @p path.
void writeExr(const std::filesystem::path& path, const LinearFrame& frame);

}  // namespace globular
