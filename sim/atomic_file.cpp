#include "atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTemporaryMarker = ".tmp";

/// ".<name>.tmp<pid>_<n>" beside the target: hidden, and tells which process owns it.
fs::path temporaryBeside(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    return target.parent_path() / ("." + target.filename().string() + kTemporaryMarker +
                                   std::to_string(::getpid()) + "_" +
                                   std::to_string(counter++));
}

/// The owning process id of a temporary's file name, or 0 when it is not one.
long temporaryOwner(const std::string& name) {
    if (name.empty() || name[0] != '.') return 0;
    const auto marker = name.rfind(kTemporaryMarker);
    const auto underscore = name.rfind('_');
    if (marker == std::string::npos || underscore == std::string::npos || underscore < marker) {
        return 0;
    }
    const std::string pid = name.substr(marker + 4, underscore - marker - 4);
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) return 0;
    return std::stol(pid);
}

void syncToDisk(const fs::path& file) {
    int fd = ::open(file.c_str(), O_RDONLY);
    if (fd < 0) throw IoError("cannot reopen " + file.string() + ": " + std::strerror(errno));
    int rc = ::fsync(fd);
    int err = errno;
    ::close(fd);
    if (rc != 0) throw IoError("cannot flush " + file.string() + ": " + std::strerror(err));
}

}  // namespace

std::size_t removeStaleTemporaries(const fs::path& dir) {
    std::size_t removed = 0;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const long owner = temporaryOwner(it->path().filename().string());
        if (owner <= 0 || !it->is_regular_file()) continue;
        if (::kill(pid_t(owner), 0) == 0 || errno != ESRCH) continue;  // owner still running
        std::error_code ignored;
        if (fs::remove(it->path(), ignored)) ++removed;
    }
    return removed;
}

void ensureWritableDirectory(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw IoError("cannot create directory " + dir.string() + ": " + ec.message());
    if (!fs::is_directory(dir)) throw IoError(dir.string() + " is not a directory");
    if (::access(dir.c_str(), W_OK) != 0) {
        throw IoError("directory " + dir.string() + " is not writable: " +
                      std::strerror(errno));
    }
}

void writeAtomically(const fs::path& target,
                     const std::function<void(const fs::path&)>& write) {
    if (target.has_parent_path()) ensureWritableDirectory(target.parent_path());
    const fs::path temporary = temporaryBeside(target);
    try {
        write(temporary);
        if (!fs::exists(temporary)) throw IoError("nothing was written");
        syncToDisk(temporary);
        std::error_code ec;
        fs::rename(temporary, target, ec);
        if (ec) throw IoError("cannot rename into place: " + ec.message());
    } catch (const std::exception& e) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw IoError("cannot write " + target.string() + ": " + e.what());
    }
}

void writeFileAtomically(const fs::path& target, const std::string& contents) {
    writeAtomically(target, [&](const fs::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        if (!out) throw IoError(std::strerror(errno));
        out.write(contents.data(), std::streamsize(contents.size()));
        out.flush();
        if (!out) throw IoError(std::string("write failed: ") + std::strerror(errno));
    });
}

}  // namespace globular
