#include "globules.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <bit>

namespace globular {

namespace {

/// Calls body(k) for k in [0, n), in parallel.
template <typename Body>
void forEachIndex(std::size_t n, Body&& body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t k = r.begin(); k != r.end(); ++k) body(k);
                      });
}

/// values[k] = old values[order[k]]; @p scratch takes the old buffer.
void permuteArray(std::vector<float>& values, const std::vector<uint32_t>& order,
                  std::vector<float>& scratch) {
    scratch.resize(values.size());
    forEachIndex(order.size(), [&](std::size_t k) { scratch[k] = values[order[k]]; });
    values.swap(scratch);
}

}  // namespace

bool Globules::consistent() const {
    const std::size_t n = size();
    for (const auto* a : {&py, &pz, &vx, &vy, &vz, &radius, &mass}) {
        if (a->size() != n) return false;
    }
    return id.size() == n && (material.empty() || material.size() == n) &&
           (temperature.empty() || temperature.size() == n);
}

void Globules::reserve(std::size_t n) {
    for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &radius, &mass}) a->reserve(n);
    id.reserve(n);
    if (!material.empty()) material.reserve(n);
    if (!temperature.empty()) temperature.reserve(n);
}

void Globules::clear() {
    for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &radius, &mass}) a->clear();
    id.clear();
    material.clear();
    temperature.clear();
}

std::size_t Globules::add(Vec3 p, Vec3 v, float r, float m, int32_t globuleId) {
    px.push_back(float(p.x));
    py.push_back(float(p.y));
    pz.push_back(float(p.z));
    vx.push_back(float(v.x));
    vy.push_back(float(v.y));
    vz.push_back(float(v.z));
    radius.push_back(r);
    mass.push_back(m);
    id.push_back(globuleId);
    return size() - 1;
}

void Globules::permute(const std::vector<uint32_t>& order, std::vector<float>& scratch) {
    for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &radius, &mass}) permuteArray(*a, order, scratch);
    if (!temperature.empty()) permuteArray(temperature, order, scratch);
    // The ids travel through the same float scratch, bit for bit.
    scratch.resize(id.size());
    forEachIndex(order.size(), [&](std::size_t k) { scratch[k] = std::bit_cast<float>(id[order[k]]); });
    forEachIndex(order.size(), [&](std::size_t k) { id[k] = std::bit_cast<int32_t>(scratch[k]); });
    if (!material.empty()) {
        std::vector<uint8_t> old(material);
        forEachIndex(order.size(), [&](std::size_t k) { material[k] = old[order[k]]; });
    }
}

void Globules::permute(const std::vector<uint32_t>& order) {
    std::vector<float> scratch;
    permute(order, scratch);
}

}  // namespace globular
