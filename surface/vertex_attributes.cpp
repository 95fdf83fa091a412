#include "vertex_attributes.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "globule_bins.h"

namespace globular {

namespace {

/// A globule near a vertex and its kernel weight there.
struct Weighted {
    uint32_t globule;
    float weight;
};

/// The globules whose influence reaches index-space point @p p, with their weights, in
/// the bins' fixed order; @p nearest: the closest globule binned near it (any distance),
/// or UINT32_MAX.
void gather(const GlobuleBins& bins, const MetaballKernel& kernel, const double p[3],
            std::vector<Weighted>& out, uint32_t& nearest) {
    out.clear();
    nearest = std::numeric_limits<uint32_t>::max();
    double nearestDistance = std::numeric_limits<double>::infinity();
    constexpr int kShift = GlobuleBins::kBlockLog2;
    const uint64_t key = GlobuleBins::pack(int64_t(std::floor(p[0])) >> kShift,
                                           int64_t(std::floor(p[1])) >> kShift,
                                           int64_t(std::floor(p[2])) >> kShift);
    bins.forEachGlobuleNear(key, [&](uint32_t i) {
        const double dx = bins.centreX(i) - p[0], dy = bins.centreY(i) - p[1],
                     dz = bins.centreZ(i) - p[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < nearestDistance) {
            nearestDistance = d2;
            nearest = i;
        }
        const double r = bins.influenceVoxels(i);
        const float w = kernel.value(float(d2 / (r * r)));
        if (w > 0.0f) out.push_back({i, w});
    });
}

}  // namespace

CarriedAttributes attributesOf(const Globules& globules, bool severalMaterials) {
    CarriedAttributes which;
    which.velocity = true;
    which.temperature = !globules.temperature.empty();
    which.material = severalMaterials || std::any_of(globules.material.begin(), globules.material.end(),
                                 [](uint8_t m) { return m != 0; });
    return which;
}

void carryGlobuleAttributes(TriangleMesh& mesh, const Globules& globules,
                            const MetaballKernel& kernel, double influence, double voxelSize,
                            CarriedAttributes which) {
    if (!which.any()) return;
    const std::size_t n = mesh.vertexCount();
    std::vector<float> velocity[3];
    for (auto& component : velocity) component.resize(which.velocity ? n : 0);
    std::vector<float> temperature(which.temperature ? n : 0);
    std::vector<float> material(which.material ? n : 0);
    const GlobuleBins bins(globules, voxelSize, influence);
    const int materials = globules.material.empty()
                              ? 1
                              : 1 + *std::max_element(globules.material.begin(),
                                                      globules.material.end());
    const double toIndex = 1.0 / voxelSize;

    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](auto range) {
        std::vector<Weighted> near;
        std::vector<double> perMaterial(materials);
        for (std::size_t v = range.begin(); v < range.end(); ++v) {
            const double p[3] = {mesh.positions[3 * v] * toIndex,
                                 mesh.positions[3 * v + 1] * toIndex,
                                 mesh.positions[3 * v + 2] * toIndex};
            uint32_t nearest;
            gather(bins, kernel, p, near, nearest);
            if (near.empty() && nearest != std::numeric_limits<uint32_t>::max()) {
                near.push_back({nearest, 1.0f});
            }
            // Kernel-weighted means, sum(w x) / sum(w), in one pass over the neighbours.
            double sum = 0, weighted[3] = {0, 0, 0}, warmth = 0;
            for (const Weighted& g : near) {
                const double w = g.weight;
                sum += w;
                if (which.velocity) {
                    weighted[0] += w * globules.vx[g.globule];
                    weighted[1] += w * globules.vy[g.globule];
                    weighted[2] += w * globules.vz[g.globule];
                }
                if (which.temperature) warmth += w * globules.temperature[g.globule];
            }
            if (which.velocity) {
                for (int a = 0; a < 3; ++a) {
                    velocity[a][v] = sum > 0 ? float(weighted[a] / sum) : 0.0f;
                }
            }
            if (which.temperature) temperature[v] = sum > 0 ? float(warmth / sum) : 0.0f;
            if (which.material) {
                std::fill(perMaterial.begin(), perMaterial.end(), 0.0);
                for (const Weighted& g : near) perMaterial[globules.materialOf(g.globule)] += g.weight;
                material[v] = float(std::max_element(perMaterial.begin(), perMaterial.end()) -
                                    perMaterial.begin());
            }
        }
    });
    if (which.velocity) {
        const char* names[3] = {"vx", "vy", "vz"};
        for (int a = 0; a < 3; ++a) {
            mesh.attributes.push_back(
                {names[a], VertexAttribute::Type::Float32, std::move(velocity[a])});
        }
    }
    if (which.temperature) {
        mesh.attributes.push_back(
            {"temperature", VertexAttribute::Type::Float32, std::move(temperature)});
    }
    if (which.material) {
        mesh.attributes.push_back({"material", VertexAttribute::Type::Int32, std::move(material)});
    }
}

}  // namespace globular
