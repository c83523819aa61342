#include "gnuplot.hpp"

#include <fstream>
#include <iterator>
#include <random>

#include <fmt/format.h>

#include "command.hpp"
#include "io/child_process.hpp"
#include "io/output_file.hpp"

namespace pba::app {

bool gnuplotAvailable() { return io::findProgram("gnuplot").has_value(); }

void runGnuplot(const std::string& script, const std::filesystem::path& workDir, const std::vector<std::string>& args)
{
    if (!gnuplotAvailable())
        throw RuntimeFailure("gnuplot is not installed: install the Debian package gnuplot-nox "
                             "(scripts/install-deps.sh does)");
    const auto scriptPath = workDir / "plot.gp";
    std::ofstream(scriptPath) << script;
    std::vector<std::string> argv{"gnuplot", "-c", "plot.gp"};
    argv.insert(argv.end(), args.begin(), args.end());
    const auto log = workDir / "gnuplot.log";
    const int status = io::runProgram(argv, {workDir, log, false});
    if (status != 0) {
        const std::string message = io::firstLine(log);
        throw RuntimeFailure(fmt::format("gnuplot failed ({}){}{}", io::describeExit(status),
                                         message.empty() ? "" : ": ", message));
    }
}

void publish(const std::filesystem::path& made, const std::filesystem::path& target)
{
    std::ifstream in(made, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof())
        throw RuntimeFailure(fmt::format("{}: gnuplot's picture cannot be read", made.string()));
    io::writeFileAtomically(target, bytes);
}

ScratchDir::ScratchDir(const std::string& prefix)
    : m_folder(std::filesystem::temp_directory_path() / fmt::format("{}-{:08x}", prefix, std::random_device()()),
               io::Temporary::Kind::Folder)
{
}

} // namespace pba::app
