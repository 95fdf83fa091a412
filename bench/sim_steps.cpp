// Times a fixed number of simulation steps on a given workload, for peer comparisons
// (bench/lammps/compare.sh) and the memory measurement of bench/run.sh:
//
//   sim_steps (--ply FILE | --block N) --steps S [--threads 1,2] [--neighbors grid|all_pairs]
//             [--memory] [--candidates]
//
// --ply reads the initial globules with a `points` emitter (make_workload's PLY);
// --block builds liquidBlock(N) directly (bench_workload.h). Material, gravity, ground,
// integrator and dt are globular's defaults: the paper's liquid (drag included), forward
// Euler, dt 0.001; --neighbors all_pairs runs the paper's O(N^2) loop instead of the grid.
// For each thread count a fresh simulation runs S steps; the line
//
//   neighbors=grid threads=T globules=N steps=S wall_s=W cpu_s=C globule_steps_per_s=N*S/W
//
// times the steps only (construction and reading are left out; the first step, which
// allocates the neighbour workspace, is counted). cpu_s is user + system time of all
// threads over the same steps. --memory adds the process's resident memory (VmRSS, VmHWM)
// before construction, after it and after the steps, and the bytes the Globules arrays hold.
// --candidates counts, after the steps, the candidates the grid hands the force kernel per
// globule and how many of them lie within the drag reach and the radial window, and times
// one grid rebuild alone (the serial part of a step).

#include <tbb/global_control.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_workload.h"
#include "forces.h"

using namespace globular;

namespace {

std::size_t globuleBytes(const Globules& g) {
    std::size_t bytes = 0;
    for (const auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass})
        bytes += a->capacity() * sizeof(float);
    return bytes + g.id.capacity() * sizeof(int32_t);
}

void memoryLine(const char* stage) {
    std::cout << "memory stage=" << stage << " rss_kib=" << bench::procStatusKiB("VmRSS")
              << " hwm_kib=" << bench::procStatusKiB("VmHWM") << '\n';
}

/// Candidates per globule from the grid's 27-cell neighbourhood, and those within the
/// search cutoff and the radial window; the time of one grid rebuild per globule.
void candidateLine(const Globules& g, const PairForce& pair) {
    NeighborGrid grid;
    const bench::Stopwatch watch;
    buildGrid(g, pair, grid);
    const double buildNs = 1e9 * watch.wall() / double(g.size());
    float radiusMax = 0;
    for (const float r : g.radius) radiusMax = std::max(radiusMax, r);
    const float reach2 = pair.cutoff(2 * radiusMax) * pair.cutoff(2 * radiusMax);
    const float radial2 = (pair.cr * 2 * radiusMax) * (pair.cr * 2 * radiusMax);
    double candidates = 0, inReach = 0, inRadial = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        grid.forEachCandidate(g.px[i], g.py[i], g.pz[i], [&](uint32_t j) {
            if (j == i) return;
            const float dx = g.px[i] - g.px[j], dy = g.py[i] - g.py[j], dz = g.pz[i] - g.pz[j];
            const float d2 = dx * dx + dy * dy + dz * dz;
            candidates += 1;
            inReach += d2 < reach2;
            inRadial += d2 < radial2;
        });
    }
    const double n = double(g.size());
    std::cout << "candidates per_globule=" << candidates / n << " within_search_cutoff="
              << inReach / n << " within_radial_window=" << inRadial / n
              << " grid_build_ns_per_globule=" << buildNs << '\n';
}

[[noreturn]] void usage() {
    std::cerr << "usage: sim_steps (--ply FILE | --block N) --steps S [--threads 1,2] "
                 "[--neighbors grid|all_pairs] [--memory] [--candidates]\n";
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) try {
    std::string ply;
    int64_t block = 0, steps = 0;
    std::vector<int> threads{1, 2};
    std::string neighbors = "grid";
    bool memory = false, candidates = false;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        const auto value = [&]() -> std::string {
            if (a + 1 >= argc) usage();
            return argv[++a];
        };
        if (arg == "--ply") {
            ply = value();
        } else if (arg == "--block") {
            block = std::atoll(value().c_str());
        } else if (arg == "--steps") {
            steps = std::atoll(value().c_str());
        } else if (arg == "--threads") {
            threads.clear();
            std::stringstream list(value());
            for (std::string t; std::getline(list, t, ',');) threads.push_back(std::atoi(t.c_str()));
        } else if (arg == "--neighbors") {
            neighbors = value();
            if (neighbors != "grid" && neighbors != "all_pairs") usage();
        } else if (arg == "--candidates") {
            candidates = true;
        } else if (arg == "--memory") {
            memory = true;
        } else {
            usage();
        }
    }
    if ((ply.empty() == (block <= 0)) || steps <= 0 || threads.empty()) usage();

    SimulationSetup setup = ply.empty() ? bench::liquidBlock(block) : bench::pointsWorkload(ply);
    setup.simulation.neighbors = neighbors;
    for (const int t : threads) {
        if (t < 1) usage();
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, std::size_t(t));
        if (memory) memoryLine("start");
        Simulation sim(setup);
        const double n = double(sim.globules().size());
        if (memory) memoryLine("constructed");
        const bench::Stopwatch watch;
        for (int64_t s = 0; s < steps; ++s) sim.step(setup.simulation.dt);
        const double wall = watch.wall(), cpu = watch.cpu();
        std::cout << std::setprecision(6) << "neighbors=" << neighbors << " threads=" << t
                  << " globules=" << int64_t(n)
                  << " steps=" << steps << " wall_s=" << wall << " cpu_s=" << cpu
                  << " globule_steps_per_s=" << n * double(steps) / wall << '\n';
        if (memory) {
            memoryLine("stepped");
            std::cout << "memory globules_arrays_bytes=" << globuleBytes(sim.globules()) << '\n';
        }
        if (candidates) candidateLine(sim.globules(), PairForce::fromMaterial(setup.material));
    }
    return 0;
} catch (const std::exception& e) {
    std::cerr << "sim_steps: " << e.what() << '\n';
    return 1;
}
