#include "sphere_culling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sphere_pass.h"

namespace globular::detail {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr std::size_t kGrain = 4096;
constexpr int kBandRows = 16;  // rows of the depth grid drawn by one task
constexpr int kBlock = 8;      // pixels per side of a block of the coarse test

// The core reaches out to this fraction of the radius (the miss distance of the eye ray
// from the centre). Larger covers more pixels but bounds the depth less tightly.
constexpr double kCameraCore = 0.9;
constexpr double kLightCore = 0.9;

bool finite(float x, float y, float z, float r) {
    return std::isfinite(x) && std::isfinite(y) && std::isfinite(z) && std::isfinite(r) && r > 0;
}

// Pixels [first, last] of a row or column of @p count that a span [lo, hi] touches;
// empty when first > last. Clamped before conversion to int.
void pixelSpan(float lo, float hi, int count, int& first, int& last) {
    const float limit = float(count + 1);
    first = std::max(0, int(std::floor(std::clamp(lo, -1.0f, limit))));
    last = std::min(count - 1, int(std::floor(std::clamp(hi, -1.0f, limit))));
}

}  // namespace

void cameraDiscs(const Globules& g, const FrameUniforms& f, std::vector<ScreenDisc>& discs) {
    discs.resize(g.size());
    const Mat4& view = f.view;
    const double pixel = f.pixelAngle;  // image-plane units per pixel at unit focal length
    // A ray Delta pixels from another is at most Delta * pixel radians from it (the map
    // from the image plane to directions never stretches). cosMin: the smallest cosine
    // between a ray through the image and the view direction (a corner).
    const double cosMin =
        1.0 / std::sqrt(1.0 + dot(f.camRight, f.camRight) + dot(f.camUp, f.camUp));
    const double zNear = f.zNear;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.size(), kGrain), [&](auto range) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
            ScreenDisc& d = discs[i];
            d = ScreenDisc{};
            const float x = g.px[i], y = g.py[i], z = g.pz[i], r = g.radius[i];
            if (!finite(x, y, z, r)) continue;  // never drawn: the shaders skip it
            const Vec3 v{view(0, 0) * x + view(0, 1) * y + view(0, 2) * z + view(0, 3),
                         view(1, 0) * x + view(1, 1) * y + view(1, 2) * z + view(1, 3),
                         view(2, 0) * x + view(2, 1) * y + view(2, 2) * z + view(2, 3)};
            const float size = spriteSize(v, r, f.focalPixels[0], f.focalPixels[1], zNear);
            if (!std::isfinite(size)) {  // reaches the near plane: drawn as it is
                d.half = kInfinity;
                continue;
            }
            const double depth = -v.z, distance = length(v);
            d.x = float(0.5 * f.width + v.x / depth * f.focalPixels[0]);
            d.y = float(0.5 * f.height + v.y / depth * f.focalPixels[1]);
            d.half = 0.5f * size + 1.0f;
            // Fragments are shaded at pixel centres. The silhouette reaches farthest from
            // the projected centre along the radial direction (the axis extent there); the
            // anti-aliased edge adds at most half a pixel's angle, under 0.8 pixels.
            const double focal = std::max(f.focalPixels[0], f.focalPixels[1]);
            const double radial = std::sqrt(v.x * v.x + v.y * v.y);
            d.reach = 0.5f * (spriteSize({radial, 0, v.z}, r, focal, focal, zNear) - 1.0f) + 1.0f;
            // Window depth is stored in 24 bits: two depths d apart stay ordered when d is
            // more than a few steps of 2^-24 * depth^2 / zNear; plus float rounding.
            const double margin = 16.0 * 0x1p-24 * depth * depth / zNear + 1e-5 * depth;
            d.nearDepth = float(depth - r - margin);
            // Samples within Delta pixels of the centre see rays that pass the centre at
            // b <= distance * Delta * pixel. With b <= r - 0.6 pixel * distance the sample
            // is inside the silhouette by more than the half pixel of anti-aliasing, so
            // alpha-to-coverage covers all of its samples. Such a ray, at angle theta from
            // the view direction, writes a depth of at most (with the centre-to-ray offset
            // perpendicular to the ray, of length <= b)
            //   depth + b sin(theta) - sqrt(r^2 - b^2) cos(theta),
            // and theta is at most the centre's angle plus asin(b / distance).
            const double b = std::min(kCameraCore * r, r - 0.6 * pixel * distance);
            // Only a sphere wholly drawn occludes: its centre in the view (points are
            // clipped by their centre) and all of it within the depth range.
            const bool drawn = d.x >= 0 && d.x <= f.width && d.y >= 0 && d.y <= f.height &&
                               depth + r < 0.999 * f.zFar;
            d.coreRadius = drawn ? float(b / (distance * pixel) - 0.01) : 0.0f;
            const double sinSpread = std::clamp(b / distance, 0.0, 1.0);
            const double cosRay = std::max(  // cos(centre angle + spread), no trigonometry
                cosMin,
                (depth * std::sqrt(1 - sinSpread * sinSpread) - radial * sinSpread) / distance);
            d.coreDepth = float(depth + b * std::sqrt(1 - cosRay * cosRay) -
                                std::sqrt(std::max(r * r - b * b, 0.0)) * cosRay);
        }
    });
}

void lightDiscs(const Globules& g, const FrameUniforms& f, std::vector<ScreenDisc>& discs) {
    discs.resize(g.size());
    const Mat4& m = f.lightViewProj;
    const Vec3 toward = f.lightToward.front();
    // Normalised depth (-1..1) per world unit towards the light: negative.
    const double depthPerUnit = m(2, 0) * toward.x + m(2, 1) * toward.y + m(2, 2) * toward.z;
    const double size = f.shadowMapSize, tpu = f.texelsPerUnit;
    const double margin = 16.0 * 0x1p-23 + 1e-6;  // 24-bit depth in -1..1, float rounding
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.size(), kGrain), [&](auto range) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
            ScreenDisc& d = discs[i];
            d = ScreenDisc{};
            const float x = g.px[i], y = g.py[i], z = g.pz[i], r = g.radius[i];
            if (!finite(x, y, z, r)) continue;
            const double cx = m(0, 0) * x + m(0, 1) * y + m(0, 2) * z + m(0, 3);
            const double cy = m(1, 0) * x + m(1, 1) * y + m(1, 2) * z + m(1, 3);
            const double cz = m(2, 0) * x + m(2, 1) * y + m(2, 2) * z + m(2, 3);
            const double radiusDepth = std::abs(r * depthPerUnit);
            // The shadow sprite: 2 r texelsPerUnit + 1 texels; its fragments within the
            // disc write cz - radiusDepth sqrt(1 - rho^2), rho the distance over r.
            d.x = float((0.5 * cx + 0.5) * size);
            d.y = float((0.5 * cy + 0.5) * size);
            d.half = float(r * tpu + 1.5);
            d.reach = float(r * tpu + 0.01);  // texel centres within the disc
            d.nearDepth = float(cz - radiusDepth - margin);
            // Only a sphere wholly drawn occludes (see cameraDiscs): its centre in the map,
            // all of it between the near and far planes.
            const bool drawn = d.x >= 0 && d.x <= size && d.y >= 0 && d.y <= size &&
                               cz - radiusDepth > -1 + margin && cz + radiusDepth < 1 - margin;
            d.coreRadius = drawn ? float(kLightCore * r * tpu - 0.01) : 0.0f;
            d.coreDepth = float(cz - radiusDepth * std::sqrt(1 - kLightCore * kLightCore));
        }
    });
}

std::vector<uint32_t> unoccluded(const std::vector<ScreenDisc>& discs, int width, int height) {
    std::vector<uint32_t> indices;
    OcclusionCuller().cull(discs, width, height, indices);
    return indices;
}

void OcclusionCuller::cull(const std::vector<ScreenDisc>& discs, int width, int height,
                           std::vector<uint32_t>& indices) {
    // Per pixel, the nearest depth behind which all its samples are covered by some core.
    // Rows are drawn in bands, in parallel; each band gathers the discs whose cores reach
    // it (a counting sort by band), so each pixel is written by one thread only.
    std::vector<float>& grid = mGrid;
    grid.assign(std::size_t(width) * height, kInfinity);
    const int bands = (height + kBandRows - 1) / kBandRows;
    auto bandSpan = [&](const ScreenDisc& d, int& b0, int& b1) {
        int y0, y1;
        pixelSpan(d.y - d.coreRadius, d.y + d.coreRadius, height, y0, y1);
        b0 = y0 / kBandRows;
        b1 = y1 < y0 ? b0 - 1 : y1 / kBandRows;
    };
    auto occludes = [](const ScreenDisc& d) { return d.coreRadius > 0 && std::isfinite(d.half); };
    std::vector<std::size_t>& start = mStart;
    start.assign(bands + 1, 0);
    for (const ScreenDisc& d : discs) {
        if (!occludes(d)) continue;
        int b0, b1;
        bandSpan(d, b0, b1);
        for (int b = b0; b <= b1; ++b) ++start[b + 1];
    }
    for (int b = 0; b < bands; ++b) start[b + 1] += start[b];
    // Copies, not indices: the raster then reads each band's cores in sequence.
    std::vector<Core>& byBand = mCores;
    byBand.resize(start[bands]);
    {
        std::vector<std::size_t>& next = mNext;
        next.assign(start.begin(), start.end() - 1);
        for (const ScreenDisc& d : discs) {
            if (!occludes(d)) continue;
            int b0, b1;
            bandSpan(d, b0, b1);
            for (int b = b0; b <= b1; ++b)
                byBand[next[b]++] = {d.x, d.y, d.coreRadius, d.coreDepth};
        }
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](auto range) {
        for (int b = range.begin(); b < range.end(); ++b) {
            const int top = std::min(height, (b + 1) * kBandRows) - 1;
            for (std::size_t k = start[b]; k < start[b + 1]; ++k) {
                const Core& d = byBand[k];
                // The pixels wholly inside the circle: in the row [py, py + 1], those whose
                // far corner in x is within the circle's half-width at the row's far edge.
                const float r2 = d.radius * d.radius;
                int y0, y1;
                pixelSpan(d.y - d.radius, d.y + d.radius, height, y0, y1);
                for (int py = std::max(y0, b * kBandRows); py <= std::min(y1, top); ++py) {
                    const float dy =
                        std::max(std::abs(float(py) - d.y), std::abs(float(py + 1) - d.y));
                    if (dy * dy >= r2) continue;
                    const float w = std::sqrt(r2 - dy * dy);
                    const int x0 = std::max(0, int(std::ceil(std::max(d.x - w, -1.0f))));
                    const int x1 =
                        std::min(width, int(std::floor(std::min(d.x + w, float(width) + 1)))) - 1;
                    float* row = &grid[std::size_t(py) * width];
                    for (int px = x0; px <= x1; ++px) row[px] = std::min(row[px], d.depth);
                }
            }
        }
    });
    // The farthest of each kBlock x kBlock block: most hidden spheres are hidden by a
    // handful of these, without reading every pixel they reach.
    const int blockColumns = (width + kBlock - 1) / kBlock;
    const int blockRows = (height + kBlock - 1) / kBlock;
    std::vector<float>& blockFar = mBlockFar;
    blockFar.assign(std::size_t(blockColumns) * blockRows, -kInfinity);
    tbb::parallel_for(tbb::blocked_range<int>(0, blockRows, 1), [&](auto range) {
        for (int by = range.begin(); by < range.end(); ++by) {
            for (int py = by * kBlock; py < std::min(height, (by + 1) * kBlock); ++py) {
                const float* row = &grid[std::size_t(py) * width];
                float* far = &blockFar[std::size_t(by) * blockColumns];
                for (int px = 0; px < width; ++px) {
                    far[px / kBlock] = std::max(far[px / kBlock], row[px]);
                }
            }
        }
    });
    std::vector<uint8_t>& visible = mVisible;
    visible.assign(discs.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, discs.size(), kGrain), [&](auto range) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
            const ScreenDisc& d = discs[i];
            if (!(d.half >= 0)) continue;  // never drawn
            if (std::isinf(d.half)) {
                visible[i] = 1;
                continue;
            }
            // The pixels whose centres are within reach.
            int x0, x1, y0, y1;
            pixelSpan(d.x - d.reach - 0.5f, d.x + d.reach - 0.5f, width, x0, x1);
            pixelSpan(d.y - d.reach - 0.5f, d.y + d.reach - 0.5f, height, y0, y1);
            bool hiddenByBlocks = true;
            for (int by = y0 / kBlock; by <= y1 / kBlock && hiddenByBlocks && y0 <= y1; ++by) {
                const float* far = &blockFar[std::size_t(by) * blockColumns];
                for (int bx = x0 / kBlock; bx <= x1 / kBlock && x0 <= x1; ++bx) {
                    if (!(far[bx] < d.nearDepth)) {
                        hiddenByBlocks = false;
                        break;
                    }
                }
            }
            bool seen = false;
            for (int py = y0; py <= y1 && !seen && !hiddenByBlocks; ++py) {
                const float dy = float(py) + 0.5f - d.y;
                if (dy * dy > d.reach * d.reach) continue;
                const float w = std::sqrt(d.reach * d.reach - dy * dy);
                const int first = std::max(x0, int(std::ceil(d.x - w - 0.5f)));
                const int last = std::min(x1, int(std::floor(d.x + w - 0.5f)));
                const float* row = &grid[std::size_t(py) * width];
                for (int px = first; px <= last; ++px) {
                    if (!(row[px] < d.nearDepth)) {
                        seen = true;
                        break;
                    }
                }
            }
            visible[i] = seen ? 1 : 0;
        }
    });
    indices.clear();
    for (std::size_t i = 0; i < discs.size(); ++i) {
        if (visible[i]) indices.push_back(uint32_t(i));
    }
}

}  // namespace globular::detail
