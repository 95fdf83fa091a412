#pragma once
// The material of eq. (2)-(8): the constants of the inter-globule force and the
// presets that make it behave as powder, liquid or solid.
// \see Miller & Pearce, "Globular Dynamics", Computers & Graphics 13(3), 1989, and
//      ../shared/PAPER_NOTES.md for how we read the paper's open points.

#include <string>

#include "vec3.h"

namespace globular {

class SettingsSection;
class Reporter;

/// The `[material]` section of a scene, or one of its `[[material]]` sections.
struct MaterialSettings {
    std::string name;               ///< how emitters and [[material_pair]] name it
    std::string preset = "liquid";  ///< powder | liquid | solid | custom
    double r0 = 1.0;     ///< rest distance where repulsion and attraction cancel, world units
    double b1 = 2.0;     ///< strength of the radial force
    double m = 5.0;      ///< repulsion exponent
    double n = 3.0;      ///< attraction exponent
    double alpha = 1.5;  ///< liquid drag reach C_d = alpha * r0, in [1.5, 2] per the paper
    /// Window constants as numbers (not factors): 0 takes the preset's value
    /// (powder C_r = C_d = r0; liquid C_r = r0, C_d = alpha r0; solid C_r = C_d = 2 r0).
    double cr = 0.0;
    double cd = 0.0;
    /// sRGB colour for [render] color_by = "material"; (0, 0, 0): a distinct colour by
    /// the material's place in the scene (materialColor).
    Vec3 color{0, 0, 0};

    void describe(SettingsSection& section);
    /// Throws SceneError naming the key for values that leave the model undefined;
    /// warns (through @p reporter) for values outside the paper's recommended ranges.
    void validate(const SettingsSection& section, Reporter& reporter) const;

    double resolvedCr() const;  ///< C_r after the preset is applied
    double resolvedCd() const;  ///< C_d after the preset is applied
};

/// The colour of material number @p index: its own, or a distinct one from a palette.
Vec3 materialColor(const MaterialSettings& material, std::size_t index);

}  // namespace globular
