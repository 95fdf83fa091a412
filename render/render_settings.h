#pragma once
// The `[render]`, `[camera]` and `[[light]]` sections of a scene: plain structs with
// defaults, bound to TOML keys by describe() and checked by validate().
// Colours are display (sRGB) values in [0, 1], as an artist picks them; the renderer
// shades in linear light and encodes the PNG back to sRGB.

#include <cstdint>
#include <string>

#include "vec3.h"

namespace globular {

class SettingsSection;

struct RenderSettings {
    int64_t width = 1280;                ///< pixels
    int64_t height = 720;                ///< pixels
    std::string mode = "spheres";        ///< spheres | surface | fluid
    int64_t samples = 4;                 ///< multisample anti-aliasing samples per pixel, 1 = off
    std::string colorBy = "constant";    ///< constant | speed | height | material | temperature
    Vec3 color{0.16, 0.42, 0.82};        ///< base colour (sRGB), used by color_by = constant
    double rampMin = 0;                  ///< speed (units/s) or height (units) at the ramp's start
    double rampMax = 0;                  ///< ... and end; rampMin == rampMax: the animation's range
    double temperatureLow = 0;           ///< temperature at the blackbody ramp's black end
    double temperatureHigh = 100;        ///< ... and at its white end (> temperatureLow)
    double specular = 0.5;               ///< dielectrics' reflectance: f0 = 0.16 specular^2
    std::string environment;             ///< lat-long OpenEXR of the light all around; "": the sky
    double environmentIntensity = 1.0;   ///< multiplies the environment's radiance, 0 = none
    double shadowSoftness = 2.0;         ///< penumbra radius of the key light's shadow, texels
    double ambientOcclusion = 0.8;       ///< strength of screen-space ambient occlusion, 0 = off
    double occlusionRadius = 0;          ///< its reach, world units; 0 = the content's size / 30
    bool ground = true;                  ///< draw the ground plane
    Vec3 groundColor{0.72, 0.70, 0.66};  ///< sRGB
    double checkerSize = 0;              ///< ground checker edge, world units; 0 = automatic
    Vec3 background{0.86, 0.88, 0.91};   ///< sRGB; the ground fades into it at the horizon
    int64_t shadowMapSize = 2048;        ///< largest shadow map, texels per side
    int64_t contactSheet = 0;            ///< frames tiled into contact_sheet.png, 0 = none
    int64_t contactColumns = 0;          ///< tiles per row, 0 = automatic
    int64_t contactTileWidth = 480;      ///< pixels per tile
    bool movie = false;                  ///< assemble frames/ into movie.mp4 with ffmpeg
    double movieFps = 0;                 ///< movie frame rate, 0 = the simulation's fps
    double exposure = 0;                 ///< stops: linear radiance times 2^exposure
    std::string toneMapping = "none";    ///< none (clip) | aces (tone_map.h)
    int64_t pngBits = 8;                 ///< bits per channel of the PNG frames: 8 or 16
    bool exr = false;                    ///< also write frames/frame.NNNN.exr (exr_image.h)
    bool transparent = false;            ///< background alpha 0 (PNG RGBA, EXR A)
    double fluidSmoothing = 2;           ///< mode fluid: the depth filter's reach, globule radii
    bool motionBlur = false;             ///< accumulate sub-frames over the shutter (sub_frames.h)
    double shutter = 0.5;                ///< open time, fraction of 1/fps, centred on the frame
    int64_t motionSamples = 8;           ///< sub-frames accumulated (motion blur, depth of field)
    double aperture = 0;                 ///< lens radius, world units; 0 = pinhole (no depth of field)
    double focusDistance = 0;            ///< world units from the eye; 0 = the camera's target
    std::string gl = "osmesa";           ///< OpenGL back end: osmesa | egl (gl_context.h)

    void describe(SettingsSection& section);
    /// @throw SceneError naming the key (e.g. color_by = speed with mode = surface,
    ///        temperature_high not above temperature_low).
    void validate() const;
    /// As validate(), with the key's file, line and column from @p section.
    void validate(const SettingsSection& section) const;
};

/// The camera. Left as by default (position equal to target), it frames the whole
/// animation automatically; a scene that gives a position (and target) gets that camera.
struct CameraSettings {
    Vec3 position{0, 0, 0};  ///< eye, world units; equal to target: automatic framing
    Vec3 target{0, 0, 0};    ///< the point looked at, world units
    double fov = 40;         ///< vertical field of view, degrees
    /// Frame automatically while position and target are unset (equal). False: always the
    /// given camera (then position must differ from target).
    bool autoFrame = true;
    /// Automatic framing glides with the action (followTheAction) instead of holding one
    /// camera for the whole shot (autoFrame).
    bool follow = true;
    double followSeconds = 1.5;  ///< the time window framed and smoothed around each frame

    /// Whether the renderer places the camera itself: autoFrame and no camera given.
    bool automatic() const { return autoFrame && position == target; }

    void describe(SettingsSection& section);
    /// Turns autoFrame off when the scene gave position or target but not auto_frame, so
    /// the resolved scene says what happened. Optional: automatic() already holds.
    void noteGivenKeys(const SettingsSection& section);
    /// @throw SceneError naming the key (auto_frame = false with position equal to target).
    void validate() const;
    void validate(const SettingsSection& section) const;
};

/// A directional light. The first light is the key light and casts shadows.
struct LightSettings {
    Vec3 direction{0.55, -1.0, -0.35};  ///< the way the light travels (towards the ground)
    Vec3 color{1.0, 0.97, 0.92};        ///< sRGB
    double intensity = 1.0;             ///< multiplies color
    bool shadows = true;                ///< casts shadows (only the first light can)

    void describe(SettingsSection& section);
    /// @throw SceneError naming the key (zero direction).
    void validate() const;
    void validate(const SettingsSection& section) const;
};

}  // namespace globular
