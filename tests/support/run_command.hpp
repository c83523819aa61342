#pragma once
// Runs the `pba` program (or any shell command) from a test and captures what it said.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace pba::test {

struct CommandResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

inline std::string readFile(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// A fresh empty directory under the test temp dir.
inline std::filesystem::path freshDir(const std::string& name)
{
    const auto dir = std::filesystem::path(::testing::TempDir()) / ("pba_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Runs `command` with /bin/sh; stdout and stderr are captured separately.
inline CommandResult runShell(const std::string& command)
{
    const auto errPath = std::filesystem::temp_directory_path() / ("pba_test_err_" + std::to_string(::getpid()));
    CommandResult result;
    FILE* pipe = ::popen((command + " 2>" + errPath.string()).c_str(), "r");
    if (!pipe)
        return result;
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        result.out.append(buffer, n);
    const int status = ::pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.err = readFile(errPath);
    std::filesystem::remove(errPath);
    return result;
}

/// Runs the pba binary under test with the given arguments (already shell-quoted).
inline CommandResult runPba(const std::string& args) { return runShell(std::string(PBA_BINARY) + " " + args); }

} // namespace pba::test
