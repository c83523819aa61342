#include "stability.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "pba/forces.hpp"
#include "pba/spring_network.hpp"

namespace pba::study {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kSeriesPoints = 2000;

/// The stiffness of the world's springs as a list of terms k u u^T coupling two moving bodies
/// (or one, for an anchored spring or a spring to a fixed body), at the start state.
struct StiffnessTerm {
    std::size_t a, b; ///< b == kNone: a spring from a to something fixed
    double k;
    dvec3 u;
};
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

class StiffnessCollector final : public ForceVisitor {
public:
    explicit StiffnessCollector(const World& world) : m_world(world) {}
    std::vector<StiffnessTerm> terms;
    bool degenerate = false;

    void visit(const Spring& s) override { add(s.particle(), kNone, s.anchor(), s.stiffness()); }
    void visit(const TwoBodySpring& s) override
    {
        add(s.first(), s.second(), m_world.body(s.second()).getPos(), s.stiffness());
    }
    void visit(const SpringNetwork& springs) override
    {
        for (std::size_t s = 0; s < springs.size(); ++s) {
            const SpringNetwork::Link l = springs.link(s);
            add(l.a, l.b, m_world.body(l.b).getPos(), l.stiffness);
        }
    }

private:
    void add(std::size_t a, std::size_t b, const dvec3& other, double k)
    {
        const bool aMoves = !m_world.body(a).isFixed();
        const bool bMoves = b != kNone && !m_world.body(b).isFixed();
        if (!aMoves && !bMoves)
            return;
        const dvec3 d = other - m_world.body(a).getPos();
        const double length = glm::length(d);
        if (!(length > 0.0)) {
            degenerate = true;
            return;
        }
        // A spring to a fixed body is a spring to an anchor at that body's place.
        if (aMoves)
            terms.push_back({a, bMoves ? b : kNone, k, d / length});
        else
            terms.push_back({b, kNone, k, d / length});
    }

    const World& m_world;
};

/// A spring's ends and rest length, to tell when a run has left the linear regime.
struct SpringSpan {
    std::size_t a, b; ///< b == kNone: anchored at `anchor`
    dvec3 anchor;
    double restLength;
    double stiffness;
};

class SpanCollector final : public ForceVisitor {
public:
    std::vector<SpringSpan> spans;
    void visit(const Spring& s) override { add({s.particle(), kNone, s.anchor(), s.restLength(), s.stiffness()}); }
    void visit(const TwoBodySpring& s) override { add({s.first(), s.second(), dvec3(0.0), s.restLength(), s.stiffness()}); }
    void visit(const SpringNetwork& springs) override
    {
        for (std::size_t s = 0; s < springs.size(); ++s) {
            const SpringNetwork::Link l = springs.link(s);
            add({l.a, l.b, dvec3(0.0), l.restLength, l.stiffness});
        }
    }

private:
    void add(const SpringSpan& span)
    {
        if (span.restLength > 0.0) // a zero-length spring has no side to turn inside out
            spans.push_back(span);
    }
};

/// True if some spring is stretched to twice its rest length or compressed through zero: past
/// that the linearisation the theory rests on is gone (the spring turns inside out), and a
/// blown-up chain or cloth can tangle into a bounded but meaningless state rather than grow.
bool leftLinearRegime(const World& world, const std::vector<SpringSpan>& spans)
{
    for (const auto& s : spans) {
        const dvec3 other = s.b == kNone ? s.anchor : world.body(s.b).getPos();
        if (!(std::abs(glm::length(world.body(s.a).getPos() - other) - s.restLength) < s.restLength))
            return true;
    }
    return false;
}

/// y = M^-1/2 K M^-1/2 x over every body (fixed ones stay zero): symmetric, with the
/// eigenvalues of M^-1 K, so the power iteration's Rayleigh quotient converges monotonically.
void applySymmetric(const std::vector<StiffnessTerm>& terms, const std::vector<double>& invSqrtMass,
                    const std::vector<dvec3>& x, std::vector<dvec3>& y)
{
    std::fill(y.begin(), y.end(), dvec3(0.0));
    for (const auto& t : terms) {
        const dvec3 xa = x[t.a] * invSqrtMass[t.a];
        const dvec3 xb = t.b == kNone ? dvec3(0.0) : x[t.b] * invSqrtMass[t.b];
        const dvec3 f = t.k * glm::dot(t.u, xa - xb) * t.u; // K's blocks: +k u u^T on the diagonal, -k u u^T off it
        y[t.a] += f * invSqrtMass[t.a];
        if (t.b != kNone)
            y[t.b] -= f * invSqrtMass[t.b];
    }
}

double dot(const std::vector<dvec3>& a, const std::vector<dvec3>& b)
{
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        s += glm::dot(a[i], b[i]);
    return s;
}

/// The start vector of the iterations below: alternating in sign from body to body (the shape of
/// the highest mode of a chain or a grid, so they start close to it) and differing per axis.
std::vector<dvec3> alternatingStart(const std::vector<std::uint8_t>& moving)
{
    std::vector<dvec3> x(moving.size(), dvec3(0.0));
    for (std::size_t i = 0; i < x.size(); ++i)
        if (moving[i])
            x[i] = (i % 2 == 0 ? 1.0 : -1.0) * dvec3(1.0, 0.8 + 0.1 * std::sin(double(i)), 0.6 + 0.1 * std::cos(double(i)));
    return x;
}

/// Largest eigenvalue of the symmetric positive semi-definite operator by power iteration.
double powerIteration(const std::vector<StiffnessTerm>& terms, const std::vector<double>& invSqrtMass,
                      std::vector<dvec3> x)
{
    std::vector<dvec3> y(x.size());
    double lambda = 0.0;
    // The error of the Rayleigh quotient shrinks as (lambda_2 / lambda_1)^(2 k): close
    // eigenvalues (long chains) need many iterations, so the loop runs until the quotient
    // stops changing at rounding, not for a fixed count.
    for (int iteration = 0; iteration < 200000; ++iteration) {
        const double norm = std::sqrt(dot(x, x));
        if (!(norm > 0.0))
            return 0.0;
        for (auto& v : x)
            v /= norm;
        applySymmetric(terms, invSqrtMass, x, y);
        const double next = dot(x, y);
        std::swap(x, y);
        if (iteration > 10 && std::abs(next - lambda) <= 1e-15 * std::abs(next))
            return next;
        lambda = next;
    }
    return lambda;
}

/// The largest eigenvalue of the symmetric tridiagonal matrix (diagonal a, off-diagonal b[i]
/// between rows i - 1 and i), by bisection on its Sturm sequence.
double largestTridiagonalEigenvalue(const std::vector<double>& a, const std::vector<double>& b)
{
    const std::size_t k = a.size();
    double low = 0.0, high = 0.0;
    for (std::size_t i = 0; i < k; ++i) { // Gershgorin's discs hold every eigenvalue
        const double radius = (i > 0 ? std::abs(b[i]) : 0.0) + (i + 1 < k ? std::abs(b[i + 1]) : 0.0);
        low = std::min(low, a[i] - radius);
        high = std::max(high, a[i] + radius);
    }
    auto below = [&](double x) { // how many eigenvalues are below x
        std::size_t count = 0;
        double d = 1.0;
        for (std::size_t i = 0; i < k; ++i) {
            d = a[i] - x - (i > 0 ? b[i] * b[i] / d : 0.0);
            if (d == 0.0)
                d = -1e-300;
            count += d < 0.0 ? 1 : 0;
        }
        return count;
    };
    for (int i = 0; i < 200 && high - low > 1e-16 * std::max(std::abs(high), std::abs(low)); ++i) {
        const double middle = 0.5 * (low + high);
        (below(middle) == k ? high : low) = middle;
    }
    return high;
}

/// Largest eigenvalue of the symmetric positive semi-definite operator by Lanczos's iteration,
/// every new vector orthogonalised against all before it (so no copy of a converged eigenvalue
/// appears): its largest Ritz value converges as a Chebyshev polynomial's growth, in about the
/// square root of the power iteration's count, which on a cloth's close eigenvalues is the
/// difference between a second and a hundredth of one. Past kMaxLanczos vectors (their memory)
/// the power iteration finishes the job.
double largestEigenvalue(const std::vector<StiffnessTerm>& terms, const std::vector<double>& invSqrtMass,
                         const std::vector<std::uint8_t>& moving)
{
    constexpr std::size_t kMaxLanczos = 300;
    std::vector<dvec3> x = alternatingStart(moving);
    const double norm = std::sqrt(dot(x, x));
    if (!(norm > 0.0))
        return 0.0;
    for (auto& v : x)
        v /= norm;
    std::vector<std::vector<dvec3>> basis{x};
    std::vector<double> alpha, beta{0.0};
    std::vector<dvec3> w(x.size());
    double ritz = 0.0;
    int unchanged = 0;
    const std::size_t most = std::min(kMaxLanczos, 3 * x.size());
    while (basis.size() <= most) {
        applySymmetric(terms, invSqrtMass, basis.back(), w);
        alpha.push_back(dot(basis.back(), w));
        for (int pass = 0; pass < 2; ++pass) // twice is enough (Kahan and Parlett)
            for (const auto& q : basis) {
                const double c = dot(q, w);
                for (std::size_t i = 0; i < w.size(); ++i)
                    w[i] -= c * q[i];
            }
        const double next = largestTridiagonalEigenvalue(alpha, beta);
        unchanged = std::abs(next - ritz) <= 1e-15 * std::abs(next) ? unchanged + 1 : 0;
        ritz = next;
        const double length = std::sqrt(dot(w, w));
        if (unchanged >= 3 || !(length > 1e-14 * std::max(ritz, 1e-300)))
            return ritz; // converged, or the space the start vector reaches is exhausted
        beta.push_back(length);
        for (auto& v : w)
            v /= length;
        basis.push_back(w);
    }
    return powerIteration(terms, invSqrtMass, basis.back());
}

} // namespace

bool hasMovingSprings(const World& world)
{
    StiffnessCollector collector(world);
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(collector);
    return !collector.terms.empty();
}

std::optional<double> highestFrequency(const World& world)
{
    StiffnessCollector collector(world);
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(collector);
    if (collector.terms.empty() || collector.degenerate)
        return std::nullopt;
    const std::size_t n = world.bodyCount();
    std::vector<double> invSqrtMass(n, 0.0);
    std::vector<std::uint8_t> moving(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        if (!world.body(i).isFixed()) {
            invSqrtMass[i] = 1.0 / std::sqrt(world.body(i).getMass());
            moving[i] = 1;
        }
    const double lambda = largestEigenvalue(collector.terms, invSqrtMass, moving);
    if (!(lambda > 0.0))
        return std::nullopt;
    return std::sqrt(lambda);
}

double largestStartStretch(const World& world)
{
    SpanCollector springs;
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(springs);
    double stretch = 0.0;
    for (const auto& s : springs.spans) {
        const dvec3 other = s.b == kNone ? s.anchor : world.body(s.b).getPos();
        stretch = std::max(stretch, std::abs(glm::length(world.body(s.a).getPos() - other) - s.restLength) / s.restLength);
    }
    return stretch;
}

double theoryDtLimit(Integrator integrator, double omega)
{
    switch (integrator) {
    case Integrator::ForwardEuler:
        return kNaN;
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic:
    case Integrator::VelocityVerlet:
    case Integrator::Splitting:
        return 2.0 / omega;
    case Integrator::ImplicitEuler:
    case Integrator::Xpbd:
        return std::numeric_limits<double>::infinity();
    case Integrator::RK4:
        return 2.0 * std::sqrt(2.0) / omega;
    }
    return kNaN;
}

StabilityRun runStability(const Scene& scene, Integrator integrator, double dt, double omega,
                          const StabilityCriterion& criterion)
{
    World world = scene.world;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed())
            world.body(i).setIntegrator(integrator);
    SpanCollector springs;
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(springs);
    const double e0 = world.totalEnergy();
    const double bound = e0 + (criterion.energyFactor - 1.0) * std::abs(e0);
    const double horizon = criterion.periods * 2.0 * std::numbers::pi / omega;
    const auto steps = static_cast<std::uint64_t>(std::ceil(horizon / dt));
    const std::uint64_t stride = std::max<std::uint64_t>(1, steps / kSeriesPoints);
    StabilityRun run{dt, true, false, {}};
    auto sample = [&](double e) {
        run.series.t.push_back(world.time());
        run.series.energyRatio.push_back(e0 != 0.0 ? e / e0 : 1.0);
    };
    sample(e0);
    for (std::uint64_t n = 1; n <= steps; ++n) {
        try {
            world.step(dt);
        } catch (const BlowUpError&) { // a state not finite, or a rigid body inside a wall
            run.stable = false;
            return run;
        }
        const double e = world.totalEnergy();
        const bool bounded = e <= bound; // false for NaN too
        if (!bounded || leftLinearRegime(world, springs.spans)) {
            run.stable = false;
            run.leftLinearRegime = bounded;
            sample(e);
            return run;
        }
        if (n % stride == 0 || n == steps)
            sample(e);
    }
    return run;
}

namespace {

/// The springs' own energy scale, sum k L^2 / 2 (each stretched by its rest length).
double springEnergyScale(const Scene& scene)
{
    SpanCollector springs;
    for (std::size_t i = 0; i < scene.world.forceCount(); ++i)
        scene.world.force(i).accept(springs);
    double scale = 0.0;
    for (const auto& span : springs.spans)
        scale += 0.5 * span.stiffness * span.restLength * span.restLength;
    return scale;
}

/// An integrator with no limit to bisect for: the ladder's runs, each run's end energy the damping
/// it costs, and the largest dt up to which every run was stable.
void climbTheLadder(const Scene& scene, double omega, const StabilityCriterion& criterion, StabilityResult& result)
{
    bool allStable = true;
    for (double omegaDt : kLadderOmegaDt) {
        result.ladder.push_back(runStability(scene, result.integrator, omegaDt / omega, omega, criterion));
        allStable = allStable && result.ladder.back().stable;
        if (allStable)
            result.measuredDt = omegaDt / omega;
    }
    if (std::isnan(result.measuredDt))
        result.unmeasured = fmt::format("unstable at omega dt = {:g} already", kLadderOmegaDt[0]);
}

} // namespace

StabilityResult measureStabilityLimit(const Scene& scene, Integrator integrator, double omega,
                                      const StabilityCriterion& criterion)
{
    StabilityResult result{integrator, omega, theoryDtLimit(integrator, omega), kNaN, {}, {}, {}, {}};
    // "No energy" is measured against the springs' own scale: a cloth at rest keeps rounding-sized
    // energies that no bound can be set by.
    if (!(std::abs(scene.world.totalEnergy()) > 1e-12 * springEnergyScale(scene))) {
        result.unmeasured = "the scene starts with no energy (at rest at equilibrium): no bound to set";
        return result;
    }
    if (std::isinf(result.theoryDt)) {
        climbTheLadder(scene, omega, criterion, result);
        return result;
    }
    // The last two runs' reasons: a spring that leaves its linear range at the same time at dt
    // and dt / 2 does so by the scene's own motion (a hanging cloth stretching), not the
    // integrator's, and halving further would only cost time.
    bool leftLinear = false, leftLinearBefore = false;
    double leftAt = -1.0, leftAtBefore = -2.0;
    auto stable = [&](double dt) {
        const StabilityRun run = runStability(scene, integrator, dt, omega, criterion);
        leftLinearBefore = leftLinear;
        leftAtBefore = leftAt;
        leftLinear = run.leftLinearRegime;
        leftAt = run.series.t.empty() ? -1.0 : run.series.t.back();
        return run.stable;
    };
    // Whether the scene's own motion leaves the linear regime: an accurate run (RK4 at omega dt
    // = 0.05) does too. Two halvings that leave at the same time are not enough: forward Euler's
    // spring left (0, 2 L) at 1.98 s at omega dt 0.5 and 0.25, where the exact swing never does.
    std::optional<bool> accurateLeaves;
    const auto sceneLeavesLinear = [&] {
        if (!accurateLeaves)
            accurateLeaves = runStability(scene, Integrator::RK4, 0.05 / omega, omega, criterion).leftLinearRegime;
        return *accurateLeaves;
    };
    // Bracket [lo, hi] with lo stable and hi not, from omega dt = 1.
    double lo = 1.0 / omega, hi = lo;
    if (stable(lo)) {
        for (hi = 2.0 * lo; stable(hi); hi *= 2.0) {
            lo = hi;
            if (hi * omega >= kMaxOmegaDt) {
                result.unmeasured = fmt::format("stable up to omega dt = {:g}", kMaxOmegaDt);
                return result;
            }
        }
    } else {
        for (lo = 0.5 * hi; !stable(lo); lo *= 0.5) {
            hi = lo;
            if (leftLinear && leftLinearBefore && std::abs(leftAt - leftAtBefore) <= 0.1 * leftAt &&
                sceneLeavesLinear()) {
                result.unmeasured = fmt::format("a spring leaves lengths (0, 2 L) at t = {:.3g} s whatever the dt: "
                                                "the scene leaves the linear regime the theory is for",
                                                leftAt);
                // Its panel still shows how: at the smallest dt tried and at omega dt = 1.
                result.below = runStability(scene, integrator, lo, omega, criterion);
                result.above = runStability(scene, integrator, 1.0 / omega, omega, criterion);
                return result;
            }
            if (0.5 * lo * omega < kMinOmegaDt) {
                result.unmeasured = fmt::format("unstable down to omega dt = {:g}", lo * omega);
                result.below = runStability(scene, integrator, lo, omega, criterion);
                result.above = runStability(scene, integrator, 1.0 / omega, omega, criterion);
                return result;
            }
        }
    }
    while (hi - lo > criterion.tolerance * lo) {
        const double mid = 0.5 * (lo + hi);
        (stable(mid) ? lo : hi) = mid;
    }
    result.measuredDt = lo;
    result.below = runStability(scene, integrator, lo * (1.0 - kStabilityMargin), omega, criterion);
    result.above = runStability(scene, integrator, lo * (1.0 + kStabilityMargin), omega, criterion);
    return result;
}

} // namespace pba::study
