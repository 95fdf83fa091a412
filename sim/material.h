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

/// The constants of eq. (2)-(8): a material's own, or one of its phases.
struct ForceConstants {
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

    void describeConstants(SettingsSection& section);
    /// Throws SceneError naming the key for values that leave the model undefined;
    /// warns (through @p reporter) for values outside the paper's recommended ranges.
    void validate(const SettingsSection& section, Reporter& reporter) const;

    double resolvedCr() const;  ///< C_r after the preset is applied
    double resolvedCd() const;  ///< C_d after the preset is applied
};

/// The `[material]` section of a scene, or one of its `[[material]]` sections: its force
/// constants, and what temperature does to it (thermal scenes, thermal.h).
struct MaterialSettings : ForceConstants {
    std::string name;  ///< how emitters and [[material_pair]] name it
    /// sRGB colour for [render] color_by = "material"; (0, 0, 0): a distinct colour by
    /// the material's place in the scene (materialColor).
    Vec3 color{0, 0, 0};
    double roughness = 0.35;  ///< render: perceptual roughness in [0, 1] (surface_look.h)
    double metallic = 0;      ///< render: 0 = dielectric, 1 = metal
    double subsurface = 0;    ///< render: wrap of the diffuse light in [0, 1] (surface_look.h)

    // How the renderer draws it as a liquid (render/liquid_optics.h). Light crossing a
    // depth d of it keeps exp(-absorption * density * d) of each linear RGB channel.
    std::string look = "auto";  ///< auto (liquid for preset = liquid) | liquid | opaque
    Vec3 absorption{0.30, 0.09, 0.035};  ///< per world unit at density 1, linear RGB
    double density = 1.0;                ///< scales absorption; 0 = clear
    double ior = 1.33;                   ///< index of refraction

    // Heat. A globule's heat capacity is its mass times heatCapacity.
    double heatCapacity = 1.0;  ///< per unit mass
    double conductivity = 1.0;  ///< heat flow between touching globules per degree of difference
    double expansion = 0.0;     ///< beta: buoyancy -beta (T - T_ref) m g

    // Phase. With a [material.solid] or [material.liquid] table, a pair's constants blend
    // from the solid's at or below tSolid to the liquid's at or above tLiquid (smoothstep
    // of the pair's mean temperature); a phase not given is the material's own constants.
    bool phases = false;  ///< either table was given
    double tSolid = 0, tLiquid = 0;
    ForceConstants solid, liquid;

    /// Describes the material's own keys (the phases are nested tables, see describePhase).
    void describe(SettingsSection& section);
    /// The keys of a [material.solid] or [material.liquid] table.
    static void describePhase(SettingsSection& section, ForceConstants& phase) {
        phase.describeConstants(section);
    }
    /// ForceConstants::validate, plus the melting range.
    void validate(const SettingsSection& section, Reporter& reporter) const;

    /// The constants below tSolid (its own without phases).
    const ForceConstants& solidConstants() const { return phases ? solid : *this; }
    /// The constants above tLiquid (its own without phases).
    const ForceConstants& liquidConstants() const { return phases ? liquid : *this; }
};

/// The colour of material number @p index: its own, or a distinct one from a palette.
Vec3 materialColor(const MaterialSettings& material, std::size_t index);

}  // namespace globular
