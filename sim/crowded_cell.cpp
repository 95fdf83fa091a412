#include "crowded_cell.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace globular {

namespace {

int32_t cubeOf(float v, double inverseCell) {
    const double c = std::floor(double(v) * inverseCell);
    if (!(c == c)) return 0;  // NaN
    return int32_t(std::clamp(c, -2147483647.0, 2147483647.0));
}

uint64_t hashOf(int32_t x, int32_t y, int32_t z) {
    uint64_t h = uint64_t(uint32_t(x)) * 0x9E3779B97F4A7C15ull;
    h ^= uint64_t(uint32_t(y)) * 0xC2B2AE3D27D4EB4Full;
    h ^= uint64_t(uint32_t(z)) * 0x165667B19E3779F9ull;
    return h ^ (h >> 31);
}

}  // namespace

uint32_t CrowdedCell::most(const float* x, const float* y, const float* z, std::size_t n,
                           double cell) {
    // At most half full, so a probe ends after a couple of slots.
    const std::size_t size = std::bit_ceil(std::max<std::size_t>(2 * n, 64));
    if (mSlots.size() != size) {
        mSlots.assign(size, Slot{});
    } else {
        std::fill(mSlots.begin(), mSlots.end(), Slot{});
    }
    const std::size_t mask = size - 1;
    const double inverse = 1.0 / cell;
    uint32_t most = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const int32_t cx = cubeOf(x[i], inverse), cy = cubeOf(y[i], inverse),
                      cz = cubeOf(z[i], inverse);
        for (std::size_t s = hashOf(cx, cy, cz) & mask;; s = (s + 1) & mask) {
            Slot& slot = mSlots[s];
            if (slot.count == 0) slot = {cx, cy, cz, 0};
            if (slot.x == cx && slot.y == cy && slot.z == cz) {
                most = std::max(most, ++slot.count);
                break;
            }
        }
    }
    return most;
}

}  // namespace globular
