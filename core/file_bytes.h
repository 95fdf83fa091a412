#pragma once
// Reading a whole input file into memory, bounded: what every reader does first, so
// that a FIFO, a device (/dev/zero) or a huge file is refused before it is read.

#include <cstdint>
#include <filesystem>
#include <string>

namespace globular {

/// The file's bytes. @throw std::runtime_error (without the path: callers add it) when
/// it is missing, not a regular file, larger than @p maxBytes or unreadable.
std::string readFileBytes(const std::filesystem::path& path, uint64_t maxBytes);

}  // namespace globular
