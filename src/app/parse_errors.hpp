#pragma once
// CLI11's parse errors in pba's words: one line naming the option or the argument and the reason.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace pba::app {

/// CLI11's words for a few errors, in pba's: the option and the reason, and the command a
/// mistyped one was meant to be. `args` are the arguments as typed.
std::string parseErrorText(const CLI::ParseError& e, const CLI::App& app, const std::vector<std::string>& args);

} // namespace pba::app
