#include "render_settings.h"

#include <cmath>
#include <functional>

#include "errors.h"
#include "settings_schema.h"

namespace globular {

namespace {

using KeyName = std::function<std::string(const std::string& key)>;

KeyName plainKeys(const std::string& section) {
    return [section](const std::string& key) { return "[" + section + "] key '" + key + "'"; };
}

KeyName placedKeys(const SettingsSection& section) {
    return [&section](const std::string& key) { return section.describeKey(key); };
}

const NumberRange kUnit = NumberRange::between(0, 1);

void checkRender(const RenderSettings& s, const KeyName& name) {
    const auto n = s.samples;
    if (n != 1 && n != 2 && n != 4 && n != 8 && n != 16) {
        throw SceneError(name("samples") + " = " + std::to_string(n) +
                         ": must be 1, 2, 4, 8 or 16");
    }
    if (s.colorBy == "speed" && s.mode == "surface") {
        throw SceneError(name("color_by") +
                         " = \"speed\": needs mode = \"spheres\" (the surface mesh carries "
                         "no velocities); use \"height\", \"material\", \"temperature\" or "
                         "\"constant\"");
    }
    if (!(s.temperatureHigh > s.temperatureLow)) {
        throw SceneError(name("temperature_high") + " = " + numberForMessage(s.temperatureHigh) +
                         ": must be above temperature_low = " +
                         numberForMessage(s.temperatureLow));
    }
    if (s.pngBits != 8 && s.pngBits != 16) {
        throw SceneError(name("png_bits") + " = " + std::to_string(s.pngBits) +
                         ": must be 8 or 16");
    }
    if (!std::isfinite(s.exposure) || std::abs(s.exposure) > 20) {
        throw SceneError(name("exposure") + " = " + numberForMessage(s.exposure) +
                         ": must be within -20 to 20 stops");
    }
    if (s.toneMapping != "none" && s.toneMapping != "aces") {
        throw SceneError(name("tone_mapping") + " = \"" + s.toneMapping +
                         "\": must be \"none\" or \"aces\"");
    }
    if (s.rampMax < s.rampMin) {
        throw SceneError(name("ramp_max") + " = " + std::to_string(s.rampMax) +
                         ": must not be below ramp_min = " + std::to_string(s.rampMin));
    }
}

void checkCamera(const CameraSettings& c, const KeyName& name) {
    if (!c.autoFrame && length(c.position - c.target) <= 0) {
        throw SceneError(name("target") +
                         ": must differ from position when auto_frame = "
                         "false (the view direction would be undefined)");
    }
}

void checkLight(const LightSettings& l, const KeyName& name) {
    if (length(l.direction) <= 0) {
        throw SceneError(name("direction") + " = [0, 0, 0]: a light needs a direction");
    }
}

}  // namespace

void RenderSettings::describe(SettingsSection& s) {
    s.integer("width", width, 16, 16384, "image width, pixels");
    s.integer("height", height, 16, 16384, "image height, pixels");
    s.choice("mode", mode, {"spheres", "surface", "fluid"},
             "spheres: each globule a shaded sphere of its radius; surface: the surfacing "
             "stage's mesh (a liquid when every [material] looks liquid and color_by = "
             "\"constant\"); fluid: a liquid surface straight from the globules, in screen "
             "space (no surface stage)");
    s.integer("samples", samples, 1, 16, "multisample anti-aliasing samples per pixel (1 = off)");
    s.choice("color_by", colorBy, {"constant", "speed", "height", "material", "temperature"},
             "colour by the constant color, by speed or height through a colour ramp, by "
             "each globule's [[material]] color, or by temperature through a blackbody ramp "
             "(surface mode: the mesh's per-vertex material or temperature)");
    s.vec3("color", color, kUnit, "base colour, sRGB in [0, 1]");
    s.number("ramp_min", rampMin, NumberRange::any(),
             "speed (units/s) or height (units) mapped to the ramp's start");
    s.number("ramp_max", rampMax, NumberRange::any(),
             "value mapped to the ramp's end; equal to ramp_min: the animation's own range");
    s.number("temperature_low", temperatureLow, NumberRange::any(),
             "temperature at the black end of the blackbody ramp (color_by = \"temperature\"), "
             "degrees of the scene's [thermal] temperatures");
    s.number("temperature_high", temperatureHigh, NumberRange::any(),
             "temperature at the white end of the blackbody ramp; must be above "
             "temperature_low");
    s.number("specular", specular, kUnit,
             "reflectance of dielectric materials (Filament's): f0 = 0.16 specular^2, 0.5 = 4% "
             "(water, plastic), 0 = no specular reflection at all");
    s.retired("ambient",
              "the environment lights the scene now (the procedural sky or [render] "
              "environment), scaled by environment_intensity; see also ambient_occlusion");
    s.text("environment", environment,
           "the light all around: a lat-long (equirectangular) HDR OpenEXR file, +y up, its "
           "middle looking along -z (relative to the scene file); \"\": the procedural "
           "sky, its sun glow towards the key light");
    s.number("environment_intensity", environmentIntensity, NumberRange::nonNegative(),
             "multiplies the environment's radiance (image-based diffuse and specular light); "
             "0 = lit by the [[light]]s alone");
    s.number("shadow_softness", shadowSoftness, {0, 16},
             "penumbra radius of the key light's shadow, shadow-map texels (about pixels), "
             "percentage-closer filtered; 0 = hard");
    s.number("ambient_occlusion", ambientOcclusion, kUnit,
             "strength of screen-space ambient occlusion (darkens creases and contacts); 0 = off");
    s.number("occlusion_radius", occlusionRadius, NumberRange::nonNegative(),
             "reach of the ambient occlusion, world units; 0 = a 30th of the size of what the "
             "animation occupies");
    s.flag("ground", ground, "draw the ground plane (at [ground] height)");
    s.vec3("ground_color", groundColor, kUnit, "ground colour, sRGB in [0, 1]");
    s.number("checker_size", checkerSize, NumberRange::nonNegative(),
             "edge of a ground checker square, world units; 0 = automatic");
    s.vec3("background", background, kUnit, "background colour, sRGB in [0, 1]");
    s.integer("shadow_map_size", shadowMapSize, 256, 8192,
              "largest shadow map, texels per side (it follows the screen below that)");
    s.integer("contact_sheet", contactSheet, 0, 1000,
              "frames tiled into contact_sheet.png, evenly spaced; 0 = no sheet");
    s.integer("contact_columns", contactColumns, 0, 100,
              "tiles per row of the contact sheet; 0 = automatic");
    s.integer("contact_tile_width", contactTileWidth, 16, 4096,
              "width of one contact sheet tile, pixels");
    s.flag("movie", movie, "assemble the frames into movie.mp4 (needs ffmpeg on PATH)");
    s.number("movie_fps", movieFps, NumberRange::nonNegative(),
             "movie frames per second; 0 = the simulation's fps");
    s.number("exposure", exposure, {-20, 20},
             "exposure, stops: the linear image is multiplied by 2^exposure before tone "
             "mapping (not in the EXR, which stays scene-linear)");
    s.choice("tone_mapping", toneMapping, {"none", "aces"},
             "none: linear values clipped at 1 and sRGB-encoded; aces: the filmic ACES fit "
             "(Narkowicz 2015), highlights roll off instead of clipping");
    s.integer("png_bits", pngBits, 8, 16, "bits per channel of the PNG frames: 8 or 16 (sRGB)");
    s.flag("exr", exr,
           "also write frames/frame.NNNN.exr: half-float linear RGBA (premultiplied), float Z "
           "(distance from the eye), half N.x N.y N.z (world-space normal) and, for spheres and "
           "the fluid, forward.u forward.v (screen motion over one frame, pixels)");
    s.number("fluid_smoothing", fluidSmoothing, {0, 20},
             "mode = \"fluid\": reach of the filter that smooths the globules' spheres into "
             "one surface, in globule radii (0 = the bare spheres)");
    s.flag("transparent", transparent,
           "transparent background: alpha 0 where nothing is drawn (PNG RGBA, EXR A); the "
           "ground, when drawn, fades into alpha instead of the background colour");
    s.flag("motion_blur", motionBlur,
           "motion blur: each frame averages motion_samples sub-frames over the shutter, the "
           "globules moved along their velocities (surface mode: the mesh's vertices along "
           "their vx vy vz; a mesh without them stays sharp)");
    s.number("shutter", shutter, kUnit,
             "time the shutter is open, as a fraction of the frame interval 1/fps, centred on "
             "the frame's instant (0.5: a 180-degree shutter)");
    s.integer("motion_samples", motionSamples, 1, 256,
              "sub-frames averaged per frame for motion blur and depth of field (the frame "
              "costs that many renders)");
    s.number("aperture", aperture, NumberRange::nonNegative(),
             "depth of field: radius of the thin lens, world units; 0 = a pinhole, all sharp");
    s.number("focus_distance", focusDistance, NumberRange::nonNegative(),
             "depth of field: distance from the eye to the plane in focus, world units; 0 = "
             "the camera's target");
    s.choice("gl", gl, {"osmesa", "egl"},
             "OpenGL back end: osmesa (Mesa's llvmpipe, off-screen) or egl (EGL surfaceless: "
             "llvmpipe here, the GPU where there is one); the environment variable "
             "GLOBULAR_GL, when set, wins");
}

void RenderSettings::validate() const { checkRender(*this, plainKeys("render")); }
void RenderSettings::validate(const SettingsSection& s) const { checkRender(*this, placedKeys(s)); }

void CameraSettings::describe(SettingsSection& s) {
    s.vec3("position", position, NumberRange::any(),
           "eye position, world units; left equal to target: automatic framing");
    s.vec3("target", target, NumberRange::any(), "point looked at, world units");
    s.number("fov", fov, {1, 170}, "vertical field of view, degrees");
    s.flag("auto_frame", autoFrame,
           "frame the whole animation automatically unless position and target are given");
    s.flag("follow", follow,
           "automatic framing glides with the action: each frame framed on the frames within "
           "follow_seconds of it, the moves smoothed over that window, so the subject never "
           "shrinks to a speck; false: one still camera for the whole shot");
    s.number("follow_seconds", followSeconds, {0.04, 600},
             "time window of the following camera around each frame, seconds");
}

void CameraSettings::noteGivenKeys(const SettingsSection& s) {
    if (s.placeOf("auto_frame")) return;
    if (s.placeOf("position") || s.placeOf("target")) autoFrame = false;
}

void CameraSettings::validate() const { checkCamera(*this, plainKeys("camera")); }
void CameraSettings::validate(const SettingsSection& s) const { checkCamera(*this, placedKeys(s)); }

void LightSettings::describe(SettingsSection& s) {
    s.vec3("direction", direction, NumberRange::any(),
           "direction the light travels (from the light into the scene)");
    s.vec3("color", color, kUnit, "light colour, sRGB in [0, 1]");
    s.number("intensity", intensity, NumberRange::nonNegative(), "multiplies color");
    s.flag("shadows", shadows, "casts shadows (only the first light does)");
}

void LightSettings::validate() const { checkLight(*this, plainKeys("light")); }
void LightSettings::validate(const SettingsSection& s) const { checkLight(*this, placedKeys(s)); }

}  // namespace globular
