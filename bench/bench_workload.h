#pragma once
// The simulation benchmark's workload, shared by sim_bench, make_workload and sim_steps: the paper's
// liquid (radius 1, r0 1, b1 2, m 5, n 3, C_r = r0, C_d = 1.5 r0) on a jittered lattice of
// spacing 1.05 resting on the ground, fixed seed.

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>

#include "simulation.h"

namespace globular::bench {

/// A cube of about @p count globules resting on the ground: the benchmarks' workload.
inline SimulationSetup liquidBlock(int64_t count, const std::string& neighbors = "grid") {
    SimulationSetup setup;
    setup.simulation.neighbors = neighbors;
    const double spacing = 1.05;
    const double side = std::ceil(std::cbrt(double(count))) * spacing;
    EmitterSettings box;
    box.type = "box";
    box.count = count;
    box.spacing = spacing;
    box.jitter = 0.05;
    box.min = {-side / 2, 0.5, -side / 2};
    box.max = {side / 2, 0.5 + side, side / 2};
    setup.emitters = {box};
    return setup;
}

/// The same material, ground and gravity with the globules read from a PLY file
/// (a `points` emitter).
inline SimulationSetup pointsWorkload(const std::string& plyPath) {
    SimulationSetup setup;
    EmitterSettings points;
    points.type = "points";
    points.file = plyPath;
    points.count = 0;
    setup.emitters = {points};
    return setup;
}

/// Wall and CPU (user + system, all threads) seconds since construction.
class Stopwatch {
public:
    Stopwatch() : mWall(std::chrono::steady_clock::now()), mCpu(cpuSeconds()) {}
    double wall() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - mWall).count();
    }
    double cpu() const { return cpuSeconds() - mCpu; }

    static double cpuSeconds() {
        rusage u{};
        getrusage(RUSAGE_SELF, &u);
        return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
               1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
    }

private:
    std::chrono::steady_clock::time_point mWall;
    double mCpu;
};

/// A field of /proc/self/status in KiB ("VmRSS", "VmHWM"), or -1.
inline long procStatusKiB(const std::string& field) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(field + ":", 0) == 0) return std::stol(line.substr(field.size() + 1));
    }
    return -1;
}

}  // namespace globular::bench
