#include "parse_errors.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "command.hpp"
#include "scene/closest_name.hpp"

namespace pba::app {

namespace {

/// What the command could not place: the first option it did not know, with the one it is close
/// to, or else the first word past its positionals. An unknown option's value is among them too
/// (CLI11 lists "1 --time" for `--time 1`), so an option is looked for first.
std::optional<std::string> extraArgumentText(const CLI::App& app)
{
    const auto parsed = app.get_subcommands();
    const CLI::App& command = parsed.empty() ? app : *parsed.front();
    const std::string name = parsed.empty() ? "pba" : "pba " + command.get_name();
    std::vector<std::string> known;
    for (const CLI::Option* option : command.get_options())
        for (const std::string& longName : option->get_lnames())
            known.push_back("--" + longName);
    const std::vector<std::string> extras = command.remaining();
    for (const std::string& extra : extras) {
        if (extra.size() < 2 || extra[0] != '-')
            continue;
        const std::string flag = extra.substr(0, extra.find('='));
        const auto close = scene_detail::closestName(flag, known);
        return fmt::format("unknown option '{}' of `{}`{} (`{} --help` lists its options)", flag, name,
                           close ? fmt::format(": did you mean '{}'?", *close) : "", name);
    }
    // No option among them: words past the command's positionals, named from the first.
    if (!extras.empty())
        return fmt::format("unexpected argument '{}' of `{}` (`{} --help` lists its arguments)", extras.front(),
                           name, name);
    return std::nullopt;
}

} // namespace

std::string parseErrorText(const CLI::ParseError& e, const CLI::App& app, const std::vector<std::string>& args)
{
    const std::string what = e.what();
    if (dynamic_cast<const CLI::ConversionError*>(&e)) {
        // "Could not convert: --dt = abc": every option CLI11 converts is a number.
        const std::string prefix = "Could not convert: ";
        const std::size_t equals = what.find(" = ");
        if (what.rfind(prefix, 0) == 0 && equals != std::string::npos) {
            const std::string option = what.substr(prefix.size(), equals - prefix.size()), value = what.substr(equals + 3);
            // A number that failed to convert was read for a whole-number option (--fps 0.5).
            char* end = nullptr;
            std::strtod(value.c_str(), &end);
            if (!value.empty() && end == value.c_str() + value.size())
                return fmt::format("{}: expected a whole number, got '{}'", option, value);
            return fmt::format("{}: cannot read '{}' as a number", option, value);
        }
    }
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
        // "--dt: At Most 1 required but received 2": an option given twice.
        const std::string marker = ": At Most 1 required but received ";
        if (const std::size_t at = what.find(marker); at != std::string::npos)
            return fmt::format("{}: given {} times; give it once", what.substr(0, at), what.substr(at + marker.size()));
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&e) && !args.empty() && args.front().rfind("-", 0) != 0) {
        std::vector<std::string> commands;
        for (const CLI::App* command : app.get_subcommands({}))
            commands.push_back(command->get_name());
        if (std::find(commands.begin(), commands.end(), args.front()) == commands.end())
            return unknownCommandText(app, args.front());
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&e))
        if (const auto extra = extraArgumentText(app))
            return *extra;
    return what;
}

} // namespace pba::app
