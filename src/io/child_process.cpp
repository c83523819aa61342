#include "io/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "io/output_file.hpp"

extern char** environ;

namespace pba::io {

std::optional<std::filesystem::path> findProgram(std::string_view name)
{
    const char* path = std::getenv("PATH");
    std::string_view dirs = path ? path : "/usr/bin:/bin";
    while (!dirs.empty()) {
        const std::size_t colon = dirs.find(':');
        const std::string_view dir = dirs.substr(0, colon);
        const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : std::string(dir)) / name;
        if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate))
            return candidate;
        dirs = colon == std::string_view::npos ? std::string_view() : dirs.substr(colon + 1);
    }
    return std::nullopt;
}

std::string describeExit(int status)
{
    if (WIFEXITED(status))
        return fmt::format("exit status {}", WEXITSTATUS(status));
    if (WIFSIGNALED(status))
        return fmt::format("killed by signal {} ({})", WTERMSIG(status), ::strsignal(WTERMSIG(status)));
    return fmt::format("wait status {}", status);
}

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const Options& options)
{
    const auto program = findProgram(argv.at(0));
    if (!program)
        throw WriteError(fmt::format("{} is not installed (not on PATH)", argv[0]));
    int pipeEnds[2] = {-1, -1};
    if (options.pipeInput && ::pipe2(pipeEnds, O_CLOEXEC) != 0)
        throw WriteError(fmt::format("cannot start {}: {}", argv[0], std::strerror(errno)));

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (options.pipeInput)
        posix_spawn_file_actions_adddup2(&actions, pipeEnds[0], 0);
    else
        posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    const std::string log = options.log.empty() ? std::string("/dev/null") : options.log.string();
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    if (!options.workDir.empty())
        posix_spawn_file_actions_addchdir_np(&actions, options.workDir.c_str());

    // The child starts with the default signal handling pba changed: nothing blocked (pba's
    // threads block SIGINT, SIGTERM and SIGHUP for its watcher), SIGPIPE and SIGXFSZ deadly again.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGXFSZ})
        sigaddset(&defaults, signal);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

    std::vector<char*> args;
    for (const std::string& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const int error = ::posix_spawn(&m_pid, program->c_str(), &actions, &attributes, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (options.pipeInput)
        ::close(pipeEnds[0]);
    if (error != 0) {
        if (options.pipeInput)
            ::close(pipeEnds[1]);
        throw WriteError(fmt::format("cannot start {}: {}", argv[0], std::strerror(error)));
    }
    m_input = pipeEnds[1];
    registerChild(m_pid);
}

ChildProcess::~ChildProcess()
{
    if (m_pid > 0) {
        ::kill(m_pid, SIGTERM);
        wait();
    }
}

bool ChildProcess::write(const void* bytes, std::size_t size)
{
    // SIGPIPE is ignored (main()), so a program that stopped reading gives EPIPE here.
    return m_input >= 0 && writeAll(m_input, bytes, size);
}

int ChildProcess::wait()
{
    if (m_input >= 0) {
        ::close(m_input);
        m_input = -1;
    }
    int status = 0;
    while (::waitpid(m_pid, &status, 0) < 0 && errno == EINTR) {
    }
    unregisterChild(m_pid);
    m_pid = -1;
    return status;
}

int runProgram(const std::vector<std::string>& argv, const ChildProcess::Options& options)
{
    ChildProcess child(argv, options);
    return child.wait();
}

std::string firstLine(const std::filesystem::path& log)
{
    std::ifstream in(log);
    std::string line;
    while (std::getline(in, line))
        if (!line.empty())
            return line;
    return "";
}

} // namespace pba::io
