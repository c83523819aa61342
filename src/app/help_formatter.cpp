#include "help_formatter.hpp"

#include <sstream>

namespace pba::app {

std::string wrapText(const std::string& text, std::size_t width)
{
    std::string out;
    std::size_t lineStart = 0; // where the current output line starts in `out`
    std::size_t k = 0;
    while (k < text.size()) {
        const std::size_t end = text.find_first_of(" \n", k);
        const std::string word = text.substr(k, end == std::string::npos ? std::string::npos : end - k);
        const bool first = out.size() == lineStart;
        if (!first && out.size() - lineStart + 1 + word.size() > width) {
            out += '\n';
            lineStart = out.size();
        } else if (!first) {
            out += ' ';
        }
        out += word;
        if (end == std::string::npos)
            break;
        if (text[end] == '\n') {
            out += '\n';
            lineStart = out.size();
        }
        k = end + 1;
    }
    return out;
}

std::string HelpFormatter::make_description(const CLI::App* app) const
{
    return wrapText(CLI::Formatter::make_description(app), kHelpWidth);
}

std::string HelpFormatter::make_option_opts(const CLI::Option* opt) const
{
    if (opt->get_option_text().empty() && opt->get_expected_max() == 0)
        return {}; // a flag: no value to name, and its exclusions are in its description
    return CLI::Formatter::make_option_opts(opt);
}

std::string HelpFormatter::make_option_desc(const CLI::Option* opt) const
{
    return wrapText(CLI::Formatter::make_option_desc(opt), kHelpWidth - get_column_width());
}

std::string HelpFormatter::make_subcommand(const CLI::App* sub) const
{
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_display_name(true),
                             wrapText(sub->get_description(), kHelpWidth - get_column_width()), get_column_width());
    return out.str();
}

} // namespace pba::app
