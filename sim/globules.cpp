#include "globules.h"

namespace globular {

namespace {
template <typename T>
void permuteArray(std::vector<T>& values, const std::vector<uint32_t>& order) {
    std::vector<T> out(values.size());
    for (std::size_t k = 0; k < order.size(); ++k) out[k] = values[order[k]];
    values.swap(out);
}
}  // namespace

bool Globules::consistent() const {
    const std::size_t n = size();
    for (const auto* a : {&py, &pz, &vx, &vy, &vz, &radius, &mass}) {
        if (a->size() != n) return false;
    }
    return id.size() == n;
}

void Globules::reserve(std::size_t n) {
    for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &radius, &mass}) a->reserve(n);
    id.reserve(n);
}

void Globules::clear() {
    for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &radius, &mass}) a->clear();
    id.clear();
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

void Globules::permute(const std::vector<uint32_t>& order) {
    for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &radius, &mass}) permuteArray(*a, order);
    permuteArray(id, order);
}

}  // namespace globular
