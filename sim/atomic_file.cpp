#include "atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

fs::path temporaryBeside(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    return target.parent_path() / ("." + target.filename().string() + ".tmp" +
                                   std::to_string(::getpid()) + "_" +
                                   std::to_string(counter++));
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
