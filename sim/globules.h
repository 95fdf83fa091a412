#pragma once
// The globules of a simulation, stored as a struct of arrays so force loops stream
// through memory and vectorise. Single precision: positions span at most a few
// thousand radii, and float halves the memory traffic of the hot loops.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "vec3.h"

namespace globular {

struct Globules {
    std::vector<float> px, py, pz;  ///< position, world units
    std::vector<float> vx, vy, vz;  ///< velocity, world units per second
    std::vector<float> radius;      ///< world units
    std::vector<float> mass;        ///< mass units (1 per globule by default)
    std::vector<int32_t> id;        ///< stable identity, unique, survives reordering
    /// Index into the scene's materials; empty when the scene has one (no cost then).
    std::vector<uint8_t> material;
    /// Temperature, degrees of the scene's choosing; empty when the scene has no
    /// [thermal] section enabled (no cost then).
    std::vector<float> temperature;

    std::size_t size() const { return px.size(); }
    /// Material of globule @p i (0 when there is one material).
    uint8_t materialOf(std::size_t i) const { return material.empty() ? 0 : material[i]; }
    /// Whether every array holds size() elements (material, temperature: or none).
    bool consistent() const;
    bool empty() const { return px.empty(); }

    void reserve(std::size_t n);
    void clear();
    /// Appends one globule; @return its index.
    std::size_t add(Vec3 position, Vec3 velocity, float radius, float mass, int32_t id);

    Vec3 position(std::size_t i) const { return {px[i], py[i], pz[i]}; }
    Vec3 velocity(std::size_t i) const { return {vx[i], vy[i], vz[i]}; }

    /// Reorders every array so that new index k holds old index order[k].
    void permute(const std::vector<uint32_t>& order);
    /// The same, reusing @p scratch (any contents) instead of allocating: the force loop
    /// reorders the globules every step.
    void permute(const std::vector<uint32_t>& order, std::vector<float>& scratch);
};

}  // namespace globular
