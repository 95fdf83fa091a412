#pragma once
// Clusters of overlapping globules: two globules are connected when they overlap
// (distance < r_i + r_j), and a cluster is a connected group. The frame statistics'
// cluster count and largest cluster (frame_stats.h).

#include <cstddef>
#include <vector>

#include "globules.h"

namespace globular {

/// The size of each cluster of overlapping globules in @p g, in no particular order; a
/// globule with a non-finite or astronomically distant position is a cluster of one.
std::vector<std::size_t> overlapClusterSizes(const Globules& g);

}  // namespace globular
