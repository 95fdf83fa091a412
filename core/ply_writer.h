#pragma once
// The writing half of PLY (ply_reader.h is the other): the header of a binary
// little-endian file from the same element and property descriptions the reader parses,
// for globule clouds (sim/) and meshes (surface/). The rows are the writer's own.

#include <string>
#include <vector>

#include "ply_reader.h"

namespace globular {

/// "ply", "format binary_little_endian 1.0", "comment @p comment", each element with its
/// count and properties ("property float x", "property list uchar int vertex_indices"),
/// then "end_header", each line ending in a newline.
std::string plyHeader(const std::string& comment, const std::vector<PlyElement>& elements);

}  // namespace globular
