#pragma once
// One parser per force type of the scene file's "forces" array. A new force type
// (the blow dryer, say) is one more entry in the table of force_parsers.cpp.
#include <memory>
#include <string>
#include <vector>

#include "json_reader.hpp"
#include "pba/force.hpp"
#include "pba/world.hpp"

namespace pba::scene_detail {

/// Reads the force described by `reader` (its "type" key already read). The world holds
/// the scene's particles and surfaces, so a force can name a particle or cut a hole in the floor.
using ForceParser = std::unique_ptr<Force> (*)(ObjectReader& reader, World& world);

struct ForceType {
    const char* name;
    ForceParser parse;
    std::vector<std::string> keys; ///< the keys its parser reads, besides "type"
};

const std::vector<ForceType>& forceTypes();

} // namespace pba::scene_detail
