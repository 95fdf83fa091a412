#include "fig2_plot.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "atomic_file.h"
#include "errors.h"
#include "material.h"
#include "pair_force.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

PairForce forceFor(const ForceCurveSpec& spec, const Fig2Settings& settings) {
    MaterialSettings material;
    material.preset = "custom";
    material.r0 = settings.r0;
    material.b1 = settings.b1;
    material.m = spec.m;
    material.n = spec.n;
    material.cr = settings.cr;
    material.cd = settings.cr;
    return PairForce::fromMaterial(material);
}

/// The radial force at distance @p d: P along x, no relative velocity, so the drag
/// term is zero and f_x is D S_r (b1/D^m - b2/D^n).
double radialForce(const PairForce& force, double d, double radiusSum) {
    float f[3] = {0, 0, 0};
    force.accumulate(float(d), 0, 0, 0, 0, 0, float(radiusSum), f);
    return f[0];
}

std::string shellQuote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

std::vector<ForceCurveSpec> paperForceCurves() {
    return {{"A", 5, 3}, {"B", 10, 3}, {"C", 5, 1}, {"D", 5, 4}};
}

ForceCurve sampleForceCurve(const ForceCurveSpec& spec, const Fig2Settings& settings) {
    const PairForce force = forceFor(spec, settings);
    ForceCurve curve;
    curve.spec = spec;
    const int n = settings.samples < 2 ? 2 : settings.samples;
    for (int k = 0; k < n; ++k) {
        const double d =
            settings.minDistance + (settings.maxDistance - settings.minDistance) * k / (n - 1);
        curve.distance.push_back(d);
        curve.force.push_back(radialForce(force, d, 2 * settings.radius));
    }
    return curve;
}

ForceCurveSummary summarizeForceCurve(const ForceCurveSpec& spec, const Fig2Settings& settings) {
    const PairForce force = forceFor(spec, settings);
    const double radiusSum = 2 * settings.radius;
    const double from = 0.5 * settings.r0, to = settings.cr * radiusSum;
    const int steps = 20000;
    const double h = (to - from) / steps;
    ForceCurveSummary s;
    s.spec = spec;
    std::vector<double> f(steps + 1);
    for (int k = 0; k <= steps; ++k) f[k] = radialForce(force, from + k * h, radiusSum);
    int dip = 0;
    for (int k = 0; k <= steps; ++k) {
        if (f[k] < f[dip]) dip = k;
        if (f[k] < 0) s.attractionArea += f[k] * h;
    }
    s.dipForce = f[dip];
    s.dipDistance = from + dip * h;
    s.halfReach = to;
    for (int k = dip; k <= steps; ++k) {
        if (f[k] > 0.5 * f[dip]) {
            s.halfReach = from + k * h;
            break;
        }
    }
    s.forceAt08 = radialForce(force, 0.8 * settings.r0, radiusSum);
    return s;
}

Fig2Output writeFig2(const fs::path& dir, const Fig2Settings& settings, int widthPx, int heightPx) {
    Fig2Output out;
    out.csv = dir / "fig2_force.csv";
    out.script = dir / "fig2_force.gp";
    const fs::path png = dir / "fig2_force.png";

    std::vector<ForceCurve> curves;
    for (const auto& spec : paperForceCurves()) curves.push_back(sampleForceCurve(spec, settings));
    std::ostringstream csv;
    csv << "distance";
    for (const auto& c : curves) csv << ",force_m" << c.spec.m << "_n" << c.spec.n;
    csv << "\n";
    char number[32];
    for (std::size_t k = 0; k < curves.front().distance.size(); ++k) {
        std::snprintf(number, sizeof number, "%.6g", curves.front().distance[k]);
        csv << number;
        for (const auto& c : curves) {
            std::snprintf(number, sizeof number, ",%.9g", c.force[k]);
            csv << number;
        }
        csv << "\n";
    }
    writeFileAtomically(out.csv, csv.str());

    // The script names files relative to DIR; gnuplot runs there.
    std::ostringstream gp;
    gp << "# Fig. 2: radial force against distance (globular figures). Run in this folder.\n"
       << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
       << "  set terminal pngcairo size " << widthPx << "," << heightPx << " font 'sans,10'\n"
       << "} else {\n"
       << "  set terminal png size " << widthPx << "," << heightPx << "\n"
       << "}\n"
       << "# globular names a temporary output (-e \"output='...'\") and renames it into place.\n"
       << "if (!exists('output')) output = 'fig2_force.png'\n"
       << "set output output\n"
       << "set datafile separator ','\n"
       << "set key top right\n"
       << "set grid\n"
       << "set xlabel 'distance D between centres (r_0 = " << settings.r0 << ", radii "
       << settings.radius << ")'\n"
       << "set ylabel 'radial force (+ repulsion, - attraction)'\n"
       << "set title 'Fig. 2: D S_r (b_1/D^m - b_2/D^n), b_1 = " << settings.b1
       << ", C_r = " << settings.cr << "'\n"
       << "set xrange [" << settings.minDistance << ":" << settings.maxDistance << "]\n"
       << "set yrange [-1:3]\n"
       << "set xzeroaxis lt -1\n"
       << "plot ";
    for (std::size_t i = 0; i < curves.size(); ++i) {
        gp << (i ? ", \\\n     " : "") << "'fig2_force.csv' using 1:" << (i + 2)
           << " with lines lw 2 title '" << curves[i].spec.label << ": m = " << curves[i].spec.m
           << ", n = " << curves[i].spec.n << "'";
    }
    gp << "\n";
    writeFileAtomically(out.script, gp.str());

    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
        out.message = "gnuplot is not installed: wrote the CSV and the script, skipped the PNG";
        return out;
    }
    // Through the atomic path, like every other file: gnuplot writes a temporary.
    try {
        writeAtomically(png, [&](const fs::path& temporary) {
            const std::string command = "cd " + shellQuote(dir.string()) + " && gnuplot -e " +
                                        shellQuote("output='" + temporary.filename().string() + "'") +
                                        " fig2_force.gp >/dev/null 2>gnuplot.log";
            if (std::system(command.c_str()) != 0) throw IoError("gnuplot failed");
        });
    } catch (const IoError&) {
        out.message = "gnuplot failed (see " + (dir / "gnuplot.log").string() +
                      "): wrote the CSV and the script, skipped the PNG";
        return out;
    }
    std::error_code ignored;
    fs::remove(dir / "gnuplot.log", ignored);
    out.png = png;
    return out;
}

}  // namespace globular
