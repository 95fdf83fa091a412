// Writes the simulation benchmark's workload for a peer comparison (bench/lammps/):
//
//   make_workload N OUTDIR [TABLE_POINTS]
//
//   OUTDIR/globules.ply   the initial globules of liquidBlock(N) (bench_workload.h) as
//                         globular's PLY cache: sim_steps reads it with a points emitter
//   OUTDIR/globules.data  the same positions as a LAMMPS data file (atom_style atomic,
//                         mass 1, zero velocities, a box with a margin around the block)
//   OUTDIR/radial.table   the radial part of the pair force as a LAMMPS pair table,
//                         keyword GLOBULAR_RADIAL, TABLE_POINTS (default 4000) rows spaced
//                         in r^2 from 0.05 to the neighbour cutoff (so LAMMPS's linear
//                         table of the same length uses the values as they are)
//   OUTDIR/radial_forces.txt  "id fx fy fz": globular's radial force (pair_force.h, all
//                         pairs, zero velocities) on the globules with LAMMPS ids 1..200,
//                         for compare.sh to check LAMMPS's table forces against
//   OUTDIR/workload.txt   key = value lines the script reads (count, box, cutoffs)
//
// The force column is globular's own PairForce (pair_force.h) evaluated at zero relative
// velocity: F(D) = D S_r(D) (b1/D^m - b2/D^n), positive = repulsive, exactly zero at and
// beyond C_r (r_i + r_j). The energy column is -integral of F (trapezoid rule on a grid
// 64 times finer than the table, from the cutoff down), E(cutoff) = 0.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "bench_workload.h"
#include "globule_cache.h"
#include "pair_force.h"

using namespace globular;

namespace {

/// Radial force magnitude between two globules of radius 1 at distance @p d (zero
/// relative velocity, so the drag term vanishes), positive = repulsive.
double radialForce(const PairForce& pair, double d, float radiusSum) {
    float f[3] = {0, 0, 0};
    pair.accumulate(float(d), 0, 0, 0, 0, 0, radiusSum, f);
    return double(f[0]);
}

}  // namespace

int main(int argc, char** argv) try {
    if (argc < 3) {
        std::cerr << "usage: make_workload N OUTDIR [TABLE_POINTS]\n";
        return 2;
    }
    const int64_t count = std::atoll(argv[1]);
    const std::filesystem::path out = argv[2];
    const int tablePoints = argc > 3 ? std::atoi(argv[3]) : 4000;
    if (count <= 0 || tablePoints < 100) {
        std::cerr << "make_workload: N must be > 0 and TABLE_POINTS >= 100\n";
        return 2;
    }
    std::filesystem::create_directories(out);

    const SimulationSetup setup = bench::liquidBlock(count);
    Simulation sim(setup);  // emits the block at t = 0, exactly as sim_bench does
    const Globules& g = sim.globules();
    writeGlobulePly(out / "globules.ply", g);

    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    float maxRadius = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        const float p[3] = {g.px[i], g.py[i], g.pz[i]};
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
        }
        maxRadius = std::max(maxRadius, g.radius[i]);
    }

    // The neighbour search reach of globular (both windows) and the radial window.
    const PairForce pair = PairForce::fromMaterial(setup.material);
    const float radiusSum = 2 * maxRadius;
    const double searchCutoff = pair.cutoff(radiusSum);  // max(C_r, C_d) (r_i + r_j)
    const double radialCutoff = pair.cr * radiusSum;     // C_r (r_i + r_j)

    // LAMMPS box: a margin of 10 around the block sideways and above; below, room for
    // the ground wall (at y = -1, see compare.sh) and globules sinking into it.
    const double margin = 10;
    const double box[3][2] = {{lo[0] - margin, hi[0] + margin},
                              {-3.0, hi[1] + margin},
                              {lo[2] - margin, hi[2] + margin}};
    {
        std::ofstream data(out / "globules.data");
        data.precision(9);
        data << "LAMMPS data file: globular liquidBlock(" << count << "), bench/make_workload\n\n"
             << g.size() << " atoms\n1 atom types\n\n"
             << box[0][0] << ' ' << box[0][1] << " xlo xhi\n"
             << box[1][0] << ' ' << box[1][1] << " ylo yhi\n"
             << box[2][0] << ' ' << box[2][1] << " zlo zhi\n\n"
             << "Masses\n\n1 " << g.mass.front() << "\n\nAtoms # atomic\n\n";
        for (std::size_t i = 0; i < g.size(); ++i) {
            data << i + 1 << " 1 " << g.px[i] << ' ' << g.py[i] << ' ' << g.pz[i] << '\n';
        }
        if (!data) throw std::runtime_error("cannot write " + (out / "globules.data").string());
    }

    {
        // Rows equally spaced in r^2 between inner and the search cutoff (LAMMPS "RSQ").
        const double inner = 0.05, outer = searchCutoff;
        const std::size_t rows = static_cast<std::size_t>(tablePoints);
        std::vector<double> r(rows), f(rows), e(rows, 0.0);
        for (int k = 0; k < tablePoints; ++k) {
            const double rsq = inner * inner + (outer * outer - inner * inner) * k / (tablePoints - 1);
            r[std::size_t(k)] = std::sqrt(rsq);
            f[std::size_t(k)] = radialForce(pair, r[std::size_t(k)], radiusSum);
        }
        const int sub = 64;
        for (int k = tablePoints - 2; k >= 0; --k) {
            const double a = r[std::size_t(k)], b = r[std::size_t(k) + 1], h = (b - a) / sub;
            double integral = 0;
            for (int s = 0; s < sub; ++s) {
                integral += 0.5 * h * (radialForce(pair, a + s * h, radiusSum) +
                                       radialForce(pair, a + (s + 1) * h, radiusSum));
            }
            e[std::size_t(k)] = e[std::size_t(k) + 1] + integral;
        }
        std::ofstream table(out / "radial.table");
        table.precision(10);
        table << "# globular radial pair force F(D) = D S_r (b1/D^m - b2/D^n), b1 " << pair.b1
              << " b2 " << pair.b2 << " m " << pair.m << " n " << pair.n << " C_r " << pair.cr
              << ", radii " << maxRadius << ": zero beyond " << radialCutoff
              << "\n# columns: index r energy force (force > 0 repulsive)\n\nGLOBULAR_RADIAL\n"
              << "N " << tablePoints << " RSQ " << inner << ' ' << outer << "\n\n";
        for (int k = 0; k < tablePoints; ++k) {
            table << k + 1 << ' ' << r[std::size_t(k)] << ' ' << e[std::size_t(k)] << ' '
                  << f[std::size_t(k)] << '\n';
        }
        if (!table) throw std::runtime_error("cannot write " + (out / "radial.table").string());
    }

    {
        // Reference forces on the first globules, summed over every other globule.
        const std::size_t checked = std::min<std::size_t>(200, g.size());
        std::ofstream forces(out / "radial_forces.txt");
        forces.precision(9);
        for (std::size_t i = 0; i < checked; ++i) {
            float f[3] = {0, 0, 0};
            for (std::size_t j = 0; j < g.size(); ++j) {
                if (j == i) continue;
                pair.accumulate(g.px[i] - g.px[j], g.py[i] - g.py[j], g.pz[i] - g.pz[j], 0, 0, 0,
                                g.radius[i] + g.radius[j], f);
            }
            forces << i + 1 << ' ' << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
        }
    }

    std::ofstream info(out / "workload.txt");
    info << "count = " << g.size() << "\nsearch_cutoff = " << searchCutoff
         << "\nradial_cutoff = " << radialCutoff << "\ntable_points = " << tablePoints
         << "\nblock_lo = " << lo[0] << ' ' << lo[1] << ' ' << lo[2]
         << "\nblock_hi = " << hi[0] << ' ' << hi[1] << ' ' << hi[2] << '\n';
    std::cout << "wrote " << g.size() << " globules, search cutoff " << searchCutoff
              << ", radial cutoff " << radialCutoff << " to " << out.string() << '\n';
    return 0;
} catch (const std::exception& e) {
    std::cerr << "make_workload: " << e.what() << '\n';
    return 1;
}
