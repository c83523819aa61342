#pragma once
// Which known name a mistyped one was meant to be: for the "did you mean" of an unknown scene,
// JSON key, force type or command.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pba::scene_detail {

/// Edit distance with transpositions (optimal string alignment): "stifness" is 1 from
/// "stiffness", "mass" 2 from "max".
std::size_t editDistance(std::string_view a, std::string_view b);

/// The candidate closest to `word` if it is close enough to be a typo of it (at most 2 edits,
/// and at most a third of its length, at least 1); none when two are equally close.
std::optional<std::string> closestName(std::string_view word, const std::vector<std::string>& candidates);

} // namespace pba::scene_detail
