#include "globule_cache.h"

#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/PointIndexGrid.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <numeric>
#include <string>

#include "errors.h"
#include "vdb_archive.h"

namespace globular {

namespace fs = std::filesystem;
namespace vdbp = openvdb::points;

namespace {

constexpr const char* kGridName = "globules";
/// The smallest point-grid voxel (world units); OpenVDB's ScaleMap refuses voxel
/// volumes below about 3e-15.
constexpr double kMinVoxelSize = 1e-4;
/// Index-space coordinates must stay well inside int32.
constexpr double kMaxIndexCoord = 1e9;

void initializeVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

void checkArraySizes(const fs::path& path, const Globules& g) {
    if (!g.consistent()) {
        throw IoError("cannot write " + path.string() + ": globule arrays differ in size");
    }
}

/// Caches larger than this are refused before they are read (1e8 globules take 4 GB).
constexpr uint64_t kMaxCacheBytes = uint64_t(16) << 30;

/// @brief Positions of the struct of arrays in the shape OpenVDB's PointPartitioner and
/// createPointDataGrid read, so nothing is copied into a vector of Vec3.
struct PositionList {
    using PosType = openvdb::Vec3R;
    using value_type = openvdb::Vec3R;
    const Globules& g;
    std::size_t size() const { return g.size(); }
    void getPos(std::size_t n, openvdb::Vec3R& p) const { p = {g.px[n], g.py[n], g.pz[n]}; }
};

/// Velocities as a point attribute list (populateAttribute's contract).
struct VelocityList {
    using value_type = openvdb::Vec3f;
    const Globules& g;
    std::size_t size() const { return g.size(); }
    void get(value_type& v, std::size_t n, openvdb::Index = 0) const {
        v = {g.vx[n], g.vy[n], g.vz[n]};
    }
};

/// One scalar array as a point attribute list.
template <typename T>
struct ArrayList {
    using value_type = T;
    const std::vector<T>& values;
    std::size_t size() const { return values.size(); }
    void get(value_type& v, std::size_t n, openvdb::Index = 0) const { v = values[n]; }
};

/// @brief Voxel edge of the point grid: twice the largest radius, so globules resting
/// about a radius apart share a voxel with a handful of neighbours (OpenVDB suggests ~8
/// points per voxel). Far-flung globules enlarge it so index coordinates fit in int32.
/// @throw IoError when a position or temperature is not finite: such a frame cannot be
///        stored.
double chooseVoxelSize(const fs::path& path, const Globules& g) {
    float maxRadius = 0;
    double maxAbs = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        const float p[3] = {g.px[i], g.py[i], g.pz[i]};
        for (float c : p) {
            if (!std::isfinite(c)) {
                throw IoError("cannot write " + path.string() + ": globule " +
                              std::to_string(g.id[i]) + " has a non-finite position");
            }
            maxAbs = std::max(maxAbs, double(std::fabs(c)));
        }
        if (std::isfinite(g.radius[i])) maxRadius = std::max(maxRadius, g.radius[i]);
        if (!g.temperature.empty() && !std::isfinite(g.temperature[i])) {
            throw IoError("cannot write " + path.string() + ": globule " +
                          std::to_string(g.id[i]) + " has a non-finite temperature");
        }
        if (!(g.mass[i] > 0) || !std::isfinite(g.mass[i])) {
            throw IoError("cannot write " + path.string() + ": globule " +
                          std::to_string(g.id[i]) + " has mass " + std::to_string(g.mass[i]) +
                          ", not a positive finite number");
        }
    }
    double voxelSize = maxRadius > 0 ? 2.0 * maxRadius : 1.0;
    return std::max({voxelSize, kMinVoxelSize, maxAbs / kMaxIndexCoord});
}

vdbp::PointDataGrid::Ptr buildGrid(const fs::path& path, const Globules& g, const CacheInfo& info) {
    auto transform = openvdb::math::Transform::createLinearTransform(chooseVoxelSize(path, g));
    const PositionList positions{g};
    auto indexGrid =
        openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(positions, *transform);
    // Full-precision positions: the cache is also what a resumed simulation starts from.
    auto grid = vdbp::createPointDataGrid<vdbp::NullCodec, vdbp::PointDataGrid>(
        *indexGrid, positions, *transform);
    auto& tree = grid->tree();
    const auto& indexTree = indexGrid->tree();
    vdbp::appendAttribute<openvdb::Vec3f>(tree, "v");
    vdbp::appendAttribute<float>(tree, "pscale", 1.0f);
    vdbp::appendAttribute<int32_t>(tree, "id");
    vdbp::appendAttribute<float>(tree, "mass", 1.0f);
    vdbp::appendAttribute<int32_t>(tree, "material");
    vdbp::populateAttribute(tree, indexTree, "v", VelocityList{g});
    vdbp::populateAttribute(tree, indexTree, "pscale", ArrayList<float>{g.radius});
    vdbp::populateAttribute(tree, indexTree, "id", ArrayList<int32_t>{g.id});
    vdbp::populateAttribute(tree, indexTree, "mass", ArrayList<float>{g.mass});
    std::vector<int32_t> materials(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) materials[i] = g.materialOf(i);
    vdbp::populateAttribute(tree, indexTree, "material", ArrayList<int32_t>{materials});
    if (!g.temperature.empty()) {
        vdbp::appendAttribute<float>(tree, "temperature");
        vdbp::populateAttribute(tree, indexTree, "temperature", ArrayList<float>{g.temperature});
    }

    grid->setName(kGridName);
    grid->setCreator("globular");
    grid->insertMeta("frame", openvdb::Int32Metadata(info.frame));
    grid->insertMeta("time", openvdb::DoubleMetadata(info.time));
    return grid;
}

using Leaf = vdbp::PointDataTree::LeafNodeType;

/// @brief Calls sink(k, value) for the k-th point of @p leaf (in beginIndexAll order)
/// with attribute @p index, which may be stored as any of the types @p Stored (a DCC
/// tool may have written doubles or 64-bit ids).
template <typename... Stored, typename Sink>
void forEachValue(const Leaf& leaf, std::size_t index, const std::string& name, Sink&& sink) {
    const std::string& type = leaf.attributeSet().descriptor().valueType(index);
    const auto visitAs = [&](auto stored) {
        if (type != openvdb::typeNameAsString<decltype(stored)>()) return false;
        vdbp::AttributeHandle<decltype(stored)> handle(leaf.constAttributeArray(index));
        std::size_t k = 0;
        for (auto it = leaf.beginIndexAll(); it; ++it, ++k) sink(k, handle.get(*it));
        return true;
    };
    if (!(visitAs(Stored()) || ...)) {
        throw std::runtime_error("attribute " + name + " has unsupported type " + type);
    }
}

/// Copies the points of @p leaf into @p out from index @p start on.
void readLeaf(const Leaf& leaf, const openvdb::math::Transform& xform, std::size_t start,
              Globules& out) {
    const auto& descriptor = leaf.attributeSet().descriptor();
    const std::size_t pIndex = descriptor.find("P");
    if (pIndex == vdbp::AttributeSet::INVALID_POS)
        throw std::runtime_error("points have no attribute P");
    std::vector<openvdb::Coord> voxel(leaf.pointCount());
    std::size_t k = 0;
    for (auto it = leaf.beginIndexAll(); it; ++it) voxel[k++] = it.getCoord();
    forEachValue<openvdb::Vec3f, openvdb::Vec3d>(
        leaf, pIndex, "P", [&](std::size_t k, const auto& p) {
            const openvdb::Vec3d world = xform.indexToWorld(openvdb::Vec3d(p) + voxel[k].asVec3d());
            out.px[start + k] = float(world.x());
            out.py[start + k] = float(world.y());
            out.pz[start + k] = float(world.z());
        });
    if (std::size_t i = descriptor.find("v"); i != vdbp::AttributeSet::INVALID_POS) {
        forEachValue<openvdb::Vec3f, openvdb::Vec3d>(leaf, i, "v",
                                                     [&](std::size_t k, const auto& v) {
                                                         out.vx[start + k] = float(v.x());
                                                         out.vy[start + k] = float(v.y());
                                                         out.vz[start + k] = float(v.z());
                                                     });
    }
    if (std::size_t i = descriptor.find("pscale"); i != vdbp::AttributeSet::INVALID_POS) {
        forEachValue<float, double>(
            leaf, i, "pscale", [&](std::size_t k, auto r) { out.radius[start + k] = float(r); });
    }
    if (std::size_t i = descriptor.find("id"); i != vdbp::AttributeSet::INVALID_POS) {
        forEachValue<int32_t, int64_t>(
            leaf, i, "id", [&](std::size_t k, auto id) { out.id[start + k] = int32_t(id); });
    }
    if (std::size_t i = descriptor.find("mass"); i != vdbp::AttributeSet::INVALID_POS) {
        forEachValue<float, double>(leaf, i, "mass", [&](std::size_t k, auto m) {
            // The force loop divides by it.
            if (!(m > 0) || m > std::numeric_limits<float>::max()) {
                throw std::runtime_error("a mass is not a positive finite float");
            }
            out.mass[start + k] = float(m);
        });
    }
    if (std::size_t i = descriptor.find("material"); i != vdbp::AttributeSet::INVALID_POS) {
        forEachValue<int32_t, int64_t>(leaf, i, "material", [&](std::size_t k, auto m) {
            if (m < 0 || m > 255) throw std::runtime_error("a material index is out of range");
            out.material[start + k] = uint8_t(m);
        });
    }
    if (std::size_t i = descriptor.find("temperature"); i != vdbp::AttributeSet::INVALID_POS) {
        // Present on one leaf, present on all: the descriptor is shared by the tree.
        if (out.temperature.empty()) out.temperature.assign(out.size(), 0.0f);
        forEachValue<float, double>(leaf, i, "temperature", [&](std::size_t k, auto t) {
            if (!std::isfinite(t) || std::abs(t) > std::numeric_limits<float>::max()) {
                throw std::runtime_error("a temperature is not a finite float");
            }
            out.temperature[start + k] = float(t);
        });
    }
}

/// @brief Globules of a point grid, ordered by id so that a cache reads back in the
/// same order whatever spatial order the grid stored them in. Serial: it runs in a
/// reader's child process, which must not use TBB.
Globules globulesOf(const vdbp::PointDataGrid& grid) {
    const auto& tree = grid.tree();
    openvdb::tree::LeafManager<const vdbp::PointDataTree> leaves(tree, 0, /*serial=*/true);
    std::vector<std::size_t> start(leaves.leafCount() + 1, 0);
    for (std::size_t l = 0; l < leaves.leafCount(); ++l) {
        start[l + 1] = start[l] + leaves.leaf(l).pointCount();
    }
    const std::size_t n = start.back();
    if (n > std::size_t(INT32_MAX)) throw std::runtime_error("more than 2^31 points");
    Globules out;
    for (auto* a : {&out.px, &out.py, &out.pz, &out.vx, &out.vy, &out.vz}) a->assign(n, 0.0f);
    out.radius.assign(n, 1.0f);
    out.mass.assign(n, 1.0f);
    out.id.resize(n);
    std::iota(out.id.begin(), out.id.end(), 0);
    out.material.assign(n, 0);

    for (std::size_t l = 0; l < leaves.leafCount(); ++l) {
        readLeaf(leaves.leaf(l), grid.transform(), start[l], out);
    }

    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return out.id[a] < out.id[b]; });
    out.permute(order);
    return out;
}

// What a reader's child process sends back: count, frame, time, whether temperature is
// present (one byte), then the arrays.
struct Packet {
    std::string bytes;
    template <typename T>
    void value(const T& v) {
        bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    template <typename T>
    void array(const std::vector<T>& v) {
        if (v.empty()) return;  // data() may be null
        bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
};

std::string packGlobules(const Globules& g, const CacheInfo& info) {
    Packet p;
    p.value(uint64_t(g.size()));
    p.value(int32_t(info.frame));
    p.value(info.time);
    p.value(uint8_t(g.temperature.empty() ? 0 : 1));
    for (const auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
        p.array(*a);
    }
    p.array(g.id);
    p.array(g.material);
    p.array(g.temperature);
    return std::move(p.bytes);
}

/// @throw std::runtime_error when @p bytes are not exactly one packet.
Globules unpackGlobules(const std::string& bytes, CacheInfo& info) {
    std::size_t pos = 0;
    const auto take = [&](void* to, std::size_t size) {
        if (size > bytes.size() - pos) throw std::runtime_error("short answer from the reader");
        if (size > 0) std::memcpy(to, bytes.data() + pos, size);  // data() of {} may be null
        pos += size;
    };
    uint64_t n = 0;
    int32_t frame = 0;
    take(&n, sizeof n);
    take(&frame, sizeof frame);
    take(&info.time, sizeof info.time);
    uint8_t hasTemperature = 0;
    take(&hasTemperature, sizeof hasTemperature);
    info.frame = frame;
    if (hasTemperature > 1) throw std::runtime_error("malformed answer from the reader");
    const uint64_t perGlobule =
        (8 + hasTemperature) * sizeof(float) + sizeof(int32_t) + sizeof(uint8_t);
    if (n > (bytes.size() - pos) / perGlobule || n * perGlobule != bytes.size() - pos) {
        throw std::runtime_error("answer of the wrong size from the reader");
    }
    Globules g;
    for (auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
        a->resize(n);
        take(a->data(), n * sizeof(float));
    }
    g.id.resize(n);
    take(g.id.data(), n * sizeof(int32_t));
    g.material.resize(n);
    take(g.material.data(), n * sizeof(uint8_t));
    if (hasTemperature) {
        g.temperature.resize(n);
        take(g.temperature.data(), n * sizeof(float));
    }
    return g;
}

/// Runs in the reader's child process: OpenVDB parses the file there.
std::string parseCache(const fs::path& path) {
    // Here too: the reader helper may have been forked before this program's first read.
    initializeVdb();
    openvdb::io::File file(path.string());
    // No delayed loading: a memory-mapped, truncated file would fault on access.
    file.open(/*delayLoad=*/false);
    if (!file.hasGrid(kGridName)) {
        std::string names;
        for (auto it = file.beginName(); it != file.endName(); ++it) {
            names += (names.empty() ? "" : ", ") + *it;
        }
        throw std::runtime_error(std::string("no grid named '") + kGridName +
                                 "' (grids: " + (names.empty() ? "none" : names) + ")");
    }
    const openvdb::GridBase::Ptr base = file.readGrid(kGridName);
    file.close();
    const auto grid = openvdb::gridPtrCast<vdbp::PointDataGrid>(base);
    if (!grid) {
        throw std::runtime_error(std::string("grid '") + kGridName + "' is a " + base->type() +
                                 ", not a point data grid");
    }
    CacheInfo info;
    if (auto frame = grid->getMetadata<openvdb::Int32Metadata>("frame")) {
        info.frame = frame->value();
    }
    if (auto time = grid->getMetadata<openvdb::DoubleMetadata>("time")) {
        info.time = time->value();
    }
    return packGlobules(globulesOf(*grid), info);
}

}  // namespace

void writeGlobuleVdb(const fs::path& path, const Globules& globules, const CacheInfo& info) {
    initializeVdb();
    checkArraySizes(path, globules);
    vdbp::PointDataGrid::Ptr grid;
    try {
        grid = buildGrid(path, globules, info);
    } catch (const IoError&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError("cannot write " + path.string() + ": " + e.what());
    }
    writeVdbFile(path, openvdb::GridCPtrVec{grid});
}

Globules readGlobuleVdb(const fs::path& path, CacheInfo* info) {
    initializeVdb();
    const std::string answer =
        parseVdbInChild(path, kMaxCacheBytes, parseCache);
    try {
        CacheInfo read;
        Globules globules = unpackGlobules(answer, read);
        if (info) *info = read;
        return globules;
    } catch (const std::exception& e) {
        throw IoError("cannot read " + path.string() + ": " + e.what());
    }
}

}  // namespace globular
