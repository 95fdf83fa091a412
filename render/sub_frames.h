#pragma once
// Motion blur and depth of field by accumulation: a frame is the average of sub-frames,
// each drawn at its own instant within the shutter interval (globules moved along their
// velocities) and through its own point of a thin lens (the eye moved on the lens disc,
// the image shifted to keep the plane in focus in register). With enough sub-frames this
// is the box-filtered exposure of a film camera; the passes (depth, normal, motion) come
// from the first sub-frame, the one at the frame's instant and the lens's centre when
// there is one.

#include <vector>

#include "camera.h"
#include "globules.h"
#include "linear_frame.h"
#include "mesh_view.h"
#include "render_settings.h"

namespace globular {

struct SubFrame {
    double seconds = 0;            ///< offset from the frame's instant
    double lensX = 0, lensY = 0;   ///< eye offset along the camera's right and up, world units
};

/// The sub-frames of a frame of @p r, @p frameSeconds (1/fps) long. One sub-frame (at the
/// frame's instant, through the lens's centre) unless motion_blur or aperture ask for
/// more. Times are the midpoints of motion_samples equal slices of the shutter, centred
/// on the frame; lens points are a Fibonacci spiral over the lens disc (even in area).
/// The one nearest the frame's instant and the lens's centre comes first.
std::vector<SubFrame> subFrames(const RenderSettings& r, double frameSeconds);

/// The camera of @p sub: the eye moved on the lens (along the camera's right and up),
/// looking the same way. Its image is then shifted by lensShift() so that the plane in
/// focus lands where the lens's centre sees it: together an off-axis (sheared) frustum,
/// the exact thin-lens model, drawn by the renderer's symmetric one.
ViewCamera throughLens(const ViewCamera& camera, const SubFrame& sub);

/// The shift, pixels (x right, y up), that brings the plane in focus of @p sub's image
/// back in register: the lens offset times focalPixels / focus distance, the distance
/// r.focusDistance (0: from the eye to the camera's target). A point at distance z then
/// lands lens * focalPixels * (1/focus - 1/z) pixels away: over the lens, a disc of
/// radius aperture * focalPixels * |z - focus| / (focus * z), the thin lens's circle of
/// confusion.
struct PixelShift {
    double x = 0, y = 0;
};
PixelShift lensShift(const ViewCamera& camera, const SubFrame& sub, const RenderSettings& r,
                     double focalPixelsX, double focalPixelsY);

/// Adds @p frame's rgba, shifted by @p shift (bilinear; the edge pixels extend beyond the
/// border), to @p sum (the same size).
void addShifted(std::vector<float>& sum, const LinearFrame& frame, PixelShift shift);

/// @p globules with each centre moved by its velocity times @p seconds.
Globules movedBy(const Globules& globules, double seconds);

/// @p mesh with each vertex moved by its velocity times @p seconds, its positions held in
/// @p storage; @p mesh itself when it has no velocities or @p seconds is 0.
MeshView movedBy(const MeshView& mesh, double seconds, std::vector<float>& storage);

}  // namespace globular
