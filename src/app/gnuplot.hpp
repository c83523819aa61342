#pragma once
// Pictures are drawn by gnuplot (Debian's gnuplot-nox, pngcairo terminal), driven through a
// script: a well-kept plotting tool rather than hand-drawn charts. The script is pba's own
// text; anything from a user (a scene's name) reaches gnuplot only as an argument (ARG1, ...),
// which gnuplot holds as a string value, never as script text. gnuplot writes into a scratch
// folder under fixed names; pba copies the pictures to their targets.
#include <filesystem>
#include <string>
#include <vector>

#include "io/output_file.hpp"

namespace pba::app {

/// True if `gnuplot` is on the PATH.
bool gnuplotAvailable();

/// Runs `script` with gnuplot in `workDir` (data files are referred to relative to it), with
/// `args` as its ARG1, ARG2, ... Throws RuntimeFailure naming the Debian package when gnuplot is
/// missing, and with gnuplot's own message when it fails.
void runGnuplot(const std::string& script, const std::filesystem::path& workDir,
                const std::vector<std::string>& args = {});

/// Copies a picture gnuplot made in a scratch folder to its target, completely or not at all.
void publish(const std::filesystem::path& made, const std::filesystem::path& target);

/// A scratch folder, removed when this object dies or the program is stopped by a signal.
class ScratchDir {
public:
    explicit ScratchDir(const std::string& prefix);
    const std::filesystem::path& path() const { return m_folder.path(); }

private:
    io::Temporary m_folder; // never committed
};

} // namespace pba::app
