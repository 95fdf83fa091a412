#pragma once
// Where each stage's per-frame files live in an output directory (DESIGN.md).
// Frames are numbered from 1 (the initial state) and printed with 4 digits.

#include <filesystem>
#include <string>

namespace globular {

std::string frameNumber(int frame);  ///< 7 -> "0007"

std::filesystem::path cacheVdbPath(const std::filesystem::path& outDir, int frame);
std::filesystem::path cachePlyPath(const std::filesystem::path& outDir, int frame);
std::filesystem::path surfaceVdbPath(const std::filesystem::path& outDir, int frame);
/// @param extension "ply" or "obj"
std::filesystem::path meshPath(const std::filesystem::path& outDir, int frame,
                               const std::string& extension);
/// cache/colliders.NNNN.toml: each collider's pose at the frame's time (the sim stage's).
std::filesystem::path colliderPosesPath(const std::filesystem::path& outDir, int frame);
/// mesh/colliders.NNNN.ply: the scene's colliders at the frame's time.
std::filesystem::path collidersMeshPath(const std::filesystem::path& outDir, int frame);
std::filesystem::path framePngPath(const std::filesystem::path& outDir, int frame);

}  // namespace globular
