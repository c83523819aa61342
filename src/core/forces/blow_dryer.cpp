#include "pba/blow_dryer.hpp"

#include "pba/body.hpp"
#include "pba/particle.hpp"

#include <type_traits>

#include "pba/detail/blow_dryer_kernel.hpp"
#include "pba/swarm.hpp"
#include "pba/world.hpp"

#include "parallel.hpp"

namespace pba {

namespace {

/// The field over a body's surface: at each sample's point and velocity, weighted by its share
/// of the area, so that a body wholly in a uniform field feels what a particle at its centre
/// would, and one across the jet's edge or off its axis feels a torque. A point or a ball (no
/// samples) feels the field at its centre, a ball of `radius` by its size.
template <class At>
void addSpreadOverSurface(const BodyStates& in, std::size_t i, double radius, const At& at, Accumulators& out)
{
    const State& s = in.states[i];
    const Surface surface = in.bodies[i]->surface();
    if (surface.samples.empty()) {
        out.add(i, at(s.pos, s.vel, radius));
        return;
    }
    const Pose& pose = in.pose(i);
    const dmat3 r = surface.turnsWithBody ? glm::mat3_cast(pose.orientation) : dmat3(1.0);
    dvec3 force(0.0), torque(0.0);
    for (const SurfaceSample& sample : surface.samples) {
        const dvec3 arm = r * sample.point;
        const dvec3 f = sample.share * at(s.pos + arm, s.vel + glm::cross(pose.angularVelocity, arm), 0.0);
        force += f;
        torque += glm::cross(arm, f);
    }
    out.add(i, force, torque);
}

} // namespace

dvec3 blowDryerForce(const BlowDryerField& f, const dvec3& x, const dvec3& v, double radius)
{
    return blowDryerForce<DryerAxis::Any, true>(BlowDryerKernelT<double>(f), x, v, radius);
}

dvec3 blowDryerAirVelocity(const BlowDryerField& f, const dvec3& x)
{
    if (!(f.airSpeed > 0.0) || f.strength == 0.0)
        return dvec3(0.0);
    BlowDryerField pushOnly = f;
    pushOnly.airSpeed = 0.0;
    pushOnly.axisPull = 0.0;
    return blowDryerForce(pushOnly, x) * (f.airSpeed / f.strength);
}

bool insideBlowDryerCone(const BlowDryerField& f, const dvec3& x)
{
    const dvec3 d = x - f.nozzle;
    const double h = glm::dot(d, f.axis);
    const double r = glm::length(d - h * f.axis);
    return h >= 0.0 && h < f.height && r < f.nozzleRadius + (f.topRadius - f.nozzleRadius) * h / f.height;
}

bool insideBlowDryerShaft(const BlowDryerField& f, const dvec3& x)
{
    const auto [d, h, rho, r2, across2] = DryerFrameT<DryerAxis::Any, double>(f.nozzle, f.axis, x);
    return inBlowDryerShaft(BlowDryerKernelT<double>(f), d.y, across2);
}

BlowDryer::BlowDryer(const BlowDryerField& field)
    : m_field(field), m_kernel(std::make_shared<const BlowDryerKernelT<double>>(field))
{
}

dvec3 BlowDryer::force(std::size_t, const Body& body, const dvec3& x, const dvec3& v) const
{
    // Only air with a density asks for the body's size (a cast on every call otherwise).
    const auto* particle = m_kernel->dragPerArea != 0.0 ? dynamic_cast<const Particle*>(&body) : nullptr;
    return blowDryerForce<DryerAxis::Any, true>(*m_kernel, x, v, particle ? particle->getRadius() : 0.0);
}

void BlowDryer::setField(const BlowDryerField& field)
{
    m_field = field;
    m_kernel = std::make_shared<const BlowDryerKernelT<double>>(field);
}

void BlowDryer::accumulate(const BodyStates& in, Accumulators& out) const
{
    // An upward axis (every built-in scene's) picks coordinates instead of projecting on it, as
    // in a swarm's loop: the same values, found with fewer multiplications.
    // Without a pull (axis_pull 0, as in every built-in scene) its arithmetic is left out.
    const BlowDryerKernelT<double>& kernel = *m_kernel;
    // Air with a density gives a ball (a body with a radius) a force of its size.
    const bool sized = kernel.dragPerArea != 0.0;
    auto each = [&](auto axis, auto pull) {
        const auto at = [&](const dvec3& x, const dvec3& v, double radius) {
            return blowDryerForce<decltype(axis)::value, true, double, decltype(pull)::value>(kernel, x, v, radius);
        };
        if (in.poses.empty()) // no body of the world turns: every one is a point
            detail::addToEachMoving(in, out, [&](std::size_t i) {
                return at(in.states[i].pos, in.states[i].vel, sized ? in.radius(i) : 0.0);
            });
        else
            detail::forEachIndex(in.bodies.size(), [&](std::size_t i) {
                if (in.moving(i))
                    addSpreadOverSurface(in, i, sized ? in.radius(i) : 0.0, at, out);
            });
    };
    using Up = std::integral_constant<DryerAxis, DryerAxis::Up>;
    using Any = std::integral_constant<DryerAxis, DryerAxis::Any>;
    const bool up = m_field.axis == dvec3(0.0, 1.0, 0.0);
    if (kernel.pull != 0.0 || sized)
        up ? each(Up{}, std::true_type{}) : each(Any{}, std::true_type{});
    else
        up ? each(Up{}, std::false_type{}) : each(Any{}, std::false_type{});
}

bool BlowDryer::addToSwarmFields(SwarmFields& fields) const
{
    fields.dryers.push_back(m_field.as<float>());
    return true;
}

std::vector<WorldDryer> blowDryers(const World& world)
{
    struct Finder final : ForceVisitor {
        std::vector<WorldDryer> found;
        std::size_t index = 0;
        void visit(const BlowDryer& dryer) override { found.push_back({index, dryer.field()}); }
    } finder;
    for (; finder.index < world.forceCount(); ++finder.index)
        world.force(finder.index).accept(finder);
    return finder.found;
}

} // namespace pba
