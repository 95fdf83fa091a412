#pragma once
// Colliders as the renderer draws them: each analytic shape tessellated in its own frame
// (a mesh collider: its own triangles) and placed at its pose on a frame. Containers
// (inside = true), cups and mesh shells (a bowl) are drawn see-through as a cutaway: their
// far walls and floor, not the near walls that would hide the liquid inside (renderer.h,
// Prop). Other colliders are opaque solids.

#include <vector>

#include "collider.h"
#include "collider_solid.h"
#include "mesh.h"

namespace globular {

/// Triangles wound counter-clockwise seen from outside the solid, with unit normals, at
/// @p pose. A plane, which has no edge, is drawn as a square of 20 units around its
/// centre. @p solid is the collider's (a mesh collider's triangles are read from it).
TriangleMesh colliderMesh(const ColliderSettings& collider, const ColliderSolid& solid,
                          const Pose& pose);

/// Every collider of a scene in one mesh at @p poses (what mesh/colliders.NNNN.ply holds).
TriangleMesh collidersMesh(const std::vector<ColliderSettings>& colliders,
                           const std::vector<ColliderSolid>& solids,
                           const std::vector<Pose>& poses);

/// Whether the renderer draws @p collider as a cutaway.
bool drawnSeeThrough(const ColliderSettings& collider);

}  // namespace globular
