#include "environment_light.h"

#include <filesystem>
#include <memory>
#include <mutex>
#include <sstream>

#include "gl_api.h"

namespace globular::detail {

namespace {

// 128 texels per face for the mirror level: sharper than the blur of any rough surface
// and cheap to pre-filter (about 0.3 s on one core, once per environment).
constexpr int kBaseSize = 128;
constexpr int kLevels = 5;  // roughness 0, 0.25, ..., 1 at 128, 64, ..., 8 texels
constexpr int kSamples = 32;  // on the first rough level, 4x more on each next

std::string keyOf(const std::string& file, const SkyLook& sky) {
    if (!file.empty()) {  // a file rewritten in place is read again
        std::error_code error;
        const auto time = std::filesystem::last_write_time(file, error);
        return "file:" + file + ":" + std::to_string(time.time_since_epoch().count());
    }
    std::ostringstream key;
    key.precision(9);
    for (Vec3 v : {sky.zenith, sky.horizon, sky.ground, sky.sunToward, sky.sunGlow}) {
        key << v.x << ' ' << v.y << ' ' << v.z << ' ';
    }
    return key.str();
}

}  // namespace

EnvironmentLight::EnvironmentLight() : mCube(gl::makeTexture()) {}

namespace {

struct Prepared {
    PrefilteredCube cube;
    IrradianceSH irradiance;
};

/// The last environment prepared in this process, shared by its renderers (a test or a
/// benchmark makes many for the same sky).
std::shared_ptr<const Prepared> preparedFor(const std::string& key, const std::string& file,
                                            const SkyLook& sky) {
    static std::mutex mutex;
    static std::string lastKey;
    static std::shared_ptr<const Prepared> last;
    {
        std::lock_guard lock(mutex);
        if (last && key == lastKey) return last;
    }
    const LatLongImage radiance = file.empty() ? proceduralSky(sky) : readLatLongExr(file);
    auto prepared = std::make_shared<Prepared>(
        Prepared{prefilterGgx(radiance, kBaseSize, kLevels, kSamples), irradianceSH(radiance)});
    std::lock_guard lock(mutex);
    lastKey = key;
    last = prepared;
    return prepared;
}

}  // namespace

void EnvironmentLight::prepare(const std::string& file, const SkyLook& sky) {
    const std::string key = keyOf(file, sky);
    if (key == mKey) return;
    const std::shared_ptr<const Prepared> prepared = preparedFor(key, file, sky);
    const PrefilteredCube& cube = prepared->cube;
    mIrradiance = prepared->irradiance;
    mLevels = cube.levelCount();
    glActiveTexture(GL_TEXTURE0 + kEnvironmentUnit);
    glBindTexture(GL_TEXTURE_CUBE_MAP, mCube.id());
    for (int l = 0; l < mLevels; ++l) {
        const int size = cube.sizeOf(l);
        const std::size_t faceFloats = std::size_t(size) * size * 3;
        for (int f = 0; f < 6; ++f) {
            glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, l, GL_RGB16F, size, size, 0, GL_RGB,
                         GL_FLOAT, cube.levels[l].data() + f * faceFloats);
        }
    }
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, mLevels - 1);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
        glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
    }
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glActiveTexture(GL_TEXTURE0);
    gl::checkErrors("uploading the environment");
    mKey = key;
}

void EnvironmentLight::bind() const {
    glActiveTexture(GL_TEXTURE0 + kEnvironmentUnit);
    glBindTexture(GL_TEXTURE_CUBE_MAP, mCube.id());
    glActiveTexture(GL_TEXTURE0);
}

}  // namespace globular::detail
