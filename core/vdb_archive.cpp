#include "vdb_archive.h"

#include <openvdb/io/Archive.h>
#include <openvdb/io/Stream.h>

#include <cstring>
#include <sstream>
#include <stdexcept>

#include "atomic_file.h"
#include "errors.h"
#include "file_bytes.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

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
        throw std::runtime_error(bytes.empty() ? "the file is empty" : "not a VDB file");
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
    if (metadataCount < 0) throw std::runtime_error("negative metadata count");
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

/// OpenVDB's archive writer aimed at any stream (io::File only writes to a path and
/// does not check what the disk said).
class MemoryArchive : public openvdb::io::Archive {
public:
    void encode(std::ostream& os, const openvdb::GridCPtrVec& grids, bool seekable,
                const openvdb::MetaMap& metadata) const {
        write(os, grids, seekable, metadata);
    }
};

}  // namespace

std::string encodeVdb(const openvdb::GridCPtrVec& grids, const openvdb::MetaMap& fileMetadata,
                      bool seekable) {
    openvdb::initialize();
    openvdb::MetaMap metadata(fileMetadata);
    metadata.removeMeta(kChecksumKey);
    metadata.insertMeta(kChecksumKey, openvdb::StringMetadata(std::string(kChecksumDigits, '0')));
    MemoryArchive archive;
    // Statistics metadata needs TBB, which a reader's child process must not use; the
    // parent's files keep what io::File would write.
    archive.setGridStatsMetadataEnabled(seekable);
    std::ostringstream out(std::ios::binary);
    archive.encode(out, grids, seekable, metadata);
    if (!out) throw std::runtime_error("cannot encode the VDB file in memory");
    std::string bytes = std::move(out).str();
    sealVdbChecksum(bytes);
    return bytes;
}

void sealVdbChecksum(std::string& bytes) {
    const VdbLayout layout = scanVdbLayout(bytes);
    if (layout.checksumOffset == std::string::npos) {
        throw std::runtime_error("VDB checksum placeholder missing");
    }
    const std::string sum = checksumHex(bytes, layout.gridsOffset);
    bytes.replace(layout.checksumOffset, kChecksumDigits, sum);
}

void writeVdbFile(const fs::path& path, const openvdb::GridCPtrVec& grids,
                  const openvdb::MetaMap& fileMetadata) {
    std::string bytes;
    try {
        bytes = encodeVdb(grids, fileMetadata);
    } catch (const std::exception& e) {
        throw IoError("cannot write " + path.string() + ": " + e.what());
    }
    writeFileAtomically(path, bytes);
}

void checkVdbBytes(const std::string& bytes) {
    const VdbLayout layout = scanVdbLayout(bytes);
    if (layout.checksumOffset == std::string::npos) return;  // not ours: layout only
    if (bytes.compare(layout.checksumOffset, kChecksumDigits,
                      checksumHex(bytes, layout.gridsOffset)) != 0) {
        throw std::runtime_error("file is corrupt (checksum mismatch)");
    }
}

std::string parseVdbInChild(const fs::path& path, uint64_t maxBytes, PathParser parse) {
    try {
        checkVdbBytes(readFileBytes(path, maxBytes));
    } catch (const std::exception& e) {
        throw IoError("cannot read " + path.string() + ": " + e.what());
    }
    return parseInWarmReader(path, parse);
}

openvdb::GridPtrVecPtr decodeStreamedVdb(const std::string& bytes) {
    openvdb::initialize();
    std::istringstream in(bytes, std::ios::binary);
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    return stream.getGrids();
}

}  // namespace globular
