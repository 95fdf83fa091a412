// libFuzzer target for the files a scene's colliders bring in: a collider poses file
// (cache/colliders.NNNN.toml, sim/collider_poses.h), read against a two-collider scene,
// and a mesh collider's OBJ file (readMeshObj, core/mesh.h).
//
// Input: a mode byte (even: poses file, odd: OBJ), then the file. An IoError (or a
// SceneError) is the expected answer to a bad file; anything else (a sanitizer report,
// another exception, a crash) is a bug. A poses file that reads gives one rotation per
// collider, each a rotation; a mesh that reads has indices within its vertices.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "collider_poses.h"
#include "errors.h"
#include "fuzz_input.h"
#include "mesh.h"

namespace {

const globular_fuzz::InputFile gPoses("globular_poses_fuzz", ".toml");
const globular_fuzz::InputFile gMesh("globular_obj_fuzz", ".obj");

std::vector<globular::ColliderSettings> twoColliders() {
    globular::ColliderSettings ball, wall;
    ball.name = "ball";
    ball.shape = "sphere";
    wall.name = "wall";
    wall.shape = "plane";
    return {ball, wall};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string bytes = globular_fuzz::bytesOf(data + 1, size - 1);
    try {
        if (data[0] % 2 == 0) {
            gPoses.write(bytes);
            const auto poses = globular::readColliderPoses(gPoses.path(), twoColliders());
            if (poses.size() != 2) std::abort();
            for (const auto& pose : poses) {
                for (const auto& row : pose.rotation) {
                    const double norm = row[0] * row[0] + row[1] * row[1] + row[2] * row[2];
                    if (!(std::abs(norm - 1) < 1e-5)) std::abort();
                }
            }
        } else {
            gMesh.write(bytes);
            const globular::TriangleMesh mesh = globular::readMeshObj(gMesh.path());
            if (mesh.normals.size() != mesh.positions.size()) std::abort();
            for (uint32_t index : mesh.triangles) {
                if (index >= mesh.vertexCount()) std::abort();
            }
        }
    } catch (const globular::Error&) {
    }
    return 0;
}
