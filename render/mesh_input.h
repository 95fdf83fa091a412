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

/// Wavefront OBJ: v and vn lines, f lines of v, v//vn, v/vt or v/vt/vn (indices from 1 or
/// negative from the end), polygons split into fans. Normals are used when there is one
/// per vertex, as the surface stage writes them; otherwise computed from the faces.
/// @throw IoError naming @p path and the line at fault.
TriangleMesh readMeshObj(const std::filesystem::path& path);

}  // namespace globular
