#include "globule_cache.h"

#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/PointIndexGrid.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <mutex>
#include <numeric>
#include <string>

#include "atomic_file.h"
#include "errors.h"

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

// OpenVDB trusts its input: a truncated or corrupted file trips assertions or reads
// garbage sizes. So before OpenVDB sees a file, its layout is checked here (header,
// file metadata, grid descriptors and their extents), and files written by
// writeGlobuleVdb also carry a checksum of everything after the file metadata, in the
// file-level string metadata kChecksumKey (16 hex digits; other tools ignore it).

constexpr const char* kChecksumKey = "globular_checksum";
constexpr std::size_t kChecksumDigits = 16;
constexpr int64_t kVdbMagic = 0x56444220;    // "VDB "
constexpr uint32_t kOldestVdbVersion = 222;  // OpenVDB reads nothing older

/// Bounds-checked little-endian reads from file bytes.
struct ByteReader {
    const std::string& bytes;
    std::size_t pos = 0;

    void need(uint64_t n) const {
        if (n > bytes.size() - pos) throw std::runtime_error("file is truncated");
    }
    template <typename T>
    T read() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, bytes.data() + pos, sizeof v);
        pos += sizeof v;
        return v;
    }
    void skip(uint64_t n) {
        need(n);
        pos += n;
    }
    std::string readString() {
        const uint32_t n = read<uint32_t>();
        need(n);
        pos += n;
        return bytes.substr(pos - n, n);
    }
};

struct VdbLayout {
    std::size_t gridsOffset = 0;                     ///< first byte after file metadata
    std::size_t checksumOffset = std::string::npos;  ///< hex digits of kChecksumKey
};

/// @throw std::runtime_error saying what is wrong with the layout of a VDB file.
VdbLayout scanVdbLayout(const std::string& bytes) {
    ByteReader in{bytes};
    if (bytes.size() < sizeof(int64_t) || in.read<int64_t>() != kVdbMagic) {
        throw std::runtime_error("not a VDB file");
    }
    const uint32_t version = in.read<uint32_t>();
    if (version < kOldestVdbVersion) {
        throw std::runtime_error("VDB file format " + std::to_string(version) + " is too old");
    }
    in.skip(2 * sizeof(uint32_t));  // library version
    const bool hasGridOffsets = in.read<char>() != 0;
    in.skip(36);  // UUID
    VdbLayout layout;
    const int32_t metadataCount = in.read<int32_t>();
    for (int32_t m = 0; m < metadataCount; ++m) {
        const std::string name = in.readString(), type = in.readString();
        const uint32_t size = in.read<uint32_t>();
        if (name == kChecksumKey && type == "string" && size == kChecksumDigits) {
            layout.checksumOffset = in.pos;
        }
        in.skip(size);
    }
    layout.gridsOffset = in.pos;
    const int32_t gridCount = in.read<int32_t>();
    if (gridCount < 0) throw std::runtime_error("negative grid count");
    if (!hasGridOffsets) return layout;  // a streamed file: grids follow back to back
    for (int32_t g = 0; g < gridCount; ++g) {
        in.readString();  // unique name
        in.readString();  // grid type
        in.readString();  // instance parent
        const auto gridPos = in.read<int64_t>(), blockPos = in.read<int64_t>(),
                   endPos = in.read<int64_t>();
        if (!(int64_t(in.pos) <= gridPos && gridPos <= blockPos && blockPos <= endPos)) {
            throw std::runtime_error("grid descriptor " + std::to_string(g) + " is corrupt");
        }
        if (uint64_t(endPos) > bytes.size()) {
            throw std::runtime_error("file is truncated (grid " + std::to_string(g) +
                                     " ends at byte " + std::to_string(endPos) + " of " +
                                     std::to_string(bytes.size()) + ")");
        }
        in.pos = std::size_t(endPos);
    }
    return layout;
}

/// 64-bit FNV-1a over 8-byte words (then the tail bytes): fast, and any flipped bit,
/// cut or shifted block changes it.
std::string checksumHex(const std::string& bytes, std::size_t begin) {
    uint64_t h = 0xcbf29ce484222325ull;
    constexpr uint64_t kPrime = 0x100000001b3ull;
    std::size_t i = begin;
    for (; i + 8 <= bytes.size(); i += 8) {
        uint64_t w;
        std::memcpy(&w, bytes.data() + i, 8);
        h = (h ^ w) * kPrime;
    }
    for (; i < bytes.size(); ++i) h = (h ^ uint8_t(bytes[i])) * kPrime;
    std::string hex(kChecksumDigits, '0');
    for (std::size_t d = 0; d < kChecksumDigits; ++d, h >>= 4) {
        hex[kChecksumDigits - 1 - d] = "0123456789abcdef"[h & 15];
    }
    return hex;
}

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(std::strerror(errno));
    std::string bytes(fs::file_size(path), '\0');
    in.read(bytes.data(), std::streamsize(bytes.size()));
    if (std::size_t(in.gcount()) != bytes.size()) throw std::runtime_error("read failed");
    return bytes;
}

/// Fills in the checksum placeholder of a VDB file just written.
void sealChecksum(const fs::path& path) {
    const std::string bytes = readBytes(path);
    const VdbLayout layout = scanVdbLayout(bytes);
    if (layout.checksumOffset == std::string::npos) {
        throw std::runtime_error("checksum placeholder missing");
    }
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(std::streamoff(layout.checksumOffset));
    file.write(checksumHex(bytes, layout.gridsOffset).data(), kChecksumDigits);
    file.flush();
    if (!file) throw std::runtime_error("cannot write checksum");
}

/// @throw std::runtime_error when the file at @p path is not an intact VDB file.
void verifyVdbFile(const fs::path& path) {
    const std::string bytes = readBytes(path);
    const VdbLayout layout = scanVdbLayout(bytes);
    if (layout.checksumOffset == std::string::npos) return;  // not ours: layout only
    if (bytes.compare(layout.checksumOffset, kChecksumDigits,
                      checksumHex(bytes, layout.gridsOffset)) != 0) {
        throw std::runtime_error("file is corrupt (checksum mismatch)");
    }
}

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
/// @throw IoError when a position is not finite: such a frame cannot be stored.
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
    vdbp::populateAttribute(tree, indexTree, "v", VelocityList{g});
    vdbp::populateAttribute(tree, indexTree, "pscale", ArrayList<float>{g.radius});
    vdbp::populateAttribute(tree, indexTree, "id", ArrayList<int32_t>{g.id});

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
}

/// @brief Globules of a point grid, ordered by id so that a cache reads back in the
/// same order whatever spatial order the grid stored them in.
Globules globulesOf(const vdbp::PointDataGrid& grid) {
    const auto& tree = grid.tree();
    openvdb::tree::LeafManager<const vdbp::PointDataTree> leaves(tree);
    std::vector<std::size_t> start(leaves.leafCount() + 1, 0);
    for (std::size_t l = 0; l < leaves.leafCount(); ++l) {
        start[l + 1] = start[l] + leaves.leaf(l).pointCount();
    }
    const std::size_t n = start.back();
    Globules out;
    for (auto* a : {&out.px, &out.py, &out.pz, &out.vx, &out.vy, &out.vz}) a->assign(n, 0.0f);
    out.radius.assign(n, 1.0f);
    out.mass.assign(n, 1.0f);
    out.id.resize(n);
    std::iota(out.id.begin(), out.id.end(), 0);

    leaves.foreach (
        [&](const Leaf& leaf, std::size_t l) { readLeaf(leaf, grid.transform(), start[l], out); });

    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return out.id[a] < out.id[b]; });
    out.permute(order);
    return out;
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
    writeAtomically(path, [&](const fs::path& temporary) {
        openvdb::MetaMap fileMetadata;
        fileMetadata.insertMeta(kChecksumKey,
                                openvdb::StringMetadata(std::string(kChecksumDigits, '0')));
        openvdb::io::File(temporary.string()).write(openvdb::GridCPtrVec{grid}, fileMetadata);
        sealChecksum(temporary);
    });
}

Globules readGlobuleVdb(const fs::path& path, CacheInfo* info) {
    initializeVdb();
    const auto fail = [&](const std::string& what) {
        return IoError("cannot read " + path.string() + ": " + what);
    };
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw fail("no such file");
    try {
        verifyVdbFile(path);
        openvdb::io::File file(path.string());
        // No delayed loading: a memory-mapped, truncated file would fault on access.
        file.open(/*delayLoad=*/false);
        if (!file.hasGrid(kGridName)) {
            std::string names;
            for (auto it = file.beginName(); it != file.endName(); ++it) {
                names += (names.empty() ? "" : ", ") + *it;
            }
            throw fail(std::string("no grid named '") + kGridName +
                       "' (grids: " + (names.empty() ? "none" : names) + ")");
        }
        const openvdb::GridBase::Ptr base = file.readGrid(kGridName);
        file.close();
        const auto grid = openvdb::gridPtrCast<vdbp::PointDataGrid>(base);
        if (!grid) {
            throw fail(std::string("grid '") + kGridName + "' is a " + base->type() +
                       ", not a point data grid");
        }
        Globules globules = globulesOf(*grid);
        if (info) {
            *info = CacheInfo{};
            if (auto frame = grid->getMetadata<openvdb::Int32Metadata>("frame")) {
                info->frame = frame->value();
            }
            if (auto time = grid->getMetadata<openvdb::DoubleMetadata>("time")) {
                info->time = time->value();
            }
        }
        return globules;
    } catch (const IoError&) {
        throw;  // already names the file
    } catch (const std::exception& e) {
        throw fail(e.what());
    }
}

}  // namespace globular
