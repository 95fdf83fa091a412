#include "isolated_parse.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>

#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;  // gcc
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;  // clang
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

constexpr char kAnswered = 'O', kFailed = 'E';
constexpr uint64_t kMinChildMemory = uint64_t(256) << 20;

void writeAll(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;  // the parent gave up on us
        data += n;
        size -= std::size_t(n);
    }
}

uint64_t addressSpaceInUse() {
    std::ifstream statm("/proc/self/statm");
    uint64_t pages = 0;
    statm >> pages;
    return pages * uint64_t(::sysconf(_SC_PAGE_SIZE));
}

uint64_t halfOfPhysicalMemory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) / 2 : 0;
}

[[noreturn]] void runChild(int fd, const std::function<std::string()>& parse,
                           uint64_t memoryBytes) {
    // What a damaged file makes a library print (or the allocator, as it aborts) is noise
    // to the user: the parent names the file and the failure.
    if (!std::getenv("GLOBULAR_CHILD_STDERR")) {
        const int null = ::open("/dev/null", O_WRONLY);
        if (null >= 0) ::dup2(null, STDERR_FILENO);
    }
    limitAddressSpaceGrowth(memoryBytes);
    std::string answer;
    char status = kAnswered;
    try {
        answer = parse();
    } catch (const std::bad_alloc&) {
        status = kFailed;
        answer = "the file asks for more than " + std::to_string(memoryBytes >> 20) +
                 " MiB of memory (damaged?)";
    } catch (const std::exception& e) {
        status = kFailed;
        answer = e.what();
    } catch (...) {
        status = kFailed;
        answer = "unknown error";
    }
    writeAll(fd, &status, 1);
    writeAll(fd, answer.data(), answer.size());
    ::_exit(0);  // no atexit handlers, no flushing of the parent's buffers
}

/// One child: forks, collects its answer until @p seconds have passed. @return false when
/// it ran out of time (it is killed and reaped); otherwise its wait status in @p status.
bool runOnce(const fs::path& path, const std::function<std::string()>& parse,
             const ChildLimits& limits, std::string& received, int& status) {
    const auto fail = [&](const std::string& what) {
        return IoError("cannot read " + path.string() + ": " + what);
    };
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
        throw fail(std::string("cannot open a pipe to a reader process: ") + std::strerror(errno));
    }
    const pid_t pid = ::fork();
    if (pid < 0) {
        const int err = errno;
        ::close(fds[0]);
        ::close(fds[1]);
        throw fail(std::string("cannot start a reader process: ") + std::strerror(err));
    }
    if (pid == 0) {
        ::close(fds[0]);
        runChild(fds[1], parse, limits.memoryBytes);
    }
    ::close(fds[1]);

    bool timedOut = false;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::milliseconds(int64_t(limits.seconds * 1000));
    char buffer[1 << 16];
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                              deadline - std::chrono::steady_clock::now())
                              .count();
        if (left <= 0) {
            timedOut = true;
            break;
        }
        pollfd p{fds[0], POLLIN, 0};
        const int ready = ::poll(&p, 1, int(std::min<int64_t>(left, 1000)));
        if (ready < 0 && errno != EINTR) break;
        if (ready <= 0) continue;
        const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;  // end of the answer
        received.append(buffer, std::size_t(n));
    }
    ::close(fds[0]);
    if (timedOut) ::kill(pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return !timedOut;
}

}  // namespace

double readerSeconds(const fs::path& path) {
    std::error_code ec;
    const uint64_t size = fs::file_size(path, ec);
    return 20.0 + (ec ? 0.0 : double(size) / 10e6);
}

ChildLimits readerLimits(const fs::path& path, ChildLimits limits) {
    if (limits.seconds <= 0) limits.seconds = readerSeconds(path);
    if (limits.memoryBytes == 0) {
        // Decompressed data may be far larger than the file, but not beyond reason: a
        // damaged size field then fails fast instead of touching gigabytes.
        std::error_code ec;
        const uint64_t size = fs::file_size(path, ec);
        const uint64_t byFile = std::max<uint64_t>(kMinChildMemory, ec ? 0 : size * 64);
        const uint64_t half = halfOfPhysicalMemory();
        limits.memoryBytes = half > 0 ? std::min(byFile, half) : byFile;
    }
    return limits;
}

bool addressSpaceCanBeLimited() { return !kAddressSanitizer; }

void limitAddressSpaceGrowth(uint64_t bytes) {
    rlimit r{};
    if (kAddressSanitizer || ::getrlimit(RLIMIT_AS, &r) != 0) return;
    r.rlim_cur = bytes > 0 ? rlim_t(addressSpaceInUse() + bytes) : r.rlim_max;
    if (r.rlim_max != RLIM_INFINITY && r.rlim_cur > r.rlim_max) r.rlim_cur = r.rlim_max;
    ::setrlimit(RLIMIT_AS, &r);
}

std::string parseInChild(const fs::path& path, const std::function<std::string()>& parse,
                         ChildLimits limits) {
    const auto fail = [&](const std::string& what) {
        return IoError("cannot read " + path.string() + ": " + what);
    };
    limits = readerLimits(path, limits);

    // A reader that hangs gets one more try: the child of a process with other threads
    // can start with a lock held by a thread it does not have (fork copies only the
    // caller), a hazard of the moment of the fork that a second fork does not share.
    // A file that makes the reader loop times out twice.
    std::string received;
    int status = 0;
    bool answered = false;
    for (int attempt = 0; attempt < 2 && !answered; ++attempt) {
        received.clear();
        answered = runOnce(path, parse, limits, received, status);
    }
    if (!answered) {
        throw fail("reading took longer than " + std::to_string(int(limits.seconds)) +
                   " s, twice (a damaged file can make the reader loop)");
    }
    if (WIFSIGNALED(status)) {
        const int sig = WTERMSIG(status);
        throw fail(std::string("the file is damaged: its reader crashed (") +
                   (sigabbrev_np(sig) ? std::string("SIG") + sigabbrev_np(sig)
                                      : "signal " + std::to_string(sig)) +
                   ")");
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || received.empty()) {
        throw fail("the file is damaged: its reader failed (exit status " +
                   std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
    }
    // The message may quote the damaged file's bytes.
    if (received[0] == kFailed) throw fail(quoteForMessage(received.substr(1), 300));
    if (received[0] != kAnswered) throw fail("the reader process answered nonsense");
    received.erase(0, 1);
    return received;
}

}  // namespace globular
