#pragma once
// A progress bar on stderr for long work: frames or runs done, total, elapsed, remaining,
// drawn only when stderr is a terminal; the one-line summary at the end goes to stdout.
#include <chrono>
#include <string>

namespace pba::app {

class Progress {
public:
    Progress(std::string what, long total);
    void update(long done);
    /// Erases the bar and prints the closing summary line on stdout ("wrote x.mp4 (600
    /// frames, ...) in 12.3 s").
    void finish(const std::string& summary);
    /// Erases the bar (for a command whose summary goes elsewhere).
    void clear();

private:
    std::string m_what;
    long m_total;
    bool m_terminal;
    std::chrono::steady_clock::time_point m_start;
    std::chrono::steady_clock::time_point m_lastDraw;
};

} // namespace pba::app
