#pragma once
// The particles every surface benchmark uses: a puddle of globules of radius 1 on a
// jittered lattice of spacing 1 (the paper's r0), four times as wide and deep as high,
// the state a poured liquid settles into. Fixed seed, so every run and vdb_tool see the
// same particles.

#include <cmath>
#include <cstddef>
#include <random>

#include "globules.h"

namespace globular {

inline Globules benchPuddle(std::size_t count, unsigned seed = 1989) {
    const int width = int(std::ceil(std::cbrt(4.0 * double(count))));
    const int layers = int(std::ceil(double(count) / (double(width) * width)));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.2, 0.2);
    Globules g;
    g.reserve(count);
    for (int y = 0; y < layers; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int z = 0; z < width; ++z) {
                if (g.size() == count) return g;
                g.add({x + jitter(rng), y + jitter(rng), z + jitter(rng)}, {0, 0, 0}, 1.0f, 1.0f,
                      int32_t(g.size()));
            }
        }
    }
    return g;
}

}  // namespace globular
