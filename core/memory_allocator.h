#pragma once
// Which allocator serves the executables' memory (README, "Memory allocator").

#include <string>

namespace globular {

/// The allocator behind malloc and new in this process and how it is configured, for
/// `globular --version` and the benchmarks' headers: "jemalloc 5.3.0 (huge pages:
/// always)", or "the C library's malloc" in builds without jemalloc (sanitizers).
std::string memoryAllocator();

}  // namespace globular
