#pragma once
// movie.mp4 from the rendered frames, through the ffmpeg command when it is installed.

#include <filesystem>
#include <string>

namespace globular {

/// The full path of @p program found on PATH, or empty when it is not there.
std::filesystem::path findOnPath(const std::string& program);

/// Encodes frames/frame.NNNN.png of @p outDir, frames @p firstFrame to @p lastFrame, at
/// @p fps into @p outDir / "movie.mp4" (H.264, yuv420p, so every player opens it),
/// atomically. @p ffmpeg is the program to run (see findOnPath).
/// @throw IoError with ffmpeg's exit status when it fails.
void assembleMovie(const std::filesystem::path& ffmpeg, const std::filesystem::path& outDir,
                   int firstFrame, int lastFrame, double fps);

}  // namespace globular
