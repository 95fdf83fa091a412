#pragma once
// Where every collider stands on each frame, as the simulation moved it: written by the
// sim stage beside the caches (cache/colliders.NNNN.toml) and read by the surface and
// render stages, so a dynamic collider is drawn and cut where the globules met it.
// The file is TOML, one [[collider]] table per collider in scene order:
//   name = "ball"
//   translation = [x, y, z]          world = rotation * local + translation
//   rotation = [[r00, r01, r02], [r10, r11, r12], [r20, r21, r22]]
//   velocity = [vx, vy, vz]          of the collider's frame origin (world units / s)
//   angular_velocity = [wx, wy, wz]  radians / s, world axes

#include <filesystem>
#include <vector>

#include "collider.h"
#include "collider_motion.h"

namespace globular {

/// Writes @p motions (one per collider of @p colliders) for @p frame at @p time,
/// atomically. @throw IoError naming @p path.
void writeColliderPoses(const std::filesystem::path& path, int frame, double time,
                        const std::vector<ColliderSettings>& colliders,
                        const std::vector<ColliderMotion>& motions);

/// Reads a poses file written for @p colliders. @throw IoError naming @p path and what is
/// wrong (not TOML, a count or name that does not match the scene, a non-finite number,
/// a rotation that is not one).
std::vector<Pose> readColliderPoses(const std::filesystem::path& path,
                                    const std::vector<ColliderSettings>& colliders);

/// The poses of @p colliders on @p frame in the output folder @p outDir: from the sim
/// stage's file; where it is absent (caches from before the file existed), from the
/// keyframes, which is only possible when no collider is dynamic.
/// @throw IoError naming the missing or unreadable file.
std::vector<Pose> colliderPosesOnFrame(const std::vector<ColliderSettings>& colliders,
                                       const std::filesystem::path& outDir, int frame,
                                       double fps);

}  // namespace globular
