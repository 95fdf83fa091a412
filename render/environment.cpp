#include "environment.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>
#include <string>

#include "errors.h"

namespace globular {

namespace {

constexpr double kPi = std::numbers::pi;

double smoothstep(double a, double b, double x) {
    const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

Vec3 mix(Vec3 a, Vec3 b, double t) { return a + (b - a) * t; }

/// Direction through texel coordinates (s, t) in [0, 1] of cube face @p face (GL order).
Vec3 cubeDirection(int face, double s, double t) {
    const double sc = 2 * s - 1, tc = 2 * t - 1;
    switch (face) {
        case 0: return normalized({1, -tc, -sc});
        case 1: return normalized({-1, -tc, sc});
        case 2: return normalized({sc, 1, tc});
        case 3: return normalized({sc, -1, -tc});
        case 4: return normalized({sc, -tc, 1});
        default: return normalized({-sc, -tc, -1});
    }
}

/// The face a direction leaves through and its texel coordinates (s, t) in [0, 1].
int cubeFace(Vec3 d, double& s, double& t) {
    const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
    int face;
    double sc, tc, ma;
    if (ax >= ay && ax >= az) {
        face = d.x > 0 ? 0 : 1;
        sc = d.x > 0 ? -d.z : d.z;
        tc = -d.y;
        ma = ax;
    } else if (ay >= az) {
        face = d.y > 0 ? 2 : 3;
        sc = d.x;
        tc = d.y > 0 ? d.z : -d.z;
        ma = ay;
    } else {
        face = d.z > 0 ? 4 : 5;
        sc = d.z > 0 ? d.x : -d.x;
        tc = -d.y;
        ma = az;
    }
    s = 0.5 * (sc / ma + 1);
    t = 0.5 * (tc / ma + 1);
    return face;
}

/// Bilinear lookup in one level (clamped at the face's edges).
Vec3 sampleLevel(const std::vector<float>& level, int size, Vec3 d) {
    double s, t;
    const int face = cubeFace(d, s, t);
    const double x = std::clamp(s * size - 0.5, 0.0, size - 1.0);
    const double y = std::clamp(t * size - 0.5, 0.0, size - 1.0);
    const int x0 = std::min(int(x), size - 1), y0 = std::min(int(y), size - 1);
    const int x1 = std::min(x0 + 1, size - 1), y1 = std::min(y0 + 1, size - 1);
    const double fx = x - x0, fy = y - y0;
    const float* base = level.data() + std::size_t(face) * size * size * 3;
    auto at = [&](int i, int j) {
        const float* p = base + (std::size_t(j) * size + i) * 3;
        return Vec3{p[0], p[1], p[2]};
    };
    return mix(mix(at(x0, y0), at(x1, y0), fx), mix(at(x0, y1), at(x1, y1), fx), fy);
}

double radicalInverse(uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return double(bits) * 2.3283064365386963e-10;
}

/// Walter et al. 2007's GGX distribution of half vectors, D(h).
double ggx(double noh, double alpha) {
    const double a2 = alpha * alpha;
    const double f = noh * noh * (a2 - 1) + 1;
    return a2 / (kPi * f * f);
}

/// Sample @p i of @p count: a GGX half vector about n (Hammersley points), its light
/// direction l = reflect(-n, h) and n.h.
struct LobeSample {
    Vec3 l;
    double nol, noh;
};
LobeSample ggxSample(Vec3 n, double alpha, int i, int count) {
    const double phi = 2 * kPi * (i + 0.5) / count;
    const double xi = radicalInverse(uint32_t(i));
    const double cosTheta = std::sqrt((1 - xi) / (1 + (alpha * alpha - 1) * xi));
    const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    const Vec3 helper = std::abs(n.y) < 0.999 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    const Vec3 tx = normalized(cross(helper, n));
    const Vec3 ty = cross(n, tx);
    const Vec3 h = tx * (sinTheta * std::cos(phi)) + ty * (sinTheta * std::sin(phi)) + n * cosTheta;
    const Vec3 l = h * (2 * dot(n, h)) - n;
    return {l, dot(n, l), cosTheta};
}

/// Perceptual roughness to GGX alpha (Burley 2012), kept off 0 so the lobe stays finite.
double alphaOf(double roughness) { return std::max(roughness * roughness, 1e-3); }

}  // namespace

Vec3 latLongDirection(double u, double v) {
    const double phi = 2 * kPi * u - kPi, theta = kPi * v;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

Vec3 LatLongImage::sample(Vec3 d) const {
    d = normalized(d);
    const double u = std::atan2(d.x, -d.z) / (2 * kPi) + 0.5;
    const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
    const double x = u * width - 0.5;
    const double y = std::clamp(v * height - 0.5, 0.0, height - 1.0);
    const int x0 = int(std::floor(x)), y0 = std::min(int(y), height - 1);
    const int y1 = std::min(y0 + 1, height - 1);
    const double fx = x - x0, fy = y - y0;
    const int xa = ((x0 % width) + width) % width, xb = (xa + 1) % width;
    return mix(mix(at(xa, y0), at(xb, y0), fx), mix(at(xa, y1), at(xb, y1), fx), fy);
}

LatLongImage proceduralSky(const SkyLook& sky, int width, int height) {
    LatLongImage image{width, height, std::vector<float>(std::size_t(3) * width * height)};
    const Vec3 sun = normalized(sky.sunToward);
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            const Vec3 d = latLongDirection((i + 0.5) / width, (j + 0.5) / height);
            // Brighter towards the horizon (a longer path through the air), then the
            // sun's glow: a wide aureole and a tighter halo.
            Vec3 up = mix(sky.horizon, sky.zenith, std::sqrt(std::max(d.y, 0.0)));
            const double c = std::max(dot(d, sun), 0.0);
            up = up + sky.sunGlow * (0.25 * std::pow(c, 4) + 0.75 * std::pow(c, 48));
            const Vec3 l = mix(sky.ground, up, smoothstep(-0.03, 0.03, d.y));
            float* p = &image.rgb[3 * (std::size_t(j) * width + i)];
            p[0] = float(l.x);
            p[1] = float(l.y);
            p[2] = float(l.z);
        }
    }
    return image;
}

LatLongImage readLatLongExr(const std::filesystem::path& path) {
    const std::string name = "environment file '" + path.string() + "'";
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw IoError(name + " does not exist or is not a file ([render] environment)");
    }
    LatLongImage image;
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        image.width = window.max.x - window.min.x + 1;
        image.height = window.max.y - window.min.y + 1;
        const Imf::ChannelList& channels = file.header().channels();
        for (const char* c : {"R", "G", "B"}) {
            if (!channels.findChannel(c)) {
                throw IoError(name + " has no " + c +
                              " channel (an RGB lat-long HDR image is expected)");
            }
        }
        if (image.width < 2 || image.height < 1 || image.width > 65536 || image.height > 32768) {
            throw IoError(name + " is " + std::to_string(image.width) + "x" +
                          std::to_string(image.height) + " pixels: not a lat-long image");
        }
        image.rgb.assign(std::size_t(3) * image.width * image.height, 0.0f);
        Imf::FrameBuffer buffer;
        const std::size_t xStride = 3 * sizeof(float), yStride = xStride * image.width;
        char* origin = reinterpret_cast<char*>(image.rgb.data()) -
                       (window.min.x * xStride + window.min.y * yStride);
        const char* names[] = {"R", "G", "B"};
        for (int c = 0; c < 3; ++c) {
            buffer.insert(names[c], Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), xStride,
                                               yStride, 1, 1, 0.0));
        }
        file.setFrameBuffer(buffer);
        file.readPixels(window.min.y, window.max.y);
    } catch (const IoError&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError(name + " cannot be read as OpenEXR: " + e.what());
    }
    for (float& v : image.rgb) {
        if (!std::isfinite(v)) {
            throw IoError(name + " holds a non-finite radiance (" + std::to_string(v) + ")");
        }
        v = std::max(v, 0.0f);  // lossy compression leaves tiny negatives around black
    }
    return image;
}

IrradianceSH irradianceSH(const LatLongImage& radiance) {
    IrradianceSH sum{};
    const int w = radiance.width, h = radiance.height;
    for (int j = 0; j < h; ++j) {
        const double theta = kPi * (j + 0.5) / h;
        const double solidAngle = (2 * kPi / w) * (kPi / h) * std::sin(theta);
        for (int i = 0; i < w; ++i) {
            const Vec3 d = latLongDirection((i + 0.5) / w, (j + 0.5) / h);
            const Vec3 l = radiance.at(i, j) * solidAngle;
            const double x = d.x, y = d.y, z = d.z;
            const double basis[9] = {0.282094792, 0.488602512 * y, 0.488602512 * z,
                                     0.488602512 * x, 1.092548431 * x * y, 1.092548431 * y * z,
                                     0.315391565 * (3 * z * z - 1), 1.092548431 * x * z,
                                     0.546274215 * (x * x - y * y)};
            for (int k = 0; k < 9; ++k) sum[k] = sum[k] + l * basis[k];
        }
    }
    // Convolution with the clamped cosine scales band l by A_l (pi, 2 pi / 3, pi / 4);
    // the basis functions' constants are folded in so evaluation is a plain polynomial.
    const double band[9] = {kPi, 2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4,
                            kPi / 4, kPi / 4, kPi / 4, kPi / 4};
    const double constant[9] = {0.282094792, 0.488602512, 0.488602512, 0.488602512, 1.092548431,
                                1.092548431, 0.315391565, 1.092548431, 0.546274215};
    IrradianceSH c;
    for (int k = 0; k < 9; ++k) c[k] = sum[k] * (band[k] * constant[k]);
    return c;
}

Vec3 evaluateIrradiance(const IrradianceSH& c, Vec3 n) {
    const double x = n.x, y = n.y, z = n.z;
    return c[0] + c[1] * y + c[2] * z + c[3] * x + c[4] * (x * y) + c[5] * (y * z) +
           c[6] * (3 * z * z - 1) + c[7] * (x * z) + c[8] * (x * x - y * y);
}

Vec3 PrefilteredCube::sample(Vec3 direction, double lod) const {
    const Vec3 d = normalized(direction);
    lod = std::clamp(lod, 0.0, double(levelCount() - 1));
    const int l0 = int(lod), l1 = std::min(l0 + 1, levelCount() - 1);
    const Vec3 a = sampleLevel(levels[l0], sizeOf(l0), d);
    return l1 == l0 ? a : mix(a, sampleLevel(levels[l1], sizeOf(l1), d), lod - l0);
}

PrefilteredCube prefilterGgx(const LatLongImage& radiance, int baseSize, int levelCount,
                             int samples) {
    // The source: the image on a cube (2x2 samples per texel) with a box-filtered mip chain.
    PrefilteredCube source;
    source.baseSize = baseSize;
    for (int l = 0; (baseSize >> l) >= 1; ++l) {
        const int size = baseSize >> l;
        std::vector<float> level(std::size_t(6) * size * size * 3);
        for (int f = 0; f < 6; ++f) {
            for (int j = 0; j < size; ++j) {
                for (int i = 0; i < size; ++i) {
                    Vec3 v{0, 0, 0};
                    if (l == 0) {
                        for (int k = 0; k < 4; ++k) {
                            const double s = (i + 0.25 + 0.5 * (k & 1)) / size;
                            const double t = (j + 0.25 + 0.5 * (k >> 1)) / size;
                            v = v + radiance.sample(cubeDirection(f, s, t)) * 0.25;
                        }
                    } else {
                        const std::vector<float>& up = source.levels[l - 1];
                        const int s2 = 2 * size;
                        for (int k = 0; k < 4; ++k) {
                            const std::size_t at =
                                ((std::size_t(f) * s2 + 2 * j + (k >> 1)) * s2 + 2 * i + (k & 1)) * 3;
                            v = v + Vec3{up[at], up[at + 1], up[at + 2]} * 0.25;
                        }
                    }
                    float* p = &level[((std::size_t(f) * size + j) * size + i) * 3];
                    p[0] = float(v.x);
                    p[1] = float(v.y);
                    p[2] = float(v.z);
                }
            }
        }
        source.levels.push_back(std::move(level));
    }
    PrefilteredCube out;
    out.baseSize = baseSize;
    out.levels.push_back(source.levels[0]);  // roughness 0: the mirror image
    const double texelSolidAngle = 4 * kPi / (6.0 * baseSize * baseSize);
    for (int l = 1; l < levelCount && (baseSize >> l) >= 1; ++l) {
        const int size = baseSize >> l;
        const double alpha = alphaOf(double(l) / (levelCount - 1));
        // Wider lobes on fewer texels: more samples each, the same work per level.
        const int count = std::min(samples << (2 * (l - 1)), 16 * samples);
        // Per sample, the source level whose texels are as large as the sample's share of
        // the lobe (Colbert and Krivanek 2007), one level blurrier (Karis 2013): few
        // samples then integrate a smooth image without sparkles.
        std::vector<LobeSample> lobe;
        std::vector<double> lods;
        double weightSum = 0;
        const Vec3 z{0, 0, 1};
        for (int k = 0; k < count; ++k) {
            const LobeSample s = ggxSample(z, alpha, k, count);
            if (s.nol <= 0) continue;
            const double pdf = ggx(s.noh, alpha) / 4;  // of l, with n = v
            const double sampleSolidAngle = 1 / (count * pdf + 1e-12);
            lods.push_back(std::max(0.5 * std::log2(sampleSolidAngle / texelSolidAngle) + 1, 0.0));
            lobe.push_back(s);
            weightSum += s.nol;
        }
        std::vector<float> level(std::size_t(6) * size * size * 3);
        for (int f = 0; f < 6; ++f) {
            for (int j = 0; j < size; ++j) {
                for (int i = 0; i < size; ++i) {
                    const Vec3 n = cubeDirection(f, (i + 0.5) / size, (j + 0.5) / size);
                    const Vec3 helper = std::abs(n.y) < 0.999 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
                    const Vec3 tx = normalized(cross(helper, n));
                    const Vec3 ty = cross(n, tx);
                    Vec3 v{0, 0, 0};
                    for (std::size_t k = 0; k < lobe.size(); ++k) {
                        const Vec3& d = lobe[k].l;  // about +z: rotate into n's frame
                        const Vec3 world = tx * d.x + ty * d.y + n * d.z;
                        v = v + source.sample(world, lods[k]) * lobe[k].nol;
                    }
                    v = v * (1 / weightSum);
                    float* p = &level[((std::size_t(f) * size + j) * size + i) * 3];
                    p[0] = float(v.x);
                    p[1] = float(v.y);
                    p[2] = float(v.z);
                }
            }
        }
        out.levels.push_back(std::move(level));
    }
    return out;
}

Vec3 ggxReference(const LatLongImage& radiance, Vec3 n, double roughness, int samples) {
    n = normalized(n);
    const double alpha = alphaOf(roughness);
    Vec3 sum{0, 0, 0};
    double weight = 0;
    for (int k = 0; k < samples; ++k) {
        const LobeSample s = ggxSample(n, alpha, k, samples);
        if (s.nol <= 0) continue;
        sum = sum + radiance.sample(s.l) * s.nol;
        weight += s.nol;
    }
    return sum * (1 / weight);
}

}  // namespace globular
