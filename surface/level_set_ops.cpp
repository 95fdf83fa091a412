// Level-set steps of surfacing: the levelSetRebuild reference path, filters, droplet
// removal and the fog volume. The heaviest OpenVDB templates live here, in one translation unit.
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_for.h>

#include <memory>

#include "surface_grids.h"

namespace globular {

using openvdb::FloatGrid;

FloatGrid::Ptr rebuildLevelSet(const FloatGrid& field, double isoValue, double bandWidth) {
    // levelSetRebuild meshes the iso surface and re-voxelises it with signs from a flood
    // fill of the exterior, so it works on a density-like field (larger inside) as well as
    // on a distance field.
    FloatGrid::Ptr levelSet =
        openvdb::tools::levelSetRebuild(field, float(isoValue), float(bandWidth), float(bandWidth));
    levelSet->setGridClass(openvdb::GRID_LEVEL_SET);
    levelSet->setName("surface");
    return levelSet;
}

void applyFilters(FloatGrid& levelSet, const std::vector<FilterStep>& chain) {
    if (chain.empty() || levelSet.tree().leafCount() == 0) return;
    openvdb::tools::LevelSetFilter<FloatGrid> filter(levelSet);
    const double voxel = levelSet.voxelSize()[0];
    for (const FilterStep& step : chain) {
        const int count = int(step.amount);
        switch (step.kind) {
            case FilterKind::Gaussian:
                filter.gaussian(count);
                break;
            case FilterKind::MeanCurvature:
                for (int i = 0; i < count; ++i) filter.meanCurvature();
                break;
            case FilterKind::Laplacian:
                for (int i = 0; i < count; ++i) filter.laplacian();
                break;
            // offset() adds to the distance: negative moves the surface outward. It
            // advances in half-voxel steps with renormalisation, so any distance is safe.
            case FilterKind::Dilate:
                filter.offset(float(-step.amount * voxel));
                break;
            case FilterKind::Erode:
                filter.offset(float(step.amount * voxel));
                break;
        }
    }
}

std::size_t removeDroplets(FloatGrid::Ptr& levelSet, double minVolume) {
    if (minVolume <= 0 || levelSet->tree().leafCount() == 0) return 0;
    std::vector<FloatGrid::Ptr> pieces;
    openvdb::tools::segmentSDF(*levelSet, pieces);
    std::vector<FloatGrid::Ptr> kept;
    for (auto& piece : pieces) {
        if (openvdb::tools::levelSetVolume(*piece, true) >= minVolume) kept.push_back(piece);
    }
    const std::size_t removed = pieces.size() - kept.size();
    if (removed == 0) return 0;

    // The pieces are disjoint surfaces: their union (minimum of distances) is the level set
    // without the droplets.
    FloatGrid::Ptr result = FloatGrid::create(levelSet->background());
    result->setTransform(levelSet->transform().copy());
    result->setGridClass(openvdb::GRID_LEVEL_SET);
    result->setName(levelSet->getName());
    for (auto& piece : kept) openvdb::tools::csgUnion(*result, *piece);
    levelSet = result;
    return removed;
}

FloatGrid::Ptr levelSetToFog(const FloatGrid& levelSet) {
    FloatGrid::Ptr fog = levelSet.deepCopy();
    openvdb::tools::sdfToFogVolume(*fog);
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    fog->setName("density");
    // Values in [0, 1]: half floats keep them to 2^-11, and halve the file.
    fog->setSaveFloatAsHalf(true);
    return fog;
}

void keepInside(FloatGrid& grid, const FloatGrid& levelSet, double margin) {
    const float limit = float(margin);
    const float background = grid.background();
    const auto& distances = levelSet.tree();
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
    // Leaf by leaf: where the level set has no leaf, one tile value decides a whole leaf.
    leaves.foreach([&](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
        const auto* band = distances.probeConstLeaf(leaf.origin());
        if (!band && distances.getValue(leaf.origin()) <= limit) return;
        for (auto it = leaf.beginValueOn(); it; ++it) {
            if (!band || band->getValue(it.pos()) > limit) {
                it.setValue(background);
                it.setValueOff();
            }
        }
    });
    openvdb::tools::pruneInactive(grid.tree());
}

openvdb::Vec3SGrid::Ptr velocityInBand(const FloatGrid& x, const FloatGrid& y,
                                       const FloatGrid& z, const FloatGrid& levelSet,
                                       double margin) {
    using VecLeaf = openvdb::Vec3STree::LeafNodeType;
    auto vel = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    vel->setTransform(levelSet.transform().copy());
    vel->setName("vel");
    vel->setGridClass(openvdb::GRID_UNKNOWN);
    vel->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    // Half floats: 11 significant bits (a relative error under 5e-4), plenty for motion
    // blur, and half the file.
    vel->setSaveFloatAsHalf(true);
    const float limit = float(margin);
    // One output leaf per band leaf, made in parallel (the means' leaves share one
    // layout: a probe per leaf, no lookups per voxel), then handed to the tree serially.
    std::vector<const openvdb::FloatTree::LeafNodeType*> band;
    band.reserve(levelSet.tree().leafCount());
    levelSet.tree().getNodes(band);
    std::vector<std::unique_ptr<VecLeaf>> out(band.size());
    const auto &tx = x.tree(), &ty = y.tree(), &tz = z.tree();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.size(), 32), [&](auto range) {
        for (std::size_t b = range.begin(); b < range.end(); ++b) {
            const auto& distances = *band[b];
            const auto* lx = tx.probeConstLeaf(distances.origin());
            if (!lx) continue;
            const auto* ly = ty.probeConstLeaf(distances.origin());
            const auto* lz = tz.probeConstLeaf(distances.origin());
            // The voxels kept: in the band, within the margin, and where the means are.
            VecLeaf::NodeMaskType kept;
            const float* distance = distances.buffer().data();
            for (auto on = distances.getValueMask().beginOn(); on; ++on) {
                if (!(distance[on.pos()] > limit) && lx->isValueOn(on.pos())) kept.setOn(on.pos());
            }
            if (kept.isOff()) continue;
            auto leaf = std::make_unique<VecLeaf>(distances.origin(), vel->background());
            openvdb::Vec3s* values = leaf->buffer().data();
            for (auto on = kept.beginOn(); on; ++on) {
                const openvdb::Index i = on.pos();
                values[i] = openvdb::Vec3s(lx->getValue(i), ly ? ly->getValue(i) : 0.0f,
                                           lz ? lz->getValue(i) : 0.0f);
            }
            leaf->setValueMask(kept);
            out[b] = std::move(leaf);
        }
    });
    auto& tree = vel->tree();
    for (auto& leaf : out) {
        if (leaf) tree.addLeaf(leaf.release());
    }
    return vel;
}

}  // namespace globular
