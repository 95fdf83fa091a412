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
/// What a request to the helper asks for: a reader forked for one file, or a warm reader.
constexpr uint64_t kForkReader = 0, kStartWarmReader = 1;
/// Where a forked process keeps its socket: where the caller ran with stdin closed, the
/// socket may have been fd 0.
constexpr int kSocket = 3;

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

/// A request's parser and path (after its kind, for the helper). @return false at the
/// socket's end.
bool receiveRequest(int fd, PathParser& parse, std::string& path) {
    uint64_t header[2];  // the parser, the path's length
    if (!receiveAll(fd, header, sizeof header)) return false;
    path.assign(header[1], '\0');
    if (!receiveAll(fd, path.data(), path.size())) return false;
    parse = reinterpret_cast<PathParser>(static_cast<uintptr_t>(header[0]));
    return true;
}

bool sendAnswer(int fd, char status, const std::string& answer) {
    const uint64_t size = answer.size();
    return sendAll(fd, &status, 1) && sendAll(fd, &size, sizeof size) &&
           sendAll(fd, answer.data(), answer.size());
}

/// The warm reader's life: parses one file after another in this one process, each
/// under parseInChild's memory limit, and answers as the helper does. The first parse
/// that fails ends it, so a reader that met a damaged file never reads another. Ends
/// also when the socket closes.
[[noreturn]] void serveWarm(int fd) {
    for (;;) {
        PathParser parse = nullptr;
        std::string path;
        if (!receiveRequest(fd, parse, path)) ::_exit(0);
        const ChildLimits limits = readerLimits(path);
        char status = kAnswered;
        std::string answer;
        limitAddressSpaceGrowth(limits.memoryBytes);
        try {
            answer = parse(path);
        } catch (const std::exception& e) {
            status = kFailed;
            answer = e.what();
        } catch (...) {
            status = kFailed;
        }
        limitAddressSpaceGrowth(0);
        if (!sendAnswer(fd, status, answer) || status != kAnswered) ::_exit(0);
    }
}

/// Sends @p fd (none where negative) and @p value across the socket @p to.
bool sendDescriptor(int to, int fd, int64_t value) {
    msghdr message{};
    iovec data{&value, sizeof value};
    message.msg_iov = &data;
    message.msg_iovlen = 1;
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
    if (fd >= 0) {
        message.msg_control = control;
        message.msg_controllen = sizeof control;
        cmsghdr* c = CMSG_FIRSTHDR(&message);
        c->cmsg_level = SOL_SOCKET;
        c->cmsg_type = SCM_RIGHTS;
        c->cmsg_len = CMSG_LEN(sizeof(int));
        std::memcpy(CMSG_DATA(c), &fd, sizeof fd);
    }
    ssize_t n;
    while ((n = ::sendmsg(to, &message, MSG_NOSIGNAL)) < 0 && errno == EINTR) {
    }
    return n == ssize_t(sizeof value);
}

/// Receives what sendDescriptor sent, waiting until @p deadline. @return the descriptor
/// (close-on-exec), or -1 where none came.
int receiveDescriptor(int from, int64_t& value, std::chrono::steady_clock::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    pollfd p{from, POLLIN, 0};
    if (left <= 0 || ::poll(&p, 1, int(left)) <= 0) return -1;
    msghdr message{};
    iovec data{&value, sizeof value};
    message.msg_iov = &data;
    message.msg_iovlen = 1;
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
    message.msg_control = control;
    message.msg_controllen = sizeof control;
    ssize_t n;
    while ((n = ::recvmsg(from, &message, MSG_CMSG_CLOEXEC)) < 0 && errno == EINTR) {
    }
    if (n != ssize_t(sizeof value)) return -1;
    int fd = -1;
    for (cmsghdr* c = CMSG_FIRSTHDR(&message); c; c = CMSG_NXTHDR(&message, c)) {
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_RIGHTS) {
            std::memcpy(&fd, CMSG_DATA(c), sizeof fd);
        }
    }
    return fd;
}

/// In the helper: forks a warm reader and sends the caller its socket and process id
/// (or -1 and no socket where it could not).
bool startWarmReader(int fd) {
    int pair[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) != 0) {
        return sendDescriptor(fd, -1, -1);
    }
    const pid_t pid = ::fork();
    if (pid == 0) {
        // Its own socket in place of the helper's, which it must not hold open: the
        // caller learns that the helper is gone when that socket closes.
        if (::dup2(pair[1], kSocket) < 0) ::_exit(1);
        if (::close_range(kSocket + 1, ~0u, 0) != 0) {
            for (int other = kSocket + 1; other < 4096; ++other) ::close(other);
        }
        serveWarm(kSocket);
    }
    ::close(pair[1]);
    const bool sent = sendDescriptor(fd, pid > 0 ? pair[0] : -1, pid > 0 ? pid : -1);
    ::close(pair[0]);
    return sent;
}

std::chrono::steady_clock::time_point secondsFromNow(double seconds) {
    return std::chrono::steady_clock::now() + std::chrono::milliseconds(int64_t(seconds * 1000));
}

bool sendRequest(int fd, const fs::path& path, PathParser parse) {
    const std::string name = path.string();
    const uint64_t header[2] = {uint64_t(reinterpret_cast<uintptr_t>(parse)), name.size()};
    return sendAll(fd, header, sizeof header) && sendAll(fd, name.data(), name.size());
}

/// What sendAnswer sent, received by @p deadline.
bool receiveAnswer(int fd, char& status, std::string& answer,
                   std::chrono::steady_clock::time_point deadline) {
    uint64_t size = 0;
    if (!receiveAll(fd, &status, 1, &deadline) || !receiveAll(fd, &size, sizeof size, &deadline)) {
        return false;
    }
    try {
        answer.resize(size);  // a reader fed a hostile file might send any size
    } catch (const std::exception&) {
        return false;
    }
    return receiveAll(fd, answer.data(), size, &deadline);
}

/// The helper's life: one request at a time. A reader forked for one file (the parser,
/// the path) is answered with a status byte, a length and parseInChild's result or
/// message; a warm reader, with its socket. Ends when the socket closes, that is when
/// this program's main process has exited.
[[noreturn]] void serve(int fd) {
    for (;;) {
        // Warm readers that the caller stopped: this helper is their parent.
        while (::waitpid(-1, nullptr, WNOHANG) > 0) {
        }
        uint64_t kind = 0;
        if (!receiveAll(fd, &kind, sizeof kind)) ::_exit(0);
        if (kind == kStartWarmReader) {
            if (!startWarmReader(fd)) ::_exit(0);
            continue;
        }
        PathParser parse = nullptr;
        std::string path;
        if (!receiveRequest(fd, parse, path)) ::_exit(0);
        char status = kAnswered;
        std::string answer;
        try {
            answer = parseInChild(path, [&] { return parse(path); });
        } catch (const std::exception& e) {
            status = kFailed;
            answer = e.what();
        }
        if (!sendAnswer(fd, status, answer)) ::_exit(0);
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
        // The reader's own limit, twice (parseInChild retries once), and a margin for the
        // helper's forks.
        const auto deadline = secondsFromNow(2 * readerSeconds(path) + 10.0);
        const bool ok = sendAll(mFd, &kForkReader, sizeof kForkReader) &&
                        sendRequest(mFd, path, parse) &&
                        receiveAnswer(mFd, status, answer, deadline);
        if (!ok) stop();
        return ok;
    }

    /// A new warm reader's socket and process id, or -1 where the helper could not
    /// start one.
    int startWarm(pid_t& pid) {
        std::lock_guard lock(mMutex);
        if (mFd < 0 && !mGaveUp && !start()) mGaveUp = true;
        if (mFd < 0) return -1;
        int64_t id = -1;
        int fd = -1;
        if (sendAll(mFd, &kStartWarmReader, sizeof kStartWarmReader)) {
            fd = receiveDescriptor(mFd, id, secondsFromNow(10.0));
        }
        if (fd < 0 || id <= 0) {
            if (fd >= 0) ::close(fd);
            stop();
            return -1;
        }
        pid = pid_t(id);
        return fd;
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

/// This process's side of the warm reader: one at a time, started through the helper on
/// first use and after each one that stopped.
class WarmReader {
public:
    /// The reader's answer; false where it gave none (failed, crashed, hung or could not
    /// be started), and then the reader is stopped.
    bool ask(const fs::path& path, PathParser parse, double seconds, std::string& answer) {
        std::lock_guard lock(mMutex);
        if (mFd < 0) mFd = theHelper().startWarm(mPid);
        if (mFd < 0) return false;
        char status = 0;
        const auto deadline = secondsFromNow(seconds > 0 ? seconds : readerSeconds(path));
        const bool ok = sendRequest(mFd, path, parse) &&
                        receiveAnswer(mFd, status, answer, deadline) && status == kAnswered;
        if (!ok) stop();
        return ok;
    }

    ~WarmReader() { stop(); }

private:
    /// The helper, its parent, reaps it.
    void stop() {
        if (mFd < 0) return;
        ::kill(mPid, SIGKILL);
        ::close(mFd);
        mFd = -1;
        mPid = -1;
    }

    std::mutex mMutex;
    int mFd = -1;
    pid_t mPid = -1;
};

WarmReader& theWarmReader() {
    static WarmReader reader;
    return reader;
}

}  // namespace

void startReaderHelper() { theHelper().startIfStopped(); }

std::string parseInWarmReader(const fs::path& path, PathParser parse, double seconds) {
    std::string answer;
    if (theWarmReader().ask(path, parse, seconds, answer)) return answer;
    return parseInHelperChild(path, parse);
}

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
