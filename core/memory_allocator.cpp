// The executables' allocator. With GLOBULAR_JEMALLOC they link jemalloc and this file
// hands it its configuration; elsewhere (sanitizer builds, the tests) malloc is libc's.
#include "memory_allocator.h"

#if defined(GLOBULAR_JEMALLOC)
#include <jemalloc/jemalloc.h>

// Read by jemalloc at start-up, before the MALLOC_CONF variable (which still overrides
// it). Transparent huge pages for the heap and jemalloc's own metadata: a surfacing frame
// allocates hundreds of thousands of 2 KiB OpenVDB leaves, and on 4 KiB pages every
// first touch is a page fault (on this project's virtual machines 15 % of the surface
// step's time went to faults); the force loop's grid-order reads miss the TLB less.
// Measured: docs/performance.md, "Second pass: page faults".
const char* malloc_conf = "thp:always,metadata_thp:always";
#endif

namespace globular {

std::string memoryAllocator() {
#if defined(GLOBULAR_JEMALLOC)
    const auto option = [](const char* name) -> std::string {
        const char* value = nullptr;
        std::size_t size = sizeof value;
        if (mallctl(name, &value, &size, nullptr, 0) != 0 || value == nullptr) return "?";
        return value;
    };
    std::string version = option("version");  // "5.3.0-0-g<commit>": the release
    version = version.substr(0, version.find('-'));
    return "jemalloc " + version + " (huge pages: " + option("opt.thp") + ")";
#else
    return "the C library's malloc";
#endif
}

}  // namespace globular
