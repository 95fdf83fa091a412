#include "vertex_attributes.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

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

/// A globule binned near a block: centre (index space) and squared influence radius.
struct Candidate {
    double x, y, z, r2;
    uint32_t globule;
};

/// The globules whose influence may reach block @p key, in the bins' fixed order
/// (forEachGlobuleNear): looked up once for all the vertices in that block.
void candidatesNear(const GlobuleBins& bins, uint64_t key, std::vector<Candidate>& out) {
    out.clear();
    bins.forEachGlobuleNear(key, [&](uint32_t i) {
        const double r = bins.influenceVoxels(i);
        out.push_back({bins.centreX(i), bins.centreY(i), bins.centreZ(i), r * r, i});
    });
}

/// Those of @p all whose influence sphere meets the box [@p lo, @p hi] (index space), in
/// their order, into @p out. Exact as a filter: per axis the box's nearest point lies
/// between the centre and any point in the box, so its distance, rounded, is never larger
/// than a vertex's, and no candidate that reaches a vertex in the box is dropped.
void candidatesMeeting(const std::vector<Candidate>& all, const double lo[3], const double hi[3],
                       std::vector<Candidate>& out) {
    out.clear();
    for (const Candidate& c : all) {
        const double dx = c.x - std::clamp(c.x, lo[0], hi[0]);
        const double dy = c.y - std::clamp(c.y, lo[1], hi[1]);
        const double dz = c.z - std::clamp(c.z, lo[2], hi[2]);
        if (dx * dx + dy * dy + dz * dz < c.r2) out.push_back(c);
    }
}

/// The globules of @p candidates whose influence reaches index-space point @p p, with
/// their weights, in the candidates' order; @p nearest: the closest candidate (any
/// distance), or UINT32_MAX.
void gather(const std::vector<Candidate>& candidates, const MetaballKernel& kernel,
            const double p[3], std::vector<Weighted>& out, uint32_t& nearest) {
    out.clear();
    nearest = std::numeric_limits<uint32_t>::max();
    double nearestDistance = std::numeric_limits<double>::infinity();
    for (const Candidate& c : candidates) {
        const double dx = c.x - p[0], dy = c.y - p[1], dz = c.z - p[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < nearestDistance) {
            nearestDistance = d2;
            nearest = c.globule;
        }
        // Beyond the influence radius the kernel is 0: most candidates, no kernel call.
        if (!(d2 < c.r2)) continue;
        const float w = kernel.value(float(d2 / c.r2));
        if (w > 0.0f) out.push_back({c.globule, w});
    }
}

/// A vertex's attributes, written into per-vertex arrays: the kernel-weighted means of
/// the globules that reach it, sum(w x) / sum(w), and the material of most weight.
struct VertexMeans {
    const Globules& globules;
    CarriedAttributes which;
    std::vector<float> velocity[3], temperature, material;

    VertexMeans(const Globules& g, CarriedAttributes w, std::size_t vertices)
        : globules(g), which(w) {
        for (auto& component : velocity) component.resize(which.velocity ? vertices : 0);
        temperature.resize(which.temperature ? vertices : 0);
        material.resize(which.material ? vertices : 0);
    }

    /// @p near: the globules reaching vertex @p v with their weights; @p perMaterial:
    /// scratch, one entry per material.
    void set(std::size_t v, const std::vector<Weighted>& near, std::vector<double>& perMaterial) {
        double sum = 0, weighted[3] = {0, 0, 0}, warmth = 0;
        for (const Weighted& g : near) {  // one pass over the neighbours
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
            for (int a = 0; a < 3; ++a) velocity[a][v] = sum > 0 ? float(weighted[a] / sum) : 0.0f;
        }
        if (which.temperature) temperature[v] = sum > 0 ? float(warmth / sum) : 0.0f;
        if (which.material) {
            std::fill(perMaterial.begin(), perMaterial.end(), 0.0);
            for (const Weighted& g : near) perMaterial[globules.materialOf(g.globule)] += g.weight;
            material[v] = float(std::max_element(perMaterial.begin(), perMaterial.end()) -
                                perMaterial.begin());
        }
    }
};

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
    carryGlobuleAttributes(mesh, globules, GlobuleBins(globules, voxelSize, influence), kernel,
                           voxelSize, which);
}

void carryGlobuleAttributes(TriangleMesh& mesh, const Globules& globules,
                            const GlobuleBins& bins, const MetaballKernel& kernel,
                            double voxelSize, CarriedAttributes which) {
    if (!which.any()) return;
    const std::size_t n = mesh.vertexCount();
    VertexMeans means(globules, which, n);
    const int materials = globules.material.empty()
                              ? 1
                              : 1 + *std::max_element(globules.material.begin(),
                                                      globules.material.end());
    const double toIndex = 1.0 / voxelSize;

    // Vertices grouped by the block they lie in (then by index: a total order, so the
    // parallel sort is deterministic); each block looks its candidate globules up once.
    std::vector<std::pair<uint64_t, uint32_t>> byBlock(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](auto range) {
        for (std::size_t v = range.begin(); v < range.end(); ++v) {
            byBlock[v] = {GlobuleBins::blockKeyAt(mesh.positions[3 * v] * toIndex,
                                                  mesh.positions[3 * v + 1] * toIndex,
                                                  mesh.positions[3 * v + 2] * toIndex),
                          uint32_t(v)};
        }
    });
    tbb::parallel_sort(byBlock.begin(), byBlock.end());
    std::vector<std::size_t> groupStart;
    for (std::size_t k = 0; k < n; ++k) {
        if (k == 0 || byBlock[k].first != byBlock[k - 1].first) groupStart.push_back(k);
    }
    groupStart.push_back(n);

    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groupStart.size() - 1, 4), [&](auto groups) {
        std::vector<Weighted> near;
        std::vector<Candidate> candidates, reaching;
        std::vector<double> perMaterial(materials);
        const auto indexPoint = [&](std::size_t v, double p[3]) {
            for (int a = 0; a < 3; ++a) p[a] = mesh.positions[3 * v + a] * toIndex;
        };
        for (std::size_t group = groups.begin(); group < groups.end(); ++group) {
            candidatesNear(bins, byBlock[groupStart[group]].first, candidates);
            // The block's candidates come from every block within the largest influence
            // of it; few reach the block's vertices. Those that may are tested per vertex.
            double lo[3], hi[3];
            indexPoint(byBlock[groupStart[group]].second, lo);
            std::copy(lo, lo + 3, hi);
            for (std::size_t k = groupStart[group] + 1; k < groupStart[group + 1]; ++k) {
                double p[3];
                indexPoint(byBlock[k].second, p);
                for (int a = 0; a < 3; ++a) {
                    lo[a] = std::min(lo[a], p[a]);
                    hi[a] = std::max(hi[a], p[a]);
                }
            }
            candidatesMeeting(candidates, lo, hi, reaching);
            for (std::size_t k = groupStart[group]; k < groupStart[group + 1]; ++k) {
                const std::size_t v = byBlock[k].second;
                double p[3];
                indexPoint(v, p);
                uint32_t nearest;
                gather(reaching, kernel, p, near, nearest);
                if (near.empty()) {
                    // None reaches it: the nearest of all the block's candidates stands in.
                    gather(candidates, kernel, p, near, nearest);
                    if (nearest != std::numeric_limits<uint32_t>::max()) {
                        near.push_back({nearest, 1.0f});
                    }
                }
                means.set(v, near, perMaterial);
            }
        }
    });
    if (which.velocity) {
        const char* names[3] = {"vx", "vy", "vz"};
        for (int a = 0; a < 3; ++a) {
            mesh.attributes.push_back(
                {names[a], VertexAttribute::Type::Float32, std::move(means.velocity[a])});
        }
    }
    if (which.temperature) {
        mesh.attributes.push_back(
            {"temperature", VertexAttribute::Type::Float32, std::move(means.temperature)});
    }
    if (which.material) {
        mesh.attributes.push_back(
            {"material", VertexAttribute::Type::Int32, std::move(means.material)});
    }
}

}  // namespace globular
