// The halo of an MPI domain decomposition of a cached frame (docs/scale.md): the frame's
// globules cut into P = 2, 4, ..., 64 domains by recursive coordinate bisection (each cut
// across the longest side of a domain's globules, at their median: equal counts, as
// LAMMPS's `balance rcb` does), and for each P the ghosts, the globules a domain must
// receive from others every step because they lie within the interaction cutoff of its
// region.
//
//   halo_fraction CACHE.vdb [--refine K] [--spacing D] [--later LATER.vdb]
//
// --refine K synthesises a pile of K times as many globules from the cache: the same shape
// at K^(1/3) times the size, the same globule size and density (each globule, moved out
// from the pile's foot by the scale, stands for a cube of side K^(1/3) D, D the rest
// spacing, which is filled with K globules at uniform random places; fixed seed).
// Prints one Markdown row per P: ghosts / N (the halo fraction), the largest domain's
// ghosts / owned, and the domains a domain exchanges with (mean, most). --later: also the
// imbalance (the most globules a domain owns over the mean) when the cuts made for CACHE
// are kept for the frame LATER: what a decomposition that is never rebalanced costs.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "errors.h"
#include "globule_cache.h"
#include "material.h"
#include "pair_force.h"

using namespace globular;

namespace {

using Point = std::array<float, 3>;

/// A domain's region of space: the cuts that bound it (infinite where none does).
struct Region {
    Point lo{-INFINITY, -INFINITY, -INFINITY}, hi{INFINITY, INFINITY, INFINITY};
    /// The squared distance from @p p to the region.
    float distance2To(const Point& p) const {
        float d2 = 0;
        for (int a = 0; a < 3; ++a) {
            const float e = std::max({0.0f, lo[a] - p[a], p[a] - hi[a]});
            d2 += e * e;
        }
        return d2;
    }
};

/// Splits @p indices [begin, end) of @p points into @p parts regions (a power of two).
void bisect(const std::vector<Point>& points, std::vector<uint32_t>& indices, std::size_t begin,
            std::size_t end, int parts, const Region& region, std::vector<Region>& out,
            std::vector<std::pair<std::size_t, std::size_t>>& ranges) {
    if (parts == 1) {
        out.push_back(region);
        ranges.emplace_back(begin, end);
        return;
    }
    Point lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t k = begin; k < end; ++k) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], points[indices[k]][a]);
            hi[a] = std::max(hi[a], points[indices[k]][a]);
        }
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a) axis = hi[a] - lo[a] > hi[axis] - lo[axis] ? a : axis;
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(indices.begin() + std::ptrdiff_t(begin), indices.begin() + std::ptrdiff_t(middle),
                     indices.begin() + std::ptrdiff_t(end),
                     [&](uint32_t i, uint32_t j) { return points[i][axis] < points[j][axis]; });
    const float cut = points[indices[middle]][axis];
    Region left = region, right = region;
    left.hi[axis] = cut;
    right.lo[axis] = cut;
    bisect(points, indices, begin, middle, parts / 2, left, out, ranges);
    bisect(points, indices, middle, end, parts / 2, right, out, ranges);
}

std::vector<Point> refine(const Globules& g, int factor, float spacing) {
    const float scale = std::cbrt(float(factor));
    Point foot{0, INFINITY, 0};
    for (std::size_t i = 0; i < g.size(); ++i) {
        foot[0] += g.px[i] / float(g.size());
        foot[1] = std::min(foot[1], g.py[i]);
        foot[2] += g.pz[i] / float(g.size());
    }
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> offset(-0.5f * scale * spacing, 0.5f * scale * spacing);
    std::vector<Point> out;
    out.reserve(g.size() * std::size_t(factor));
    for (std::size_t i = 0; i < g.size(); ++i) {
        const Point c{foot[0] + scale * (g.px[i] - foot[0]), foot[1] + scale * (g.py[i] - foot[1]),
                      foot[2] + scale * (g.pz[i] - foot[2])};
        for (int k = 0; k < factor; ++k) out.push_back({c[0] + offset(rng), c[1] + offset(rng), c[2] + offset(rng)});
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: halo_fraction CACHE.vdb [--refine K] [--spacing D]\n");
        return 2;
    }
    int factor = 1;
    float spacing = 1.05f;
    std::string later;
    for (int a = 2; a + 1 < argc; a += 2) {
        const std::string key = argv[a];
        if (key == "--refine") {
            factor = std::atoi(argv[a + 1]);
        } else if (key == "--later") {
            later = argv[a + 1];
        } else if (key == "--spacing") {
            spacing = std::strtof(argv[a + 1], nullptr);
        } else {
            std::fprintf(stderr, "halo_fraction: unknown option %s\n", key.c_str());
            return 2;
        }
    }
    if (factor < 1 || !(spacing > 0)) {
        std::fprintf(stderr, "halo_fraction: --refine must be >= 1 and --spacing > 0\n");
        return 2;
    }
    try {
        const Globules g = readGlobuleVdb(argv[1]);
        float largest = 0;
        for (float r : g.radius) largest = std::max(largest, r);
        // The grid's cell: the reach of the widest window (the default liquid's C_d) at
        // the largest radius sum. Ghosts are refreshed every step, so no skin is added.
        const MaterialSettings liquid;
        const float cutoff = PairForce::fromMaterial(liquid).cutoff(2 * largest);
        std::vector<Point> points;
        if (factor == 1) {
            for (std::size_t i = 0; i < g.size(); ++i) points.push_back({g.px[i], g.py[i], g.pz[i]});
        } else {
            points = refine(g, factor, spacing);
        }
        Point lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
        for (const Point& p : points) {
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], p[a]);
                hi[a] = std::max(hi[a], p[a]);
            }
        }
        std::printf("# %s%s: %zu globules, extent %.0f x %.0f x %.0f, cutoff %.2f\n", argv[1],
                    factor > 1 ? (" refined x" + std::to_string(factor)).c_str() : "",
                    points.size(), hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], cutoff);
        std::vector<Point> laterPoints;
        if (!later.empty()) {
            const Globules h = readGlobuleVdb(later);
            for (std::size_t i = 0; i < h.size(); ++i) laterPoints.push_back({h.px[i], h.py[i], h.pz[i]});
        }
        std::printf("| domains | ghosts / N | largest domain: ghosts / owned | neighbours (mean, most) |%s\n",
                    later.empty() ? "" : " imbalance at --later, cuts kept |");
        std::printf("|---|---|---|---|%s\n", later.empty() ? "" : "---|");
        for (int parts = 2; parts <= 64; parts *= 2) {
            std::vector<uint32_t> indices(points.size());
            for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i);
            std::vector<Region> regions;
            std::vector<std::pair<std::size_t, std::size_t>> ranges;
            bisect(points, indices, 0, indices.size(), parts, Region{}, regions, ranges);
            std::vector<std::size_t> ghosts(std::size_t(parts), 0);
            std::vector<std::vector<char>> exchanges(std::size_t(parts), std::vector<char>(std::size_t(parts), 0));
            for (int owner = 0; owner < parts; ++owner) {
                for (std::size_t k = ranges[std::size_t(owner)].first; k < ranges[std::size_t(owner)].second; ++k) {
                    const Point& p = points[indices[k]];
                    for (int d = 0; d < parts; ++d) {
                        if (d != owner && regions[std::size_t(d)].distance2To(p) <= cutoff * cutoff) {
                            ++ghosts[std::size_t(d)];
                            exchanges[std::size_t(d)][std::size_t(owner)] = 1;
                        }
                    }
                }
            }
            std::size_t total = 0;
            double worst = 0, neighbours = 0;
            int most = 0;
            for (int d = 0; d < parts; ++d) {
                const std::size_t owned = ranges[std::size_t(d)].second - ranges[std::size_t(d)].first;
                total += ghosts[std::size_t(d)];
                worst = std::max(worst, double(ghosts[std::size_t(d)]) / double(owned));
                int n = 0;
                for (char e : exchanges[std::size_t(d)]) n += e;
                neighbours += n;
                most = std::max(most, n);
            }
            std::printf("| %d | %.4f | %.4f | %.1f, %d |", parts, double(total) / double(points.size()),
                        worst, neighbours / parts, most);
            if (!laterPoints.empty()) {
                std::vector<std::size_t> owned(std::size_t(parts), 0);
                for (const Point& p : laterPoints) {
                    for (int d = 0; d < parts; ++d) {
                        if (regions[std::size_t(d)].distance2To(p) == 0) {  // boundaries: the first
                            ++owned[std::size_t(d)];
                            break;
                        }
                    }
                }
                const std::size_t fullest = *std::max_element(owned.begin(), owned.end());
                std::printf(" %.2f |", double(fullest) * parts / double(laterPoints.size()));
            }
            std::printf("\n");
        }
    } catch (const Error& e) {
        std::fprintf(stderr, "halo_fraction: %s\n", e.what());
        return 1;
    }
    return 0;
}
