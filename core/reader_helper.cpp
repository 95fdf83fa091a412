#include "reader_helper.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "errors.h"
#include "isolated_parse.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

constexpr char kAnswered = 'O', kFailed = 'E';

bool sendAll(int fd, const void* data, std::size_t size) {
    const char* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::send(fd, bytes, size, MSG_NOSIGNAL);  // EPIPE, not SIGPIPE
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        bytes += n;
        size -= std::size_t(n);
    }
    return true;
}

/// Reads exactly @p size bytes, giving up at @p deadline (none: wait as long as it takes).
bool receiveAll(int fd, void* data, std::size_t size,
                const std::chrono::steady_clock::time_point* deadline = nullptr) {
    char* bytes = static_cast<char*>(data);
    while (size > 0) {
        if (deadline) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                                  *deadline - std::chrono::steady_clock::now())
                                  .count();
            if (left <= 0) return false;
            pollfd p{fd, POLLIN, 0};
            const int ready = ::poll(&p, 1, int(std::min<int64_t>(left, 1000)));
            if (ready < 0 && errno != EINTR) return false;
            if (ready <= 0) continue;
        }
        const ssize_t n = ::recv(fd, bytes, size, 0);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        bytes += n;
        size -= std::size_t(n);
    }
    return true;
}

/// The helper's life: one request at a time (the parser, the path), answered with a
/// status byte, a length and parseInChild's result or message. Ends when the socket
/// closes, that is when this program's main process has exited.
[[noreturn]] void serve(int fd) {
    for (;;) {
        uint64_t header[2];  // the parser, the path's length
        if (!receiveAll(fd, header, sizeof header)) ::_exit(0);
        std::string path(header[1], '\0');
        if (!receiveAll(fd, path.data(), path.size())) ::_exit(0);
        const auto parse = reinterpret_cast<PathParser>(static_cast<uintptr_t>(header[0]));
        char status = kAnswered;
        std::string answer;
        try {
            answer = parseInChild(path, [&] { return parse(path); });
        } catch (const std::exception& e) {
            status = kFailed;
            answer = e.what();
        }
        const uint64_t size = answer.size();
        if (!sendAll(fd, &status, 1) || !sendAll(fd, &size, sizeof size) ||
            !sendAll(fd, answer.data(), answer.size())) {
            ::_exit(0);
        }
    }
}

/// The helper process, started by startReaderHelper or on first use.
class ReaderHelper {
public:
    /// Forks the helper where none runs; where that fails, ask forks the readers here.
    void startIfStopped() {
        std::lock_guard lock(mMutex);
        if (mFd < 0 && !start()) mGaveUp = true;
    }

    /// The answer of the helper's reader, or false where the helper could not give one
    /// (then it is gone, and later calls fork their readers themselves).
    bool ask(const fs::path& path, PathParser parse, char& status, std::string& answer) {
        std::lock_guard lock(mMutex);
        if (mFd < 0 && !mGaveUp && !start()) mGaveUp = true;
        if (mFd < 0) return false;
        const std::string name = path.string();
        const uint64_t header[2] = {uint64_t(reinterpret_cast<uintptr_t>(parse)), name.size()};
        // The reader's own limit, twice (parseInChild retries once), and a margin for the
        // helper's forks.
        const double seconds = 2 * readerSeconds(path) + 10.0;
        const auto deadline = std::chrono::steady_clock::now() +
                              std::chrono::milliseconds(int64_t(seconds * 1000));
        uint64_t size = 0;
        bool ok = sendAll(mFd, header, sizeof header) && sendAll(mFd, name.data(), name.size()) &&
                  receiveAll(mFd, &status, 1, &deadline) &&
                  receiveAll(mFd, &size, sizeof size, &deadline);
        if (ok) {
            answer.assign(size, '\0');
            ok = receiveAll(mFd, answer.data(), size, &deadline);
        }
        if (!ok) stop();
        return ok;
    }

    ~ReaderHelper() { stop(); }

private:
    bool start() {
        int fds[2];
        if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) return false;
        const pid_t pid = ::fork();
        if (pid < 0) {
            ::close(fds[0]);
            ::close(fds[1]);
            return false;
        }
        if (pid == 0) {
            // Nothing of the main process's but the socket: no output lock, no pipe a
            // caller waits on, no terminal input. Ctrl-C is the main process's to handle
            // (it stops cleanly and closes the socket, which ends the helper).
            ::signal(SIGINT, SIG_IGN);
            // The socket first: where the caller ran with stdin closed, it may be fd 0.
            constexpr int kSocket = 3;
            if (::dup2(fds[1], kSocket) < 0) ::_exit(1);
            const int null = ::open("/dev/null", O_RDWR);
            if (null >= 0) {
                ::dup2(null, STDIN_FILENO);
                ::dup2(null, STDOUT_FILENO);
                if (!std::getenv("GLOBULAR_CHILD_STDERR")) ::dup2(null, STDERR_FILENO);
            }
            if (::close_range(kSocket + 1, ~0u, 0) != 0) {
                for (int fd = kSocket + 1; fd < 4096; ++fd) ::close(fd);
            }
            serve(kSocket);
        }
        ::close(fds[1]);
        mFd = fds[0];
        mPid = pid;
        return true;
    }

    void stop() {
        if (mFd < 0) return;
        ::close(mFd);
        ::kill(mPid, SIGKILL);
        while (::waitpid(mPid, nullptr, 0) < 0 && errno == EINTR) {
        }
        mFd = -1;
        mPid = -1;
    }

    std::mutex mMutex;
    int mFd = -1;
    pid_t mPid = -1;
    bool mGaveUp = false;
};

ReaderHelper& theHelper() {
    static ReaderHelper helper;
    return helper;
}

}  // namespace

void startReaderHelper() { theHelper().startIfStopped(); }

std::string parseInHelperChild(const fs::path& path, PathParser parse) {
    char status = 0;
    std::string answer;
    if (!theHelper().ask(path, parse, status, answer)) {
        return parseInChild(path, [&] { return parse(path); });
    }
    if (status != kAnswered) throw IoError(answer);  // parseInChild's own message
    return answer;
}

}  // namespace globular
