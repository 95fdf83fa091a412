#include "render_plan.h"

#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>

#include "errors.h"
#include "file_bytes.h"
#include "frame_paths.h"
#include "render_stage.h"
#include "state_file.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

// Part of the fingerprint: raise it whenever what a plan measures, or how (autoFrame, the
// ramp's range), changes, so plans an older build measured are measured again.
constexpr int kFormat = 2;  // 2: the following camera's path
// A plan is a few hundred bytes plus the contact sheet's frame list and, with a following
// camera, about 130 bytes a frame.
constexpr uint64_t kMaxPlanBytes = 64 << 20;

/// Shortest text that reads back as exactly @p v, always a TOML float.
std::string number(double v) {
    if (!std::isfinite(v)) throw Error("render plan: a non-finite number cannot be written");
    char buffer[64];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
    std::string text(buffer, end);
    if (text.find_first_of(".e") == std::string::npos) text += ".0";
    return text;
}

std::string vec3(Vec3 v) {
    std::string text = "[";
    text += number(v.x);
    text += ", ";
    text += number(v.y);
    text += ", ";
    text += number(v.z);
    return text + "]";
}

std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

/// Size and modification time of @p path, or "-" when it is absent.
std::string stamp(const fs::path& path) {
    std::error_code error;
    const auto size = fs::file_size(path, error);
    if (error) return "-";
    const auto time = fs::last_write_time(path, error);
    if (error) return "-";
    return std::to_string(size) + "@" + std::to_string(time.time_since_epoch().count());
}

[[noreturn]] void bad(const std::string& source, const std::string& key, const std::string& why) {
    throw IoError("render plan " + quoteForMessage(source, 300) + ": key '" + key + "' " + why +
                  " (delete the file to have it measured again)");
}

double readNumber(const toml::table& t, const std::string& key, const std::string& source) {
    const toml::node* node = t.at_path(key).node();
    if (!node) bad(source, key, "is missing");
    if (const auto v = node->value<double>()) return *v;
    bad(source, key, "is not a number");
}

int readInt(const toml::table& t, const std::string& key, const std::string& source) {
    const toml::node* node = t.at_path(key).node();
    if (!node) bad(source, key, "is missing");
    if (const auto v = node->value_exact<int64_t>(); v && *v >= 0 && *v < (int64_t(1) << 31))
        return int(*v);
    bad(source, key, "is not a frame number or size");
}

bool readBool(const toml::table& t, const std::string& key, const std::string& source) {
    const toml::node* node = t.at_path(key).node();
    if (!node) bad(source, key, "is missing");
    if (const auto v = node->value_exact<bool>()) return *v;
    bad(source, key, "is not true or false");
}

std::string readString(const toml::table& t, const std::string& key, const std::string& source) {
    const toml::node* node = t.at_path(key).node();
    if (!node) bad(source, key, "is missing");
    if (const auto v = node->value_exact<std::string>()) return *v;
    bad(source, key, "is not a string");
}

Vec3 readVec3(const toml::table& t, const std::string& key, const std::string& source) {
    const toml::node* node = t.at_path(key).node();
    const toml::array* a = node ? node->as_array() : nullptr;
    if (!a || a->size() != 3) bad(source, key, "is not an array of 3 numbers");
    double v[3];
    for (std::size_t i = 0; i < 3; ++i) {
        const auto x = (*a)[i].value<double>();
        if (!x) bad(source, key, "is not an array of 3 numbers");
        v[i] = *x;
    }
    return {v[0], v[1], v[2]};
}

/// The following camera's path ([camera] path_positions and path_targets, both or
/// neither), one camera per frame of the plan.
std::vector<ViewCamera> readPath(const toml::table& t, const RenderPlan& plan,
                                 const std::string& source) {
    if (!t.at_path("camera.path_positions").node() && !t.at_path("camera.path_targets").node()) {
        return {};
    }
    const long frames = long(plan.lastFrame) - plan.firstFrame + 1;
    std::vector<ViewCamera> path;
    for (const bool eyes : {true, false}) {
        const char* key = eyes ? "camera.path_positions" : "camera.path_targets";
        const toml::node* node = t.at_path(key).node();
        const toml::array* a = node ? node->as_array() : nullptr;
        if (!a || long(a->size()) != frames) {
            bad(source, key, "is not an array of " + std::to_string(frames) + " points");
        }
        path.resize(a->size(), plan.camera);
        for (std::size_t i = 0; i < a->size(); ++i) {
            const toml::array* p = (*a)[i].as_array();
            double v[3];
            for (std::size_t j = 0; j < 3; ++j) {
                const auto x = p && p->size() == 3 ? (*p)[j].value<double>() : std::nullopt;
                if (!x || !std::isfinite(*x)) bad(source, key, "holds a point that is not 3 finite numbers");
                v[j] = *x;
            }
            (eyes ? path[i].position : path[i].target) = {v[0], v[1], v[2]};
        }
    }
    return path;
}

}  // namespace

const ViewCamera& RenderPlan::cameraFor(int frame) const {
    const long i = long(frame) - firstFrame;
    return i >= 0 && i < long(path.size()) ? path[std::size_t(i)] : camera;
}

fs::path renderPlanPath(const fs::path& outDir) { return outDir / "render_plan.toml"; }

std::string renderPlanFingerprint(const RenderJob& job, const fs::path& outDir, int firstFrame,
                                  int lastFrame) {
    const RenderSettings& r = job.render;
    const CameraSettings& c = job.camera;
    std::ostringstream text;
    text << "plan " << kFormat << "\nmode " << r.mode << "\ncolor_by " << r.colorBy << "\nramp "
         << number(r.rampMin) << " " << number(r.rampMax) << "\nsize " << r.width << " "
         << r.height << "\ncamera " << c.automatic() << " " << c.follow << " "
         << number(c.followSeconds) << " " << vec3(c.position) << " "
         << vec3(c.target) << " " << number(c.fov) << "\nground " << number(job.groundHeight)
         << "\nmesh_format " << job.meshFormat << "\nfps " << number(job.fps)
         << "\ncontact_sheet " << r.contactSheet << "\ncolliders "
         << job.colliders.colliders.size() << "\nframes " << firstFrame << "-" << lastFrame
         << "\n";
    for (int f = firstFrame; f <= lastFrame; ++f) {
        const fs::path input = r.mode == "surface" ? meshPath(outDir, f, job.meshFormat)
                                                   : cacheVdbPath(outDir, f);
        text << f << " " << stamp(input) << " " << stamp(colliderPosesPath(outDir, f)) << "\n";
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(fingerprint(text.str())));
    return hex;
}

std::string renderPlanToml(const RenderPlan& plan) {
    std::ostringstream out;
    out << "# globular render plan: what every frame of the animation shares, measured once\n"
           "# from all its cached frames. Renders of any frame range read it; it is measured\n"
           "# again when the fingerprint of its settings and inputs no longer matches.\n"
        << "format = " << kFormat << "\n"
        << "fingerprint = " << quoted(plan.fingerprint) << "\n"
        << "first_frame = " << plan.firstFrame << "\n"
        << "last_frame = " << plan.lastFrame << "\n"
        << "mode = " << quoted(plan.mode) << "\n"
        << "width = " << plan.width << "\n"
        << "height = " << plan.height << "\n"
        << "\n[camera]\n"
        << "position = " << vec3(plan.camera.position) << "\n"
        << "target = " << vec3(plan.camera.target) << "\n"
        << "fov = " << number(plan.camera.fov) << "  # vertical, degrees\n"
        << "automatic = " << (plan.automaticCamera ? "true" : "false") << "\n";
    if (!plan.path.empty()) {
        out << "# the following camera, frame by frame from first_frame\n";
        for (const bool eyes : {true, false}) {
            out << (eyes ? "path_positions" : "path_targets") << " = [\n";
            for (const ViewCamera& c : plan.path) {
                out << "  " << vec3(eyes ? c.position : c.target) << ",\n";
            }
            out << "]\n";
        }
    }
    out
        << "\n[ramp]\n"
        << "color_by = " << quoted(plan.colorBy) << "\n"
        << "empty = " << (plan.ramp.empty ? "true" : "false") << "\n"
        << "min = " << number(plan.ramp.min) << "\n"
        << "max = " << number(plan.ramp.max) << "\n"
        << "\n[content]  # the animation's robust bounds, world units\n"
        << "empty = " << (plan.content.empty ? "true" : "false") << "\n"
        << "min = " << vec3(plan.content.min) << "\n"
        << "max = " << vec3(plan.content.max) << "\n"
        << "\n[contact_sheet]\n"
        << "frames = [";
    for (std::size_t i = 0; i < plan.sheetFrames.size(); ++i) {
        out << (i ? ", " : "") << plan.sheetFrames[i];
    }
    out << "]\n";
    return out.str();
}

RenderPlan parseRenderPlan(const std::string& text, const std::string& source) {
    toml::table t;
    try {
        t = toml::parse(text, source);
    } catch (const toml::parse_error& e) {
        throw IoError("render plan " + quoteForMessage(source, 300) + ": not TOML (" +
                      quoteForMessage(std::string(e.description())) + " at line " +
                      std::to_string(e.source().begin.line) +
                      "; delete the file to have it measured again)");
    }
    if (readInt(t, "format", source) != kFormat) bad(source, "format", "is not " + std::to_string(kFormat));
    RenderPlan plan;
    plan.fingerprint = readString(t, "fingerprint", source);
    plan.firstFrame = readInt(t, "first_frame", source);
    plan.lastFrame = readInt(t, "last_frame", source);
    plan.mode = readString(t, "mode", source);
    plan.width = readInt(t, "width", source);
    plan.height = readInt(t, "height", source);
    plan.camera.position = readVec3(t, "camera.position", source);
    plan.camera.target = readVec3(t, "camera.target", source);
    plan.camera.fov = readNumber(t, "camera.fov", source);
    plan.automaticCamera = readBool(t, "camera.automatic", source);
    plan.path = readPath(t, plan, source);
    plan.colorBy = readString(t, "ramp.color_by", source);
    plan.ramp.empty = readBool(t, "ramp.empty", source);
    plan.ramp.min = readNumber(t, "ramp.min", source);
    plan.ramp.max = readNumber(t, "ramp.max", source);
    plan.content.empty = readBool(t, "content.empty", source);
    plan.content.min = readVec3(t, "content.min", source);
    plan.content.max = readVec3(t, "content.max", source);
    const toml::array* frames = t.at_path("contact_sheet.frames").as_array();
    if (!frames) bad(source, "contact_sheet.frames", "is not an array of frame numbers");
    for (const toml::node& node : *frames) {
        const auto f = node.value_exact<int64_t>();
        if (!f || *f < plan.firstFrame || *f > plan.lastFrame) {
            bad(source, "contact_sheet.frames", "holds a value that is not a frame of " +
                                                    std::to_string(plan.firstFrame) + "-" +
                                                    std::to_string(plan.lastFrame));
        }
        plan.sheetFrames.push_back(int(*f));
    }
    if (plan.lastFrame < plan.firstFrame) bad(source, "last_frame", "is before first_frame");
    return plan;
}

RenderPlan readRenderPlan(const fs::path& path) {
    std::string text;
    try {
        text = readFileBytes(path, kMaxPlanBytes);
    } catch (const std::exception& e) {
        throw IoError("cannot read render plan " + path.string() + ": " + e.what());
    }
    return parseRenderPlan(text, path.string());
}

}  // namespace globular
