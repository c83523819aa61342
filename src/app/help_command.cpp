// `pba help [COMMAND]`: the same text as `pba --help` or `pba COMMAND --help`, for those who
// type the word rather than the flag.
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"

namespace pba::app {

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
    std::vector<std::string> names;
    for (const CLI::App* command : root.get_subcommands({}))
        names.push_back(command->get_name());
    throw UsageError(fmt::format("help: no command '{}' (the commands are {})", name, fmt::join(names, ", ")));
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
