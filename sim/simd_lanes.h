#pragma once
// Lane masks for the AVX-512 loops of the force kernel and the neighbour grid.

#include <cstdint>

#if defined(__AVX512F__)
#include <immintrin.h>

namespace globular {

/// The lanes of a 16-wide step with @p left elements still to go.
inline __mmask16 firstLanes(uint32_t left) {
    return left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1);
}

}  // namespace globular
#endif
