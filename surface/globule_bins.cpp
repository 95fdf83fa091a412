#include "globule_bins.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "errors.h"

namespace globular {

namespace {

constexpr int64_t kOffset = int64_t(1) << 20;
constexpr uint64_t kFieldMask = (uint64_t(1) << 21) - 1;

std::string describeGlobule(const Globules& g, std::size_t i) {
    std::ostringstream out;
    out << "globule id " << (i < g.id.size() ? g.id[i] : int32_t(i)) << " at (" << g.px[i] << ", "
        << g.py[i] << ", " << g.pz[i] << ") radius " << g.radius[i];
    return out.str();
}

}  // namespace

uint64_t GlobuleBins::pack(int64_t bx, int64_t by, int64_t bz) {
    return (uint64_t(bx + kOffset) << 42) | (uint64_t(by + kOffset) << 21) | uint64_t(bz + kOffset);
}

std::array<int64_t, 3> GlobuleBins::unpack(uint64_t key) {
    return {int64_t((key >> 42) & kFieldMask) - kOffset,
            int64_t((key >> 21) & kFieldMask) - kOffset, int64_t(key & kFieldMask) - kOffset};
}

GlobuleBins::GlobuleBins(const Globules& g, double voxelSize, double influence) {
    const std::size_t n = g.size();
    const double toIndex = 1.0 / voxelSize;
    mCentre.resize(3 * n);
    mInfluence.assign(n, 0.0f);

    // Validation and index-space centres, serially: a few milliseconds per million
    // globules, and the first bad globule named is the same on every run.
    std::vector<uint64_t> keys(n, 0);
    float maxInfluence = 0;
    // Keep every block and its reach inside the packed 21-bit range.
    const double limit = double(kMaxBlockCoord / 2) * kBlockDim;
    for (std::size_t i = 0; i < n; ++i) {
        const double x = g.px[i] * toIndex, y = g.py[i] * toIndex, z = g.pz[i] * toIndex;
        const double r = double(g.radius[i]) * influence * toIndex;
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(r)) {
            throw SimulationError("cannot surface " + describeGlobule(g, i) +
                                  ": its position or radius is not finite");
        }
        if (std::abs(x) + r > limit || std::abs(y) + r > limit || std::abs(z) + r > limit) {
            throw ResourceError("cannot surface " + describeGlobule(g, i) +
                                ": it lies beyond the " + std::to_string(int64_t(limit)) +
                                " voxels from the origin a grid can index; raise voxel_size");
        }
        mCentre[3 * i] = x;
        mCentre[3 * i + 1] = y;
        mCentre[3 * i + 2] = z;
        if (r <= 0) continue;
        mInfluence[i] = float(r);
        maxInfluence = std::max(maxInfluence, float(r));
        keys[i] = blockKeyAt(x, y, z);
        mSorted.push_back(uint32_t(i));
    }
    mReach = int(std::ceil(maxInfluence / kBlockDim));
    for (int dx = -mReach; dx <= mReach; ++dx) {
        for (int dy = -mReach; dy <= mReach; ++dy) {
            for (int dz = -mReach; dz <= mReach; ++dz) {
                mOrder.push_back({dx, dy, dz, dx * dx + dy * dy + dz * dz});
            }
        }
    }
    std::stable_sort(mOrder.begin(), mOrder.end(),
                     [](const auto& a, const auto& b) { return a[3] < b[3]; });

    // (block, index) is a total order, so the parallel sort is deterministic.
    tbb::parallel_sort(mSorted.begin(), mSorted.end(), [&](uint32_t a, uint32_t b) {
        return keys[a] < keys[b] || (keys[a] == keys[b] && a < b);
    });
    for (std::size_t k = 0; k < mSorted.size(); ++k) {
        const uint64_t key = keys[mSorted[k]];
        if (mCellKeys.empty() || mCellKeys.back() != key) {
            mCellKeys.push_back(key);
            mCellStart.push_back(uint32_t(k));
        }
    }
    mCellStart.push_back(uint32_t(mSorted.size()));

    // Candidate blocks: per occupied cell, the box of blocks its globules' voxel ranges
    // cover. Boxes overlap between cells; sort + unique merges them.
    tbb::enumerable_thread_specific<std::vector<uint64_t>> perThread;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mCellKeys.size(), 64), [&](auto range) {
        auto& out = perThread.local();
        for (std::size_t c = range.begin(); c < range.end(); ++c) {
            int64_t lo[3] = {INT64_MAX, INT64_MAX, INT64_MAX};
            int64_t hi[3] = {INT64_MIN, INT64_MIN, INT64_MIN};
            for (uint32_t k = mCellStart[c]; k < mCellStart[c + 1]; ++k) {
                const uint32_t i = mSorted[k];
                const double r = mInfluence[i];
                for (int a = 0; a < 3; ++a) {
                    const int64_t first = int64_t(std::ceil(mCentre[3 * i + a] - r));
                    const int64_t last = int64_t(std::floor(mCentre[3 * i + a] + r));
                    if (first > last) continue;  // too small to cover a voxel centre
                    lo[a] = std::min(lo[a], first >> kBlockLog2);
                    hi[a] = std::max(hi[a], last >> kBlockLog2);
                }
            }
            for (int64_t bx = lo[0]; bx <= hi[0]; ++bx) {
                for (int64_t by = lo[1]; by <= hi[1]; ++by) {
                    for (int64_t bz = lo[2]; bz <= hi[2]; ++bz) out.push_back(pack(bx, by, bz));
                }
            }
        }
    });
    for (auto& part : perThread) mCandidates.insert(mCandidates.end(), part.begin(), part.end());
    tbb::parallel_sort(mCandidates.begin(), mCandidates.end());
    mCandidates.erase(std::unique(mCandidates.begin(), mCandidates.end()), mCandidates.end());
}

GlobuleBins::Footprint GlobuleBins::measure(const Globules& g, double voxelSize,
                                             double influence) {
    Footprint f;
    double maxInfluence = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        const double r = double(g.radius[i]) * influence / voxelSize;
        if (!(r > 0) || !std::isfinite(r)) continue;  // left out, or refused when binned
        // A cell's box spans its globules' spheres plus at most the cell itself: the
        // sum over globules bounds the sum over cells.
        const double side = 2.0 * r / kBlockDim + 3.0;
        f.largestBlocks = std::max(f.largestBlocks, std::pow(2.0 * r / kBlockDim + 1.0, 3));
        f.listedBlocks += side * side * side;
        maxInfluence = std::max(maxInfluence, r);
    }
    const double reach = std::ceil(maxInfluence / kBlockDim);
    f.nearOrderSize = std::pow(2.0 * reach + 1.0, 3);
    return f;
}

uint64_t GlobuleBins::Footprint::bytes() const {
    // Candidates in per-thread lists, then merged (2 x 8 bytes), and 16-byte offsets.
    const double total = 16.0 * listedBlocks + 16.0 * nearOrderSize;
    return total >= 1.8e19 ? UINT64_MAX : uint64_t(total);
}

std::pair<uint32_t, uint32_t> GlobuleBins::cellRange(int64_t bx, int64_t by, int64_t bz) const {
    const uint64_t key = pack(bx, by, bz);
    auto it = std::lower_bound(mCellKeys.begin(), mCellKeys.end(), key);
    if (it == mCellKeys.end() || *it != key) return {0, 0};
    const std::size_t c = std::size_t(it - mCellKeys.begin());
    return {mCellStart[c], mCellStart[c + 1]};
}

}  // namespace globular
