#include "surface_estimate.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "globule_bins.h"

namespace globular {

namespace {

// One dense 8^3 float leaf: 2 KiB of values, 64 bytes of mask, origin and bookkeeping.
constexpr uint64_t kBytesPerLeaf = 2048 + 64 + 64;
// Peak over the stage's steps: the field, plus the level set and the band's working data
// (fieldToLevelSet: about 5 KiB per leaf near the surface) alive at once. Measured on the
// benchmark frames (peak RSS / field leaves / kBytesPerLeaf): 3.7 at 1e4 globules, where
// most leaves lie near the surface, 1.9 at 1e6; see docs/surface.md.
constexpr double kPeakFactor = 4.0;
// Per value averaged in the field's pass (the velocity's three components, the
// temperature): its mean grid, of the field's leaves, lives through the level set, then
// its copy in "vel" or "temperature". Measured at 4,000 globules: the velocity raised the
// peak RSS by 9.6 field-sized grids, about 3 per component.
constexpr double kPeakPerChannel = 3.0;
// Per globule: the Globules arrays (40 bytes) and the bins (centre, radius, key, order).
constexpr uint64_t kBytesPerGlobule = 40 + 24 + 4 + 8 + 4;

uint64_t readNumberAfter(const std::string& file, const std::string& label) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(label, 0) == 0) {
            std::istringstream rest(line.substr(label.size()));
            uint64_t value = 0;
            if (rest >> value) return value;
        }
    }
    return 0;
}

uint64_t readSingleNumber(const std::string& file) {
    std::ifstream in(file);
    uint64_t value = 0;
    if (in >> value) return value;  // "max" (no limit) fails to parse: 0
    return 0;
}

}  // namespace

SurfaceEstimate estimateSurface(const Globules& globules, const SurfaceSettings& settings,
                                uint64_t budget) {
    SurfaceEstimate e;
    e.voxelSize = resolveVoxelSize(settings, globules);
    e.globules = globules.size();
    constexpr double kVoxelsPerLeaf = GlobuleBins::kBlockDim * GlobuleBins::kBlockDim *
                                      GlobuleBins::kBlockDim;
    const double channels = 3.0 + (globules.temperature.empty() ? 0.0 : 1.0);
    const double peakFactor = kPeakFactor + kPeakPerChannel * channels;
    const auto fieldBytes = [&](double leaves) {
        return leaves * double(kBytesPerLeaf) * peakFactor +
               double(e.globules) * double(kBytesPerGlobule);
    };
    const auto saturate = [](double v) { return v >= 1.8e19 ? UINT64_MAX : uint64_t(v); };
    const GlobuleBins::Footprint footprint =
        GlobuleBins::measure(globules, e.voxelSize, settings.influence);
    const uint64_t binning = footprint.bytes();
    const uint64_t lowerBound = saturate(fieldBytes(footprint.largestBlocks));
    if (budget > 0 && std::max(binning, lowerBound) > budget) {
        e.fieldLeaves = std::size_t(std::min(footprint.largestBlocks, 1.8e19));
        e.voxels = saturate(footprint.largestBlocks * kVoxelsPerLeaf);
        e.bytes = std::max(binning, lowerBound);
        return e;
    }
    const GlobuleBins bins(globules, e.voxelSize, settings.influence);
    e.fieldLeaves = bins.candidateBlocks().size();
    e.voxels = uint64_t(e.fieldLeaves) * uint64_t(kVoxelsPerLeaf);
    e.bytes = std::max(saturate(fieldBytes(double(e.fieldLeaves))), binning);
    return e;
}

uint64_t availableMemoryBytes() {
    uint64_t available = readNumberAfter("/proc/meminfo", "MemAvailable:") * 1024;
    const uint64_t limit = readSingleNumber("/sys/fs/cgroup/memory.max");
    if (limit > 0) {
        const uint64_t used = readSingleNumber("/sys/fs/cgroup/memory.current");
        const uint64_t headroom = limit > used ? limit - used : 0;
        if (available == 0 || headroom < available) available = headroom;
    }
    return available;
}

std::string formatBytes(uint64_t bytes) {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(2);
    const double b = double(bytes);
    if (b >= 1024.0 * 1024 * 1024) {
        out << b / (1024.0 * 1024 * 1024) << " GiB";
    } else if (b >= 1024.0 * 1024) {
        out.precision(1);
        out << b / (1024.0 * 1024) << " MiB";
    } else {
        out.precision(1);
        out << b / 1024.0 << " KiB";
    }
    return out.str();
}

}  // namespace globular
