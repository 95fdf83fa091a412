// The AVX2 functions of sim/simd_lanes.h behind a plain interface, for left_pack_test.cpp.
// This file alone is built with AVX2 (tests/sim_tests.cmake) and uses no standard
// library templates, so no AVX2 copy of an inline function reaches the test's other code.
#include "left_pack_probe.h"

#include "simd_lanes.h"

#if !defined(__AVX2__)
#error "left_pack_probe.cpp is built with -mavx2 -mfma"
#endif

void leftPackLanes(unsigned mask, float out[8]) {
    _mm256_storeu_ps(out, globular::leftPack(_mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7), mask));
}

unsigned firstLanesMask(uint32_t left) {
    return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(globular::firstLanes8(left))));
}

float laneSum(const float v[8]) { return globular::sumLanes(_mm256_loadu_ps(v)); }
