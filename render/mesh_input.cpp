#include "mesh_input.h"

#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

TriangleMesh readSurfaceMesh(const fs::path& path, const std::string& format) {
    if (!fs::exists(path)) {
        throw IoError("missing surface mesh " + path.string() +
                      ": run the surface stage first (globular run SCENE --stages surface), "
                      "or render with [render] mode = \"spheres\"");
    }
    return format == "obj" ? readMeshObj(path) : readMeshPly(path);
}

}  // namespace globular
