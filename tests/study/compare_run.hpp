#pragma once
// What the study tests that run `pba compare` share: the run into a folder and its report.
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.hpp"

namespace pba::test {

struct CompareRun {
    CommandResult result;
    std::string report; ///< the folder's report.md ("" when pba failed)
    bool ok() const { return result.exitCode == 0; }
};

/// Runs `pba compare ARGS --out DIR` and reads the report it wrote. A test asserts
/// `ASSERT_TRUE(run.ok()) << run.result.err` before reading on.
inline CompareRun runCompare(const std::string& args, const std::filesystem::path& dir)
{
    CompareRun run{runPba("compare " + args + " --out " + dir.string()), {}};
    if (run.ok())
        run.report = readFile(dir / "report.md");
    return run;
}

/// A CSV file's lines split at their commas, the header first.
inline std::vector<std::vector<std::string>> csvRows(const std::filesystem::path& path)
{
    std::vector<std::vector<std::string>> rows;
    std::istringstream csv(readFile(path));
    for (std::string line; std::getline(csv, line);) {
        std::vector<std::string>& cells = rows.emplace_back();
        std::stringstream fields(line);
        for (std::string cell; std::getline(fields, cell, ',');)
            cells.push_back(cell);
    }
    return rows;
}

} // namespace pba::test
