#pragma once
// Colliders as the renderer draws them: each analytic shape tessellated in its own frame
// and placed at its pose at a frame's time. Containers (inside = true) and cups are drawn
// see-through as a cutaway: their far walls and floor, not the near walls that would hide
// the liquid inside (renderer.h, Prop). Other colliders are opaque solids.

#include <vector>

#include "collider.h"
#include "mesh.h"

namespace globular {

/// Triangles wound counter-clockwise seen from outside the solid, with unit normals.
/// A plane, which has no edge, is drawn as a square of 20 units around its centre.
TriangleMesh colliderMesh(const ColliderSettings& collider, double time);

/// Every collider of a scene in one mesh at @p time (what mesh/colliders.NNNN.ply holds).
TriangleMesh collidersMesh(const std::vector<ColliderSettings>& colliders, double time);

/// Whether the renderer draws @p collider as a cutaway.
bool drawnSeeThrough(const ColliderSettings& collider);

}  // namespace globular
