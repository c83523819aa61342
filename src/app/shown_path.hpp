#pragma once
// A path as the commands print it: in a "wrote PATH" line, or an error naming a scene file.
#include <string>

#include "scene/one_line.hpp"

namespace pba::app {

/// `path` with its control characters escaped (a newline as \n, a tab as \t) and nothing cut, so
/// that each line pba prints stays one line and still names the file.
inline std::string shownPath(const std::string& path)
{
    return scene_detail::oneLine(path, scene_detail::kWhole);
}

} // namespace pba::app
