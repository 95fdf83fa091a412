#include "filter_chain.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "errors.h"
#include "settings_schema.h"

namespace globular {

namespace {

struct FilterSpec {
    FilterKind kind;
    const char* name;
    bool integral;  ///< amount is a count or a stencil width
    double min, max;
    bool minExclusive;
};

constexpr FilterSpec kSpecs[] = {
    {FilterKind::Gaussian, "gaussian", true, 1, 8, false},
    {FilterKind::MeanCurvature, "mean_curvature", true, 1, 100, false},
    {FilterKind::Laplacian, "laplacian", true, 1, 100, false},
    {FilterKind::Dilate, "dilate", false, 0, 64, true},
    {FilterKind::Erode, "erode", false, 0, 64, true},
};

const char* kSyntax =
    "expected steps like \"gaussian:2, dilate:1, erode:1\" (gaussian, mean_curvature, "
    "laplacian, dilate, erode)";

std::string trim(const std::string& s) {
    const auto begin = s.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) return "";
    const auto end = s.find_last_not_of(" \t\r\n");
    return s.substr(begin, end - begin + 1);
}

std::string formatAmount(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

}  // namespace

const char* filterName(FilterKind kind) {
    for (const auto& spec : kSpecs) {
        if (spec.kind == kind) return spec.name;
    }
    return "?";
}

std::vector<FilterStep> parseFilterChain(const std::string& text) {
    std::vector<FilterStep> chain;
    if (trim(text).empty()) return chain;

    std::vector<std::string> names;
    for (const auto& spec : kSpecs) names.emplace_back(spec.name);

    std::stringstream stream(text);
    std::string part;
    int index = 0;
    while (std::getline(stream, part, ',')) {
        ++index;
        const std::string step = trim(part);
        const std::string where = "filter step " + std::to_string(index);
        if (step.empty()) throw SceneError(where + " is empty; " + kSyntax);

        const auto colon = step.find(':');
        const std::string name = trim(step.substr(0, colon));
        const FilterSpec* spec = nullptr;
        for (const auto& s : kSpecs) {
            if (name == s.name) spec = &s;
        }
        if (!spec) {
            const std::string hint = closestMatch(name, names);
            throw SceneError(where + " '" + step + "': unknown filter '" + name + "'" +
                             (hint.empty() ? "" : " (did you mean '" + hint + "'?)") + "; " +
                             kSyntax);
        }

        FilterStep parsed{spec->kind, 1.0};
        if (colon != std::string::npos) {
            const std::string amount = trim(step.substr(colon + 1));
            double value = 0;
            const auto [end, ec] =
                std::from_chars(amount.data(), amount.data() + amount.size(), value);
            if (amount.empty() || ec != std::errc() || end != amount.data() + amount.size() ||
                !std::isfinite(value)) {
                throw SceneError(where + " '" + step + "': amount '" + amount +
                                 "' is not a number; " + kSyntax);
            }
            parsed.amount = value;
        }
        const double v = parsed.amount;
        const bool belowMin = spec->minExclusive ? !(v > spec->min) : !(v >= spec->min);
        if (belowMin || v > spec->max || (spec->integral && v != std::floor(v))) {
            throw SceneError(where + " '" + step + "': " + spec->name + " takes " +
                             (spec->integral ? "an integer in [" : "a number in ") +
                             (spec->integral ? "" : (spec->minExclusive ? "(" : "[")) +
                             formatAmount(spec->min) + ", " + formatAmount(spec->max) + "]" +
                             (spec->kind == FilterKind::Gaussian ? " (voxels)"
                              : spec->integral                   ? " (iterations)"
                                                                 : " (voxels)"));
        }
        chain.push_back(parsed);
    }
    // getline drops a trailing empty field: "gaussian," must still be an error.
    if (trim(text).back() == ',') {
        throw SceneError("filter step " + std::to_string(index + 1) + " is empty; " + kSyntax);
    }
    return chain;
}

std::string formatFilterChain(const std::vector<FilterStep>& chain) {
    std::string text;
    for (const auto& step : chain) {
        if (!text.empty()) text += ", ";
        text += std::string(filterName(step.kind)) + ":" + formatAmount(step.amount);
    }
    return text;
}

}  // namespace globular
