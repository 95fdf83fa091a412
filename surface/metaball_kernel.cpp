#include "metaball_kernel.h"

#include "errors.h"

namespace globular {

double MetaballKernel::qAtLevel(double level) const {
    if (!(level > 0.0 && level < 1.0)) {
        throw SceneError("iso level " + std::to_string(level) + " must be in (0, 1)");
    }
    switch (type) {
        case KernelType::Blinn: {
            const double a = blinnSharpness, tail = std::exp(-a);
            return -std::log(level * (1.0 - tail) + tail) / a;
        }
        case KernelType::Murakami:
            return 1.0 - std::sqrt(level);
        case KernelType::Wyvill:
            break;
    }
    // The Wyvill cubic falls monotonically on [0, 1]: bisect in double precision, which
    // reaches the float resolution of q long before 60 halvings.
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        const double c = 1.0 + mid * (-22.0 / 9.0 + mid * (17.0 / 9.0 - mid * (4.0 / 9.0)));
        (c > level ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

const std::vector<std::string>& kernelNames() {
    static const std::vector<std::string> names{"wyvill", "blinn", "murakami"};
    return names;
}

KernelType kernelFromName(const std::string& name) {
    const auto& names = kernelNames();
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (names[i] == name) return KernelType(i);
    }
    throw SceneError("unknown metaball kernel '" + name + "' (wyvill, blinn or murakami)");
}

}  // namespace globular
