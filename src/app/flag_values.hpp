#pragma once
// How pba reads a list flag's value (`--dt 0.01,0.02`): one word, split at its commas here
// rather than by CLI11, which merges a repeated flag into one list.
#include <string>
#include <vector>

namespace pba::app {

/// `text` split at its commas (none for an empty text, a flag not given); throws UsageError naming `flag` for an empty item (`rk4,`), which
/// is a typo or a script's unset variable, not a shorter list.
std::vector<std::string> listItems(const std::string& flag, const std::string& text);

/// listItems() read as numbers; throws UsageError naming `flag` and the item that is not one.
std::vector<double> numberList(const std::string& flag, const std::string& text);

} // namespace pba::app
