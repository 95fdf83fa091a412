#include "simulation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "errors.h"
#include "reporter.h"

namespace globular {

namespace {

constexpr int kMaxSubstepRefinement = 64;
constexpr std::size_t kMaxMaterials = 16;  // an index per globule in one byte, and a small table  // on_explosion = substep: up to 64x more steps
std::string describeRunaway(const Globules& g, long i, double maxSpeed) {
    std::ostringstream out;
    const Vec3 p = g.position(std::size_t(i)), v = g.velocity(std::size_t(i));
    if (!std::isfinite(p.x + p.y + p.z + v.x + v.y + v.z)) {
        out << "globule " << g.id[std::size_t(i)] << " has a non-finite position or velocity";
    } else {
        out << "globule " << g.id[std::size_t(i)] << " moves at " << length(v)
            << " units/s, above max_speed " << maxSpeed;
    }
    return out.str();
}

}  // namespace

Simulation::Simulation(const SimulationSetup& setup)
    : mSetup(setup),
      mForces(PairTable(setup.materials(), setup.materialPairs),
              ExternalForces{setup.simulation.gravity, setup.ground,
                             ColliderSet(setup.colliders, setup.sceneDir, Simulation::colliderReach(setup),
                                         setup.simulation.gravity, setup.ground),
                             ThermalSources(setup.thermal, setup.heaters, setup.materials(),
                                            setup.simulation.gravity, setup.ground)},
              setup.simulation.neighbors == "all_pairs"),
      mStableStep(setup),
      mIntegrator(makeIntegrator(setup.simulation.integrator)) {
    const std::vector<MaterialSettings> materials = setup.materials();
    if (materials.size() > kMaxMaterials) {
        throw SceneError("a scene has at most " + std::to_string(kMaxMaterials) +
                         " materials, this one " + std::to_string(materials.size()));
    }
    for (std::size_t k = 0; k < setup.emitters.size(); ++k) {
        mEmitters.push_back(
            makeEmitter(setup.emitters[k], uint64_t(setup.simulation.seed), k, setup.sceneDir));
        const int material = materialIndex(materials, setup.emitters[k].material);
        if (material < 0) {
            throw SceneError("[[emitter]] " + std::to_string(k) + " names material '" +
                             setup.emitters[k].material + "', which no [[material]] has");
        }
        if (materials.size() > 1) mEmitterMaterials.push_back(uint8_t(material));
    }
    std::size_t planned = plannedCount();
    if (planned > std::size_t(INT32_MAX)) throw ResourceError("more than 2^31 globules requested");
    mGlobules.reserve(planned);
    for (std::size_t k = 0; k < mEmitters.size(); ++k) emitFrom(k, 0.0);
}

double Simulation::colliderReach(const SimulationSetup& setup) {
    double largest = 0;
    for (const EmitterSettings& e : setup.emitters) largest = std::max(largest, e.radius);
    largest = std::max(largest, 1e-3);
    // The force loop skips a collider for a whole neighbour-grid cell (one interaction
    // cutoff wide) when its distance at the cell's centre exceeds sqrt(3) times the
    // cell's half-diagonal (forces.cpp): the field must tell that far.
    const double cell = PairTable(setup.materials(), setup.materialPairs).cutoff(float(2 * largest));
    return 2 * largest + 1.5 * cell + 1;
}

std::size_t Simulation::plannedCount(const SimulationSetup& setup) {
    std::size_t total = 0;
    for (const auto& e : setup.emitters) {
        const std::size_t n = plannedGlobules(e);
        total = n > SIZE_MAX - total ? SIZE_MAX : total + n;
    }
    return total;
}

std::vector<MaterialSettings> SimulationSetup::materials() const {
    std::vector<MaterialSettings> all{material};
    all.insert(all.end(), otherMaterials.begin(), otherMaterials.end());
    return all;
}

void Simulation::emitFrom(std::size_t k, double time) {
    const std::size_t before = mGlobules.size();
    mEmitters[k]->emit(time, mGlobules, mNextId);
    if (!mEmitterMaterials.empty()) mGlobules.material.resize(mGlobules.size(), mEmitterMaterials[k]);
    if (mSetup.thermal.enabled) {
        mGlobules.temperature.resize(mGlobules.size(), float(mSetup.emitters[k].temperature));
    }
    const Globules& g = mGlobules;
    for (std::size_t i = before; i < g.size(); ++i) {
        if (!std::isfinite(g.px[i] + g.py[i] + g.pz[i]) ||
            !std::isfinite(g.vx[i] + g.vy[i] + g.vz[i])) {
            const std::string& type = mSetup.emitters[k].type;
            throw SceneError(
                "[[emitter]] " + std::to_string(k) + " (type " + type + ") places globule " +
                std::to_string(i - before) + " at a non-finite position or velocity: its " +
                (type == "box"     ? "min, max, spacing, jitter or velocity"
                 : type == "spout" ? "center, spacing, nozzle_radius, jitter, direction or speed"
                 : type == "helix" ? "center, helix_radius, spacing, jitter or velocity"
                                   : "offset, jitter or velocity") +
                " is too large for single-precision positions");
        }
    }
}

std::size_t Simulation::plannedCount() const {
    std::size_t total = 0;
    for (const auto& e : mEmitters) total += e->total();
    return total;
}

void Simulation::step(double dt) {
    for (std::size_t k = 0; k < mEmitters.size(); ++k) emitFrom(k, mTime);
    mForces.setStep(mTime, dt);
    // The force computation keeps the globules in neighbour-grid order (see forces.h).
    mIntegrator->step(mGlobules, float(dt),
                      [this](Globules& g, Accelerations& a) { mForces.compute(g, a); },
                      &mForces.colliders());
    mTime += dt;
    ++mSteps;
}

long Simulation::findRunaway() const {
    const float limit2 = float(mSetup.simulation.maxSpeed * mSetup.simulation.maxSpeed);
    const Globules& g = mGlobules;
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, g.size(), 4096), -1L,
        [&](const tbb::blocked_range<std::size_t>& r, long found) {
            for (std::size_t i = r.begin(); i != r.end() && found < 0; ++i) {
                const float v2 = g.vx[i] * g.vx[i] + g.vy[i] * g.vy[i] + g.vz[i] * g.vz[i];
                const float p = g.px[i] + g.py[i] + g.pz[i];
                if (!(v2 <= limit2) || !std::isfinite(p)) found = long(i);
            }
            return found;
        },
        [](long a, long b) { return a < 0 ? b : (b < 0 ? a : std::min(a, b)); });
}

long Simulation::stepTo(double frameEnd, int64_t steps, int refine, int64_t& taken) {
    const double frameStart = mTime;
    for (int64_t s = 0;; ++s) {
        double dt = 0;
        bool last = false;
        if (steps > 0) {
            dt = (frameEnd - frameStart) / double(steps);
            last = s + 1 == steps;
        } else {
            // Adaptive: what is due is emitted first, so that the bound sees it.
            for (std::size_t k = 0; k < mEmitters.size(); ++k) emitFrom(k, mTime);
            const double longest =
                std::min(mSetup.simulation.dt, mStableStep.bound(mGlobules).step()) / refine;
            const double left = frameEnd - mTime;
            // The steps left share what remains of the frame evenly: the last one ends on it.
            const double count = std::max(1.0, std::ceil(left / longest - 1e-9));
            if (!(count < 1e12)) {
                throw SimulationError("adaptive time step: the stability bound fell to " +
                                      std::to_string(longest) + " s at t = " +
                                      std::to_string(mTime) + " s (a runaway state)");
            }
            dt = left / count;
            last = count == 1;
            // A frame's last step may be cut short to land on the instant: not a bound.
            if (!last) mShortestStep = std::min(mShortestStep, dt);
        }
        step(dt);
        ++taken;
        const long runaway = findRunaway();
        if (runaway >= 0 || last) return runaway;
    }
}

void Simulation::advanceFrame(int frame, Reporter& reporter) {
    const SimulationSettings& sim = mSetup.simulation;
    const int64_t baseSteps = sim.adaptive ? 0 : sim.substepsPerFrame();
    const double frameEnd = double(frame - 1) / sim.fps;
    const bool retry = sim.onExplosion == "substep";
    SimulationState saved;
    if (retry) saved = saveState();
    for (int refine = 1;; refine *= 2) {
        int64_t taken = 0;
        const double stepStart = mTime;
        const long runaway = stepTo(frameEnd, baseSteps * refine, refine, taken);
        if (runaway < 0) {
            mTime = frameEnd;  // no drift from summing dt
            mForces.colliders().setTime(mTime);
            return;
        }
        std::ostringstream why;
        why << "simulation exploded at frame " << frame << ", step " << taken;
        if (baseSteps > 0) why << " of " << baseSteps * refine;
        why << " (t = " << mTime << " s): " << describeRunaway(mGlobules, runaway, sim.maxSpeed);
        const double dt = baseSteps > 0 ? (frameEnd - stepStart) / double(baseSteps * refine)
                                        : (mTime - stepStart) / double(std::max<int64_t>(taken, 1));
        why << ". The step dt = " << dt << " s is likely too large for these material parameters";
        if (!retry || refine >= kMaxSubstepRefinement) {
            why << "; try dt = " << dt / 4
                << (retry ? "" : " or set simulation.on_explosion = \"substep\"");
            throw SimulationError(why.str());
        }
        reporter.warn(why.str() + "; retrying the frame with steps half as long");
        restoreState(saved);
    }
}

SimulationState Simulation::saveState() const {
    SimulationState state;
    state.globules = mGlobules;
    state.time = mTime;
    state.steps = mSteps;
    state.nextId = mNextId;
    for (const auto& e : mEmitters) state.emitted.push_back(e->emitted());
    if (auto* carried = mIntegrator->carriedState()) state.carried = *carried;
    for (const RigidBody& body : mForces.colliders().bodies()) state.bodies.push_back(body.state);
    return state;
}

void Simulation::restoreState(const SimulationState& state) {
    if (state.emitted.size() != mEmitters.size()) {
        throw Error("saved state has " + std::to_string(state.emitted.size()) +
                    " emitters, the scene " + std::to_string(mEmitters.size()));
    }
    std::vector<RigidBody>& bodies = mForces.colliders().bodies();
    if (state.bodies.size() != bodies.size()) {
        throw Error("saved state has " + std::to_string(state.bodies.size()) +
                    " dynamic colliders, the scene " + std::to_string(bodies.size()));
    }
    const std::size_t materials = mForces.pairs().materials();
    const Globules& g = state.globules;
    const bool fits = materials == 1 ? g.material.empty()
                                     : g.material.size() == g.size() &&
                                           std::all_of(g.material.begin(), g.material.end(),
                                                       [&](uint8_t m) { return m < materials; });
    if (!fits) {
        throw Error("saved state's globule materials do not fit the scene's " +
                    std::to_string(materials) + " material(s)");
    }
    const bool thermal = mSetup.thermal.enabled;
    if (thermal ? g.temperature.size() != g.size() : !g.temperature.empty()) {
        throw Error(thermal ? "saved state has no temperatures, but the scene is thermal"
                            : "saved state has temperatures, but the scene is not thermal");
    }
    if (thermal && !state.carried.x.empty() && state.carried.heat.size() != state.carried.x.size()) {
        throw Error("saved state's integrator state has no heating rates");
    }
    for (std::size_t b = 0; b < bodies.size(); ++b) bodies[b].state = state.bodies[b];
    mGlobules = state.globules;
    mTime = state.time;
    mSteps = state.steps;
    mNextId = state.nextId;
    for (std::size_t k = 0; k < mEmitters.size(); ++k) mEmitters[k]->skipTo(state.emitted[k]);
    if (auto* carried = mIntegrator->carriedState()) *carried = state.carried;
}

}  // namespace globular
