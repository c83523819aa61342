#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pba/scene/scene.hpp"

namespace pba {

Scene resizedClothInTheDryer(int side)
{
    if (side < 2)
        throw std::invalid_argument(fmt::format("a cloth needs at least 2 x 2 particles, not {} x {}", side, side));
    nlohmann::json scene = nlohmann::json::parse(builtinSceneText("cloth-in-the-dryer"));
    nlohmann::json& cloth = scene["cloths"][0];
    // The sheet keeps its mass, so each particle weighs `scale` times the built-in's; every force
    // on a particle scales with it (each spring's stiffness and damping, the dryer's push and its
    // air drag, all proportional to the dryer's strength), so its accelerations, and the product
    // omega dt that keeps the explicit step stable, are the built-in's.
    const double scale = cloth["columns"].get<double>() * cloth["rows"].get<double>() / (double(side) * side);
    cloth["columns"] = side;
    cloth["rows"] = side;
    for (auto& [kind, stiffness] : cloth["stiffness"].items())
        stiffness = stiffness.get<double>() * scale;
    cloth["damping"] = cloth["damping"].get<double>() * scale;
    for (nlohmann::json& force : scene["forces"])
        if (force["type"] == "blow-dryer")
            force["strength"] = force["strength"].get<double>() * scale;
    const std::string source = fmt::format("builtin:cloth-in-the-dryer at {} x {}", side, side);
    return parseScene(scene.dump(), source);
}

} // namespace pba
