#include "renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "color_ramp.h"
#include "environment_light.h"
#include "errors.h"
#include "frame_target.h"
#include "gl_context.h"
#include "gl_objects.h"
#include "ground_pass.h"
#include "fluid_pass.h"
#include "liquid_mesh_pass.h"
#include "mesh_pass.h"
#include "occlusion_pass.h"
#include "occlusion_region.h"
#include "shadow_map.h"
#include "sphere_pass.h"
#include "sub_frames.h"
#include "tone_map.h"

namespace globular {

using detail::FrameUniforms;

namespace {

/// Whether a frame's content is drawn as a liquid (it has liquid() and says so).
template <typename Content>
bool isLiquid(const Content& content) {
    if constexpr (requires { content.liquid(); }) {
        return content.liquid();
    } else {
        return false;
    }
}

/// The content box, reaching down to the ground so shadows on it fall inside the map.
Bounds3 withGround(Bounds3 box, double groundHeight) {
    if (box.empty) {
        box.add(Vec3{-2, groundHeight, -2});
        box.add(Vec3{2, groundHeight + 1, 2});
    }
    box.add(Vec3{box.min.x, groundHeight, box.min.z});
    return box;
}

/// The ground's fade, measured from the content's centre: it starts beyond the content
/// and ends well behind it, so the horizon is a soft blend, never a hard edge.
detail::GroundLook groundLook(const FrameSetup& s, const Bounds3& box) {
    detail::GroundLook look;
    const double radius = std::max(box.radius(), 1e-3);
    const double toCamera = length(s.camera.position - s.camera.target);
    look.height = s.groundHeight;
    look.center = box.center();
    look.fadeStart = 1.2 * radius + 0.3 * toCamera;
    look.fadeEnd = 3.0 * radius + 1.5 * toCamera;
    look.checkerSize = s.render.checkerSize > 0 ? s.render.checkerSize : automaticCheckerSize(box);
    look.color = srgbToLinear(s.render.groundColor);
    look.background = srgbToLinear(s.render.background);
    look.backgroundAlpha = s.render.transparent ? 0 : 1;
    return look;
}

/// The far half of a see-through prop, seen from @p eye: its walls on the camera's side
/// of the vertical plane through its middle are left out (its floor and roof stay), so
/// what it contains shows, and what is left is drawn two-sided.
TriangleMesh cutaway(const TriangleMesh& mesh, Vec3 eye) {
    Bounds3 box;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        box.add(Vec3{mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]});
    }
    const Vec3 middle = box.center();
    const Vec3 toEye = normalized(Vec3{eye.x - middle.x, 0, eye.z - middle.z});
    TriangleMesh far = mesh;
    far.triangles.clear();
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        Vec3 centroid{0, 0, 0}, normal{0, 0, 0};
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = mesh.triangles[3 * t + k];
            centroid = centroid + (1.0 / 3) * Vec3{mesh.positions[3 * v], mesh.positions[3 * v + 1],
                                                   mesh.positions[3 * v + 2]};
            normal = normal + Vec3{mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]};
        }
        const bool horizontal = std::abs(normalized(normal).y) > 0.7;
        if (horizontal || dot(centroid - middle, toEye) < 0) {
            far.triangles.insert(far.triangles.end(), mesh.triangles.begin() + 3 * t,
                                 mesh.triangles.begin() + 3 * t + 3);
        }
    }
    return far;
}

/// What the spheres' colour ramp reads for @p colorBy.
/// @throw Error for color_by = temperature when the globules carry none.
detail::SpherePass::Value sphereValue(const Globules& globules, const std::string& colorBy) {
    using Value = detail::SpherePass::Value;
    if (colorBy == "temperature" && globules.temperature.size() != globules.size()) {
        throw Error("render: color_by = \"temperature\" but the globules carry no temperature "
                    "(the scene has no [thermal] section)");
    }
    return colorBy == "speed"         ? Value::Speed
           : colorBy == "material"    ? Value::Material
           : colorBy == "temperature" ? Value::Temperature
                                      : Value::None;
}

}  // namespace

double automaticCheckerSize(const Bounds3& content) {
    const double target = std::max(content.empty ? 1.0 : content.radius(), 1e-6) / 6.0;
    const double decade = std::pow(10.0, std::floor(std::log10(target)));
    double best = decade;
    for (double step : {1.0, 2.0, 5.0, 10.0}) {
        if (std::abs(std::log(step * decade / target)) < std::abs(std::log(best / target))) {
            best = step * decade;
        }
    }
    return best;
}

struct Renderer::Impl {
    int width, height, samples;
    detail::FrameTarget target;
    detail::ShadowMap shadowMap;
    std::optional<detail::SpherePass> spheres;  // built on first use: a mesh-only run
    std::optional<detail::MeshPass> mesh;       // compiles no sphere shaders, and so on
    std::optional<detail::FluidPass> fluid;     // the liquid look (below)
    std::optional<detail::LiquidMeshPass> liquidMesh;
    std::vector<detail::MeshPass> props;        // one per prop of the set
    detail::GroundPass ground;
    detail::EnvironmentLight environment;
    std::optional<detail::OcclusionPass> occlusion;
    LinearFrame frame;
    bool culling = true;
    bool occlusionRegions = true;
    GlBackend backend = GlBackend::OSMesa;  // its GL objects live in this back end's context

    Impl(int w, int h, int n, int shadowSize, bool passes)
        : width(w), height(h), samples(n), target(w, h, n, passes), shadowMap(shadowSize) {}

    FrameUniforms uniforms(const FrameSetup& s, const Bounds3& box, double groundReach) const {
        FrameUniforms f;
        const ViewCamera& cam = s.camera;
        const DepthRange depth = depthRange(cam.position, box, groundReach);
        const double aspect = double(width) / height;
        const double tanHalf = std::tan(cam.fov * std::numbers::pi / 360.0);
        f.width = width;
        f.height = height;
        f.view = lookAt(cam.position, cam.target);
        f.viewProj = perspective(cam.fov, aspect, depth.zNear, depth.zFar) * f.view;
        f.eye = cam.position;
        const Mat4& v = f.view;  // rows: right, up, backwards
        f.camRight = Vec3{v(0, 0), v(0, 1), v(0, 2)} * (tanHalf * aspect);
        f.camUp = Vec3{v(1, 0), v(1, 1), v(1, 2)} * tanHalf;
        f.camForward = Vec3{-v(2, 0), -v(2, 1), -v(2, 2)};
        f.zNear = float(depth.zNear);
        f.zFar = float(depth.zFar);
        f.pixelAngle = float(2.0 * tanHalf / height);
        f.focalPixels[0] = float(0.5 * width / (tanHalf * aspect));
        f.focalPixels[1] = float(0.5 * height / tanHalf);
        for (const LightSettings& light : s.lights) {
            f.lightToward.push_back(normalized(-1.0 * light.direction));
            f.lightRadiance.push_back(srgbToLinear(light.color) * light.intensity);
        }
        f.specular = float(s.render.specular);
        f.shadowed = !s.lights.empty() && s.lights.front().shadows;
        if (f.shadowed) {
            // An orthographic view along the key light around the content's bounding
            // sphere, deep enough to reach the ground behind the tallest content.
            const Vec3 center = box.center();
            const double radius = std::max(box.radius(), 1e-3);
            const Vec3 toward = f.lightToward.front();
            const Mat4 view = lookAt(center + toward * (2.0 * radius), center);
            const double reach = 3.0 * radius + 2.0 * radius / std::max(std::abs(toward.y), 0.05);
            f.lightViewProj =
                orthographic(-radius, radius, -radius, radius, 0.5 * radius, reach) * view;
            f.lightRight = {view(0, 0), view(0, 1), view(0, 2)};
            f.lightUp = {view(1, 0), view(1, 1), view(1, 2)};
            const double pixelWorld = f.pixelAngle * length(cam.position - center);
            f.shadowMapSize = shadowMap.sizeFor(2.0 * radius, pixelWorld);
            f.texelsPerUnit = float(f.shadowMapSize / (2.0 * radius));
            f.shadowTexel = 1.0f / f.texelsPerUnit;
            f.shadowBias = float(0.5 * f.shadowTexel / (reach - 0.5 * radius));
        }
        const std::string& by = s.render.colorBy;
        f.colorMode = by == "speed"         ? 1
                      : by == "height"      ? 2
                      : by == "material"    ? 3
                      : by == "temperature" ? 4
                                            : 0;
        f.baseColor = srgbToLinear(s.render.color);
        for (std::size_t k = 0; k < f.palette.size(); ++k) {
            f.palette[k] = k < s.materialColors.size() ? srgbToLinear(s.materialColors[k])
                                                       : f.baseColor;
        }
        // Temperature has its own fixed range: a hot and a cold frame must look so.
        f.rampMin = float(f.colorMode == 4 ? s.render.temperatureLow : s.ramp.min);
        f.rampMax = float(f.colorMode == 4 ? s.render.temperatureHigh : s.ramp.max);
        return f;
    }

    /// The image-based light (prepared once per environment and bound), the materials'
    /// roughness and metallic, and the shadow's softness.
    void light(FrameUniforms& f, const FrameSetup& s) {
        SkyLook sky;
        const LightSettings key = s.lights.empty() ? LightSettings{} : s.lights.front();
        sky.sunToward = normalized(-1.0 * key.direction);
        // Below the horizon: the floor lit by the sun and the sky, seen from above.
        const Vec3 sun = srgbToLinear(key.color) * key.intensity;
        const Vec3 floor = s.render.ground ? srgbToLinear(s.render.groundColor) : Vec3{0.3, 0.3, 0.3};
        const double lit = std::max(sky.sunToward.y, 0.0);
        sky.ground = {floor.x * (sun.x * lit + 0.4), floor.y * (sun.y * lit + 0.4),
                      floor.z * (sun.z * lit + 0.4)};
        if (s.render.environmentIntensity > 0) environment.prepare(s.render.environment, sky);
        environment.bind();
        f.irradianceSH = environment.irradiance();
        f.environmentMaxLod = environment.maxLod();
        f.environmentIntensity = float(s.render.environmentIntensity);
        f.shadowSoftness = float(s.render.shadowSoftness);
        for (std::size_t k = 0; k < f.roughness.size(); ++k) {
            const SurfaceLook look = k < s.materialLooks.size() ? s.materialLooks[k] : SurfaceLook{};
            f.roughness[k] = float(look.roughness);
            f.metallic[k] = float(look.metallic);
            f.subsurface[k] = float(look.subsurface);
        }
    }

    /// Screen-space ambient occlusion over what is drawn so far: the props, and
    /// @p content unless it is a liquid (drawn after), occlude; the ground does not.
    template <typename Content>
    void occlude(const FrameUniforms& f, const FrameSetup& s, const Bounds3& box,
                 const Content& content) {
        if (!(s.render.ambientOcclusion > 0)) return;
        if (!occlusion) occlusion.emplace(samples);
        const double radius = s.render.occlusionRadius > 0 ? s.render.occlusionRadius
                                                           : std::max(box.radius(), 1e-3) / 30;
        // Only around the occluders: over the whole frame the pass was a quarter of an
        // opaque mesh frame (docs/performance.md, twenty-fourth pass).
        detail::OcclusionRegion region(f, radius);
        if (!occlusionRegions) region.addEverything();
        if (!isLiquid(content)) {
            if constexpr (requires { content.addOccluders(region); }) {
                content.addOccluders(region);
            } else {
                region.addEverything();
            }
        }
        for (const Prop& prop : s.props) {
            const TriangleMesh& m = prop.mesh;
            region.addTriangles(m.positions.data(), m.vertexCount(), m.triangles.data(),
                                m.triangleCount());
        }
        const auto rects = region.whole() ? std::nullopt : std::optional(region.rects());
        occlusion->apply(f, target, float(radius), float(s.render.ambientOcclusion), rects);
    }

    /// The motion pass's interval: spheres only, with passes.
    static float motionSeconds(const FrameSetup& s, bool spheres, bool passes) {
        return spheres && passes && s.frameSeconds > 0 ? float(s.frameSeconds) : 0.0f;
    }

    /// Draws the frame of @p s as the average of its sub-frames (sub_frames.h) into
    /// `frame`. @p drawSub(setup, seconds, passes) draws one sub-frame into `frame` with
    /// the content moved on by @p seconds, reading the passes back when @p passes.
    template <typename DrawSub>
    void accumulate(const FrameSetup& s, DrawSub&& drawSub) {
        const std::vector<SubFrame> subs = subFrames(s.render, s.frameSeconds);
        if (subs.size() == 1) {
            drawSub(s, subs.front().seconds, true);
        } else {
            LinearFrame sum;
            const double tanHalf = std::tan(s.camera.fov * std::numbers::pi / 360.0);
            const double focalX = 0.5 * height / tanHalf, focalY = focalX;  // square pixels
            for (std::size_t k = 0; k < subs.size(); ++k) {
                FrameSetup sub = s;
                sub.camera = throughLens(s.camera, subs[k]);
                drawSub(sub, subs[k].seconds, k == 0);
                const PixelShift shift = lensShift(s.camera, subs[k], s.render, focalX, focalY);
                if (k == 0) {
                    sum = frame;  // the passes come from the first sub-frame
                    if (shift.x != 0 || shift.y != 0) {
                        std::fill(sum.rgba.begin(), sum.rgba.end(), 0.0f);
                        addShifted(sum.rgba, frame, shift);
                    }
                } else if (shift.x != 0 || shift.y != 0) {
                    addShifted(sum.rgba, frame, shift);
                } else {
                    for (std::size_t i = 0; i < sum.rgba.size(); ++i) sum.rgba[i] += frame.rgba[i];
                }
            }
            const float weight = 1.0f / float(subs.size());
            for (float& v : sum.rgba) v *= weight;
            frame = std::move(sum);
        }
    }

    /// Draws one (sub-)frame into `frame`: @p content has prepare(f), shadow(f) and
    /// draw(f) members. Without @p passes only the colour is read back (a later sub-frame:
    /// `frame` keeps the first one's passes).
    template <typename Content>
    void draw(const FrameSetup& s, const Bounds3& frameBox, Content&& content, bool passes) {
        const Bounds3 box = withGround(s.content.empty ? frameBox : s.content, s.groundHeight);
        const detail::GroundLook look = groundLook(s, box);
        FrameUniforms f = uniforms(s, box, look.fadeEnd);
        light(f, s);
        f.frameSeconds = motionSeconds(s, content.spheres(), target.passes());
        content.prepare(f);
        while (props.size() < s.props.size()) props.emplace_back(samples);
        for (std::size_t k = 0; k < s.props.size(); ++k) {
            const TriangleMesh m = s.props[k].seeThrough ? cutaway(s.props[k].mesh, s.camera.position)
                                                         : s.props[k].mesh;
            props[k].upload({m.positions.data(), m.normals.data(), m.vertexCount(),
                             m.triangles.data(), m.triangleCount(), true, nullptr});
        }
        FrameUniforms grey = f;  // the set in a neutral light grey, whatever colours the content
        grey.colorMode = 0;
        grey.baseColor = srgbToLinear(Vec3{0.78, 0.78, 0.76});
        grey.roughness.fill(0.5f);  // and a satin dielectric
        grey.metallic.fill(0.0f);
        grey.subsurface.fill(0.0f);

        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);
        glDisable(GL_BLEND);
        std::optional<detail::GroundRect> groundShadow = detail::GroundRect{};  // none
        if (f.shadowed) {
            shadowMap.beginDrawing(f.shadowMapSize);
            content.shadow(f);
            for (std::size_t k = 0; k < s.props.size(); ++k) {
                if (!s.props[k].seeThrough) props[k].drawShadow(f, detail::MeshPass::Cull::Back);
            }
            // The ground's shadow filter was a fifth of a liquid frame, over a floor mostly
            // out of every shadow's reach (docs/performance.md, twenty-first pass).
            if (s.render.ground) {
                groundShadow = detail::groundShadowRegion(f, shadowMap.drawnTexels(), s.groundHeight);
            }
        }
        target.bindAndClear(srgbToLinear(s.render.background), s.render.transparent ? 0 : 1);
        shadowMap.bindForSampling();
        // Content first: the ground behind it is then rejected before shading. A liquid
        // last, as it refracts what lies behind it.
        if (!isLiquid(content)) content.draw(f);
        for (std::size_t k = 0; k < s.props.size(); ++k) {
            using Cull = detail::MeshPass::Cull;
            props[k].draw(grey, target, s.props[k].seeThrough ? Cull::None : Cull::Back);
        }
        if (s.render.ground) ground.draw(f, look, groundShadow);
        // A liquid is drawn after the occlusion: without props the depth buffer then holds
        // the ground alone, a plane, which nothing occludes (every tap lies above it), so
        // the pass would leave the frame as it was (without it 238 of the pour's 240 frames
        // are byte-identical; the other two lose one pixel near the horizon that it darkened
        // by 1-3 levels of 255). It cost a fifth of the pour's 1920x1080 liquid frames on
        // llvmpipe (docs/performance.md, seventeenth pass).
        if (!isLiquid(content) || !s.props.empty()) occlude(f, s, box, content);
        if (isLiquid(content)) content.draw(f);
        target.read(frame, f.frameSeconds > 0, passes);
        gl::checkErrors("drawing a frame");
    }

    void drawFluid(const Globules& globules, const FrameSetup& s);
    void drawLiquidMesh(const MeshView& mesh, const FrameSetup& s);
};

Renderer::Renderer(int width, int height, int samples, int shadowMapSize, bool passes) {
    if (width <= 0 || height <= 0) throw Error("render: the image size must be positive");
    const GlBackend backend = selectedGlBackend();
    makeGlContextCurrent(backend);
    GLint maxSamples = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    if (samples < 1 || samples > maxSamples) {
        throw Error("render: " + std::to_string(samples) +
                    " samples per pixel requested; this OpenGL driver supports 1 to " +
                    std::to_string(maxSamples) + " (set [render] samples)");
    }
    mImpl = std::make_unique<Impl>(width, height, samples, shadowMapSize, passes);
    mImpl->backend = backend;
}

Renderer::~Renderer() {
    // Its GL objects are deleted in the context that holds them.
    try {
        if (mImpl) makeGlContextCurrent(mImpl->backend);
    } catch (const std::exception&) {
    }
}

namespace {

Image encoded(const LinearFrame& frame, const FrameSetup& setup) {
    return encode8(frame, ToneMapping::from(setup.render.exposure, setup.render.toneMapping));
}

}  // namespace

Image Renderer::drawSpheres(const Globules& globules, const FrameSetup& setup) {
    renderSpheres(globules, setup);
    return encoded(lastFrame(), setup);
}

Image Renderer::drawMesh(const MeshView& mesh, const FrameSetup& setup) {
    renderMesh(mesh, setup);
    return encoded(lastFrame(), setup);
}

Image Renderer::drawFluid(const Globules& globules, const FrameSetup& setup) {
    renderFluid(globules, setup);
    return encoded(lastFrame(), setup);
}

void Renderer::renderSpheres(const Globules& globules, const FrameSetup& setup) {
    makeGlContextCurrent(mImpl->backend);
    Impl& im = *mImpl;
    if (!im.spheres) im.spheres.emplace(im.samples);
    im.spheres->setCulling(im.culling);
    FrameSetup s = setup;
    SceneExtent own;
    if (s.content.empty || (s.render.colorBy != "constant" && s.ramp.empty)) {
        own.addFrame(globules);
    }
    if (s.ramp.empty) s.ramp = s.render.colorBy == "speed" ? own.speed : own.height;
    struct Content {
        detail::SpherePass& pass;
        const detail::FrameTarget& target;
        const Globules& globules;
        detail::SpherePass::Value value;
        bool spheres() const { return true; }
        void addOccluders(detail::OcclusionRegion& region) const { region.addSpheres(globules); }
        void prepare(const FrameUniforms& f) { pass.upload(globules, value, f); }
        void shadow(const FrameUniforms& f) { pass.drawShadow(f); }
        void draw(const FrameUniforms& f) {
            pass.drawVisibility(f, target);
            pass.drawShading(f, target);
        }
    };
    const detail::SpherePass::Value value = sphereValue(globules, s.render.colorBy);
    im.accumulate(s, [&](const FrameSetup& sub, double seconds, bool passes) {
        if (seconds == 0) {
            im.draw(sub, own.box, Content{*im.spheres, im.target, globules, value}, passes);
        } else {
            const Globules moved = movedBy(globules, seconds);
            im.draw(sub, own.box, Content{*im.spheres, im.target, moved, value}, passes);
        }
    });
}

void Renderer::renderMesh(const MeshView& mesh, const FrameSetup& setup) {
    makeGlContextCurrent(mImpl->backend);
    Impl& im = *mImpl;
    if (setup.liquidSurface) {
        im.drawLiquidMesh(mesh, setup);
        return;
    }
    if (!im.mesh) im.mesh.emplace(im.samples);
    FrameSetup s = setup;
    if (s.render.colorBy == "temperature" && !mesh.values && mesh.vertexCount > 0) {
        throw Error("render: color_by = \"temperature\" but the mesh carries no per-vertex "
                    "temperature");
    }
    SceneExtent own;
    if (s.content.empty || (s.render.colorBy != "constant" && s.ramp.empty)) {
        own.addPoints(mesh.positions, mesh.vertexCount);
    }
    if (s.ramp.empty) s.ramp = own.height;
    struct Content {
        detail::MeshPass& pass;
        const detail::FrameTarget& target;
        const MeshView& mesh;
        bool spheres() const { return false; }
        void addOccluders(detail::OcclusionRegion& region) const {
            region.addTriangles(mesh.positions, mesh.vertexCount, mesh.triangles,
                                mesh.triangleCount);
        }
        void prepare(const FrameUniforms&) { pass.upload(mesh); }
        void shadow(const FrameUniforms& f) {
            using Cull = detail::MeshPass::Cull;
            pass.drawShadow(f, mesh.closed ? Cull::Back : Cull::None);
        }
        void draw(const FrameUniforms& f) {
            using Cull = detail::MeshPass::Cull;
            pass.draw(f, target, mesh.closed ? Cull::Back : Cull::None);
        }
    };
    std::vector<float> moved;  // the sub-frame's positions, when the mesh has velocities
    im.accumulate(s, [&](const FrameSetup& sub, double seconds, bool passes) {
        const MeshView view = movedBy(mesh, seconds, moved);
        im.draw(sub, own.box, Content{*im.mesh, im.target, view}, passes);
    });
}

void Renderer::renderFluid(const Globules& globules, const FrameSetup& setup) {
    makeGlContextCurrent(mImpl->backend);
    mImpl->drawFluid(globules, setup);
}

namespace {

/// Where a liquid's refracted rays end.
detail::LiquidLook liquidLook(const FrameSetup& s) {
    return {opticsOf(s.materialOptics, 0).ior, s.render.ground, s.groundHeight};
}

/// The globules of materials drawn opaque (spheres among the liquid), none when all are
/// liquid.
Globules opaqueGlobules(const Globules& g, const std::vector<LiquidOptics>& optics) {
    Globules opaque;
    const bool any = std::any_of(optics.begin(), optics.end(),
                                 [](const LiquidOptics& o) { return !o.liquid; });
    if (!any) return opaque;
    std::vector<uint32_t> keep;
    for (std::size_t i = 0; i < g.size(); ++i) {
        if (!opticsOf(optics, g.materialOf(i)).liquid) keep.push_back(uint32_t(i));
    }
    auto pick = [&](const auto& from, auto& into) {
        if (from.size() != g.size()) return;
        into.reserve(keep.size());
        for (uint32_t i : keep) into.push_back(from[i]);
    };
    pick(g.px, opaque.px);
    pick(g.py, opaque.py);
    pick(g.pz, opaque.pz);
    pick(g.vx, opaque.vx);
    pick(g.vy, opaque.vy);
    pick(g.vz, opaque.vz);
    pick(g.radius, opaque.radius);
    pick(g.mass, opaque.mass);
    pick(g.id, opaque.id);
    pick(g.material, opaque.material);
    pick(g.temperature, opaque.temperature);
    return opaque;
}

}  // namespace

void Renderer::Impl::drawFluid(const Globules& globules, const FrameSetup& setup) {
    if (!fluid) fluid.emplace();
    FrameSetup s = setup;
    SceneExtent own;
    if (s.content.empty || (s.render.colorBy != "constant" && s.ramp.empty)) own.addFrame(globules);
    if (s.ramp.empty) s.ramp = s.render.colorBy == "speed" ? own.speed : own.height;
    detail::FluidLook look{liquidLook(s), s.materialOptics, s.render.fluidSmoothing};
    struct Content {
        Impl& im;
        const Globules& globules;
        const Globules& opaque;  // drawn as spheres, behind the liquid's refraction
        const detail::FluidLook& look;
        detail::SpherePass::Value value;  // the opaque spheres' colour by color_by
        bool spheres() const { return true; }  // globules: they have a motion pass
        bool liquid() const { return true; }
        void prepare(const FrameUniforms& f) {
            im.fluid->upload(globules, f.frameSeconds > 0);
            if (!opaque.empty()) im.spheres->upload(opaque, value, f);
        }
        void shadow(const FrameUniforms& f) {
            im.fluid->drawShadow(f);
            if (!opaque.empty()) im.spheres->drawShadow(f);
        }
        void draw(const FrameUniforms& f) {
            if (!opaque.empty()) {
                im.spheres->drawVisibility(f, im.target);
                im.spheres->drawShading(f, im.target);
            }
            im.fluid->draw(f, look);
        }
    };
    const Globules opaque = opaqueGlobules(globules, s.materialOptics);
    if (!opaque.empty() && !spheres) spheres.emplace(samples);
    const detail::SpherePass::Value value = sphereValue(opaque, s.render.colorBy);
    if (spheres) spheres->setCulling(culling);
    accumulate(s, [&](const FrameSetup& sub, double seconds, bool passes) {
        if (seconds == 0) {
            draw(sub, own.box, Content{*this, globules, opaque, look, value}, passes);
        } else {
            const Globules moved = movedBy(globules, seconds);
            const Globules movedOpaque = movedBy(opaque, seconds);
            draw(sub, own.box, Content{*this, moved, movedOpaque, look, value}, passes);
        }
    });
}

void Renderer::Impl::drawLiquidMesh(const MeshView& mesh, const FrameSetup& setup) {
    if (!liquidMesh) liquidMesh.emplace(samples);
    FrameSetup s = setup;
    SceneExtent own;
    if (s.content.empty) own.addPoints(mesh.positions, mesh.vertexCount);
    struct Content {
        detail::LiquidMeshPass& pass;
        const detail::FrameTarget& target;
        const MeshView& mesh;
        detail::LiquidLook look;
        LiquidOptics optics;
        bool spheres() const { return false; }
        bool liquid() const { return true; }
        void prepare(const FrameUniforms&) { pass.upload(mesh); }
        void shadow(const FrameUniforms& f) { pass.drawShadow(f); }
        void draw(const FrameUniforms& f) { pass.draw(f, target, look, optics); }
    };
    std::vector<float> moved;  // the sub-frame's positions, when the mesh has velocities
    accumulate(s, [&](const FrameSetup& sub, double seconds, bool passes) {
        const MeshView view = movedBy(mesh, seconds, moved);
        draw(sub, own.box,
             Content{*liquidMesh, target, view, liquidLook(s), opticsOf(s.materialOptics, 0)}, passes);
    });
}

void Renderer::setOcclusionCulling(bool on) { mImpl->culling = on; }
void Renderer::setOcclusionRegions(bool on) { mImpl->occlusionRegions = on; }

const LinearFrame& Renderer::lastFrame() const { return mImpl->frame; }

void Renderer::takeFrame(LinearFrame& frame) { std::swap(frame, mImpl->frame); }

int Renderer::width() const { return mImpl->width; }
int Renderer::height() const { return mImpl->height; }
int Renderer::samples() const { return mImpl->samples; }

}  // namespace globular
