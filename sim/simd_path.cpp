#include "simd_path.h"

#include <cstdlib>

#include "errors.h"

namespace globular {

const char* simdPathName(SimdPath path) {
    switch (path) {
        case SimdPath::Scalar: return "scalar";
        case SimdPath::Avx2: return "avx2";
        case SimdPath::Avx512: return "avx512";
    }
    return "?";
}

std::optional<SimdPath> parseSimdPath(const std::string& name) {
    for (SimdPath p : {SimdPath::Scalar, SimdPath::Avx2, SimdPath::Avx512}) {
        if (name == simdPathName(p)) return p;
    }
    return std::nullopt;
}

bool simdPathSupported(SimdPath path) {
    // libgcc's (and compiler-rt's) CPU model also checks that the OS saves the YMM and
    // ZMM registers (XGETBV), not only the CPUID bits.
    __builtin_cpu_init();
    const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    switch (path) {
        case SimdPath::Scalar: return true;
        case SimdPath::Avx2: return avx2;
        case SimdPath::Avx512:
            return avx2 && __builtin_cpu_supports("avx512f") &&
                   __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl") &&
                   __builtin_cpu_supports("avx512dq");
    }
    return false;
}

std::vector<SimdPath> supportedSimdPaths() {
    std::vector<SimdPath> paths;
    for (SimdPath p : {SimdPath::Scalar, SimdPath::Avx2, SimdPath::Avx512}) {
        if (simdPathSupported(p)) paths.push_back(p);
    }
    return paths;
}

std::string supportedSimdPathNames() {
    std::string names;
    for (SimdPath p : supportedSimdPaths()) names += std::string(names.empty() ? "" : ", ") + simdPathName(p);
    return names;
}

SimdPath chooseSimdPath(const char* environmentValue) {
    const std::string value = environmentValue ? environmentValue : "";
    if (value.empty() || value == "auto") return supportedSimdPaths().back();
    const std::optional<SimdPath> path = parseSimdPath(value);
    if (!path) {
        throw Error("GLOBULAR_SIMD=" + quoteForMessage(value) +
                    ": expected auto, scalar, avx2 or avx512");
    }
    if (!simdPathSupported(*path)) {
        throw Error("GLOBULAR_SIMD=" + value + ": this CPU lacks " +
                    (*path == SimdPath::Avx2 ? "AVX2 and FMA" : "AVX-512 (F, BW, VL, DQ)") +
                    "; it runs " + supportedSimdPathNames());
    }
    return *path;
}

SimdPath activeSimdPath() {
    static const SimdPath path = chooseSimdPath(std::getenv("GLOBULAR_SIMD"));
    return path;
}

}  // namespace globular
