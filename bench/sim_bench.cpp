// Simulation throughput in globule-steps per second: the paper's liquid (radius 1, r0 1,
// C_d = 1.5 r0) on a jittered lattice of spacing 1.05, so each globule has about 100
// neighbours within the drag reach of 3. Fixed seed. Run: build/bench/sim_bench.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "bench_workload.h"
#include "crowded_cell.h"
#include "material_pairs.h"
#include "simd_path.h"
#include "simulation.h"

using namespace globular;
using globular::bench::liquidBlock;

namespace {

void runSteps(benchmark::State& state, const SimulationSetup& setup,
              SimdPath path = activeSimdPath()) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                std::size_t(state.range(1)));
    Simulation sim(setup);
    sim.setSimdPath(path);
    sim.step(0.001);  // first step pays for allocations
    for (auto _ : state) sim.step(0.001);
    state.counters["globule_steps_per_s"] = benchmark::Counter(
        double(sim.globules().size()) * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["globules"] = double(sim.globules().size());
}

void BM_SimulationStep(benchmark::State& state) { runSteps(state, liquidBlock(state.range(0))); }

/// The plain step on each build of the force loops (simd_path.h), side by side in one
/// run: path 0 scalar, 1 AVX2, 2 AVX-512 (GLOBULAR_SIMD plays no part here).
void BM_SimulationStepSimdPath(benchmark::State& state) {
    const SimdPath path = SimdPath(state.range(2));
    if (!simdPathSupported(path)) {
        state.SkipWithError((std::string("this CPU lacks ") + simdPathName(path)).c_str());
        return;
    }
    state.SetLabel(simdPathName(path));
    runSteps(state, liquidBlock(state.range(0)), path);
}

/// The same block standing in a bowl (scenes/effectors/bowl.obj scaled by 60: a shell 1
/// thick, 139 across, its pole 30 below the ground): the cost of a mesh collider, whose
/// distance field every globule samples every step (issue 13: under 15% of a step).
void BM_SimulationStepMeshCollider(benchmark::State& state) {
    SimulationSetup setup = liquidBlock(state.range(0));
    ColliderSettings bowl;
    bowl.name = "bowl";
    bowl.shape = "mesh";
    bowl.file = std::string(GLOBULAR_SOURCE_DIR) + "/scenes/effectors/bowl.obj";
    bowl.scale = 60;
    bowl.center = {0, -30, 0};
    bowl.thickness = 1;
    setup.colliders = {bowl};
    runSteps(state, setup);
}

/// The same block as two materials, half each (the second the paper's powder), side by
/// side: the cost of several materials (issue 14), whose force loop gathers a cell's
/// candidates once per material.
void BM_SimulationStepTwoMaterials(benchmark::State& state) {
    SimulationSetup setup = liquidBlock(state.range(0));
    setup.material.name = "liquid";
    MaterialSettings powder;
    powder.name = "powder";
    powder.preset = "powder";
    setup.otherMaterials = {powder};
    EmitterSettings left = setup.emitters[0], right = left;
    const double middle = 0.5 * (left.min.x + left.max.x);
    left.max.x = right.min.x = middle;
    left.count = right.count = state.range(0) / 2;
    right.material = "powder";
    setup.emitters = {left, right};
    runSteps(state, setup);
}

/// @p setup's material given a melting range [40, 60] whose solid phase is stiffer (b1 2.5,
/// the same windows), its globules at 80 (liquid), with conduction, Newton cooling and a
/// hot ground.
void withTemperature(SimulationSetup& setup) {
    MaterialSettings& m = setup.material;
    m.phases = true;
    m.tSolid = 40;
    m.tLiquid = 60;
    m.solid = m.liquid = m;
    m.solid.b1 = 2.5;
    setup.thermal.enabled = true;
    setup.thermal.cooling = 0.1;
    setup.thermal.groundTemperature = 100;
    setup.thermal.groundTransfer = 1;
    for (EmitterSettings& e : setup.emitters) e.temperature = 80;
}

/// The block with temperature, one material (withTemperature).
void BM_SimulationStepThermal(benchmark::State& state) {
    SimulationSetup setup = liquidBlock(state.range(0));
    withTemperature(setup);
    runSteps(state, setup);
}

/// The two materials again, now with temperature (issue 14: under 20% extra per step):
/// each material has a melting range [40, 60] whose solid phase is stiffer (b1 2.5, the
/// same windows, so the reach is the step's own), the left half at 80 and the right at 20
/// (pairs blend where they meet), conduction, Newton cooling and a hot ground.
void BM_SimulationStepThermalTwoMaterials(benchmark::State& state) {
    SimulationSetup setup = liquidBlock(state.range(0));
    setup.material.name = "liquid";
    MaterialSettings powder;
    powder.name = "powder";
    powder.preset = "powder";
    for (MaterialSettings* m : {&setup.material, &powder}) {
        m->phases = true;
        m->tSolid = 40;
        m->tLiquid = 60;
        m->solid = m->liquid = *m;
        m->solid.b1 = 2.5;
    }
    setup.otherMaterials = {powder};
    setup.thermal.enabled = true;
    setup.thermal.cooling = 0.1;
    setup.thermal.groundTemperature = 100;
    setup.thermal.groundTransfer = 1;
    EmitterSettings left = setup.emitters[0], right = left;
    const double middle = 0.5 * (left.min.x + left.max.x);
    left.max.x = right.min.x = middle;
    left.count = right.count = state.range(0) / 2;
    left.temperature = 80;
    right.temperature = 20;
    right.material = "powder";
    setup.emitters = {left, right};
    runSteps(state, setup);
}

/// Mean number of other globules within @p reach of a sample of @p g's globules (every
/// 50th, against all of them): what a step's force loop evaluates per globule.
double meanNeighborsWithin(const Globules& g, float reach) {
    const std::size_t n = g.size();
    std::size_t pairs = 0, sampled = 0;
    for (std::size_t i = 0; i < n; i += 50, ++sampled) {
        for (std::size_t j = 0; j < n; ++j) {
            const float dx = g.px[i] - g.px[j], dy = g.py[i] - g.py[j], dz = g.pz[i] - g.pz[j];
            pairs += j != i && dx * dx + dy * dy + dz * dz < reach * reach;
        }
    }
    return sampled ? double(pairs) / double(sampled) : 0.0;
}

/// A dense pile: the block's lattice squeezed to spacing 0.6, so each globule has about
/// 500 neighbours within the drag reach of 3 (the block at 1.05 has about 100). The pile
/// is compressed and slowly springs apart.
SimulationSetup densePile(int64_t count) {
    SimulationSetup setup = liquidBlock(count);
    EmitterSettings& box = setup.emitters[0];
    const double spacing = 0.6;
    const double side = std::ceil(std::cbrt(double(count))) * spacing;
    box.spacing = spacing;
    box.min = {-side / 2, 0.5, -side / 2};
    box.max = {side / 2, 0.5 + side, side / 2};
    return setup;
}

/// Steps @p setup, a dense pile, a fixed number of times (it springs apart, so the steps
/// must be the same in every run); reports the mean neighbour count before and after.
void runDenseSteps(benchmark::State& state, const SimulationSetup& setup) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                std::size_t(state.range(1)));
    Simulation sim(setup);
    sim.step(0.001);
    const float reach = 3.0f;  // C_d (r_i + r_j) = 1.5 x 2
    state.counters["neighbors_before"] = meanNeighborsWithin(sim.globules(), reach);
    for (auto _ : state) sim.step(0.001);
    state.counters["neighbors_after"] = meanNeighborsWithin(sim.globules(), reach);
    state.counters["globule_steps_per_s"] = benchmark::Counter(
        double(sim.globules().size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_SimulationStepDense(benchmark::State& state) {
    runDenseSteps(state, densePile(state.range(0)));
}

/// The dense pile with temperature (withTemperature): a crowded thermal scene, the lava
/// lamp's or a melting heap's.
void BM_SimulationStepThermalDense(benchmark::State& state) {
    SimulationSetup setup = densePile(state.range(0));
    withTemperature(setup);
    runDenseSteps(state, setup);
}

/// The adaptive step's densest-cell count (CrowdedCell), once per step, on the block after
/// one step: its globules in the order the force loop left them (grid order), as in a run.
void BM_CrowdedCell(benchmark::State& state) {
    Simulation sim(liquidBlock(state.range(0)));
    sim.step(0.001);
    const Globules& g = sim.globules();
    const double cell = 2.0 * PairTable(sim.setup().materials(), sim.setup().materialPairs).cutoff(1.0f);
    CrowdedCell count;
    uint32_t most = 0;
    for (auto _ : state) {
        most = count.most(g.px.data(), g.py.data(), g.pz.data(), g.size(), cell);
        benchmark::DoNotOptimize(most);
    }
    state.counters["most"] = double(most);
}

void BM_SimulationStepAllPairs(benchmark::State& state) {
    runSteps(state, liquidBlock(state.range(0), "all_pairs"));
}

}  // namespace

BENCHMARK(BM_SimulationStep)
    ->ArgsProduct({{1000, 10000, 100000, 1000000}, {1, 2}})
    ->ArgNames({"globules", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_SimulationStepSimdPath)
    ->ArgsProduct({{100000, 1000000}, {1, 2}, {0, 1, 2}})
    ->ArgNames({"globules", "threads", "path"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_SimulationStepMeshCollider)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"globules", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_SimulationStepTwoMaterials)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"globules", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_SimulationStepThermal)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"globules", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_SimulationStepThermalTwoMaterials)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"globules", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_SimulationStepDense)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"globules", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);
BENCHMARK(BM_SimulationStepThermalDense)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"globules", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);
BENCHMARK(BM_CrowdedCell)
    ->Arg(100000)
    ->ArgName("globules")
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_SimulationStepAllPairs)
    ->ArgsProduct({{400, 10000}, {1}})
    ->ArgNames({"globules", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
