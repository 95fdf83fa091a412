#include "frame_paths.h"

#include <cstdio>

namespace globular {

std::string frameNumber(int frame) {
    char text[16];
    std::snprintf(text, sizeof text, "%04d", frame);
    return text;
}

std::filesystem::path cacheVdbPath(const std::filesystem::path& outDir, int frame) {
    return outDir / "cache" / ("globules." + frameNumber(frame) + ".vdb");
}
std::filesystem::path cachePlyPath(const std::filesystem::path& outDir, int frame) {
    return outDir / "cache" / ("globules." + frameNumber(frame) + ".ply");
}
std::filesystem::path colliderPosesPath(const std::filesystem::path& outDir, int frame) {
    return outDir / "cache" / ("colliders." + frameNumber(frame) + ".toml");
}
std::filesystem::path surfaceVdbPath(const std::filesystem::path& outDir, int frame) {
    return outDir / "surface" / ("surface." + frameNumber(frame) + ".vdb");
}
std::filesystem::path meshPath(const std::filesystem::path& outDir, int frame,
                               const std::string& extension) {
    return outDir / "mesh" / ("surface." + frameNumber(frame) + "." + extension);
}
std::filesystem::path collidersMeshPath(const std::filesystem::path& outDir, int frame) {
    return outDir / "mesh" / ("colliders." + frameNumber(frame) + ".ply");
}
std::filesystem::path framePngPath(const std::filesystem::path& outDir, int frame) {
    return outDir / "frames" / ("frame." + frameNumber(frame) + ".png");
}

}  // namespace globular
