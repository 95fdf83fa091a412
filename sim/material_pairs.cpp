#include "material_pairs.h"

#include <algorithm>

#include "errors.h"
#include "settings_schema.h"

namespace globular {

void MaterialPairSettings::describe(SettingsSection& s) {
    s.text("a", a, "one material of the pair, by name");
    s.text("b", b, "the other material");
    s.number("b1", b1, NumberRange::nonNegative(), "radial force strength (0: the mean)");
    s.number("r0", r0, NumberRange::nonNegative(), "rest distance (0: the mean)");
    s.number("m", m, NumberRange::nonNegative(), "repulsion exponent (0: the mean)");
    s.number("n", n, NumberRange::nonNegative(), "attraction exponent (0: the mean)");
    s.number("cr", cr, NumberRange::nonNegative(), "radial window C_r (0: the wider)");
    s.number("cd", cd, NumberRange::nonNegative(), "drag window C_d (0: the wider)");
}

int materialIndex(const std::vector<MaterialSettings>& materials, const std::string& name) {
    if (name.empty()) return materials.empty() ? -1 : 0;
    for (std::size_t k = 0; k < materials.size(); ++k) {
        if (materials[k].name == name) return int(k);
    }
    return -1;
}

ForceConstants PairTable::mixed(const ForceConstants& x, const ForceConstants& y) {
    ForceConstants m;
    m.preset = "custom";
    m.b1 = 0.5 * (x.b1 + y.b1);
    m.r0 = 0.5 * (x.r0 + y.r0);
    m.m = 0.5 * (x.m + y.m);
    m.n = 0.5 * (x.n + y.n);
    m.cr = std::max(x.resolvedCr(), y.resolvedCr());
    m.cd = std::max(x.resolvedCd(), y.resolvedCd());
    return m;
}

PairTable::PairTable(const PairForce& pair) : mCount(1), mPairs{pair} {
    mThermal.push_back(ThermalPair{pair, pair, 0, 0, 0, 0});
}

std::vector<PairForce> PairTable::table(const std::vector<const ForceConstants*>& own,
                                        const std::vector<MaterialSettings>& materials,
                                        const std::vector<MaterialPairSettings>& pairs) {
    const std::size_t count = own.size();
    std::vector<ForceConstants> constants(count * count);
    for (std::size_t a = 0; a < count; ++a) {
        for (std::size_t b = 0; b < count; ++b) {
            constants[a * count + b] = a == b ? *own[a] : mixed(*own[a], *own[b]);
        }
    }
    std::vector<bool> given(count * count, false);
    for (const MaterialPairSettings& p : pairs) {
        const int a = materialIndex(materials, p.a), b = materialIndex(materials, p.b);
        if (p.a.empty() || p.b.empty() || a < 0 || b < 0 || a == b) {
            throw SceneError("[[material_pair]] '" + p.a + "', '" + p.b +
                             "': a pair names two different [[material]] sections");
        }
        if (given[std::size_t(a) * count + std::size_t(b)]) {
            throw SceneError("[[material_pair]] '" + p.a + "', '" + p.b + "' is given twice");
        }
        for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
            given[std::size_t(x) * count + std::size_t(y)] = true;
            ForceConstants& m = constants[std::size_t(x) * count + std::size_t(y)];
            if (p.b1 > 0) m.b1 = p.b1;
            if (p.r0 > 0) m.r0 = p.r0;
            if (p.m > 0) m.m = p.m;
            if (p.n > 0) m.n = p.n;
            if (p.cr > 0) m.cr = p.cr;
            if (p.cd > 0) m.cd = p.cd;
        }
    }
    std::vector<PairForce> forces;
    for (const ForceConstants& m : constants) forces.push_back(PairForce::fromMaterial(m));
    return forces;
}

PairTable::PairTable(const std::vector<MaterialSettings>& materials,
                     const std::vector<MaterialPairSettings>& pairs)
    : mCount(materials.size()) {
    if (materials.empty()) throw SceneError("a scene needs a material");
    std::vector<const ForceConstants*> own, solid, liquid;
    for (const MaterialSettings& m : materials) {
        own.push_back(&m);
        solid.push_back(&m.solidConstants());
        liquid.push_back(&m.liquidConstants());
    }
    mPairs = table(own, materials, pairs);
    const std::vector<PairForce> solids = table(solid, materials, pairs);
    const std::vector<PairForce> liquids = table(liquid, materials, pairs);
    for (std::size_t a = 0; a < mCount; ++a) {
        for (std::size_t b = 0; b < mCount; ++b) {
            const MaterialSettings &x = materials[a], &y = materials[b];
            ThermalPair t{solids[a * mCount + b], liquids[a * mCount + b], 0, 0, 0, 0};
            double low = 0, high = 0;
            if (x.phases && y.phases) {
                low = 0.5 * (x.tSolid + y.tSolid);
                high = 0.5 * (x.tLiquid + y.tLiquid);
            } else if (x.phases || y.phases) {
                low = x.phases ? x.tSolid : y.tSolid;
                high = x.phases ? x.tLiquid : y.tLiquid;
            }
            if (float(high) > float(low)) {  // as the kernel compares them
                t.tSolid = float(low);
                t.tLiquid = float(high);
                t.invRange = 1.0f / (t.tLiquid - t.tSolid);
            }
            const double k = x.conductivity + y.conductivity;
            t.conductance = k > 0 ? float(2.0 * x.conductivity * y.conductivity / k) : 0.0f;
            mThermal.push_back(t);
        }
    }
}

float PairTable::cutoff(float radiusSum) const {
    float largest = 0;
    for (const PairForce& p : mPairs) largest = std::max(largest, p.cutoff(radiusSum));
    for (const ThermalPair& t : mThermal) {
        largest = std::max({largest, t.solid.cutoff(radiusSum), t.liquid.cutoff(radiusSum)});
    }
    return largest;
}

}  // namespace globular
