#pragma once
// VDB files as globular writes and checks them. A file is encoded in memory by OpenVDB's
// own archive writer (the bytes io::File would write), sealed with a checksum in the
// file-level metadata "globular_checksum" (16 hex digits; other tools ignore it) and
// written through atomic_file.h, so a full disk is an error naming the file, never a
// truncated file under a final name. Before a reader hands a file to OpenVDB (in a child
// process, isolated_parse.h), its layout is checked, and the checksum when it has one.
// INCLUDES OPENVDB: only for the .cpp files that already need it.

#include <openvdb/openvdb.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "reader_helper.h"

namespace globular {

/// The bytes of a VDB file holding @p grids and @p fileMetadata, checksum sealed.
/// @param seekable true: the layout io::File writes (grid offsets, read by every tool);
///        false: the streamed layout of io::Stream.
std::string encodeVdb(const openvdb::GridCPtrVec& grids, const openvdb::MetaMap& fileMetadata,
                      bool seekable = true);

/// Writes the checksum of VDB file @p bytes into their "globular_checksum" metadata (what
/// encodeVdb does last; tests use it to forge damaged files that pass the checksum).
/// @throw std::runtime_error when the bytes are not a VDB file with that metadata.
void sealVdbChecksum(std::string& bytes);

/// encodeVdb, then written atomically. @throw IoError naming @p path (disk full, ...).
void writeVdbFile(const std::filesystem::path& path, const openvdb::GridCPtrVec& grids,
                  const openvdb::MetaMap& fileMetadata = openvdb::MetaMap());

/// Checks the layout of VDB file bytes (header, metadata, grid descriptors and extents)
/// and, when the file carries one, the checksum. @throw std::runtime_error saying what
/// is wrong.
void checkVdbBytes(const std::string& bytes);

/// The first half of reading a VDB file that may be damaged: its bytes are read (at most
/// @p maxBytes) and checked (checkVdbBytes), then @p parse runs in another process (the
/// warm reader, and where it fails a child forked for this file: reader_helper.h) and its
/// answer is returned, for the caller to decode and check.
/// @throw IoError "cannot read PATH: ..." for every failure on the way.
std::string parseVdbInChild(const std::filesystem::path& path, uint64_t maxBytes,
                            PathParser parse);

/// Grids read back from bytes encoded with seekable = false (what a reader process sends
/// back to its parent; the bytes come from OpenVDB's own writer).
openvdb::GridPtrVecPtr decodeStreamedVdb(const std::string& bytes);

}  // namespace globular
