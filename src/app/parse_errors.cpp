#include "parse_errors.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "command.hpp"
#include "scene/closest_name.hpp"

namespace pba::app {

namespace {

/// Where the first word CLI11 could not place was typed: the command's own words, or else the
/// words before it (`pba --bogus sim`), which are root's.
std::pair<const CLI::App*, std::string> placeOfExtras(const CLI::App& app)
{
    const auto parsed = app.get_subcommands();
    if (parsed.empty() || (parsed.front()->remaining().empty() && !app.remaining().empty()))
        return {&app, "pba"};
    return {parsed.front(), "pba " + parsed.front()->get_name()};
}

/// What the command could not place: the first option it did not know, with the one it is close
/// to, or else the first word past its positionals. An unknown option's value is among them too
/// (CLI11 lists "1 --time" for `--time 1`), so an option is looked for first.
std::optional<std::string> extraArgumentText(const CLI::App& app)
{
    const auto [command, name] = placeOfExtras(app);
    std::vector<std::string> known;
    for (const CLI::Option* option : command->get_options())
        for (const std::string& longName : option->get_lnames())
            known.push_back("--" + longName);
    const std::vector<std::string> extras = command->remaining();
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

/// A word past the arguments: a mistyped command, or what extraArgumentText() finds.
std::optional<std::string> extrasText(const CLI::App& app, const std::vector<std::string>& args)
{
    if (!args.empty() && args.front().rfind("-", 0) != 0) {
        std::vector<std::string> commands;
        for (const CLI::App* command : app.get_subcommands({}))
            commands.push_back(command->get_name());
        if (std::find(commands.begin(), commands.end(), args.front()) == commands.end())
            return unknownCommandText(app, args.front());
    }
    return extraArgumentText(app);
}

/// "Could not convert: --dt = abc": every option CLI11 converts is a number.
std::optional<std::string> conversionText(const std::string& what)
{
    const std::string prefix = "Could not convert: ";
    const std::size_t equals = what.find(" = ");
    if (what.rfind(prefix, 0) != 0 || equals == std::string::npos)
        return std::nullopt;
    const std::string option = what.substr(prefix.size(), equals - prefix.size()), value = what.substr(equals + 3);
    // A number that failed to convert was read for a whole-number option (--fps 0.5).
    char* end = nullptr;
    std::strtod(value.c_str(), &end);
    if (!value.empty() && end == value.c_str() + value.size())
        return fmt::format("{}: expected a whole number, got '{}'", option, value);
    return fmt::format("{}: cannot read '{}' as a number", option, value);
}

/// `what` is "NAME: <a> X <b> Y" (a and b CLI11's words): NAME, X and Y.
std::optional<std::array<std::string, 3>> splitAround(const std::string& what, const std::string& a,
                                                      const std::string& b)
{
    const std::size_t at = what.find(a), by = what.rfind(b);
    if (at == std::string::npos || by == std::string::npos || by < at + a.size())
        return std::nullopt;
    return std::array<std::string, 3>{what.substr(0, at), what.substr(at + a.size(), by - at - a.size()),
                                      what.substr(by + b.size())};
}

/// What the help shows for an option's value (X,Y,Z for --at), where CLI11's messages name its
/// type (TEXT); `type` if the command that was parsed, or root, has no such option.
std::string valueText(const CLI::App& app, const std::string& name, const std::string& type)
{
    const auto parsed = app.get_subcommands();
    const CLI::Option* option = (parsed.empty() ? &app : parsed.front())->get_option_no_throw(name);
    if (!option)
        return type;
    return option->get_option_text().empty() ? option->get_type_name() : option->get_option_text();
}

/// The wrong number of values: "--dt: At Most 1 required but received 2" (an option given
/// twice) and "--out: 1 required FILE.csv missing" (an option with no value after it).
std::optional<std::string> countText(const std::string& what, const CLI::App& app)
{
    if (const auto given = splitAround(what, ": At Most ", " required but received ");
        given && (*given)[1] == "1")
        return fmt::format("{}: given {} times; give it once", (*given)[0], (*given)[2]);
    const std::string missingMark = " missing";
    if (const auto missing = splitAround(what, ": ", " required "); missing && what.ends_with(missingMark)) {
        const auto& [name, count, rest] = *missing;
        const std::string type = valueText(app, name, rest.substr(0, rest.size() - missingMark.size()));
        return fmt::format("{}: expected {}{}, got none", name, count == "1" ? "a value" : count + " values",
                           type.empty() ? "" : " (" + type + ")");
    }
    return std::nullopt;
}

/// A check of CLI11's own that failed: a range (--windows) or a list of words (--phase).
std::optional<std::string> validationText(const std::string& what)
{
    if (const auto range = splitAround(what, ": Value ", " not in range "))
        return fmt::format("{}: must be from {}, got {}", (*range)[0], (*range)[2], (*range)[1]);
    if (const auto member = splitAround(what, ": ", " not in {"); member && what.ends_with("}")) {
        std::string names = (*member)[2].substr(0, (*member)[2].size() - 1);
        for (std::size_t comma = names.find(','); comma != std::string::npos; comma = names.find(',', comma + 2))
            names.replace(comma, 1, ", ");
        return fmt::format("{}: unknown value '{}' (expected one of: {})", (*member)[0], (*member)[1], names);
    }
    return std::nullopt;
}

/// Options that go together or not: "--dice requires --pile-worker", "--peer-worker excludes
/// --phases", "--out is required".
std::optional<std::string> pairingText(const std::string& what, const CLI::App& app)
{
    if (what.rfind("--", 0) != 0)
        return std::nullopt;
    const std::string name = what.substr(0, what.find(' '));
    if (what == name + " is required")
        return fmt::format("{}: required; give it a value ({})", name, valueText(app, name, ""));
    if (what.rfind(name + " requires ", 0) == 0)
        return fmt::format("{}: only with {}", name, what.substr(name.size() + 10));
    if (what.rfind(name + " excludes ", 0) == 0)
        return fmt::format("{}: not with {}", name, what.substr(name.size() + 10));
    return std::nullopt;
}

} // namespace

std::string parseErrorText(const CLI::ParseError& e, const CLI::App& app, const std::vector<std::string>& args)
{
    const std::string what = e.what();
    std::optional<std::string> text;
    if (dynamic_cast<const CLI::ConversionError*>(&e))
        text = conversionText(what);
    else if (dynamic_cast<const CLI::ArgumentMismatch*>(&e))
        text = countText(what, app);
    else if (dynamic_cast<const CLI::ValidationError*>(&e))
        text = validationText(what);
    else if (dynamic_cast<const CLI::ExtrasError*>(&e))
        text = extrasText(app, args);
    else if (dynamic_cast<const CLI::RequiredError*>(&e) || dynamic_cast<const CLI::RequiresError*>(&e) ||
             dynamic_cast<const CLI::ExcludesError*>(&e))
        text = pairingText(what, app);
    return text.value_or(what);
}

} // namespace pba::app
