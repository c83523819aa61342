// `pba help [COMMAND]`: the same text as `pba --help` or `pba COMMAND --help`, for those who
// type the word rather than the flag.
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "scene/closest_name.hpp"

namespace pba::app {

std::string unknownCommandText(const CLI::App& root, const std::string& name)
{
    std::vector<std::string> commands;
    for (const CLI::App* command : root.get_subcommands({}))
        commands.push_back(command->get_name());
    const auto close = scene_detail::closestName(name, commands);
    return fmt::format("unknown command '{}'{} (the commands: {})", name,
                       close ? fmt::format(": did you mean '{}'?", *close) : "", fmt::join(commands, ", "));
}

namespace {

int printHelp(const CLI::App& root, const std::string& name)
{
    if (name.empty()) {
        // root.help() would describe the selected subcommand, `help` itself.
        fmt::print("{}", root.get_formatter()->make_help(&root, root.get_name(), CLI::AppFormatMode::Normal));
        return kExitSuccess;
    }
    for (const CLI::App* command : root.get_subcommands({}))
        if (command->get_name() == name) {
            fmt::print("{}", command->help(root.get_name()));
            return kExitSuccess;
        }
    throw UsageError("help: " + unknownCommandText(root, name));
}

} // namespace

void addHelpCommand(CLI::App& root, Action& selected)
{
    auto name = std::make_shared<std::string>();
    CLI::App* help = root.add_subcommand("help", "Print the help of pba, or of COMMAND (as `pba COMMAND --help`)");
    help->add_option("COMMAND", *name, "A command: sim, field, render, view, compare, bench, scenes")->type_name("");
    help->callback([&root, name, &selected] { selected = [&root, name] { return printHelp(root, *name); }; });
}

} // namespace pba::app
