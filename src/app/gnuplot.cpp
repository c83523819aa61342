#include "gnuplot.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>

#include <fmt/format.h>

#include "command.hpp"

namespace pba::app {

bool gnuplotAvailable() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

void runGnuplot(const std::string& script, const std::filesystem::path& workDir)
{
    if (!gnuplotAvailable())
        throw RuntimeFailure("gnuplot is not installed: install the Debian package gnuplot-nox "
                             "(scripts/install-deps.sh does)");
    const auto scriptPath = workDir / "plot.gp";
    std::ofstream(scriptPath) << script;
    const auto logPath = workDir / "gnuplot.log";
    const std::string command =
        fmt::format("cd '{}' && gnuplot plot.gp > '{}' 2>&1", workDir.string(), logPath.string());
    if (std::system(command.c_str()) != 0) {
        std::ifstream log(logPath);
        std::string first;
        std::getline(log, first);
        throw RuntimeFailure(fmt::format("gnuplot failed: {}", first));
    }
}

ScratchDir::ScratchDir(const std::string& prefix)
{
    std::random_device device;
    m_path = std::filesystem::temp_directory_path() / fmt::format("{}-{:08x}", prefix, device());
    std::filesystem::create_directories(m_path);
}

ScratchDir::~ScratchDir()
{
    std::error_code ignored;
    std::filesystem::remove_all(m_path, ignored);
}

} // namespace pba::app
