#include "pair_force.h"

#include "material.h"

namespace globular {

PairForce PairForce::fromMaterial(const ForceConstants& material) {
    PairForce f;
    f.b1 = float(material.b1);
    f.b2 = float(material.b1 * std::pow(material.r0, material.n - material.m));
    f.m = float(material.m);
    f.n = float(material.n);
    f.cr = float(material.resolvedCr());
    f.cd = float(material.resolvedCd());
    f.integerExponents = material.m == std::floor(material.m) &&
                         material.n == std::floor(material.n) && material.m <= 64 &&
                         material.n <= 64;
    f.mInt = int(material.m);
    f.nInt = int(material.n);
    return f;
}

}  // namespace globular
