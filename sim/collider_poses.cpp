#include "collider_poses.h"

#include <toml++/toml.h>

#include <cmath>
#include <sstream>

#include "atomic_file.h"
#include "errors.h"
#include "file_bytes.h"
#include "frame_paths.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

/// A poses file is a few hundred bytes a collider; anything far larger is not one.
constexpr uint64_t kMaxPosesBytes = uint64_t(16) << 20;

toml::array array(Vec3 v) { return toml::array{v.x, v.y, v.z}; }

[[noreturn]] void fail(const fs::path& path, const std::string& why) {
    throw IoError("cannot read collider poses " + path.string() + ": " + why);
}

Vec3 readVec3(const toml::node* node, const fs::path& path, const std::string& what) {
    const toml::array* a = node ? node->as_array() : nullptr;
    if (!a || a->size() != 3) fail(path, what + " is not an array of 3 numbers");
    double xyz[3];
    for (std::size_t i = 0; i < 3; ++i) {
        const auto value = (*a)[i].value<double>();
        if (!value || !std::isfinite(*value)) fail(path, what + " holds a non-finite number");
        xyz[i] = *value;
    }
    return {xyz[0], xyz[1], xyz[2]};
}

}  // namespace

void writeColliderPoses(const fs::path& path, int frame, double time,
                        const std::vector<ColliderSettings>& colliders,
                        const std::vector<ColliderMotion>& motions) {
    toml::array tables;
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        const ColliderMotion& m = motions[k];
        const Pose& p = m.now;
        toml::array rotation;
        for (const auto& row : p.rotation) rotation.push_back(toml::array{row[0], row[1], row[2]});
        // The velocity of the frame's origin (the translation point).
        tables.push_back(toml::table{{"name", colliders[k].name},
                                     {"translation", array(p.translation)},
                                     {"rotation", rotation},
                                     {"velocity", array(m.velocityAt(p.translation))},
                                     {"angular_velocity", array(m.angular)}});
    }
    std::ostringstream text;
    text << "# globular collider poses: world = rotation * local + translation\n"
         << toml::table{{"frame", frame}, {"time", time}, {"collider", tables}} << "\n";
    writeFileAtomically(path, text.str());
}

std::vector<Pose> readColliderPoses(const fs::path& path,
                                    const std::vector<ColliderSettings>& colliders) {
    std::string bytes;
    try {
        bytes = readFileBytes(path, kMaxPosesBytes);
    } catch (const std::exception& e) {
        fail(path, e.what());
    }
    toml::table root;
    try {
        root = toml::parse(bytes, path.string());
    } catch (const toml::parse_error& e) {
        std::ostringstream where;
        where << "line " << e.source().begin.line << ": " << e.description();
        fail(path, where.str());
    }
    const toml::array* tables = root["collider"].as_array();
    const std::size_t count = tables ? tables->size() : 0;
    if (count != colliders.size()) {
        fail(path, "it holds " + std::to_string(count) + " colliders, the scene " +
                       std::to_string(colliders.size()) +
                       " (simulated from another scene? run the sim stage again)");
    }
    std::vector<Pose> poses;
    for (std::size_t k = 0; k < count; ++k) {
        const toml::table* t = (*tables)[k].as_table();
        if (!t) fail(path, "collider " + std::to_string(k) + " is not a table");
        const auto name = (*t)["name"].value<std::string>();
        if (!name || *name != colliders[k].name) {
            fail(path, "collider " + std::to_string(k) + " is named '" +
                           quoteForMessage(name.value_or(""), 60) + "', the scene's '" +
                           colliders[k].name + "' (run the sim stage again)");
        }
        Pose pose;
        pose.translation = readVec3(t->get("translation"), path, "'" + *name + "' translation");
        const toml::array* rows = t->get_as<toml::array>("rotation");
        if (!rows || rows->size() != 3) fail(path, "'" + *name + "' rotation is not 3 rows");
        for (std::size_t i = 0; i < 3; ++i) {
            const Vec3 row = readVec3(rows->get(i), path, "'" + *name + "' rotation");
            pose.rotation[i][0] = row.x;
            pose.rotation[i][1] = row.y;
            pose.rotation[i][2] = row.z;
        }
        // A rotation keeps lengths and angles: R R^T = I.
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                double sum = 0;
                for (int c = 0; c < 3; ++c) sum += pose.rotation[i][c] * pose.rotation[j][c];
                if (std::abs(sum - (i == j ? 1.0 : 0.0)) > 1e-6) {
                    fail(path, "'" + *name + "' rotation is not a rotation matrix");
                }
            }
        }
        poses.push_back(pose);
    }
    return poses;
}

std::vector<Pose> colliderPosesOnFrame(const std::vector<ColliderSettings>& colliders,
                                       const fs::path& outDir, int frame, double fps) {
    const fs::path path = colliderPosesPath(outDir, frame);
    if (fs::exists(path)) return readColliderPoses(path, colliders);
    std::vector<Pose> poses;
    for (const ColliderSettings& c : colliders) {
        if (c.dynamic) {
            throw IoError("missing " + path.string() + ": collider '" + c.name +
                          "' is dynamic, so its poses come from the sim stage; run it first "
                          "(globular run SCENE --stages sim)");
        }
        poses.push_back(poseAt(c.keys, double(frame - 1) / fps));
    }
    return poses;
}

}  // namespace globular
