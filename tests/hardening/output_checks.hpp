#pragma once
// What the output tests share: finding temporaries left behind, fake helper programs, a folder
// full of someone's files, and a small disk that fills.
#include <gtest/gtest.h>

#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "io/output_file.hpp"
#include "support/run_command.hpp"

namespace pba::test {

/// Files in `dir` whose names hold ".tmp-" (a temporary left behind).
inline std::vector<std::string> temporaries(const std::filesystem::path& dir)
{
    std::vector<std::string> found;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
        if (entry.path().filename().string().find(".tmp-") != std::string::npos)
            found.push_back(entry.path().string());
    return found;
}

inline void writeText(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

/// `text` in a file as an earlier run of pba leaves it: listed in its folder's manifest, so a
/// later output may replace it.
inline void writeAsPba(const std::filesystem::path& path, const std::string& text)
{
    pba::io::writeFileAtomically(path, text);
}

/// A folder `bin` in `dir` holding an executable shell script `name`; returns the folder.
inline std::filesystem::path fakeProgram(const std::filesystem::path& dir, const std::string& name,
                                         const std::string& script)
{
    const std::filesystem::path bin = dir / "bin";
    std::filesystem::create_directories(bin);
    writeText(bin / name, "#!/bin/sh\n" + script);
    std::filesystem::permissions(bin / name, std::filesystem::perms::owner_all);
    return bin;
}

/// A fake `name` program that prints a message and fails.
inline std::filesystem::path failingProgram(const std::filesystem::path& dir, const std::string& name)
{
    return fakeProgram(dir, name, "echo \"fake " + name + " failure\" >&2\nexit 3\n");
}

/// Every file under `dir` (relative path -> bytes), to compare a folder before and after.
inline std::map<std::string, std::string> contents(const std::filesystem::path& dir)
{
    std::map<std::string, std::string> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
        files[std::filesystem::relative(entry.path(), dir).string()] =
            entry.is_directory() ? std::string("(folder)") : readFile(entry.path());
    return files;
}

/// The names whose bytes differ between two contents(), or that only one holds: a short message
/// instead of two folders of PNG bytes.
inline std::string differences(const std::map<std::string, std::string>& a, const std::map<std::string, std::string>& b)
{
    std::string names;
    for (const auto& [name, bytes] : a)
        if (!b.count(name) || b.at(name) != bytes)
            names += " " + name;
    for (const auto& [name, bytes] : b)
        if (!a.count(name))
            names += " " + name;
    return names;
}

/// Someone's files in `dir`, none of them pba's: a note, a hidden file, and a subfolder holding
/// files with pba's own names (only the folder's top level is pba's to write).
inline void fillWithUserFiles(const std::filesystem::path& dir)
{
    std::filesystem::create_directories(dir / "sub/deeper");
    writeText(dir / "notes.txt", "my notes");
    writeText(dir / ".hidden", "hidden");
    writeText(dir / "sub/frame_00000.png", "not a frame");
    writeText(dir / "sub/report.md", "my report");
    writeText(dir / "sub/deeper/data.csv", "1,2,3");
}

/// Polls `done` every 5 ms for up to `timeoutMs`; true once it holds.
inline bool waitFor(const std::function<bool()>& done, int timeoutMs = 20000)
{
    for (int waited = 0; waited < timeoutMs; waited += 5) {
        if (done())
            return true;
        ::usleep(5000);
    }
    return done();
}

/// The folder a folder output in `dir` is writing its new files into, or an empty path.
inline std::filesystem::path stagingFolder(const std::filesystem::path& dir)
{
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
        if (entry.path().filename().string().rfind(".pba-staging.tmp-", 0) == 0)
            return entry.path();
    return {};
}

/// A 64 KiB tmpfs mounted at `dir` while this lives: a disk that fills, or with MS_RDONLY in
/// `flags` one that cannot be written at all. Mounting needs root (or CAP_SYS_ADMIN); without it
/// mounted() is false and why() says so, for GTEST_SKIP.
class SmallDisk {
public:
    explicit SmallDisk(const std::filesystem::path& dir, unsigned long flags = 0) : m_dir(dir)
    {
        std::filesystem::create_directories(dir);
        if (::mount("tmpfs", dir.c_str(), "tmpfs", flags, "size=64k") == 0)
            m_mounted = true;
        else
            m_why = std::string("a small disk is a 64 KiB tmpfs, and mounting one needs root: ") + std::strerror(errno);
    }
    ~SmallDisk()
    {
        if (m_mounted)
            ::umount2(m_dir.c_str(), MNT_DETACH);
    }
    SmallDisk(const SmallDisk&) = delete;
    SmallDisk& operator=(const SmallDisk&) = delete;

    bool mounted() const { return m_mounted; }
    const std::string& why() const { return m_why; }

private:
    std::filesystem::path m_dir;
    bool m_mounted = false;
    std::string m_why;
};

} // namespace pba::test
