#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace pba::app {

Progress::Progress(std::string what, long total)
    : m_what(std::move(what)), m_total(total), m_terminal(::isatty(STDERR_FILENO) != 0),
      m_start(std::chrono::steady_clock::now()), m_lastDraw(m_start)
{
}

void Progress::update(long done)
{
    if (!m_terminal)
        return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - m_start).count();
    // Only long work gets a bar, and at most ten redraws a second.
    if (elapsed < 1.0 || (now - m_lastDraw < std::chrono::milliseconds(100) && done < m_total))
        return;
    m_lastDraw = now;
    const double fraction = m_total > 0 ? double(done) / double(m_total) : 1.0;
    const int width = 30;
    const int filled = static_cast<int>(fraction * width);
    // Until a unit of work has finished there is no rate to estimate from: "0.0 s left" there
    // read as nearly done when nothing was. Padded, so that the estimate overwrites those words.
    const std::string left = done > 0 ? fmt::format("{:.1f} s left", elapsed * (1.0 - fraction) / fraction)
                                      : std::string("estimating the time left");
    fmt::print(stderr, "\r{} [{}{}] {}/{}  {:.1f} s elapsed, {:<24}   ", m_what, std::string(filled, '#'),
               std::string(width - filled, '.'), done, m_total, elapsed, left);
    std::fflush(stderr);
}

void Progress::clear()
{
    if (m_terminal && std::chrono::steady_clock::now() - m_start >= std::chrono::seconds(1))
        fmt::print(stderr, "\r\033[K");
}

void Progress::finish(const std::string& summary)
{
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    if (m_terminal)
        fmt::print(stderr, "\r\033[K");
    // A result, like every command's "wrote ..." line: on stdout, where the bar is not.
    fmt::print("{} in {:.1f} s\n", summary, elapsed);
}

} // namespace pba::app
