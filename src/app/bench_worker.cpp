#include "bench_worker.hpp"

#include <cstdio>
#include <iostream>

#include <fmt/format.h>

#include "command.hpp"

namespace pba::app::bench {

int serveWorker(std::string_view flag, const nlohmann::json& ready, const std::vector<WorkerCommand>& commands)
{
    fmt::print("{}\n", ready.dump());
    std::fflush(stdout);
    std::string known;
    for (const WorkerCommand& c : commands)
        known += (known.empty() ? "" : ", ") + c.usage;
    for (std::string line; std::getline(std::cin, line);) {
        std::istringstream args(line);
        std::string name;
        args >> name;
        if (name.empty())
            continue;
        const WorkerCommand* command = nullptr;
        for (const WorkerCommand& c : commands)
            if (c.name == name)
                command = &c;
        if (!command)
            throw UsageError(fmt::format("{}: unknown command '{}' ({})", flag, line, known));
        fmt::print("{}\n", command->answer(args, line).dump());
        std::fflush(stdout);
    }
    return kExitSuccess;
}

long windowSteps(std::string_view flag, std::istringstream& args, const std::string& line)
{
    long steps = 0;
    if (!(args >> steps) || steps < 1)
        throw UsageError(fmt::format("{}: 'window STEPS' with STEPS >= 1, got '{}'", flag, line));
    return steps;
}

} // namespace pba::app::bench
