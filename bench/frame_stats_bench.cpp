// What the per-frame statistics (stats.csv, frame_stats.h) cost next to the frame they
// describe: the benchmark block of N globules (bench_workload.h) is stepped a few times,
// then computeFrameStats is timed on it, and the statistics' share of a frame is
// stats / (stats + steps per frame x one step). Issue 18's target: 5% or less at 1e6.
//
//   frame_stats_bench [N ...]        (default: 10000 100000 1000000; 40 steps per frame,
//                                     the paper's dt 0.001 at 25 fps)

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench_workload.h"
#include "frame_stats.h"
#include "simulation.h"

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    using namespace globular;
    std::vector<long> counts;
    for (int a = 1; a < argc; ++a) counts.push_back(std::atol(argv[a]));
    if (counts.empty()) counts = {10000, 100000, 1000000};
    constexpr int kStepsPerFrame = 40;
    std::printf("%10s %12s %12s %12s %9s  %s\n", "globules", "step (ms)", "frame (ms)",
                "stats (ms)", "share", "clusters");
    for (long n : counts) {
        Simulation sim(bench::liquidBlock(n));
        sim.step(0.001);  // grid order, as the sim stage hands frames over
        std::vector<double> steps, stats;
        for (int k = 0; k < 3; ++k) {
            bench::Stopwatch watch;
            sim.step(0.001);
            steps.push_back(watch.wall());
        }
        FrameStats s;
        for (int k = 0; k < 5; ++k) {
            bench::Stopwatch watch;
            s = computeFrameStats(sim.globules(), 1, sim.time());
            stats.push_back(watch.wall());
        }
        const double step = median(steps), stat = median(stats);
        const double frame = kStepsPerFrame * step;
        std::printf("%10ld %12.2f %12.1f %12.2f %8.2f%%  %zu (largest %.3f)\n", n, 1e3 * step,
                    1e3 * frame, 1e3 * stat, 100 * stat / (frame + stat), s.clusterCount,
                    s.largestClusterFraction);
    }
}
