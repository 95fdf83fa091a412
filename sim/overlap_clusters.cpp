// Clusters of overlapping globules (overlap_clusters.h): a grid over the globules, then
// either small cells that each hold one cluster (a compact pile) or every pair within
// reach (a loose set), into a lock-free union-find.
#include "overlap_clusters.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "neighbor_grid.h"

namespace globular {

namespace {

/// @brief Lock-free union-find (Anderson & Woll): a root only ever links below a smaller
/// index, so there are no cycles and the components are the same whatever order the
/// threads unite pairs in.
class ConcurrentUnionFind {
  public:
    explicit ConcurrentUnionFind(std::size_t n) : mParent(n) {
        for (std::size_t i = 0; i < n; ++i) mParent[i].store(uint32_t(i));
    }

    uint32_t find(uint32_t x) {
        while (true) {
            uint32_t p = mParent[x].load();
            if (p == x) return x;
            const uint32_t grandparent = mParent[p].load();
            if (grandparent != p) mParent[x].compare_exchange_weak(p, grandparent);  // halve
            x = grandparent;
        }
    }

    void unite(uint32_t a, uint32_t b) {
        while (true) {
            a = find(a);
            b = find(b);
            if (a == b) return;
            if (a < b) std::swap(a, b);
            uint32_t expected = a;  // a is a root; link it below the smaller root b
            if (mParent[a].compare_exchange_strong(expected, b)) return;
        }
    }

  private:
    std::vector<std::atomic<uint32_t>> mParent;
};

/// @brief Whether a globule can be binned: a grid cell coordinate of a non-finite or
/// astronomically distant position would overflow. Such globules stay clusters of one.
bool binnable(const Globules& g, std::size_t i, double cellSize) {
    const double limit = 1e15 * cellSize;
    for (float c : {g.px[i], g.py[i], g.pz[i]}) {
        if (!(std::fabs(c) < limit)) return false;
    }
    return true;
}

/// The size of each set of @p sets over its @p nodes, node k holding @p globulesIn(k)
/// globules, after @p singles clusters of one (globules that were not binned).
template <typename GlobulesIn>
std::vector<std::size_t> setSizes(ConcurrentUnionFind& sets, std::size_t nodes,
                                  std::size_t singles, GlobulesIn&& globulesIn) {
    std::vector<std::size_t> sizeOfRoot(nodes, 0);
    for (std::size_t k = 0; k < nodes; ++k) sizeOfRoot[sets.find(uint32_t(k))] += globulesIn(k);
    std::vector<std::size_t> sizes(singles, 1);
    for (std::size_t size : sizeOfRoot) {
        if (size > 0) sizes.push_back(size);
    }
    return sizes;
}

/// Cells whose diagonal is this fraction of the smallest overlap distance: rounding in
/// the cell of a position and in the pair test stays far inside the margin.
constexpr double kCellDiagonalFraction = 0.99;
/// Overlaps reaching farther than this many cells (radii far apart) take the pair loop.
constexpr int kMaxCellSpan = 3;
/// The cells are used where they hold at least this many globules on average.
constexpr double kMinCellOccupancy = 2.0;
/// Cell coordinates stay within +-kCellLimit (21 bits each in a key).
constexpr int64_t kCellLimit = (int64_t(1) << 20) - 2 * kMaxCellSpan;

uint64_t cellKey(int64_t x, int64_t y, int64_t z) {
    constexpr int64_t kOffset = int64_t(1) << 20;
    return (uint64_t(x + kOffset) << 42) | (uint64_t(y + kOffset) << 21) | uint64_t(z + kOffset);
}

/// Sizes of the clusters of the globules at @p px, @p py, @p pz (in grid order) of
/// @p radius, and @p unbinnable clusters of one, over cells so small that any two
/// globules in one overlap: each cell is one node of the union-find, and a pair of nearby
/// cells is united by the first overlapping pair found between them, or skipped at once
/// when they are in one cluster already (in a compact pile, nearly all). The clusters
/// are exactly those of every pair tested. Empty where testing the pairs is the better
/// way (cells holding few globules) or the only one (radii far apart, a position
/// millions of cells out).
std::vector<std::size_t> clusterSizesByCells(const std::vector<float>& px,
                                             const std::vector<float>& py,
                                             const std::vector<float>& pz,
                                             const std::vector<float>& radius,
                                             std::size_t unbinnable) {
    float rMin = INFINITY, rMax = 0;
    for (const float r : radius) {
        if (!(r > 0) || !std::isfinite(r)) return {};
        rMin = std::min(rMin, r);
        rMax = std::max(rMax, r);
    }
    // Two globules in one cell are less than its diagonal apart, under r_i + r_j.
    const double cell = kCellDiagonalFraction * 2.0 * double(rMin) / std::sqrt(3.0);
    const int span = int(std::ceil(1.001 * 2.0 * double(rMax) / cell));
    if (span > kMaxCellSpan) return {};
    const std::size_t m = px.size();
    // The cell of globule i, or false when it lies too far out for a key.
    const auto keyOf = [&](std::size_t i, uint64_t& key) {
        int64_t c[3];
        const float p[3] = {px[i], py[i], pz[i]};
        for (int a = 0; a < 3; ++a) {
            const double at = std::floor(double(p[a]) / cell);
            if (!(std::fabs(at) < double(kCellLimit))) return false;
            c[a] = int64_t(at);
        }
        key = cellKey(c[0], c[1], c[2]);
        return true;
    };
    // Worth it only where cells hold several globules (a compact pile, not a loose
    // lattice, where testing pairs is cheaper). Estimated from windows of consecutive
    // globules, which in grid order lie near each other.
    constexpr std::size_t kWindow = 2048, kWindows = 4;
    std::size_t sampled = 0, occupied = 0;
    for (std::size_t w = 0; w < kWindows; ++w) {
        const std::size_t from = m <= kWindow ? 0 : (m - kWindow) * w / (kWindows - 1);
        std::vector<uint64_t> window;
        for (std::size_t k = from; k < std::min(m, from + kWindow); ++k) {
            uint64_t key;
            if (!keyOf(k, key)) return {};
            window.push_back(key);
        }
        std::sort(window.begin(), window.end());
        sampled += window.size();
        occupied += std::size_t(std::unique(window.begin(), window.end()) - window.begin());
        if (m <= kWindow) break;
    }
    if (double(sampled) < kMinCellOccupancy * double(occupied)) return {};
    std::vector<std::pair<uint64_t, uint32_t>> keyed(m);
    std::atomic<bool> tooFar{false};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 4096), [&](const auto& range) {
        for (std::size_t k = range.begin(); k < range.end(); ++k) {
            keyed[k].second = uint32_t(k);
            if (!keyOf(k, keyed[k].first)) tooFar = true;
        }
    });
    if (tooFar) return {};
    tbb::parallel_sort(keyed.begin(), keyed.end());
    // Positions and radii in cell order; cell c holds [start[c], start[c + 1]).
    std::vector<float> x(m), y(m), z(m), r(m);
    std::vector<uint64_t> keys;
    std::vector<uint32_t> start;
    for (std::size_t k = 0; k < m; ++k) {
        const uint32_t i = keyed[k].second;
        x[k] = px[i];
        y[k] = py[i];
        z[k] = pz[i];
        r[k] = radius[i];
        if (k == 0 || keyed[k].first != keyed[k - 1].first) {
            keys.push_back(keyed[k].first);
            start.push_back(uint32_t(k));
        }
    }
    start.push_back(uint32_t(m));
    const std::size_t cells = keys.size();
    const auto overlapping = [&](std::size_t a, std::size_t b) {
        for (uint32_t s = start[a]; s < start[a + 1]; ++s) {
            for (uint32_t l = start[b]; l < start[b + 1]; ++l) {
                const float dx = x[l] - x[s], dy = y[l] - y[s], dz = z[l] - z[s];
                const float reach = r[s] + r[l];
                if (dx * dx + dy * dy + dz * dz < reach * reach) return true;
            }
        }
        return false;
    };
    // The cells after a cell in key order (x, then y, then z) within span, as key offsets
    // from it: one row along z for each (dx, dy) after (0, 0), and the rest of its own.
    // Each pair of cells is met once.
    struct Row {
        int64_t fromOffset, toOffset;
    };
    std::vector<Row> rows;
    const int64_t xStep = int64_t(1) << 42, yStep = int64_t(1) << 21;
    for (int64_t dx = 0; dx <= span; ++dx) {
        for (int64_t dy = dx == 0 ? 0 : -span; dy <= span; ++dy) {
            const int64_t zFrom = dx == 0 && dy == 0 ? 1 : -span;
            rows.push_back({dx * xStep + dy * yStep + zFrom, dx * xStep + dy * yStep + span});
        }
    }
    ConcurrentUnionFind sets(cells);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 512), [&](const auto& range) {
        // A row's first cell only moves on with the cell (a key offset is a constant):
        // one search where the range starts, then each row's cursor walks forward.
        std::vector<std::size_t> cursor(rows.size());
        for (std::size_t j = 0; j < rows.size(); ++j) {
            cursor[j] = std::size_t(std::lower_bound(keys.begin(), keys.end(),
                                                     keys[range.begin()] + rows[j].fromOffset) -
                                    keys.begin());
        }
        for (std::size_t c = range.begin(); c < range.end(); ++c) {
            uint32_t root = sets.find(uint32_t(c));
            for (std::size_t j = 0; j < rows.size(); ++j) {
                const uint64_t first = keys[c] + rows[j].fromOffset;
                const uint64_t last = keys[c] + rows[j].toOffset;
                std::size_t& at = cursor[j];
                while (at < cells && keys[at] < first) ++at;
                for (std::size_t other = at; other < cells && keys[other] <= last; ++other) {
                    if (sets.find(uint32_t(other)) == root) continue;
                    if (!overlapping(c, other)) continue;
                    sets.unite(uint32_t(c), uint32_t(other));
                    root = sets.find(uint32_t(c));
                }
            }
        }
    });
    return setSizes(sets, cells, unbinnable,
                    [&](std::size_t c) { return std::size_t(start[c + 1] - start[c]); });
}

}  // namespace

std::vector<std::size_t> overlapClusterSizes(const Globules& g) {
    const std::size_t n = g.size();
    float maxRadius = 0;
    for (float r : g.radius) {
        if (std::isfinite(r)) maxRadius = std::max(maxRadius, r);
    }
    if (!(maxRadius > 0)) return std::vector<std::size_t>(n, 1);
    const float cellSize = 2 * maxRadius;  // covers the largest overlap distance
    std::vector<uint32_t> member;          // grid point k is globule member[k]
    member.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (binnable(g, i, cellSize)) member.push_back(uint32_t(i));
    }
    const std::size_t m = member.size();
    std::vector<float> x(m), y(m), z(m), r(m);
    for (std::size_t k = 0; k < m; ++k) {
        x[k] = g.px[member[k]];
        y[k] = g.py[member[k]];
        z[k] = g.pz[member[k]];
    }
    NeighborGrid grid;
    grid.build(x.data(), y.data(), z.data(), m, cellSize);
    // Copies in the grid's order: a query's runs are then contiguous ranges of these
    // arrays, read straight through, and a pair is tested once, from its earlier end.
    // The clusters are found over these positions too, so that the union-find's reads
    // stay as local as the neighbours (sizes do not depend on the labels).
    const std::vector<uint32_t>& order = grid.sortedOrder();
    for (std::size_t s = 0; s < m; ++s) {  // in place: x, y, z now in grid order
        const uint32_t i = member[order[s]];
        x[s] = g.px[i];
        y[s] = g.py[i];
        z[s] = g.pz[i];
        r[s] = g.radius[i];
    }
    if (std::vector<std::size_t> sizes = clusterSizesByCells(x, y, z, r, n - m); !sizes.empty()) {
        return sizes;
    }
    // A loose lattice, radii far apart or positions far out: every pair within reach
    // tested.
    ConcurrentUnionFind sets(m);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, m, 1024),
        [&](const tbb::blocked_range<std::size_t>& range) {
            NeighborGrid::RunCursor cursor;
            std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> runs;
            constexpr std::size_t kChunk = 64;
            std::array<uint8_t, kChunk> overlaps;
            for (std::size_t s = range.begin(); s < range.end(); ++s) {
                // Most overlapping pairs are already in one cluster: a find on the
                // partner's side alone tells, and only the rest are united.
                uint32_t root = sets.find(uint32_t(s));
                const int count = grid.neighborRuns(x[s], y[s], z[s], cursor, runs);
                for (int q = 0; q < count; ++q) {
                    const std::size_t end = runs[q].second;
                    for (std::size_t l = std::max<std::size_t>(runs[q].first, s + 1); l < end;
                         l += kChunk) {
                        const std::size_t chunk = std::min(kChunk, end - l);
                        for (std::size_t k = 0; k < chunk; ++k) {  // vectorised test
                            const float dx = x[l + k] - x[s], dy = y[l + k] - y[s],
                                        dz = z[l + k] - z[s];
                            const float reach = r[s] + r[l + k];
                            overlaps[k] = dx * dx + dy * dy + dz * dz < reach * reach;
                        }
                        for (std::size_t k = 0; k < chunk; ++k) {
                            if (!overlaps[k]) continue;
                            const uint32_t other = sets.find(uint32_t(l + k));
                            if (other == root) continue;
                            sets.unite(root, other);
                            root = sets.find(uint32_t(s));
                        }
                    }
                }
            }
        });
    return setSizes(sets, m, n - m, [](std::size_t) { return std::size_t(1); });
}

}  // namespace globular
