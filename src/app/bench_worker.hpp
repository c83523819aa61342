#pragma once
// A `pba bench` worker: a process that a peer script (bench/peers/) drives line by line from
// standard input, so that pba's windows and a peer's are taken in turn on one machine. Each
// command's answer is one JSON line; the first line says the worker is ready.
#include <functional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace pba::app::bench {

/// A command a worker answers: its name, its usage ("window STEPS"), and its answer given the
/// rest of its line (`args`) and the whole line (for the error).
struct WorkerCommand {
    std::string name, usage;
    std::function<nlohmann::json(std::istringstream& args, const std::string& line)> answer;
};

/// Prints `ready`, then answers standard input's commands until it ends. An unknown command is a
/// UsageError naming `flag` (the worker's option, as in "--pile-worker") and the commands known.
int serveWorker(std::string_view flag, const nlohmann::json& ready, const std::vector<WorkerCommand>& commands);

/// The STEPS of "window STEPS": at least 1, or a UsageError naming `flag`.
long windowSteps(std::string_view flag, std::istringstream& args, const std::string& line);

} // namespace pba::app::bench
