#pragma once
// Per-vertex attributes of a surface mesh, carried from the globules with the surface's
// own kernel: at each vertex, every globule within its influence radius R weighs
// w = kernel(r^2 / R^2) (metaball_kernel.h), the weights the field itself sums there.
//
//   vx vy vz (float):    sum(w v) / sum(w), the kernel-weighted mean velocity (what
//                        Houdini's v and Blender's velocity attribute are made from)
//   temperature (float): sum(w T) / sum(w), the kernel-weighted mean
//   material (int):      the material with the largest sum of w (ties: the lower index)
//
// Each vertex gathers its weighted globules once and every attribute reads that list.
// A vertex no globule reaches (a dilated or cut surface) takes the nearest globule's
// values among those binned near it, or temperature 0 and material 0 when there is none.
// OpenVDB-free.

#include "globule_bins.h"
#include "globules.h"
#include "mesh.h"
#include "metaball_kernel.h"

namespace globular {

/// Which attributes carryGlobuleAttributes adds.
struct CarriedAttributes {
    bool velocity = false;     ///< vx vy vz
    bool temperature = false;  ///< needs globules.temperature
    bool material = false;
    bool any() const { return velocity || temperature || material; }
};

/// What @p globules carry: velocity always, temperature when they have one, material when the scene has
/// @p severalMaterials or some globule's material index is not 0 (so every frame of a
/// scene of several materials carries it, and a scene of one leaves it out).
CarriedAttributes attributesOf(const Globules& globules, bool severalMaterials = false);

/// Appends the attributes @p which to @p mesh.attributes, one value per vertex. Parallel
/// over vertices, each summing its globules in a fixed order: identical for any thread
/// count.
/// @param influence R as a multiple of a globule's radius; @p voxelSize world units (the
///        surface's; it only sizes the bins).
/// @throw as GlobuleBins (non-finite or far globules).
void carryGlobuleAttributes(TriangleMesh& mesh, const Globules& globules,
                            const MetaballKernel& kernel, double influence, double voxelSize,
                            CarriedAttributes which);

/// The same with the globules already binned (@p bins of @p globules at @p voxelSize and
/// the surface's influence: the splat's bins, built once per frame). Vertices are taken
/// block by block, each block looking its globules up once.
void carryGlobuleAttributes(TriangleMesh& mesh, const Globules& globules,
                            const GlobuleBins& bins, const MetaballKernel& kernel,
                            double voxelSize, CarriedAttributes which);

}  // namespace globular
