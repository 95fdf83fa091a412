#pragma once
// Which build of the force kernels runs: the same sources (force_kernels.cpp and the
// neighbour grid) are compiled once per instruction set (sim/CMakeLists.txt) and one is
// picked at start-up from the CPU, so one binary runs on every node of a farm. The
// environment variable GLOBULAR_SIMD (auto, scalar, avx2, avx512) forces a path, for
// tests and benchmarks. Each path gives bit-identical results for any thread count; the
// paths agree with each other to single-precision rounding, not bit for bit.

#include <optional>
#include <string>
#include <vector>

namespace globular {

enum class SimdPath {
    Scalar,  ///< baseline x86-64 (SSE2): plain loops
    Avx2,    ///< AVX2 and FMA: the hand-written 8-lane kernels
    Avx512,  ///< AVX-512 F, BW, VL, DQ: the hand-written 16-lane kernels
};

/// "scalar", "avx2" or "avx512".
const char* simdPathName(SimdPath path);

/// The path called @p name (simdPathName), or none.
std::optional<SimdPath> parseSimdPath(const std::string& name);

/// Whether this CPU (and its operating system, for AVX-512's registers) runs @p path.
bool simdPathSupported(SimdPath path);

/// The paths this CPU runs, slowest first.
std::vector<SimdPath> supportedSimdPaths();

/// Their names, "scalar, avx2, avx512" (for messages and the run's log).
std::string supportedSimdPathNames();

/// The path for a GLOBULAR_SIMD value (null or "auto": the fastest this CPU runs).
/// @throw Error naming the variable and value when it names no path or one this CPU
///        lacks.
SimdPath chooseSimdPath(const char* environmentValue);

/// chooseSimdPath(getenv("GLOBULAR_SIMD")), decided on the first call and kept: the
/// path every ForceField starts with.
SimdPath activeSimdPath();

}  // namespace globular
