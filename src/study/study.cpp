#include "study.hpp"

#include "parallel_runs.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include "exact_solution.hpp"
#include "pba/blow_up_watch.hpp"

namespace pba::study {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Follows one particle through a run: energy, apexes (from the state just before vy turns
/// down: y + vy^2 / 2g, exact for a state on an exact parabola), and the position error.
struct Tracker {
    std::size_t index;
    std::optional<ExactSolution> exact;
    double e0;
    ParticleResult result;
    std::vector<double> apexTimes{0.0};
    double lastApex = kNaN;
    double previousVy = 0.0;
    double previousTime = 0.0;
    std::size_t stride = 1;
    /// Only the first moving particle's series is kept: the plots follow it alone, and a series
    /// for every particle of a cloth, in every run, took gigabytes.
    bool keepSeries = false;

    /// `energies`: World::energies() now (one pass for every tracker).
    void sample(const World& world, const std::vector<double>& energies)
    {
        const Body& b = world.body(index);
        const double ratio = e0 != 0.0 ? energies[index] / e0 : 1.0;
        result.maxEnergyDeviation = std::max(result.maxEnergyDeviation, std::abs(ratio - 1.0));
        if (world.stepCount() > 0)
            result.meanEnergyRatio += ratio / double(result.steps);
        if (exact)
            result.maxPositionError =
                std::max(result.maxPositionError, glm::length(b.getPos() - exact->position(world.time())));
        if (keepSeries && world.stepCount() % stride == 0) {
            result.series.t.push_back(world.time());
            result.series.y.push_back(b.getPos().y);
            result.series.energyRatio.push_back(ratio);
        }
    }

    void beforeStep(const World& world)
    {
        previousVy = world.body(index).getVel().y;
        previousTime = world.time();
    }

    void afterStep(const World& world, const State& before)
    {
        const double vy = world.body(index).getVel().y;
        if (exact && exact->kind() == ExactSolution::Kind::Bounce && previousVy > 0.0 && vy <= 0.0 &&
            world.bounceCount(index) > 0) {
            const double g = exact->gravity();
            lastApex = before.pos.y + before.vel.y * before.vel.y / (2.0 * g);
            apexTimes.push_back(previousTime + before.vel.y / g);
        }
    }
};

/// Follows the whole system through a run: the world's total energy, the moving bodies' bounces
/// and centre of mass. A rope or a cloth has no exact solution, and any one of its particles
/// (the one next to the pin barely moves) says little about how the rope moved.
struct SystemTracker {
    std::vector<std::size_t> moving;
    double e0 = 0.0;
    ParticleResult result;
    std::size_t stride = 1;

    dvec3 centre(const World& world) const
    {
        dvec3 sum(0.0);
        double mass = 0.0;
        for (std::size_t i : moving) {
            sum += world.body(i).getMass() * world.body(i).getPos();
            mass += world.body(i).getMass();
        }
        return sum / mass;
    }

    void sample(const World& world, const std::vector<double>& energies)
    {
        double e = 0.0;
        for (double x : energies)
            e += x;
        const double ratio = e0 != 0.0 ? e / e0 : 1.0;
        result.maxEnergyDeviation = std::max(result.maxEnergyDeviation, std::abs(ratio - 1.0));
        if (world.stepCount() > 0)
            result.meanEnergyRatio += ratio / double(result.steps);
        if (std::isnan(result.firstImpactAt) &&
            std::any_of(moving.begin(), moving.end(), [&](std::size_t i) { return world.bounceCount(i) > 0; }))
            result.firstImpactAt = world.time();
        if (world.stepCount() % stride == 0) {
            const dvec3 c = centre(world);
            result.series.t.push_back(world.time());
            result.series.y.push_back(c.y);
            result.series.energyRatio.push_back(ratio);
            result.series.centre.push_back(c);
        }
    }
};

double sum(const std::vector<double>& values)
{
    double s = 0.0;
    for (double x : values)
        s += x;
    return s;
}

/// The largest distance between a run's centre of mass and the reference's at the run's
/// samples up to `until`, the reference (every step of a finer dt) interpolated linearly between
/// its steps; NaN when the reference blew up, and so is no reference.
double maxCentreDistance(const ParticleResult& run, const ParticleResult& reference, double until)
{
    if (!std::isnan(reference.blewUpAt))
        return kNaN;
    const Series& r = reference.series;
    double worst = 0.0;
    for (std::size_t k = 0; k < run.series.t.size() && run.series.t[k] <= until; ++k) {
        const double t = run.series.t[k];
        const auto hi = std::size_t(std::lower_bound(r.t.begin(), r.t.end(), t) - r.t.begin());
        if (hi >= r.t.size())
            break;
        const std::size_t lo = hi == 0 ? 0 : hi - 1;
        const double w = r.t[hi] > r.t[lo] ? (t - r.t[lo]) / (r.t[hi] - r.t[lo]) : 1.0;
        const dvec3 c = r.centre[lo] + w * (r.centre[hi] - r.centre[lo]);
        worst = std::max(worst, glm::length(run.series.centre[k] - c));
    }
    return worst;
}

} // namespace

bool followsSystem(const World& world)
{
    std::size_t moving = 0, first = world.bodyCount();
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed()) {
            first = std::min(first, i);
            ++moving;
        }
    return moving > 1 && !ExactSolution::find(world, first);
}

namespace {

/// A run's trackers: one per moving particle, and the whole system's when the run follows it.
struct RunTrackers {
    std::vector<Tracker> particles;
    SystemTracker whole;
    bool system = false;
};

/// Gives every moving body the method, and starts a tracker on each (and the system's), sampled
/// at the start.
RunTrackers startRun(World& world, Integrator integrator, CollisionResponse collision, double dt, std::uint64_t steps,
                     bool system, std::size_t seriesPoints)
{
    RunTrackers run;
    run.system = system;
    const std::vector<double> startEnergies = world.energies();
    const std::size_t stride = std::max<std::size_t>(1, static_cast<std::size_t>(steps / std::max<std::size_t>(1, seriesPoints)));
    const auto label = [&](ParticleResult& r) {
        r.integrator = integrator;
        r.collision = collision;
        r.dt = dt;
        r.steps = steps;
    };
    run.whole.e0 = sum(startEnergies);
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        if (world.body(i).isFixed())
            continue;
        world.body(i).setIntegrator(integrator);
        Tracker t{i, ExactSolution::find(world, i), startEnergies[i], {}};
        t.result.particle = world.body(i).getName();
        label(t.result);
        t.stride = stride;
        t.keepSeries = !system && run.particles.empty();
        run.particles.push_back(std::move(t));
        run.whole.moving.push_back(i);
    }
    run.whole.result.particle = kSystemRow;
    label(run.whole.result);
    run.whole.stride = stride;
    if (system)
        run.whole.sample(world, startEnergies);
    for (auto& t : run.particles)
        t.sample(world, startEnergies);
    return run;
}

/// Steps the run to its end, sampling after each step. An unstable run (forward Euler on a
/// cloth at a large dt) is a result, not a failure of the study: it stops where it blew up (a
/// state not finite, or energy gained beyond its sources' work: BlowUpWatch) and returns when
/// (NaN when it did not). The energies sampled are less the sources' work.
double stepRun(World& world, RunTrackers& run, BlowUpWatch& watch, double dt, std::uint64_t steps)
{
    std::vector<State> before(run.particles.size());
    try {
        for (std::uint64_t n = 0; n < steps; ++n) {
            for (std::size_t k = 0; k < run.particles.size(); ++k) {
                run.particles[k].beforeStep(world);
                before[k] = world.body(run.particles[k].index).getState();
            }
            world.step(dt);
            watch.check(world);
            const std::vector<double> energies = watch.energiesWithoutSourceWork(world);
            for (std::size_t k = 0; k < run.particles.size(); ++k) {
                run.particles[k].afterStep(world, before[k]);
                run.particles[k].sample(world, energies);
            }
            if (run.system)
                run.whole.sample(world, energies);
        }
    } catch (const BlowUpError& error) {
        return error.time();
    }
    return kNaN;
}

/// The run's rows: the system's first (when followed), then each particle's.
std::vector<ParticleResult> finishRun(const World& world, RunTrackers& run, double blewUpAt,
                                      const std::vector<double>& endEnergies)
{
    const auto endRatio = [&](double energy, double e0) {
        return !std::isnan(blewUpAt) ? std::numeric_limits<double>::infinity() : e0 != 0.0 ? energy / e0 : 1.0;
    };
    std::vector<ParticleResult> results;
    if (run.system) {
        ParticleResult& r = run.whole.result;
        r.blewUpAt = blewUpAt;
        r.energyRatioEnd = endRatio(sum(endEnergies), run.whole.e0);
        for (std::size_t i : run.whole.moving)
            r.bounces += world.bounceCount(i);
        r.apexRatioLast = r.periodError = r.maxPositionError = kNaN; // the error is set against the reference
        results.push_back(std::move(r));
    }
    for (auto& t : run.particles) {
        ParticleResult& r = t.result;
        r.blewUpAt = blewUpAt;
        r.energyRatioEnd = endRatio(endEnergies[t.index], t.e0);
        r.bounces = world.bounceCount(t.index);
        const bool bounce = t.exact && t.exact->kind() == ExactSolution::Kind::Bounce;
        r.apexRatioLast = bounce && !std::isnan(t.lastApex) ? t.lastApex / t.exact->height() : kNaN;
        if (bounce && t.apexTimes.size() >= 2) {
            const double measured = (t.apexTimes.back() - t.apexTimes.front()) / double(t.apexTimes.size() - 1);
            r.periodError = (measured - t.exact->period()) / t.exact->period();
        } else {
            r.periodError = kNaN;
        }
        if (!t.exact)
            r.maxPositionError = kNaN;
        results.push_back(std::move(r));
    }
    return results;
}

} // namespace

std::vector<ParticleResult> measureRun(const Scene& scene, Integrator integrator, CollisionResponse collision,
                                       double dt, double duration, bool system, std::size_t seriesPoints)
{
    World world = scene.world;
    world.setCollisionResponse(collision);
    const auto steps = static_cast<std::uint64_t>(std::max(1.0, std::round(duration / dt)));
    RunTrackers run = startRun(world, integrator, collision, dt, steps, system, seriesPoints);
    BlowUpWatch watch(world);
    const double blewUpAt = stepRun(world, run, watch, dt, steps);
    return finishRun(world, run, blewUpAt, watch.energiesWithoutSourceWork(world));
}

OrderResult measureOrder(const Scene& spring, Integrator integrator, const std::vector<double>& dts, double window)
{
    OrderResult order{integrator, dts, {}, {}, kNaN, integratorOrder(integrator)};
    for (double dt : dts) {
        const auto runs = measureRun(spring, integrator, CollisionResponse::Exact, dt, window);
        order.errors.push_back(runs.empty() ? kNaN : runs.front().maxPositionError);
    }
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (std::size_t i = 0; i < dts.size(); ++i) {
        if (dts[i] > kOrderMaxDt + 1e-12 || !(order.errors[i] > kOrderRoundingError))
            continue;
        order.fitted.push_back(dts[i]);
        const double x = std::log(dts[i]), y = std::log(order.errors[i]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        ++n;
    }
    if (n >= 2)
        order.measured = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    return order;
}

long studyTaskCount(const StudyConfig& config)
{
    const std::size_t n = config.integrators.size();
    const std::size_t limits = hasMovingSprings(config.scene.world) ? n : 0; // the count shown, not a promise
    const std::size_t references = followsSystem(config.scene.world) ? n * config.collisions.size() : 0;
    return static_cast<long>(n * config.collisions.size() * config.dts.size() + n + limits + references);
}

namespace {

bool allMovingCoupled(const World& world)
{
    bool any = false;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed()) {
            any = true;
            if (!world.isCoupled(i))
                return false;
        }
    return any;
}

/// Sets each system row's error: its centre of mass against the reference run of its method
/// and response.
void compareWithReferences(std::vector<std::vector<ParticleResult>>& runs,
                           const std::vector<std::vector<ParticleResult>>& references)
{
    for (auto& run : runs)
        for (const auto& reference : references)
            if (!run.empty() && !reference.empty() && run.front().integrator == reference.front().integrator &&
                run.front().collision == reference.front().collision)
            {
                const ParticleResult& ref = reference.front();
                const double impact = std::isnan(ref.firstImpactAt) ? std::numeric_limits<double>::infinity()
                                                                    : ref.firstImpactAt;
                run.front().maxPositionError = maxCentreDistance(run.front(), ref, std::numeric_limits<double>::infinity());
                run.front().errorBeforeImpact = maxCentreDistance(run.front(), ref, impact);
            }
}

} // namespace

StudyResult runStudy(const StudyConfig& config, const std::function<void(long, long)>& progress)
{
    struct Task {
        Integrator integrator;
        CollisionResponse collision;
        double dt;
    };
    std::vector<Task> tasks;
    for (Integrator integrator : config.integrators)
        for (CollisionResponse collision : config.collisions)
            for (double dt : config.dts)
                tasks.push_back({integrator, collision, dt});
    const Scene spring = loadScene("spring");
    StudyResult result;
    result.omegaMax = highestFrequency(config.scene.world);
    result.followsSystem = followsSystem(config.scene.world);
    result.exactActsAsReflect = allMovingCoupled(config.scene.world);
    result.lessSourceWork = config.scene.world.hasEnergySources();
    std::vector<Task> referenceTasks;
    if (result.followsSystem) {
        // A quarter of the smallest dt: the reference's own error is then a quarter (order 1) or
        // less of the finest run's, and the finest run's error is mostly its own.
        result.referenceDt = *std::min_element(config.dts.begin(), config.dts.end()) / 4.0;
        for (Integrator integrator : config.integrators)
            for (CollisionResponse collision : config.collisions)
                referenceTasks.push_back({integrator, collision, result.referenceDt});
    }
    const std::size_t orders = config.integrators.size();
    const std::size_t limits = result.omegaMax ? config.integrators.size() : 0;
    const std::size_t references = referenceTasks.size();
    const std::size_t total = references + tasks.size() + orders + limits;
    std::vector<std::vector<ParticleResult>> runs(tasks.size()), referenceRuns(references);
    result.orders.resize(orders);
    result.stability.resize(limits);
    const bool system = result.followsSystem;
    runInParallel(total, config.jobs, [&](std::size_t i) {
        // The references first: they are the longest runs, and would otherwise finish last alone.
        if (i < references) {
            const Task& t = referenceTasks[i];
            referenceRuns[i] = measureRun(config.scene, t.integrator, t.collision, t.dt, config.duration, true,
                                          std::numeric_limits<std::size_t>::max());
            referenceRuns[i].resize(1);
            return;
        }
        i -= references;
        if (i < tasks.size())
            runs[i] = measureRun(config.scene, tasks[i].integrator, tasks[i].collision, tasks[i].dt, config.duration,
                                 system);
        else if (i < tasks.size() + orders)
            result.orders[i - tasks.size()] =
                measureOrder(spring, config.integrators[i - tasks.size()], config.dts, result.orderWindow);
        else
            result.stability[i - tasks.size() - orders] = measureStabilityLimit(
                config.scene, config.integrators[i - tasks.size() - orders], *result.omegaMax, config.stability);
    }, progress);
    compareWithReferences(runs, referenceRuns);
    for (auto& run : runs)
        for (auto& r : run)
            result.runs.push_back(std::move(r));
    return result;
}

} // namespace pba::study
