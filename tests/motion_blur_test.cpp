// Motion blur and depth of field by accumulating sub-frames (render/sub_frames.h):
// where the sub-frames fall, and what they do to a sphere's coverage (the alpha of a
// transparent background), against the analytic smear length and circle of confusion.
// Draws through OSMesa.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mesh_view.h"
#include "renderer.h"
#include "sub_frames.h"

namespace globular {
namespace {

// Odd sizes: the middle pixel's centre lies on the camera's axis.
constexpr int kWidth = 201, kHeight = 101;
constexpr double kFov = 60, kEyeDistance = 10;
constexpr double kFrameSeconds = 0.04;  // 25 fps

/// Pixels per unit of lateral offset per unit of depth.
double focalPixels() { return 0.5 * kHeight / std::tan(kFov * std::numbers::pi / 360); }

/// A camera on +z looking at the origin; no ground, no shadows; a transparent background,
/// so a pixel's alpha is the fraction of it (and of the shutter) the spheres cover.
FrameSetup setup() {
    FrameSetup s;
    s.camera = {{0, 0, kEyeDistance}, {0, 0, 0}, kFov};
    LightSettings light;
    light.direction = {0, 0, -1};
    light.shadows = false;
    s.lights = {light};
    s.render.ground = false;
    s.render.transparent = true;
    s.frameSeconds = kFrameSeconds;
    return s;
}

float alpha(const LinearFrame& f, int x, int y) { return f.pixel(x, y)[3]; }

/// Pixels of the middle row (along x) and middle column (along y) with any coverage.
int rowExtent(const LinearFrame& f) {
    int n = 0;
    for (int x = 0; x < f.width; ++x) n += alpha(f, x, f.height / 2) > 0.02f;
    return n;
}
int columnExtent(const LinearFrame& f) {
    int n = 0;
    for (int y = 0; y < f.height; ++y) n += alpha(f, f.width / 2, y) > 0.02f;
    return n;
}

/// Screen width, pixels, of a sphere of radius @p r centred @p x units off the axis at
/// depth @p d: between the tangents from the eye in the plane of the axis.
double projectedSpan(double x, double r, double d) {
    const double centre = std::atan2(x, d), half = std::asin(r / std::hypot(x, d));
    return focalPixels() * (std::tan(centre + half) - std::tan(centre - half));
}

TEST(SubFrames, OneUnlessMotionBlurOrApertureAskForMore) {
    RenderSettings r;
    r.motionSamples = 8;
    EXPECT_EQ(subFrames(r, kFrameSeconds).size(), 1u);
    r.motionBlur = true;
    EXPECT_EQ(subFrames(r, kFrameSeconds).size(), 8u);
    EXPECT_EQ(subFrames(r, 0).size(), 1u);  // no frame interval: nothing to smear over
    r.motionBlur = false;
    r.aperture = 0.1;
    EXPECT_EQ(subFrames(r, kFrameSeconds).size(), 8u);
}

TEST(SubFrames, TimesAreTheMidpointsOfTheShutterCentredOnTheFrame) {
    RenderSettings r;
    r.motionBlur = true;
    r.shutter = 0.5;
    r.motionSamples = 5;
    const std::vector<SubFrame> subs = subFrames(r, kFrameSeconds);
    EXPECT_EQ(subs.front().seconds, 0.0);  // the passes' sub-frame: the frame's instant
    std::vector<double> times;
    for (const SubFrame& s : subs) times.push_back(s.seconds);
    std::sort(times.begin(), times.end());
    const double open = 0.5 * kFrameSeconds;  // 0.02 s, from -0.01 to 0.01
    for (int k = 0; k < 5; ++k) EXPECT_NEAR(times[k], -0.5 * open + (k + 0.5) * open / 5, 1e-12);
}

TEST(SubFrames, LensPointsCoverTheApertureEvenly) {
    RenderSettings r;
    r.aperture = 2;
    r.motionSamples = 64;
    const std::vector<SubFrame> subs = subFrames(r, kFrameSeconds);
    double meanX = 0, meanY = 0, meanSquare = 0;
    for (const SubFrame& s : subs) {
        const double radius = std::hypot(s.lensX, s.lensY);
        EXPECT_LE(radius, 2.0);
        meanX += s.lensX / 64;
        meanY += s.lensY / 64;
        meanSquare += radius * radius / 64;
    }
    EXPECT_NEAR(meanX, 0, 0.05);
    EXPECT_NEAR(meanY, 0, 0.05);
    EXPECT_NEAR(meanSquare, 2.0, 1e-9);  // a uniform disc of radius R: R^2 / 2
    EXPECT_EQ(std::hypot(subs.front().lensX, subs.front().lensY), 0.0);  // the passes' one
}

TEST(SubFrames, ThroughLensAndItsShiftKeepThePlaneInFocusInRegister) {
    RenderSettings r;
    r.aperture = 1;
    r.focusDistance = 4;
    const ViewCamera camera{{0, 0, 10}, {0, 0, 0}, 40};
    const SubFrame sub{0, 0.5, -0.25};
    const ViewCamera moved = throughLens(camera, sub);
    EXPECT_NEAR(moved.position.x, 0.5, 1e-12);
    EXPECT_NEAR(moved.position.y, -0.25, 1e-12);
    EXPECT_NEAR(moved.position.z, 10, 1e-12);
    EXPECT_NEAR(moved.target.x - moved.position.x, 0, 1e-12);  // looking the same way
    EXPECT_NEAR(moved.target.y - moved.position.y, 0, 1e-12);
    constexpr double kFocal = 300;  // pixels
    const PixelShift shift = lensShift(camera, sub, r, kFocal, kFocal);
    // Any point of the plane 4 units ahead lands where the lens's centre sees it; one at
    // 12 units is off by lens * focal * (1/4 - 1/12).
    for (const Vec3 p : {Vec3{0, 0, 6}, Vec3{1.3, -0.7, 6}, Vec3{-2, 2, 6}, Vec3{3, 1, -2}}) {
        const double z = 10 - p.z;
        const double x = kFocal * (p.x - moved.position.x) / z + shift.x;
        const double y = kFocal * (p.y - moved.position.y) / z + shift.y;
        const double error = z == 4 ? 0 : kFocal * (1.0 / 4 - 1.0 / z);
        EXPECT_NEAR(x, kFocal * p.x / z + 0.5 * error, 1e-9) << p.x;
        EXPECT_NEAR(y, kFocal * p.y / z - 0.25 * error, 1e-9) << p.y;
    }
}

TEST(SubFrames, AddShiftedMovesAnImageBySubPixelAmounts) {
    LinearFrame f;
    f.width = 8;
    f.height = 6;
    f.rgba.assign(8 * 6 * 4, 0.0f);
    f.rgba[(std::size_t(2) * 8 + 3) * 4 + 3] = 1;  // one pixel at (3, 2)
    std::vector<float> sum(f.rgba.size(), 0.0f);
    addShifted(sum, f, {1.25, 1.0});  // right 1.25, up 1 (one row towards the top)
    EXPECT_FLOAT_EQ(sum[(std::size_t(1) * 8 + 4) * 4 + 3], 0.75f);
    EXPECT_FLOAT_EQ(sum[(std::size_t(1) * 8 + 5) * 4 + 3], 0.25f);
    float total = 0;
    for (std::size_t i = 3; i < sum.size(); i += 4) total += sum[i];
    EXPECT_FLOAT_EQ(total, 1.0f);
}

TEST(MotionBlur, SpreadsAMovingSphereAlongItsVelocityByTheShutterLength) {
    constexpr double kRadius = 1, kSpeed = 200;  // 4 units during the half-frame shutter
    constexpr int kSamples = 16;
    Globules g;
    g.add({0, 0, 0}, {kSpeed, 0, 0}, float(kRadius), 1, 0);
    FrameSetup s = setup();
    Renderer renderer(kWidth, kHeight, 4, 1024);
    renderer.drawSpheres(g, s);
    const LinearFrame sharp = renderer.lastFrame();
    s.render.motionBlur = true;
    s.render.shutter = 0.5;
    s.render.motionSamples = kSamples;
    renderer.drawSpheres(g, s);
    const LinearFrame& blurred = renderer.lastFrame();

    const double disc = projectedSpan(0, kRadius, kEyeDistance);
    EXPECT_NEAR(rowExtent(sharp), disc, 1.5);
    EXPECT_NEAR(columnExtent(sharp), disc, 1.5);
    // The sub-frames' centres span (N - 1) / N of the smear v * shutter / fps (each is the
    // midpoint of its slice), the first and last sphere's outer tangents bound it.
    const double travel = kSpeed * 0.5 * kFrameSeconds;  // 4 units: 35 pixels
    const double lastCentre = 0.5 * travel * (kSamples - 1) / kSamples;
    const double along = projectedSpan(lastCentre, kRadius, kEyeDistance) / 2 +
                         focalPixels() / kEyeDistance * lastCentre;
    EXPECT_NEAR(rowExtent(blurred), 2 * along, 2.0) << "analytic " << 2 * along;
    EXPECT_GT(rowExtent(blurred), disc + 0.8 * focalPixels() / kEyeDistance * travel);
    EXPECT_NEAR(columnExtent(blurred), disc, 1.5);  // across the velocity: unchanged
    // Coverage is conserved: the smear holds as much alpha as the sphere.
    double sharpSum = 0, blurredSum = 0;
    for (std::size_t i = 3; i < sharp.rgba.size(); i += 4) {
        sharpSum += sharp.rgba[i];
        blurredSum += blurred.rgba[i];
    }
    EXPECT_NEAR(blurredSum, sharpSum, 0.02 * sharpSum);
}

TEST(MotionBlur, VerticalVelocitySmearsVertically) {
    Globules g;
    g.add({0, 0, 0}, {0, -150, 0}, 1.0f, 1, 0);
    FrameSetup s = setup();
    s.render.motionBlur = true;
    s.render.motionSamples = 8;
    Renderer renderer(kWidth, kHeight, 4, 1024);
    renderer.drawSpheres(g, s);
    EXPECT_GT(columnExtent(renderer.lastFrame()), rowExtent(renderer.lastFrame()) + 15);
}

TEST(MotionBlur, LeavesAStillSphereUnchanged) {
    Globules g;
    g.add({0.3, -0.2, 0}, {0, 0, 0}, 1.5f, 1, 0);
    g.add({-3, 1, -2}, {0, 0, 0}, 1.0f, 1, 0);
    FrameSetup s = setup();
    s.render.transparent = false;
    s.render.ground = true;
    s.lights.front().shadows = true;
    s.lights.front().direction = {0.3, -1, -0.2};
    Renderer renderer(kWidth, kHeight, 4, 1024);
    const Image sharp = renderer.drawSpheres(g, s);
    s.render.motionBlur = true;
    s.render.motionSamples = 8;
    const Image blurred = renderer.drawSpheres(g, s);
    ASSERT_EQ(sharp.rgba.size(), blurred.rgba.size());
    int worst = 0;
    for (std::size_t i = 0; i < sharp.rgba.size(); ++i) {
        worst = std::max(worst, std::abs(int(sharp.rgba[i]) - int(blurred.rgba[i])));
    }
    EXPECT_LE(worst, 1);  // the average of identical sub-frames, to float rounding
}

TEST(MotionBlur, MovesAMeshAlongItsVerticesVelocities) {
    // A square 2 units wide facing the camera, moving right at 100 units/s: over a
    // half-frame shutter at 25 fps its sub-frames span 2 * 15/16 units more.
    const std::vector<float> positions{-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const std::vector<uint32_t> triangles{0, 1, 2, 0, 2, 3};
    const std::vector<float> vx(4, 100.0f), still(4, 0.0f);
    MeshView mesh{positions.data(), nullptr, 4, triangles.data(), 2, false};
    FrameSetup s = setup();
    Renderer renderer(kWidth, kHeight, 4, 1024);
    renderer.drawMesh(mesh, s);
    const LinearFrame sharp = renderer.lastFrame();
    s.render.motionBlur = true;
    s.render.motionSamples = 16;
    renderer.drawMesh(mesh, s);  // no velocities: sharp
    EXPECT_EQ(rowExtent(renderer.lastFrame()), rowExtent(sharp));
    mesh.vx = vx.data();
    mesh.vy = mesh.vz = still.data();
    renderer.drawMesh(mesh, s);
    const double pixelsPerUnit = focalPixels() / kEyeDistance;
    const double side = 2 * pixelsPerUnit;
    EXPECT_NEAR(rowExtent(sharp), side, 2);  // and a partly covered pixel at each edge
    EXPECT_NEAR(rowExtent(renderer.lastFrame()) - rowExtent(sharp),
                2.0 * 15 / 16 * pixelsPerUnit, 1.5);
    EXPECT_NEAR(columnExtent(renderer.lastFrame()), columnExtent(sharp), 1);
}

TEST(MotionBlur, SmearsTheFluidModesLiquidAlongItsVelocity) {
    // A blob of 7 globules moving right at 100 units/s: 2 units over a half-frame shutter
    // at 25 fps.
    Globules g;
    for (int k = -3; k <= 3; ++k) g.add({0.4 * k, 0, 0}, {100, 0, 0}, 1.0f, 1, k + 3);
    FrameSetup s = setup();
    s.render.mode = "fluid";
    Renderer renderer(kWidth, kHeight, 4, 1024);
    renderer.drawFluid(g, s);
    const LinearFrame sharp = renderer.lastFrame();
    s.render.motionBlur = true;
    s.render.motionSamples = 16;
    renderer.drawFluid(g, s);
    // The liquid's edges fade (fluid_pass.h), so compare the alpha's second moment along
    // x rather than its extent: the smear adds the variance of the sub-frames' offsets,
    // N midpoints over a travel L: L^2 (N^2 - 1) / (12 N^2).
    auto varianceX = [](const LinearFrame& f) {
        double sum = 0, sx = 0, sxx = 0;
        for (int y = 0; y < f.height; ++y) {
            for (int x = 0; x < f.width; ++x) {
                const double a = alpha(f, x, y);
                sum += a;
                sx += a * x;
                sxx += a * double(x) * x;
            }
        }
        return sxx / sum - (sx / sum) * (sx / sum);
    };
    const double travel = 2.0 * focalPixels() / kEyeDistance;  // pixels
    const double expected = travel * travel * (16.0 * 16 - 1) / (12 * 16 * 16);
    ASSERT_GT(rowExtent(sharp), 20);
    EXPECT_NEAR(varianceX(renderer.lastFrame()) - varianceX(sharp), expected, 0.1 * expected);
    EXPECT_NEAR(columnExtent(renderer.lastFrame()), columnExtent(sharp), 2);
}

/// The second moment of the alpha about its centroid (x and y together), pixels^2, over
/// columns [x0, x1).
double spread(const LinearFrame& f, int x0, int x1) {
    double sum = 0, sx = 0, sy = 0, sxx = 0;
    for (int y = 0; y < f.height; ++y) {
        for (int x = x0; x < x1; ++x) {
            const double a = alpha(f, x, y);
            sum += a;
            sx += a * x;
            sy += a * y;
            sxx += a * (double(x) * x + double(y) * y);
        }
    }
    return sxx / sum - (sx * sx + sy * sy) / (sum * sum);
}

TEST(DepthOfField, KeepsThePlaneInFocusSharpAndBlursAFarSphereByItsCircleOfConfusion) {
    constexpr double kAperture = 1.5, kFar = 30;  // focus on the target, 10 units away
    Globules g;
    g.add({0, 0, 0}, {0, 0, 0}, 0.5f, 1, 0);                         // in focus
    g.add({-12, 0, float(kEyeDistance - kFar)}, {0, 0, 0}, 2.0f, 1, 0);  // 30 units away
    FrameSetup s = setup();
    Renderer renderer(kWidth, kHeight, 4, 1024);
    renderer.drawSpheres(g, s);
    const LinearFrame sharp = renderer.lastFrame();
    s.render.aperture = kAperture;
    s.render.motionSamples = 32;
    renderer.drawSpheres(g, s);
    const LinearFrame& blurred = renderer.lastFrame();

    // Far sphere near x = 100 - 35; the one in focus at x = 100.
    const double focusSharp = spread(sharp, 85, kWidth), focusBlurred = spread(blurred, 85, kWidth);
    EXPECT_NEAR(focusBlurred, focusSharp, 0.05 * focusSharp);
    // Each lens point shifts the far sphere by f * lens * (z - focus) / (focus * z) pixels:
    // the image is the sharp one convolved with those shifts, whose second moment adds.
    double lensMoment = 0;
    for (const SubFrame& sub : subFrames(s.render, kFrameSeconds)) {
        lensMoment += (sub.lensX * sub.lensX + sub.lensY * sub.lensY) / 32;
    }
    const double scale = focalPixels() * (kFar - kEyeDistance) / (kEyeDistance * kFar);
    const double expected = scale * scale * lensMoment;  // circle of confusion: 8.7 px radius
    const double added = spread(blurred, 0, 85) - spread(sharp, 0, 85);
    EXPECT_NEAR(added, expected, 0.03 * expected) << "circle of confusion radius "
                                                 << scale * kAperture << " pixels";
}

}  // namespace
}  // namespace globular
