#pragma once
// Metaball ("blobby") kernels: the field one globule adds at a point, as a function of
// q = r^2 / R^2, where r is the distance to the globule's centre and R its influence
// radius (a multiple of the globule radius). Every kernel is 1 at the centre, falls
// monotonically and is exactly 0 for q >= 1 (compact support), so a globule only touches
// the voxels inside its influence sphere.
//
// The kernels are an enum with an inline switch rather than a virtual interface: the
// splatter evaluates one per voxel (billions per frame) and instantiates its inner loop
// once per kernel (metaball_splat.cpp), which a virtual call would prevent.
//
// \see Wyvill, McPheeters, Wyvill, "Data Structure for Soft Objects", The Visual Computer
//      2(4):227-234, 1986: the "soft objects" polynomial
//      C(q) = 1 - 4/9 q^3 + 17/9 q^2 - 22/9 q. Note C(1/4) = 1/2 exactly, so with
//      influence 2 and iso value 0.5 a lone globule's surface lies exactly at its radius.
// \see Blinn, "A Generalization of Algebraic Surface Drawing", ACM Transactions on
//      Graphics 1(3):235-256, 1982: the exponential "blobby molecule" density
//      exp(-a r^2). Its support is infinite; we truncate it at R and shift and rescale it
//      so it stays continuous: B(q) = (exp(-a q) - exp(-a)) / (1 - exp(-a)).
// \see Murakami, Ichihara, "On a 3D display method by metaball technique", Transactions
//      of the IEICE J70-D(8):1607-1615, 1987 (the "metaball" of Murakami et al.):
//      M(q) = (1 - q)^2.

#include <cmath>
#include <string>
#include <vector>

namespace globular {

enum class KernelType { Wyvill, Blinn, Murakami };

struct MetaballKernel {
    KernelType type = KernelType::Wyvill;
    float blinnSharpness = 4.0f;  ///< 'a' of the Blinn kernel, dimensionless, > 0

    /// The kernel at @p q = r^2 / R^2; 0 for q >= 1.
    float value(float q) const {
        if (q >= 1.0f) return 0.0f;
        switch (type) {
            case KernelType::Wyvill:
                return 1.0f + q * (-22.0f / 9.0f + q * (17.0f / 9.0f - q * (4.0f / 9.0f)));
            case KernelType::Blinn: {
                const float tail = std::exp(-blinnSharpness);
                return (std::exp(-blinnSharpness * q) - tail) / (1.0f - tail);
            }
            case KernelType::Murakami: {
                const float s = 1.0f - q;
                return s * s;
            }
        }
        return 0.0f;
    }

    /// The q in [0, 1] where the kernel equals @p level (in (0, 1)): a lone globule's
    /// surface at iso value @p level lies at r = R sqrt(q).
    double qAtLevel(double level) const;

    /// The distance from a lone globule's centre to its surface, as a fraction of the
    /// influence radius, for iso value @p level in (0, 1).
    double surfaceFraction(double level) const { return std::sqrt(qAtLevel(level)); }
};

/// The kernel names a scene may use, in the order of KernelType.
const std::vector<std::string>& kernelNames();
/// @throw SceneError when @p name is not one of kernelNames().
KernelType kernelFromName(const std::string& name);

}  // namespace globular
