#include "rotation_study.hpp"

#include <algorithm>
#include <cmath>

#include "parallel_runs.hpp"
#include "pba/blow_up_watch.hpp"
#include "study/rigid_watch.hpp"

namespace pba::study {

std::optional<std::size_t> studiedRigidBody(const World& world)
{
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (world.isRigid(i) && !world.body(i).isFixed())
            return i;
    return std::nullopt;
}

int intermediateAxisOf(const dmat3& inertia)
{
    const double m[3] = {inertia[0][0], inertia[1][1], inertia[2][2]};
    for (int axis = 0; axis < 3; ++axis) {
        const double a = m[(axis + 1) % 3], c = m[(axis + 2) % 3];
        if ((a < m[axis] && m[axis] < c) || (c < m[axis] && m[axis] < a))
            return axis;
    }
    return -1;
}

namespace {

bool finite(const RigidBody& b)
{
    const dvec3 x = b.getPos(), v = b.getVel(), l = b.getAngularMomentum();
    const dquat q = b.getOrientation();
    return std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z + l.x + l.y + l.z + q.w + q.x + q.y + q.z);
}

RotationRun runOne(const Scene& scene, std::size_t body, int axis, Integrator integrator, double dt, double duration)
{
    Scene copy = scene;
    World& world = copy.world;
    // The methods studied are rigid bodies' own: particles, ropes and cloths keep theirs (a
    // trampoline's cloth, stiff and damped for implicit Euler, blows up in a few steps under any
    // explicit one).
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (world.isRigid(i) && !world.body(i).isFixed())
            world.body(i).setIntegrator(integrator);
    const auto& b = static_cast<const RigidBody&>(world.body(body));
    RotationRun run;
    run.integrator = integrator;
    run.dt = dt;
    const double e0 = world.energy(body), l0 = glm::length(b.getAngularMomentum());
    if (!(l0 > 0.0)) // no spin at the start: no |L| to keep
        run.maxMomentumDrift = kNaN;
    const auto steps = static_cast<std::uint64_t>(std::llround(duration / dt));
    const std::uint64_t every = std::max<std::uint64_t>(1, steps / 2000); // about 2000 samples a series
    const auto omegaAbout = [&] {
        return axis < 0 ? 0.0 : (glm::transpose(glm::mat3_cast(b.getOrientation())) * b.getAngularVelocity())[axis];
    };
    double previous = omegaAbout();
    std::vector<double> flips;
    BlowUpWatch watch(world);
    for (std::uint64_t n = 1; n <= steps; ++n) {
        try {
            world.step(dt);
            watch.check(world);
        } catch (const BlowUpError& error) {
            run.blewUpAt = error.time();
            break;
        }
        if (!finite(b)) {
            run.blewUpAt = world.time();
            break;
        }
        run.touched = run.touched || touchedSurfaces(world)[body] != kNone;
        const double e = world.energy(body) / e0;
        run.maxEnergyDrift = std::max(run.maxEnergyDrift, std::abs(e - 1.0));
        if (l0 > 0.0)
            run.maxMomentumDrift = std::max(run.maxMomentumDrift, std::abs(glm::length(b.getAngularMomentum()) / l0 - 1.0));
        const double w = omegaAbout();
        if (w * previous < 0.0) // the crossing, interpolated within the step (not rounded to a step)
            flips.push_back(world.time() - dt * w / (w - previous));
        previous = w;
        if (n % every == 0) {
            run.t.push_back(world.time());
            run.energyRatio.push_back(e);
            run.intermediateOmega.push_back(w);
        }
        run.steps = n;
        run.energyRatioEnd = e;
    }
    run.flips = flips.size();
    // The component changes sign twice a period: a period is the time from one sign change to
    // the one after next, averaged over all of them.
    if (flips.size() >= 3)
        run.flipPeriod = 2.0 * (flips.back() - flips.front()) / double(flips.size() - 1);
    return run;
}

} // namespace

double torqueFreeFlipPeriod(const RigidBody& body)
{
    const dmat3& inertia = body.getInertiaBody();
    if (intermediateAxisOf(inertia) < 0)
        return kNaN;
    double m[3] = {inertia[0][0], inertia[1][1], inertia[2][2]};
    std::sort(m, m + 3);
    double a = m[0];
    const double b = m[1];
    double c = m[2];
    const double e = body.getRotationalKineticEnergy();
    const double l2 = glm::dot(body.getAngularMomentum(), body.getAngularMomentum());
    if (l2 > 2.0 * e * b) // the other side of the separatrix: the same formula with a and c swapped
        std::swap(a, c);
    const double k2 = (c - b) * (l2 - 2.0 * e * a) / ((b - a) * (2.0 * e * c - l2));
    // On an axis there is no flip; on the separatrix (k = 1: spinning exactly about the
    // intermediate axis, to rounding) the period is infinite.
    if (!(k2 > 0.0 && k2 < 1.0 - 1e-9))
        return kNaN;
    return 4.0 * std::comp_ellint_1(std::sqrt(k2)) * std::sqrt(a * b * c / ((b - a) * (2.0 * e * c - l2)));
}

RotationResult runRotationStudy(const RotationConfig& config, const std::function<void(long, long)>& progress)
{
    RotationResult result;
    const World& world = config.scene.world;
    const std::optional<std::size_t> body = config.body ? config.body : studiedRigidBody(world);
    if (!body)
        return result;
    const auto& b = static_cast<const RigidBody&>(world.body(*body));
    result.body = b.getName();
    for (std::size_t j = 0; j < world.jointCount(); ++j) {
        const JointFrame frame = world.jointFrame(j);
        result.joined = result.joined || frame.bodyA == *body || frame.bodyB == *body;
    }
    result.intermediateAxis = intermediateAxisOf(b.getInertiaBody());
    result.exactPeriod = torqueFreeFlipPeriod(b);
    const dvec3 l = glm::transpose(glm::mat3_cast(b.getOrientation())) * b.getAngularMomentum(); // body frame
    result.spins = l != dvec3(0.0);
    if (const int k = result.intermediateAxis; k >= 0)
        result.flips = std::abs(l[k]) >= std::abs(l[(k + 1) % 3]) && std::abs(l[k]) >= std::abs(l[(k + 2) % 3]);
    const std::size_t dts = config.dts.size();
    result.runs.resize(config.integrators.size() * dts);
    runInParallel(result.runs.size(), config.jobs, [&](std::size_t i) {
        result.runs[i] = runOne(config.scene, *body, result.intermediateAxis, config.integrators[i / dts],
                                config.dts[i % dts], config.duration);
    }, progress);
    return result;
}

} // namespace pba::study
