#include "movie.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include "atomic_file.h"
#include "errors.h"
#include "frame_paths.h"

extern char** environ;

namespace globular {

namespace fs = std::filesystem;

fs::path findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (!path) return {};
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
        if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) {
            return candidate;
        }
    }
    return {};
}

void assembleMovie(const fs::path& ffmpeg, const fs::path& outDir, int firstFrame, int lastFrame,
                   double fps) {
    const fs::path pattern = outDir / "frames" / "frame.%04d.png";
    writeAtomically(outDir / "movie.mp4", [&](const fs::path& temporary) {
        // posix_spawn with an argument vector: no shell, so no quoting of paths.
        std::vector<std::string> args = {
            ffmpeg.string(), "-hide_banner", "-loglevel", "error", "-y", "-framerate",
            std::to_string(fps), "-start_number", std::to_string(firstFrame), "-i",
            pattern.string(), "-frames:v", std::to_string(lastFrame - firstFrame + 1),
            // H.264 in yuv420p needs even sizes; pad by a pixel rather than fail.
            "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p",
            "-crf", "18", "-movflags", "+faststart", "-f", "mp4", temporary.string()};
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        pid_t pid = 0;
        const int spawned =
            ::posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ);
        if (spawned != 0) {
            throw IoError("cannot run " + ffmpeg.string() + ": " + std::strerror(spawned));
        }
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0) {
            if (errno != EINTR)
                throw IoError("cannot wait for ffmpeg: " + std::string(std::strerror(errno)));
        }
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            throw IoError("ffmpeg failed (status " +
                          std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                          ") encoding " + pattern.string());
        }
    });
}

}  // namespace globular
