#pragma once
// Runs the `pba` program (or any shell command) from a test and captures what it said.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "support/paths.hpp"

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
inline CommandResult runPba(const std::string& args) { return runShell(pbaBinary() + " " + args); }

} // namespace pba::test

#include <csignal>
#include <functional>
#include <vector>

#include <fcntl.h>
#include <sys/resource.h>

namespace pba::test {

struct RunOptions {
    std::string path{};              ///< PATH for the program (empty: this process's)
    long long fileSizeLimit = -1;    ///< RLIMIT_FSIZE in bytes (-1: none): a stand-in for a full disk
    int stopAfterMs = -1;            ///< send `stopSignal` this long after the start (-1: never)
    int stopSignal = SIGTERM;
    std::filesystem::path workDir{}; ///< empty: this process's
    std::function<void(pid_t)> whileRunning{}; ///< called once it started, before waiting for it
    bool stderrOnTerminal = false;   ///< stderr a pseudo-terminal, as a progress bar needs (read into err)
};

/// Runs the pba binary with an argument vector, no shell: what the arguments hold reaches pba
/// exactly. exitCode is 128 + N when a signal N ended it.
inline CommandResult runPbaArgv(const std::vector<std::string>& args, const RunOptions& options = {})
{
    const auto base = std::filesystem::temp_directory_path() / ("pba_test_argv_" + std::to_string(::getpid()));
    const std::string outPath = base.string() + ".out", errPath = base.string() + ".err";
    std::vector<std::string> argv{pbaBinary()};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> pointers;
    for (auto& a : argv)
        pointers.push_back(a.data());
    pointers.push_back(nullptr);
    const int terminal = options.stderrOnTerminal ? ::posix_openpt(O_RDWR | O_NOCTTY) : -1;
    if (terminal >= 0 && (::grantpt(terminal) != 0 || ::unlockpt(terminal) != 0))
        return {};
    const std::string terminalName = terminal >= 0 ? ::ptsname(terminal) : "";
    const pid_t pid = ::fork();
    if (pid == 0) {
        std::FILE* out = std::freopen(outPath.c_str(), "w", stdout);
        std::FILE* err = std::freopen(errPath.c_str(), "w", stderr);
        (void)out;
        (void)err;
        if (terminal >= 0) {
            const int side = ::open(terminalName.c_str(), O_RDWR | O_NOCTTY);
            if (side < 0 || ::dup2(side, STDERR_FILENO) < 0)
                ::_exit(125);
            ::close(side);
            ::close(terminal);
        }
        if (!options.path.empty())
            ::setenv("PATH", options.path.c_str(), 1);
        if (options.fileSizeLimit >= 0) {
            const rlimit limit{rlim_t(options.fileSizeLimit), rlim_t(options.fileSizeLimit)};
            ::setrlimit(RLIMIT_FSIZE, &limit);
        }
        if (!options.workDir.empty() && ::chdir(options.workDir.c_str()) != 0)
            ::_exit(126);
        ::execv(pointers[0], pointers.data());
        ::_exit(127);
    }
    if (options.whileRunning)
        options.whileRunning(pid);
    if (options.stopAfterMs >= 0) {
        ::usleep(static_cast<useconds_t>(options.stopAfterMs) * 1000);
        ::kill(pid, options.stopSignal);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    CommandResult result;
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = readFile(outPath);
    result.err = readFile(errPath);
    if (terminal >= 0) {
        // What the program wrote to its terminal, up to the end its exit left (EIO) or nothing more.
        ::fcntl(terminal, F_SETFL, O_NONBLOCK);
        char buffer[4096];
        for (ssize_t n; (n = ::read(terminal, buffer, sizeof buffer)) > 0;)
            result.err.append(buffer, std::size_t(n));
        ::close(terminal);
    }
    std::filesystem::remove(outPath);
    std::filesystem::remove(errPath);
    return result;
}

} // namespace pba::test
