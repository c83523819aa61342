// Names of the integrators and collision responses, as scenes and the command line spell them.
#include "pba/collision.hpp"
#include "pba/integrator.hpp"

#include <string>

namespace pba {

namespace {

/// The names of `values`, "a, b or c": what an error about an unknown name lists.
template <class Values, class Name>
std::string nameList(const Values& values, Name name)
{
    std::string list;
    for (std::size_t k = 0; k < values.size(); ++k) {
        if (k > 0)
            list += k + 1 == values.size() ? " or " : ", ";
        list += name(values[k]);
    }
    return list;
}

} // namespace

std::string_view integratorName(Integrator integrator)
{
    switch (integrator) {
    case Integrator::ForwardEuler: return "forward-euler";
    case Integrator::SemiImplicitEuler: return "semi-implicit-euler";
    case Integrator::VelocityVerlet: return "velocity-verlet";
    case Integrator::RK4: return "rk4";
    case Integrator::ImplicitGyroscopic: return "implicit-gyroscopic";
    case Integrator::Splitting: return "splitting";
    case Integrator::ImplicitEuler: return "implicit-euler";
    case Integrator::Xpbd: return "xpbd";
    }
    return "?";
}

std::optional<Integrator> integratorFromName(std::string_view name)
{
    for (Integrator integrator : kEveryIntegrator)
        if (integratorName(integrator) == name)
            return integrator;
    return std::nullopt;
}

std::string integratorNameList()
{
    return nameList(kEveryIntegrator, integratorName);
}

int integratorOrder(Integrator integrator)
{
    switch (integrator) {
    case Integrator::ForwardEuler:
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic:
    case Integrator::ImplicitEuler:
    case Integrator::Xpbd: return 1;
    case Integrator::VelocityVerlet:
    case Integrator::Splitting: return 2;
    case Integrator::RK4: return 4;
    }
    return 0;
}

std::string_view collisionResponseName(CollisionResponse response)
{
    switch (response) {
    case CollisionResponse::Exact: return "exact";
    case CollisionResponse::Reflect: return "reflect";
    case CollisionResponse::Clamp: return "clamp";
    }
    return "?";
}

std::string_view collisionResponseSummary(CollisionResponse response)
{
    switch (response) {
    case CollisionResponse::Exact: return "exact: bounces at the time of impact (semi-implicit Euler loses energy)";
    case CollisionResponse::Reflect: return "reflect: mirrored back after the step (semi-implicit Euler keeps it)";
    case CollisionResponse::Clamp: return "clamp: put back on the surface after the step";
    }
    return "?";
}

std::optional<CollisionResponse> collisionResponseFromName(std::string_view name)
{
    for (CollisionResponse response : kAllCollisionResponses)
        if (collisionResponseName(response) == name)
            return response;
    return std::nullopt;
}

std::string collisionResponseNameList()
{
    return nameList(kAllCollisionResponses, collisionResponseName);
}

} // namespace pba

#include "pba/blow_dryer.hpp"

namespace pba {

std::string_view falloffName(Falloff falloff)
{
    switch (falloff) {
    case Falloff::Linear: return "linear";
    case Falloff::Quadratic: return "quadratic";
    case Falloff::Smooth: return "smooth";
    }
    return "?";
}

std::optional<Falloff> falloffFromName(std::string_view name)
{
    for (Falloff falloff : {Falloff::Linear, Falloff::Quadratic, Falloff::Smooth})
        if (falloffName(falloff) == name)
            return falloff;
    return std::nullopt;
}

std::string_view flowDirectionName(FlowDirection direction)
{
    return direction == FlowDirection::Vertical ? "vertical" : "cone-flow";
}

std::optional<FlowDirection> flowDirectionFromName(std::string_view name)
{
    for (FlowDirection direction : {FlowDirection::Vertical, FlowDirection::ConeFlow})
        if (flowDirectionName(direction) == name)
            return direction;
    return std::nullopt;
}

} // namespace pba
