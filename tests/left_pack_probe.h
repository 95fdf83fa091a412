#pragma once
// Plain entry points to sim/simd_lanes.h's AVX2 functions (left_pack_probe.cpp); call
// them only where the CPU runs AVX2.
#include <cstdint>

/// leftPack of the lanes (0, 1, ..., 7) with @p mask, stored to @p out.
void leftPackLanes(unsigned mask, float out[8]);
/// firstLanes8(@p left) as a movemask.
unsigned firstLanesMask(uint32_t left);
/// sumLanes of @p v.
float laneSum(const float v[8]);
