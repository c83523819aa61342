#include "force_parsers.hpp"

#include <fmt/format.h>

#include "pba/forces.hpp"

namespace pba::scene_detail {

namespace {

std::unique_ptr<Force> parseSpring(ObjectReader& reader, const World& world)
{
    const std::string name = reader.string("particle");
    const auto index = world.findBody(name);
    if (!index)
        reader.fail("particle", fmt::format("no particle named '{}'", name));
    const dvec3 anchor = reader.vec3("anchor");
    const double stiffness = reader.positive("stiffness");
    const double restLength = reader.nonNegative("rest_length", 0.0);
    const double damping = reader.nonNegative("damping", 0.0);
    return std::make_unique<Spring>(*index, anchor, stiffness, restLength, damping);
}

std::unique_ptr<Force> parseDrag(ObjectReader& reader, const World&)
{
    return std::make_unique<Drag>(reader.nonNegative("coefficient"));
}

} // namespace

const std::vector<ForceType>& forceTypes()
{
    static const std::vector<ForceType> types{
        {"spring", &parseSpring},
        {"drag", &parseDrag},
    };
    return types;
}

} // namespace pba::scene_detail
