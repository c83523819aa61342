#pragma once
// How pba reads a flag's value. Numbers are decimal: CLI11 reads them with strtold and
// strtoll(..., 0), to which `0x10` is 16, `010` is 8 and `inf` a number. A list (`--dt
// 0.01,0.02`) is one word split at its commas here rather than by CLI11, which merges a repeated
// flag into one list.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace pba::app {

/// `text` read as a decimal number: an optional sign, digits with at most one point, and an
/// optional exponent (`-0.5`, `1e-3`); nothing for hexadecimal, `inf`, `nan` or anything else.
std::optional<double> decimalNumber(const std::string& text);

/// For a numeric flag's `->transform()`: refuses a value that is not decimal, naming the flag
/// as CLI11 does a check's, and drops leading zeros, which strtoll would read as octal.
CLI::Validator decimalOnly();

/// `text` split at its commas (none for an empty text, a flag not given); throws UsageError naming
/// `flag` for an empty item (`rk4,`), which is a typo or a script's unset variable, not a shorter list.
std::vector<std::string> listItems(const std::string& flag, const std::string& text);

/// listItems() read as decimal numbers; throws UsageError naming `flag` and the item that is not one.
std::vector<double> numberList(const std::string& flag, const std::string& text);

} // namespace pba::app
