#pragma once
// Parsing a file that anyone may have damaged, in a child process. OpenVDB trusts its
// input: a damaged file can make it fault, abort inside the allocator or loop, and no
// amount of checking before it reads can cover every byte. So the parse runs in a forked
// child; a crash, a timeout or a memory limit there becomes an IoError naming the file,
// and the run goes on or stops cleanly.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace globular {

struct ChildLimits {
    double seconds = 0;        ///< wall time; 0 = readerSeconds(path)
    uint64_t memoryBytes = 0;  ///< address space the child may add; 0 = 64 times the
                               ///< file's size (at least 256 MiB, at most half of RAM)
};

/// The wall-time limit of a reader of @p path: 20 s plus 1 s per 10 MB of the file.
double readerSeconds(const std::filesystem::path& path);

/// @p limits with each 0 replaced by its default for a reader of @p path.
ChildLimits readerLimits(const std::filesystem::path& path, ChildLimits limits = {});

/// False in a build with AddressSanitizer, which reserves terabytes of shadow: there no
/// reader's address space is limited.
bool addressSpaceCanBeLimited();

/// Lets this process's address space grow by at most @p bytes from now on (RLIMIT_AS's
/// soft limit; 0, or a build with AddressSanitizer, which reserves terabytes of shadow:
/// no limit), so that a hostile size field fails as bad_alloc instead of taking the
/// machine's memory. The hard limit is left as it was, so a later call may raise it.
void limitAddressSpaceGrowth(uint64_t bytes);

/// Runs @p parse in a forked child and @return the bytes it returned. The child is a copy
/// of this process with only the calling thread: @p parse must not use TBB or start
/// threads. What it returns must be re-validated by the caller like any input.
/// @throw IoError "cannot read PATH: ..." with the message of an exception @p parse threw,
///        or saying that the reader crashed (and with which signal), ran out of time twice
///        (a hung child is retried once), ran out of memory, or could not be started.
std::string parseInChild(const std::filesystem::path& path,
                         const std::function<std::string()>& parse, ChildLimits limits = {});

}  // namespace globular
