#include "atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <regex>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

/// ".<name>.globular-tmp-<host>-<pid>-<n>" beside the target: hidden, unmistakably ours,
/// and it tells which process on which host owns it (a farm's nodes may share a folder).
constexpr const char* kTemporaryMarker = ".globular-tmp-";

const std::string& hostName() {
    static const std::string name = [] {
        char buffer[256] = {};
        if (::gethostname(buffer, sizeof buffer - 1) != 0 || buffer[0] == '\0') return std::string("localhost");
        std::string host(buffer);
        for (char& c : host) {
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '_';
        }
        return host;
    }();
    return name;
}

fs::path temporaryBeside(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    return target.parent_path() / ("." + target.filename().string() + kTemporaryMarker +
                                   hostName() + "-" + std::to_string(::getpid()) + "-" +
                                   std::to_string(counter++));
}

/// The owner of a temporary of ours on this host, or 0 when @p name is not one: exactly
/// the pattern temporaryBeside makes, nothing that merely looks like it.
long temporaryOwner(const std::string& name) {
    static const std::regex pattern(R"(^\..+\.globular-tmp-(.+)-([0-9]{1,9})-([0-9]{1,10})$)");
    std::smatch match;
    if (!std::regex_match(name, match, pattern) || match[1] != hostName()) return 0;
    return std::stol(match[2]);
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
    const auto sweep = [&](const fs::path& folder) {
        std::error_code ec;
        for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
            const long owner = temporaryOwner(it->path().filename().string());
            std::error_code typeError;
            if (owner <= 0 || owner == ::getpid() || !it->is_regular_file(typeError)) continue;
            if (::kill(pid_t(owner), 0) == 0 || errno != ESRCH) continue;  // still running
            std::error_code ignored;
            if (fs::remove(it->path(), ignored)) ++removed;
        }
    };
    sweep(dir);
    // The stages' folders (cache/, surface/, mesh/, frames/): one level down, no deeper.
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code typeError;
        if (it->is_directory(typeError) && !it->is_symlink(typeError)) sweep(it->path());
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
