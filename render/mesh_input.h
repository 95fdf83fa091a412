#pragma once
// The surfacing stage's mesh of one frame, in the format the scene chose.

#include <filesystem>
#include <string>

#include "mesh.h"

namespace globular {

/// Reads mesh/surface.NNNN.<format> as written by the surface stage.
/// @param format "ply" (surface/mesh.h's reader) or "obj".
/// @throw IoError naming the file (and, when it is missing, the stage to run first).
TriangleMesh readSurfaceMesh(const std::filesystem::path& path, const std::string& format);

}  // namespace globular
