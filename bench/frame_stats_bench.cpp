// What the per-frame statistics (stats.csv, frame_stats.h) cost next to the frame they
// describe: the benchmark block of N globules (bench_workload.h) is stepped a few times,
// then computeFrameStats is timed on it, and the statistics' share of a frame is
// stats / (stats + steps per frame x one step). Issue 18's target: 5% or less at 1e6.
//
//   frame_stats_bench [N ...]        (default: 10000 100000 1000000; 40 steps per frame,
//                                     the paper's dt 0.001 at 25 fps)
//   frame_stats_bench CACHE.vdb ...  the statistics of cached frames alone (a run's
//                                     out/cache/globules.NNNN.vdb: the pour's settled pile)

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_workload.h"
#include "frame_stats.h"
#include "globule_cache.h"
#include "simulation.h"

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

/// The median of 5 timings of computeFrameStats on @p g, seconds.
double timeStats(const globular::Globules& g, globular::FrameStats& s) {
    std::vector<double> stats;
    for (int k = 0; k < 5; ++k) {
        globular::bench::Stopwatch watch;
        s = globular::computeFrameStats(g, 1, 0);
        stats.push_back(watch.wall());
    }
    return median(stats);
}

int main(int argc, char** argv) {
    using namespace globular;
    std::vector<long> counts;
    std::vector<std::string> caches;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg.ends_with(".vdb")) {
            caches.push_back(arg);
        } else {
            counts.push_back(std::atol(argv[a]));
        }
    }
    if (!caches.empty()) {
        std::printf("%10s %12s  %s\n", "globules", "stats (ms)", "cache");
        for (const std::string& path : caches) {
            const Globules g = readGlobuleVdb(path);
            FrameStats s;
            const double stat = timeStats(g, s);
            std::printf("%10zu %12.2f  %s: %zu clusters (largest %.3f)\n", g.size(), 1e3 * stat,
                        path.c_str(), s.clusterCount, s.largestClusterFraction);
        }
        if (counts.empty()) return 0;
    }
    if (counts.empty()) counts = {10000, 100000, 1000000};
    constexpr int kStepsPerFrame = 40;
    std::printf("%10s %12s %12s %12s %9s  %s\n", "globules", "step (ms)", "frame (ms)",
                "stats (ms)", "share", "clusters");
    for (long n : counts) {
        Simulation sim(bench::liquidBlock(n));
        sim.step(0.001);  // grid order, as the sim stage hands frames over
        std::vector<double> steps;
        for (int k = 0; k < 3; ++k) {
            bench::Stopwatch watch;
            sim.step(0.001);
            steps.push_back(watch.wall());
        }
        FrameStats s;
        const double step = median(steps), stat = timeStats(sim.globules(), s);
        const double frame = kStepsPerFrame * step;
        std::printf("%10ld %12.2f %12.1f %12.2f %8.2f%%  %zu (largest %.3f)\n", n, 1e3 * step,
                    1e3 * frame, 1e3 * stat, 100 * stat / (frame + stat), s.clusterCount,
                    s.largestClusterFraction);
    }
}
