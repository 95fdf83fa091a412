#pragma once
// What every file-reading fuzz target shares: the readers take a path, so each input is
// written to one file per process under /tmp (reused, removed at exit); the first byte
// of some targets' inputs selects a mode; GLOBULAR_FUZZ_VERBOSE=1 says what each input
// read as (to triage a corpus); and an inconsistent result aborts with a message.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace globular_fuzz {

/// The input file. The path lives in the object whose destructor removes the file, so it
/// is still there when that runs (a function-local static would be destroyed first).
class InputFile {
public:
    InputFile(const std::string& stem, const std::string& extension)
        : mPath(std::filesystem::temp_directory_path() /
                (stem + "." + std::to_string(::getpid()) + extension)) {}
    ~InputFile() {
        std::error_code ignored;
        std::filesystem::remove(mPath, ignored);
    }
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    const std::filesystem::path& path() const { return mPath; }

    void write(const std::string& bytes) const {
        std::ofstream out(mPath, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), std::streamsize(bytes.size()));
        if (!out) {
            std::perror("fuzzer: cannot write the input file");
            std::abort();
        }
    }

private:
    std::filesystem::path mPath;
};

inline std::string bytesOf(const uint8_t* data, std::size_t size) {
    return std::string(reinterpret_cast<const char*>(data), size);
}

/// An input of a moded target: the first byte, odd to forge the file's checksum after the
/// mutation (so mutated bytes get past it), then the file.
struct ModedInput {
    bool forgeChecksum = false;
    std::string file;
};

inline ModedInput splitMode(const uint8_t* data, std::size_t size) {
    if (size == 0) return {};
    return {(data[0] & 1) != 0, bytesOf(data + 1, size - 1)};
}

inline bool verbose() {
    static const bool on = std::getenv("GLOBULAR_FUZZ_VERBOSE") != nullptr;
    return on;
}

[[noreturn]] inline void inconsistent(const char* target, const char* what) {
    std::fprintf(stderr, "%s: the reader returned %s\n", target, what);
    std::abort();
}

}  // namespace globular_fuzz
