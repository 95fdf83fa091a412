#pragma once
// The scalar types a PLY header may name, shared by the PLY reader and writer
// (ply_reader.h, ply_writer.h).

#include <cstddef>
#include <string_view>

namespace globular {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64, None };

/// The type a PLY header names ("uchar", "float32", ...), or None when it names none.
PlyType plyTypeNamed(std::string_view name);
/// The name a header gives @p type ("uchar", "float", ...; "" for None).
std::string_view plyTypeName(PlyType type);
/// Bytes of one binary value; 0 for None.
std::size_t plyTypeSize(PlyType type);

}  // namespace globular
