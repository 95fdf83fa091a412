#include "output_lock.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

/// "globular run scene.toml --out x" for a process id, or "" when it cannot be read.
std::string commandLineOf(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/cmdline", std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (char& c : text) {
        if (c == '\0') c = ' ';
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.size() > 200 ? text.substr(0, 200) + "..." : text;
}

}  // namespace

OutputLock::OutputLock(const fs::path& dir, Mode mode) {
    const fs::path path = dir / ".globular.lock";
    mFd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (mFd < 0) {
        throw IoError("cannot lock output folder " + dir.string() + ": cannot open " +
                      path.string() + ": " + std::strerror(errno));
    }
    struct flock lock {};
    lock.l_type = mode == Mode::Exclusive ? F_WRLCK : F_RDLCK;
    lock.l_whence = SEEK_SET;
    if (::fcntl(mFd, F_SETLK, &lock) == 0) return;
    const int err = errno;
    struct flock holder = lock;
    const bool known = ::fcntl(mFd, F_GETLK, &holder) == 0 && holder.l_type != F_UNLCK;
    ::close(mFd);
    mFd = -1;
    if (err != EACCES && err != EAGAIN) {
        throw IoError("cannot lock output folder " + dir.string() + ": " + std::strerror(err));
    }
    std::string who = "another process";
    if (known && holder.l_pid > 0) {
        const std::string command = commandLineOf(holder.l_pid);
        who = "process " + std::to_string(holder.l_pid) +
              (command.empty() ? "" : " (" + command + ")");
    }
    throw IoError("output folder " + dir.string() + " is in use by " + who +
                  (mode == Mode::Exclusive ? "" : ", which is simulating into it") +
                  "; wait for it to finish, or give another --out");
}

OutputLock::~OutputLock() {
    if (mFd >= 0) ::close(mFd);  // closing drops the lock
}

}  // namespace globular
