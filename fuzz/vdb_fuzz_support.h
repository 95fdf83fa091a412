#pragma once
// What the two VDB fuzz targets (vdb_cache_fuzzer, surface_vdb_fuzzer) share.
//
// Input format: one mode byte, then the file. An even mode byte writes the file as it is;
// an odd one first reseals the globular checksum (the file-level string metadata
// "globular_checksum", sim/vdb_archive.h) over the mutated bytes, so a mutation of one
// of our own files gets past checkVdbBytes and reaches OpenVDB in the reader's child
// process instead of ending at "checksum mismatch".
//
// The readers parse with OpenVDB in a forked child (sim/isolated_parse.h). The child is
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
#include <filesystem>
#include <fstream>
#include <string>

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

// ---------------------------------------------------------------------------------------
// The checksum, as sim/vdb_archive.cpp computes it (scanVdbLayout, checksumHex; that file
// keeps them private, so they are copied here).

constexpr const char* kChecksumKey = "globular_checksum";
constexpr std::size_t kChecksumDigits = 16;

/// Where the checksum's hex digits are and where the checksummed bytes begin (the grid
/// count after the file-level metadata); false when the header or the metadata are cut
/// short or there is no checksum entry (then there is nothing to reseal).
inline bool findChecksum(const std::string& bytes, std::size_t& checksumOffset,
                         std::size_t& gridsOffset) {
    std::size_t pos = 0;
    const auto need = [&](uint64_t n) { return n <= bytes.size() - pos; };
    const auto readU32 = [&](uint32_t& v) {
        if (!need(4)) return false;
        std::memcpy(&v, bytes.data() + pos, 4);
        pos += 4;
        return true;
    };
    // magic (8), file version (4), library version (8), has grid offsets (1), UUID (36)
    if (!need(8 + 4 + 8 + 1 + 36)) return false;
    pos += 8 + 4 + 8 + 1 + 36;
    uint32_t count = 0;
    if (!readU32(count) || int32_t(count) < 0) return false;
    checksumOffset = std::string::npos;
    for (uint32_t m = 0; m < count; ++m) {
        uint32_t nameSize = 0, typeSize = 0, valueSize = 0;
        if (!readU32(nameSize) || !need(nameSize)) return false;
        const std::string name = bytes.substr(pos, nameSize);
        pos += nameSize;
        if (!readU32(typeSize) || !need(typeSize)) return false;
        const std::string type = bytes.substr(pos, typeSize);
        pos += typeSize;
        if (!readU32(valueSize) || !need(valueSize)) return false;
        if (name == kChecksumKey && type == "string" && valueSize == kChecksumDigits) {
            checksumOffset = pos;  // the last such entry counts, as in scanVdbLayout
        }
        pos += valueSize;
    }
    gridsOffset = pos;
    return checksumOffset != std::string::npos;
}

/// 64-bit FNV-1a over 8-byte little-endian words, then the tail bytes, as 16 hex digits.
inline std::string checksumHex(const std::string& bytes, std::size_t begin) {
    uint64_t h = 0xcbf29ce484222325ull;
    constexpr uint64_t kPrime = 0x100000001b3ull;
    std::size_t i = begin;
    for (; i + 8 <= bytes.size(); i += 8) {
        uint64_t w;
        std::memcpy(&w, bytes.data() + i, 8);
        h = (h ^ w) * kPrime;
    }
    for (; i < bytes.size(); ++i) h = (h ^ uint8_t(bytes[i])) * kPrime;
    std::string hex(kChecksumDigits, '0');
    for (std::size_t d = 0; d < kChecksumDigits; ++d, h >>= 4) {
        hex[kChecksumDigits - 1 - d] = "0123456789abcdef"[h & 15];
    }
    return hex;
}

/// Rewrites the checksum of @p bytes to match them (nothing when there is none).
inline void resealChecksum(std::string& bytes) {
    std::size_t checksumOffset = 0, gridsOffset = 0;
    if (findChecksum(bytes, checksumOffset, gridsOffset)) {
        bytes.replace(checksumOffset, kChecksumDigits, checksumHex(bytes, gridsOffset));
    }
}

// ---------------------------------------------------------------------------------------

/// The reader takes a path: one file per process under /tmp, reused, removed at exit.
class InputFile {
public:
    explicit InputFile(const char* stem)
        : mPath(std::filesystem::temp_directory_path() /
                (std::string(stem) + "." + std::to_string(::getpid()) + ".vdb")) {}
    ~InputFile() {
        std::error_code ignored;
        std::filesystem::remove(mPath, ignored);
    }
    const std::filesystem::path& path() const { return mPath; }

    /// Writes the file of a fuzz input (mode byte, then the bytes; see above).
    void write(const uint8_t* data, std::size_t size) const {
        std::string bytes;
        bool reseal = false;
        if (size > 0) {
            reseal = (data[0] & 1) != 0;
            bytes.assign(reinterpret_cast<const char*>(data) + 1, size - 1);
        }
        if (reseal) resealChecksum(bytes);
        std::ofstream out(mPath, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), std::streamsize(bytes.size()));
        if (!out) {
            std::perror("vdb fuzzer: cannot write the input file");
            std::abort();
        }
    }

private:
    std::filesystem::path mPath;
};

}  // namespace globular_fuzz
