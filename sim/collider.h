#pragma once
// A set for globules to meet besides each other and the ground (the paper's section 6:
// containers, obstacles and effectors): the `[[collider]]` sections of a scene. Each
// collider is a solid with a signed distance phi (negative inside the solid) and an
// outward normal N, and acts through the penalty force of eq. (9) generalised to it:
//   F = -k_s phi N - k_d (v . N) N   while phi < 0   (phi at the centre or the surface)
// plus Coulomb friction on the tangential velocity (collider_contact.h).
//
// Shapes, in the collider's frame (cylinder and cup: axis +y from the centre of the base):
//   plane     the half-space below the plane through `center` with outward `normal`
//   box       edges `size` around `center`
//   sphere    `radius` around `center`
//   cylinder  `radius`, `height`, capped
//   cup       an open-topped cylinder: a wall and a bottom `thickness` thick (a glass)
//   mesh      an OBJ or PLY `file`, scaled by `scale` and moved by `center`: a closed
//             mesh's inside, or a shell `thickness` thick around any mesh (mesh_sdf.h)
// `inside = true` keeps globules inside a closed shape (box, sphere, cylinder, closed
// mesh): the solid is then everything outside it. `[[collider.key]]` keyframes move it
// (collider_motion.h); `dynamic = true` makes it a rigid body that gravity and the
// globules move (rigid_body.h).

#include <string>
#include <vector>

#include "collider_motion.h"
#include "surface_sample.h"
#include "vec3.h"

namespace globular {

class SettingsSection;

struct ColliderSettings {
    std::string name;
    std::string shape = "box";  ///< plane | box | sphere | cylinder | cup | mesh
    Vec3 center{0, 0, 0};       ///< box, sphere: the centre; cylinder, cup: the base's centre
    Vec3 size{1, 1, 1};         ///< box edges, world units
    double radius = 1;          ///< sphere, cylinder, cup
    double height = 1;          ///< cylinder, cup
    Vec3 normal{0, 1, 0};       ///< plane: outward normal (normalised)
    double thickness = 0;       ///< cup: wall and bottom; mesh: a shell (0 = closed mesh)
    std::string file;           ///< mesh: OBJ or PLY, relative to the scene file
    double scale = 1;           ///< mesh: uniform scale of the file's coordinates
    double voxelSize = 0;       ///< mesh: SDF voxel, world units (0 = 1/100 of its extent)
    bool inside = false;        ///< box, sphere, cylinder, mesh: globules are kept inside
    double ks = 5000;           ///< penalty stiffness (the ground's default)
    double kd = 300;            ///< penalty damping (the ground's default)
    std::string contact = "center";  ///< center | surface (offset by the globule's radius)
    double temperature = 20;    ///< thermal: its surface temperature
    double heatTransfer = 0;    ///< thermal: rate toward it while touching, 1/s (0: insulating)
    double friction = 0;        ///< Coulomb coefficient mu; 0 = frictionless, as the paper
    std::vector<ColliderKey> keys;  ///< [[collider.key]]: the motion (collider_motion.h)
    bool dynamic = false;       ///< a rigid body moved by gravity and the globules
    double mass = 10;           ///< dynamic: kilograms (a globule is 1 by default)
    Vec3 velocity{0, 0, 0};     ///< dynamic: initial velocity, world units / s
    Vec3 angularVelocity{0, 0, 0};  ///< dynamic: initial spin, degrees / s about x, y, z

    void describe(SettingsSection& section);
    /// Keys that do not apply to the shape, and inconsistent geometry.
    /// @throw SceneError naming the key.
    void validate(const SettingsSection& section) const;
};

/// Whether a [[collider]] of @p shape reads @p key (the common keys apply to all; mass,
/// velocity and angular_velocity only when @p dynamic).
bool colliderKeyApplies(const std::string& shape, const std::string& key, bool dynamic = false);

}  // namespace globular
