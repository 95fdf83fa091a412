// Render benchmarks: time per frame at 1280x720 and 1920x1080 for 1e3, 1e5 and 1e6 sphere
// globules (renderBenchPour) and for meshes of 1e5 and 1e6 triangles (renderBenchBlob),
// plus the PNG encoding of a frame, a full-HD frame written with and without its EXR
// (BM_FrameOutput), 1e6 spheres without occlusion culling, and frames without the
// image-based light, ambient occlusion and soft shadows (*PlainLight). A frame is
// upload, culling, shadow map, drawing, resolve, read-back and sRGB encoding: everything
// runRenderStage does per frame but reading the cache and writing the PNG. The GL context
// and shaders are made before timing.
// Not part of ctest; the 1e6 cases take seconds each:
//   build/bench/render_bench --benchmark_filter=Spheres/n:1000000
#include <benchmark/benchmark.h>

#include <ctime>
#include <filesystem>

#include "camera.h"
#include "exr_image.h"
#include "gl_context.h"
#include "png_image.h"
#include "render_bench_scene.h"
#include "renderer.h"
#include "tone_map.h"

namespace globular {
namespace {

void sizes(benchmark::internal::Benchmark* b, std::vector<int64_t> counts) {
    for (int64_t height : {720, 1080}) {
        for (int64_t n : counts) b->Args({n, height, 4});
    }
    // Without multisampling: what anti-aliasing costs at the largest size.
    for (int64_t height : {720, 1080}) b->Args({counts.back(), height, 1});
    b->ArgNames({"n", "height", "samples"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

/// CPU seconds of the whole process, llvmpipe's rasteriser threads included: steadier
/// than wall time when other work shares the machine.
double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Runs @p frame per iteration; reports process CPU seconds per frame as "cpu_s".
template <typename Frame>
void timeFrames(benchmark::State& state, Frame&& frame) {
    const double start = processCpuSeconds();
    for (auto _ : state) frame();
    state.counters["cpu_s"] =
        benchmark::Counter(processCpuSeconds() - start, benchmark::Counter::kAvgIterations);
}

FrameSetup setupFor(const SceneExtent& extent, int width, int height, const char* colorBy) {
    FrameSetup s;
    s.render.colorBy = colorBy;
    s.lights = {LightSettings{}};
    s.content = extent.box;
    s.ramp = std::string(colorBy) == "speed" ? extent.speed : extent.height;
    s.camera = autoFrame(extent, 0, 40, double(width) / height);
    return s;
}

/// The light of before physically based shading's extras: no environment (image-based
/// light), no ambient occlusion, hard shadows. Against the default: what they cost.
FrameSetup plainLight(FrameSetup s) {
    s.render.environmentIntensity = 0;
    s.render.ambientOcclusion = 0;
    s.render.shadowSoftness = 0;
    return s;
}

void spheres(benchmark::State& state, bool culling, bool plain = false) {
    const int height = int(state.range(1)), width = height * 16 / 9;
    const Globules g = renderBenchPour(std::size_t(state.range(0)));
    SceneExtent extent;
    extent.addFrame(g);
    FrameSetup setup = setupFor(extent, width, height, "speed");
    if (plain) setup = plainLight(setup);
    Renderer renderer(width, height, int(state.range(2)));
    renderer.setOcclusionCulling(culling);
    renderer.drawSpheres(g, setup);  // warm-up: shaders are compiled on first use
    timeFrames(state, [&] { benchmark::DoNotOptimize(renderer.drawSpheres(g, setup)); });
    state.counters["globules"] = double(g.size());
}

void BM_Spheres(benchmark::State& state) { spheres(state, true); }
BENCHMARK(BM_Spheres)->Apply([](auto* b) { sizes(b, {1000, 100000, 1000000}); });

// Without occlusion culling (the same image): what culling saves for a million globules.
void BM_SpheresUnculled(benchmark::State& state) { spheres(state, false); }
BENCHMARK(BM_SpheresUnculled)
    ->Args({1000000, 1080, 4})
    ->ArgNames({"n", "height", "samples"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same frames without image-based light, ambient occlusion and soft shadows.
void BM_SpheresPlainLight(benchmark::State& state) { spheres(state, true, true); }
BENCHMARK(BM_SpheresPlainLight)
    ->Args({100000, 1080, 4})
    ->Args({1000000, 1080, 4})
    ->ArgNames({"n", "height", "samples"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void meshFrames(benchmark::State& state, bool plain) {
    const int height = int(state.range(1)), width = height * 16 / 9;
    const TriangleMesh mesh = renderBenchBlob(std::size_t(state.range(0)));
    const MeshView view{mesh.positions.data(), mesh.normals.data(),  mesh.vertexCount(),
                        mesh.triangles.data(), mesh.triangleCount(), true};
    SceneExtent extent;
    extent.addPoints(mesh.positions.data(), mesh.vertexCount());
    FrameSetup setup = setupFor(extent, width, height, "constant");
    if (plain) setup = plainLight(setup);
    Renderer renderer(width, height, int(state.range(2)));
    renderer.drawMesh(view, setup);
    timeFrames(state, [&] { benchmark::DoNotOptimize(renderer.drawMesh(view, setup)); });
    state.counters["triangles"] = double(mesh.triangleCount());
}

void BM_Mesh(benchmark::State& state) { meshFrames(state, false); }
BENCHMARK(BM_Mesh)->Apply([](auto* b) { sizes(b, {100000, 1000000}); });

void BM_MeshPlainLight(benchmark::State& state) { meshFrames(state, true); }
BENCHMARK(BM_MeshPlainLight)
    ->Args({1000000, 1080, 4})
    ->ArgNames({"n", "height", "samples"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_WritePng(benchmark::State& state) {
    const int height = int(state.range(0)), width = height * 16 / 9;
    const Globules g = renderBenchPour(100000);
    SceneExtent extent;
    extent.addFrame(g);
    Renderer renderer(width, height, 4);
    const Image image = renderer.drawSpheres(g, setupFor(extent, width, height, "speed"));
    const auto path = std::filesystem::temp_directory_path() / "globular_render_bench.png";
    timeFrames(state, [&] { writePng(path, image); });
    std::filesystem::remove(path);
}
BENCHMARK(BM_WritePng)->Arg(720)->Arg(1080)->Unit(benchmark::kMillisecond)->UseRealTime();

// A whole 1920x1080 frame of 1e5 spheres as the render stage writes it: drawing, the PNG
// (8 or 16 bits) and, with exr, the passes and frames/frame.NNNN.exr. exr = 0 with 8 bits
// is the default output; the difference is what the EXR master costs.
void BM_FrameOutput(benchmark::State& state) {
    const bool exr = state.range(0) != 0;
    const int bits = int(state.range(1));
    const int height = 1080, width = 1920;
    const Globules g = renderBenchPour(100000);
    SceneExtent extent;
    extent.addFrame(g);
    const FrameSetup setup = setupFor(extent, width, height, "speed");
    Renderer renderer(width, height, 4, 2048, exr);
    renderer.drawSpheres(g, setup);
    const auto dir = std::filesystem::temp_directory_path();
    const ToneMapping tone = ToneMapping::from(0, "none");
    timeFrames(state, [&] {
        const Image image = renderer.drawSpheres(g, setup);
        if (bits == 16) {
            writePng(dir / "globular_render_bench.png", encode16(renderer.lastFrame(), tone));
        } else {
            writePng(dir / "globular_render_bench.png", image);
        }
        if (exr) writeExr(dir / "globular_render_bench.exr", renderer.lastFrame());
    });
    std::filesystem::remove(dir / "globular_render_bench.png");
    std::filesystem::remove(dir / "globular_render_bench.exr");
}
BENCHMARK(BM_FrameOutput)
    ->Args({0, 8})
    ->Args({1, 8})
    ->Args({0, 16})
    ->ArgNames({"exr", "png_bits"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Motion blur and depth of field at 1920x1080: motion_samples = 8 sub-frames of 1e5
// spheres of the pour (each a full render) and their accumulation; against BM_Spheres
// at the same size, what the accumulation adds beyond 8 renders.
void subFrameSpheres(benchmark::State& state, bool lens) {
    const int height = 1080, width = 1920;
    const Globules g = renderBenchPour(std::size_t(state.range(0)));
    SceneExtent extent;
    extent.addFrame(g);
    FrameSetup setup = setupFor(extent, width, height, "speed");
    setup.frameSeconds = 1.0 / 25;
    setup.render.motionSamples = 8;
    setup.render.motionBlur = !lens;
    setup.render.aperture = lens ? 0.01 * length(setup.camera.position - setup.camera.target) : 0;
    Renderer renderer(width, height, 4);
    renderer.drawSpheres(g, setup);
    timeFrames(state, [&] { benchmark::DoNotOptimize(renderer.drawSpheres(g, setup)); });
    state.counters["globules"] = double(g.size());
}
void BM_MotionBlur(benchmark::State& state) { subFrameSpheres(state, false); }
BENCHMARK(BM_MotionBlur)->Arg(100000)->ArgName("n")->Unit(benchmark::kMillisecond)->UseRealTime();
void BM_DepthOfField(benchmark::State& state) { subFrameSpheres(state, true); }
BENCHMARK(BM_DepthOfField)->Arg(100000)->ArgName("n")->Unit(benchmark::kMillisecond)->UseRealTime();

// The liquid look at 1920x1080, 4 samples: render.mode = "fluid" straight from the
// globules of the pour (splatting, smoothing, thickness and shading), and a mesh drawn
// as a liquid (its thickness pass, then its front faces refracting the ground).
void BM_Fluid(benchmark::State& state) {
    const int height = 1080, width = 1920;
    const Globules g = renderBenchPour(std::size_t(state.range(0)));
    SceneExtent extent;
    extent.addFrame(g);
    const FrameSetup setup = setupFor(extent, width, height, "constant");
    Renderer renderer(width, height, 4);
    renderer.drawFluid(g, setup);
    timeFrames(state, [&] { benchmark::DoNotOptimize(renderer.drawFluid(g, setup)); });
    state.counters["globules"] = double(g.size());
}
BENCHMARK(BM_Fluid)->Arg(100000)->Arg(1000000)->ArgName("n")->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LiquidMesh(benchmark::State& state) {
    const int height = 1080, width = 1920;
    const TriangleMesh mesh = renderBenchBlob(std::size_t(state.range(0)));
    const MeshView view{mesh.positions.data(), mesh.normals.data(),  mesh.vertexCount(),
                        mesh.triangles.data(), mesh.triangleCount(), true};
    SceneExtent extent;
    extent.addPoints(mesh.positions.data(), mesh.vertexCount());
    FrameSetup setup = setupFor(extent, width, height, "constant");
    setup.liquidSurface = true;
    Renderer renderer(width, height, 4);
    renderer.drawMesh(view, setup);
    timeFrames(state, [&] { benchmark::DoNotOptimize(renderer.drawMesh(view, setup)); });
    state.counters["triangles"] = double(mesh.triangleCount());
}
BENCHMARK(BM_LiquidMesh)->Arg(1000000)->ArgName("n")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace globular

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    benchmark::AddCustomContext("gl", globular::glContextDescription());
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
