#pragma once
// What the two VDB fuzz targets (vdb_cache_fuzzer, surface_vdb_fuzzer) share.
//
// Input format: one mode byte, then the file. An even mode byte writes the file as it is;
// an odd one first reseals the globular checksum (sealVdbChecksum, core/vdb_archive.h)
// over the mutated bytes, so a mutation of one of our own files gets past checkVdbBytes
// and reaches OpenVDB in the reader's child process instead of ending at "checksum
// mismatch".
//
// The readers parse with OpenVDB in a forked child (core/isolated_parse.h). The child is
// a copy of this process, libFuzzer and the sanitizers included: left alone, a crash
// there (expected: OpenVDB trusts its input) would run libFuzzer's deadly-signal and
// death callbacks in the child, which write crash-*/oom-*/timeout-* artifacts of the
// current input although the parent turns the crash into an IoError, as it should.
// installChildGuard() registers a fork handler that, in the child only:
//   - clears the sanitizer death callback (libFuzzer's), so a sanitizer report in the
//     child (printed to the child's stderr, /dev/null unless GLOBULAR_CHILD_STDERR is
//     set) ends the child with ASan's exit code, no artifact;
//   - restores the default action of the signals libFuzzer catches, so an abort or a
//     fault in the child kills it by that signal, as in a normal build (with
//     GLOBULAR_CHILD_STDERR set, SIGSEGV/SIGBUS/SIGFPE stay with the sanitizer, whose
//     report then shows where the child crashed);
//   - limits the child's address space to what it has plus 1 GiB (below libFuzzer's
//     -malloc_limit_mb, 2048 in CI): under ASan the library sets no limit, and a hostile
//     size field must not take the machine's memory;
//   - kills the child with SIGALRM after kChildSeconds, well inside libFuzzer's -timeout
//     (25 s in CI), where the library would wait 60 s: a file that makes OpenVDB loop is
//     an IoError ("its reader crashed (SIGALRM)"), not a libFuzzer timeout.
// fork() is called by the library only, so only the readers' children are affected.

#include <fcntl.h>
#include <pthread.h>
#include <sanitizer/common_interface_defs.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "fuzz_input.h"
#include "vdb_archive.h"

namespace globular_fuzz {

/// Wall time a reader's child may take before it is killed.
constexpr unsigned kChildSeconds = 5;
/// Address space a reader's child may add.
constexpr uint64_t kChildMemoryBytes = uint64_t(1) << 30;

/// Virtual memory size of this process, without allocating (it runs after fork).
inline uint64_t addressSpaceInUse() {
    const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
    if (fd < 0) return 0;
    char buffer[64];
    const ssize_t n = ::read(fd, buffer, sizeof buffer - 1);
    ::close(fd);
    if (n <= 0) return 0;
    uint64_t pages = 0;
    for (ssize_t i = 0; i < n && buffer[i] >= '0' && buffer[i] <= '9'; ++i) {
        pages = pages * 10 + uint64_t(buffer[i] - '0');
    }
    return pages * uint64_t(::sysconf(_SC_PAGE_SIZE));
}

inline void defaultAction(int signal) {
    struct sigaction action;
    std::memset(&action, 0, sizeof action);
    action.sa_handler = SIG_DFL;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal, &action, nullptr);
}

inline void inForkedChild() {
    __sanitizer_set_death_callback(nullptr);
    for (int signal :
         {SIGABRT, SIGILL, SIGTRAP, SIGSYS, SIGINT, SIGTERM, SIGXFSZ, SIGUSR1, SIGUSR2, SIGALRM}) {
        defaultAction(signal);
    }
    if (!std::getenv("GLOBULAR_CHILD_STDERR")) {
        for (int signal : {SIGSEGV, SIGBUS, SIGFPE}) defaultAction(signal);
    }
    if (const uint64_t inUse = addressSpaceInUse(); inUse > 0) {
        const rlimit limit{rlim_t(inUse + kChildMemoryBytes), rlim_t(inUse + kChildMemoryBytes)};
        ::setrlimit(RLIMIT_AS, &limit);
    }
    ::alarm(kChildSeconds);
}

inline void installChildGuard() {
    if (::pthread_atfork(nullptr, nullptr, inForkedChild) != 0) {
        std::fprintf(stderr, "vdb fuzzer: pthread_atfork failed\n");
        std::abort();
    }
}

/// The file of a VDB target's input (fuzz_input.h), its checksum forged when the mode
/// byte says so (nothing to forge when the layout is too broken to find it).
inline std::string vdbFile(const uint8_t* data, std::size_t size) {
    ModedInput input = splitMode(data, size);
    if (input.forgeChecksum) {
        try {
            globular::sealVdbChecksum(input.file);
        } catch (const std::exception&) {
        }
    }
    return input.file;
}

}  // namespace globular_fuzz
