#pragma once
// A set for globules to meet besides each other and the ground (the paper's section 6:
// containers and obstacles): the `[[collider]]` sections of a scene. Each collider is an
// analytic solid with a signed distance phi (negative inside the solid) and an outward
// normal N, and acts through the penalty force of eq. (9) generalised to it:
//   F = -k_s phi N - k_d (v . N) N   while phi < 0   (phi at the centre or the surface)
// plus Coulomb friction on the tangential velocity (collider_contact.h).
//
// Shapes, in the collider's frame (cylinder and cup: axis +y from the centre of the base):
//   plane     the half-space below the plane through `center` with outward `normal`
//   box       edges `size` around `center`
//   sphere    `radius` around `center`
//   cylinder  `radius`, `height`, capped
//   cup       an open-topped cylinder: a wall and a bottom `thickness` thick (a glass)
// `inside = true` keeps globules inside a closed shape (box, sphere, cylinder): the solid
// is then everything outside it. `[[collider.key]]` keyframes move it (collider_motion.h).

#include <string>
#include <vector>

#include "collider_motion.h"
#include "vec3.h"

namespace globular {

class SettingsSection;

struct ColliderSettings {
    std::string name;
    std::string shape = "box";  ///< plane | box | sphere | cylinder | cup
    Vec3 center{0, 0, 0};       ///< box, sphere: the centre; cylinder, cup: the base's centre
    Vec3 size{1, 1, 1};         ///< box edges, world units
    double radius = 1;          ///< sphere, cylinder, cup
    double height = 1;          ///< cylinder, cup
    Vec3 normal{0, 1, 0};       ///< plane: outward normal (normalised)
    double thickness = 0.2;     ///< cup: wall and bottom
    bool inside = false;        ///< box, sphere, cylinder: globules are kept inside
    double ks = 5000;           ///< penalty stiffness (the ground's default)
    double kd = 300;            ///< penalty damping (the ground's default)
    std::string contact = "center";  ///< center | surface (offset by the globule's radius)
    double friction = 0;        ///< Coulomb coefficient mu; 0 = frictionless, as the paper
    std::vector<ColliderKey> keys;  ///< [[collider.key]]: the motion (collider_motion.h)

    void describe(SettingsSection& section);
    /// Keys that do not apply to the shape, and inconsistent geometry.
    /// @throw SceneError naming the key.
    void validate(const SettingsSection& section) const;
};

/// Signed distance to a collider's surface and the outward normal there.
struct SurfaceSample {
    double phi = 0;        ///< negative inside the solid, world units
    Vec3 normal{0, 1, 0};  ///< unit, pointing out of the solid
};

/// phi and N of @p collider at @p point: the exact distance for the plane, box, sphere
/// and cylinder; for the cup the larger of the outer cylinder's and the (negated) hollow's,
/// exact but near the rim's edge. Where the normal is not unique, one of the candidates.
SurfaceSample sampleCollider(const ColliderSettings& collider, Vec3 point);

/// The same for a collider at @p motion's pose: @p point in the world, the normal too.
SurfaceSample sampleCollider(const ColliderSettings& collider, const ColliderMotion& motion,
                             Vec3 point);

/// Whether a [[collider]] of @p shape reads @p key (the common keys apply to all).
bool colliderKeyApplies(const std::string& shape, const std::string& key);

}  // namespace globular
