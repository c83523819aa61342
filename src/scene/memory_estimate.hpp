#pragma once
// What a scene's bodies will cost in memory, estimated from the document before any is built: a
// file of a kilobyte can ask for millions of particles (five 1000 x 1000 cloths), and building
// them would end in std::bad_alloc, or the kernel's killer, long after the scene was read.
#include <filesystem>
#include <string>

#include "json_reader.hpp"

namespace pba::scene_detail {

/// Refuses the first body, in the order they are read (particles, ropes, cloths, rigid bodies,
/// swarms), at which the bodies so far need more than this process may still take (the kernel's
/// MemAvailable, or less under a limit on its address space or data), naming its key, its
/// estimate and the total. An entry too malformed to estimate is skipped: its reader says what
/// is wrong with it.
void requireMemoryForBodies(const Json& document, const std::string& file, const std::filesystem::path& directory);

} // namespace pba::scene_detail
