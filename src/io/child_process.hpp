#pragma once
// Other programs (ffmpeg, gnuplot) are started from an argument vector with posix_spawn, never
// through a shell: no file name, scene name or flag can become a command.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pba::io {

/// The program's full path from PATH, or nothing.
std::optional<std::filesystem::path> findProgram(std::string_view name);

/// "exit status N" or "killed by signal N (NAME)" for a waitpid status.
std::string describeExit(int status);

class ChildProcess {
public:
    struct Options {
        std::filesystem::path workDir;  ///< empty: this process's
        std::filesystem::path log;      ///< its stdout and stderr go here (empty: /dev/null)
        bool pipeInput = false;         ///< its stdin is a pipe fed by write(); otherwise /dev/null
    };
    /// Starts argv[0] (looked up on PATH); throws WriteError if it cannot be started.
    ChildProcess(const std::vector<std::string>& argv, const Options& options);
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;
    /// Without wait(): stops the program (SIGTERM) and waits for it.
    ~ChildProcess();

    /// Feeds its stdin; false once it stopped reading (it exited or failed).
    bool write(const void* bytes, std::size_t size);
    /// Closes its stdin and waits for it; returns the waitpid status.
    int wait();

private:
    int m_pid = -1;
    int m_input = -1;
};

/// Runs a program to its end; returns the waitpid status.
int runProgram(const std::vector<std::string>& argv, const ChildProcess::Options& options);

/// The first line of a log file (a failed program's message), or "".
std::string firstLine(const std::filesystem::path& log);

} // namespace pba::io
