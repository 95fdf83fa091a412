#pragma once
// The scenes every render benchmark draws, with fixed seeds:
//  - renderBenchPour(n): the paper's pour at scale. 90% of n globules (radius 1, spacing
//    about 1, the paper's r0) in a puddle four times as wide as high, 10% in a falling
//    stream above it; speeds outward in the puddle and falling in the stream.
//  - renderBenchBlob(triangles): a bumpy closed surface of about that many triangles,
//    wound counter-clockwise seen from outside like the surface stage's meshes,
//    as the surfacing stage makes of a settled drop.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "globules.h"
#include "mesh.h"

namespace globular {

inline Globules renderBenchPour(std::size_t n, unsigned seed = 1989) {
    Globules g;
    g.reserve(n);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> jitter(0, 1);
    const double pi = std::numbers::pi;
    const auto puddle = std::size_t(0.9 * double(n));
    const double radius = std::cbrt(0.9 * double(n) * 8 / pi), height = radius / 4;
    const double streamRadius = std::sqrt(std::max(0.1 * double(n), 1.0) / (1.5 * pi * radius));
    const double top = height + 1.5 * radius;
    for (std::size_t i = 0; i < n; ++i) {
        const double rho = std::sqrt(u(rng)), angle = 2 * pi * u(rng);
        if (i < puddle) {
            const double r = radius * rho, h = height * (1 - rho * rho);
            g.add({r * std::cos(angle), h * u(rng), r * std::sin(angle)},
                  {0.5 * rho * std::cos(angle) + 0.1 * jitter(rng), 0.1 * jitter(rng),
                   0.5 * rho * std::sin(angle)},
                  1.0f, 1.0f, int32_t(i));
        } else {
            const double y = height + (top - height) * u(rng);
            g.add({streamRadius * rho * std::cos(angle), y, streamRadius * rho * std::sin(angle)},
                  {0.2 * jitter(rng), -std::sqrt(2 * 9.8 * (top - y + 1)), 0.2 * jitter(rng)}, 1.0f,
                  1.0f, int32_t(i));
        }
    }
    return g;
}

inline TriangleMesh renderBenchBlob(std::size_t triangles) {
    const int rings = std::max(4, int(std::sqrt(double(triangles) / 4)));
    const int segments = 2 * rings;
    TriangleMesh m;
    const double pi = std::numbers::pi;
    for (int i = 0; i <= rings; ++i) {
        const double theta = pi * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2 * pi * j / segments;
            const double nx = std::sin(theta) * std::cos(phi), ny = std::cos(theta),
                         nz = std::sin(theta) * std::sin(phi);
            const double r = 20 * (1 + 0.08 * std::sin(5 * phi) * std::sin(3 * theta));
            m.positions.insert(m.positions.end(),
                               {float(r * nx), float(12 + 0.6 * r * ny), float(r * nz)});
            m.normals.insert(m.normals.end(), {float(nx), float(ny), float(nz)});
        }
    }
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments;
            const uint32_t c = a + segments, d = b + segments;
            m.triangles.insert(m.triangles.end(), {a, b, c, b, d, c});
        }
    }
    return m;
}

}  // namespace globular
