#pragma once
// Test helper: two OpenVDB float grids are the same, voxel for voxel (values and active
// states), with the same tree shape.

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <cstddef>

namespace globular {

inline void expectSameGrid(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
    EXPECT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
    EXPECT_EQ(a.tree().leafCount(), b.tree().leafCount());
    auto other = b.getConstAccessor();
    std::size_t differing = 0;
    for (auto it = a.cbeginValueAll(); it; ++it) {
        if (other.getValue(it.getCoord()) != *it ||
            other.isValueOn(it.getCoord()) != it.isValueOn()) {
            ++differing;
        }
    }
    EXPECT_EQ(differing, 0u);
}

}  // namespace globular
