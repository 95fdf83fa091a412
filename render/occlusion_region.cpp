#include "occlusion_region.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "transform.h"

namespace globular::detail {

// How far a point's image moves: a point P at view depth z_P and ndc x_P, moved by at
// most d to Q, lands at |x_Q - x_P| <= d (1 / e + |x_P|) / z_Q, with e the image's half
// extent at unit distance (camRight, camUp): x = a / (e z) for the offset a along the
// axis, so x_Q - x_P = (da / e - x_P dz) / z_Q for the move (da, dz), |da|, |dz| <= d.

OcclusionRegion::OcclusionRegion(const FrameUniforms& f, double radius)
    : mFrame(f),
      mRadius(radius),
      mExtent{length(f.camRight), length(f.camUp)},
      mTiles{(f.width + kTile - 1) / kTile, (f.height + kTile - 1) / kTile},
      mNearest(std::size_t(mTiles[0]) * std::size_t(mTiles[1]),
               std::numeric_limits<float>::infinity()) {}

void OcclusionRegion::addFootprint(double x0, double x1, double y0, double y1, double depth) {
    // The pixels whose centres the footprint can reach, and one more each side: a sample
    // of a pixel may be covered where its centre is not.
    const int pixels[2] = {mFrame.width, mFrame.height};
    const double lo[2] = {x0, y0}, hi[2] = {x1, y1};
    int from[2], to[2];
    for (int a = 0; a < 2; ++a) {
        const double first = std::floor((lo[a] * 0.5 + 0.5) * pixels[a] - 0.5) - 1.0;
        const double last = std::ceil((hi[a] * 0.5 + 0.5) * pixels[a] - 0.5) + 1.0;
        if (last < 0 || first > pixels[a] - 1) return;  // off the frame
        from[a] = int(std::max(first, 0.0)) / kTile;
        to[a] = int(std::min(last, double(pixels[a] - 1))) / kTile;
    }
    for (int ty = from[1]; ty <= to[1]; ++ty) {
        float* row = mNearest.data() + std::size_t(ty) * std::size_t(mTiles[0]);
        for (int tx = from[0]; tx <= to[0]; ++tx) row[tx] = std::min(row[tx], float(depth));
    }
}

void OcclusionRegion::addTriangles(const float* positions, std::size_t vertexCount,
                                   const uint32_t* triangles, std::size_t triangleCount) {
    if (mWhole) return;
    // Each vertex projected once: ndc x, y and view depth.
    std::vector<float> image(3 * vertexCount);
    for (std::size_t v = 0; v < vertexCount; ++v) {
        const Vec3 p{positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
        const Vec4 clip = transformPoint(mFrame.viewProj, p);
        if (!(clip.w > mFrame.zNear) || !std::isfinite(clip.x) || !std::isfinite(clip.y)) {
            mWhole = true;
            return;
        }
        image[3 * v] = float(clip.x / clip.w);
        image[3 * v + 1] = float(clip.y / clip.w);
        image[3 * v + 2] = float(clip.w);
    }
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const uint32_t* corner = triangles + 3 * t;
        if (corner[0] >= vertexCount || corner[1] >= vertexCount || corner[2] >= vertexCount) {
            mWhole = true;
            return;
        }
        const float* a = &image[3 * corner[0]];
        const float* b = &image[3 * corner[1]];
        const float* c = &image[3 * corner[2]];
        // View depth is affine across a triangle: its least is at a corner.
        addFootprint(std::min({a[0], b[0], c[0]}), std::max({a[0], b[0], c[0]}),
                     std::min({a[1], b[1], c[1]}), std::max({a[1], b[1], c[1]}),
                     std::min({a[2], b[2], c[2]}));
    }
}

void OcclusionRegion::addSpheres(const Globules& g) {
    if (mWhole) return;
    const std::size_t n = g.size();
    if (g.py.size() != n || g.pz.size() != n || g.radius.size() != n) {
        mWhole = true;
        return;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const double r = std::abs(double(g.radius[i]));
        const Vec4 clip = transformPoint(mFrame.viewProj, Vec3{g.px[i], g.py[i], g.pz[i]});
        const double nearest = clip.w - r;
        if (!(nearest > mFrame.zNear) || !std::isfinite(clip.x) || !std::isfinite(clip.y)) {
            mWhole = true;
            return;
        }
        // The sphere's points lie within r of its centre, at depths >= nearest.
        const double x = clip.x / clip.w, y = clip.y / clip.w;
        const double dx = r * (1.0 / mExtent[0] + std::abs(x)) / nearest;
        const double dy = r * (1.0 / mExtent[1] + std::abs(y)) / nearest;
        addFootprint(x - dx, x + dx, y - dy, y + dy, nearest);
    }
}

std::vector<PixelRect> OcclusionRegion::rects() const {
    // A tap q of pixel p is occluded only where the depth buffer shows, at q's image, an
    // occluder at depth z_o in front of q: p then lies on the screen (|x_p| <= 1), q
    // within the radius of p, and deeper than z_o, so q's image lies within
    // radius (1 / e + 1) / z_o of p's. A tap beyond the frame counts as unoccluded
    // (occlusion_pass.cpp).
    const int pixels[2] = {mFrame.width, mFrame.height};
    std::vector<uint8_t> covered(mNearest.size(), 0);
    for (int ty = 0; ty < mTiles[1]; ++ty) {
        for (int tx = 0; tx < mTiles[0]; ++tx) {
            const float depth =
                mNearest[std::size_t(ty) * std::size_t(mTiles[0]) + std::size_t(tx)];
            if (!std::isfinite(depth)) continue;
            const int tile[2] = {tx, ty};
            int from[2], to[2];
            for (int a = 0; a < 2; ++a) {
                const double reach = mRadius * (1.0 / mExtent[a] + 1.0) / depth * 0.5 * pixels[a];
                const double first = tile[a] * kTile - reach - 1.0;
                const double last = (tile[a] + 1) * kTile - 1 + reach + 1.0;
                from[a] = int(std::max(first, 0.0)) / kTile;
                to[a] = int(std::min(last, double(pixels[a] - 1))) / kTile;
            }
            for (int y = from[1]; y <= to[1]; ++y) {
                uint8_t* row = covered.data() + std::size_t(y) * std::size_t(mTiles[0]);
                std::fill(row + from[0], row + to[0] + 1, uint8_t(1));
            }
        }
    }
    std::vector<PixelRect> runs;
    for (int ty = 0; ty < mTiles[1]; ++ty) {
        const uint8_t* row = covered.data() + std::size_t(ty) * std::size_t(mTiles[0]);
        for (int tx = 0; tx < mTiles[0];) {
            if (!row[tx]) {
                ++tx;
                continue;
            }
            const int begin = tx;
            while (tx < mTiles[0] && row[tx]) ++tx;
            runs.push_back({begin * kTile, ty * kTile, std::min(tx * kTile, pixels[0]) - 1,
                            std::min((ty + 1) * kTile, pixels[1]) - 1});
        }
    }
    return runs;
}

}  // namespace globular::detail
