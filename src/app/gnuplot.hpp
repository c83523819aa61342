#pragma once
// Pictures are drawn by gnuplot (Debian's gnuplot-nox, pngcairo terminal), driven through a
// script: a well-kept plotting tool rather than hand-drawn charts.
#include <filesystem>
#include <string>

namespace pba::app {

/// True if `gnuplot` is on the PATH.
bool gnuplotAvailable();

/// Runs `script` with gnuplot in `workDir` (data files are referred to relative to it).
/// Throws RuntimeFailure naming the Debian package when gnuplot is missing, and with
/// gnuplot's own message when it fails.
void runGnuplot(const std::string& script, const std::filesystem::path& workDir);

/// A scratch directory removed when this object dies.
class ScratchDir {
public:
    explicit ScratchDir(const std::string& prefix);
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    ~ScratchDir();
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
};

} // namespace pba::app
