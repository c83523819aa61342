#pragma once
// How `pba --help` and every command's `--help` lay out their options.
#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

namespace pba::app {

/// CLI11's formatter with two changes: a command's and an option's description are wrapped at
/// word boundaries to fit kHelpWidth columns (CLI11 2.1 prints each on one line, however long), and a flag's line
/// leaves out CLI11's "Excludes:" and "Needs:" lists, which it prints between the flag's name
/// and its description, pushing the description onto a line of its own (each description says
/// in words which options go together).
class HelpFormatter : public CLI::Formatter {
public:
    static constexpr std::size_t kHelpWidth = 100;

    std::string make_description(const CLI::App* app) const override;
    std::string make_option_opts(const CLI::Option* opt) const override;
    std::string make_option_desc(const CLI::Option* opt) const override;
    std::string make_subcommand(const CLI::App* sub) const override;
};

/// `text` with its spaces turned into line breaks wherever a line would pass `width` columns
/// (a word longer than that stays whole on its own line); its own line breaks are kept.
std::string wrapText(const std::string& text, std::size_t width);

} // namespace pba::app
