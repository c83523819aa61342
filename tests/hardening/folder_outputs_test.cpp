// A folder output (`render --out DIR/`, `compare --out DIR`) writes and replaces only pba's own
// files in the folder, those its manifest (.pba-output) lists with the bytes pba wrote, and
// leaves everything else there alone; a file with one of its names that pba did not write is a
// reason to refuse, before any work. The user's folder here is output_checks.hpp's
// fillWithUserFiles: a note, a hidden file, and a subfolder holding files with pba's names.
#include <gtest/gtest.h>

#include <csignal>
#include <string>
#include <vector>

#include "output_checks.hpp"
#include "support/run_command.hpp"

using namespace pba::test;
namespace fs = std::filesystem;

namespace {

/// `frames` frames of the spring at 10 a second, small, into the folder `out`.
std::vector<std::string> renderFrames(const std::string& out, int frames)
{
    return {"render", "spring", "--size", "64x48", "--fps", "10", "--duration", std::to_string((frames - 1) / 10.0),
            "--out", out};
}

/// A short integrator study into `out`.
std::vector<std::string> study(const std::string& scene, const std::string& out)
{
    return {"compare", scene, "--duration", "0.5", "--dt", "0.01,0.02", "--jobs", "2", "--out", out};
}

/// Every file `before` held is in `dir` with the same bytes (but pba's manifest, which changes).
void expectKept(const std::map<std::string, std::string>& before, const fs::path& dir)
{
    const auto after = contents(dir);
    for (const auto& [name, bytes] : before) {
        if (name == ".pba-output")
            continue;
        const auto now = after.find(name);
        EXPECT_TRUE(now != after.end() && now->second == bytes) << name << " was removed or changed";
    }
}

bool hasFrames(const fs::path& dir, int count)
{
    for (int i = 0; i < count; ++i)
        if (!fs::is_regular_file(dir / ("frame_0000" + std::to_string(i) + ".png")))
            return false;
    return !fs::exists(dir / ("frame_0000" + std::to_string(count) + ".png"));
}

/// Refused with exit 2 in one line naming `file` and saying why.
void expectRefused(const CommandResult& r, const fs::path& file, const std::string& why)
{
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(fs::weakly_canonical(file).string() + ": " + why), std::string::npos) << r.err;
}

} // namespace

// `--out .` is the working folder itself: the frames go beside the user's files. A shorter run
// then replaces pba's frames and removes those of the longer run, and only those.
TEST(Outputs, FramesLeaveEveryOtherFileInTheirFolder)
{
    const fs::path dir = freshDir("frames_beside_files");
    fillWithUserFiles(dir);
    const auto before = contents(dir);
    const CommandResult r = runPbaArgv(renderFrames(".", 4), {.workDir = dir});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    expectKept(before, dir);
    EXPECT_TRUE(hasFrames(dir, 4));
    EXPECT_TRUE(fs::is_regular_file(dir / ".pba-output"));

    const CommandResult shorter = runPbaArgv(renderFrames(dir.string(), 2)); // an existing folder, no '/'
    ASSERT_EQ(shorter.exitCode, 0) << shorter.err;
    expectKept(before, dir);
    EXPECT_TRUE(hasFrames(dir, 2)) << "a frame of the longer run was left";
    EXPECT_TRUE(temporaries(dir).empty());
}

// A folder named like a file is a folder all the same: `x.png/` is made, an existing `y.mp4`
// takes frames beside what it holds.
TEST(Outputs, AFolderNamedLikeAFileHoldsFrames)
{
    const fs::path dir = freshDir("folder_like_file");
    ASSERT_EQ(runPbaArgv(renderFrames("x.png/", 2), {.workDir = dir}).exitCode, 0);
    EXPECT_TRUE(hasFrames(dir / "x.png", 2));
    fs::create_directories(dir / "y.mp4");
    fillWithUserFiles(dir / "y.mp4");
    const auto before = contents(dir / "y.mp4");
    const CommandResult r = runPbaArgv(renderFrames("y.mp4", 2), {.workDir = dir});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(hasFrames(dir / "y.mp4", 2));
    expectKept(before, dir / "y.mp4");
    EXPECT_TRUE(temporaries(dir).empty());
}

// Both studies write into one folder beside the user's files and an earlier render's frames: the
// rotation study removes the particle study's files it does not write (orders.csv, its plots),
// and the frames stay pba's, which a later render replaces.
TEST(Outputs, AStudyLeavesEveryOtherFileInItsFolder)
{
    const fs::path dir = freshDir("study_beside_files");
    fillWithUserFiles(dir);
    ASSERT_EQ(runPbaArgv(renderFrames(".", 2), {.workDir = dir}).exitCode, 0);
    const auto before = contents(dir);
    const CommandResult particles = runPbaArgv(study("integrators", "."), {.workDir = dir});
    ASSERT_EQ(particles.exitCode, 0) << particles.err;
    expectKept(before, dir);
    for (const char* name : {"report.md", "results.csv", "orders.csv"})
        EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;

    const CommandResult rotation = runPbaArgv(study("dice", dir.string()));
    ASSERT_EQ(rotation.exitCode, 0) << rotation.err;
    expectKept(before, dir);
    EXPECT_NE(readFile(dir / "report.md").find("# Rotation study"), std::string::npos);
    for (const char* name : {"orders.csv", "height.png", "energy.png", "convergence.png"})
        EXPECT_FALSE(fs::exists(dir / name)) << name << " of the particle study was left";

    const CommandResult again = runPbaArgv(renderFrames(".", 3), {.workDir = dir});
    EXPECT_EQ(again.exitCode, 0) << again.err;
    EXPECT_TRUE(hasFrames(dir, 3));
    EXPECT_TRUE(fs::is_regular_file(dir / "results.csv"));
    EXPECT_TRUE(temporaries(dir).empty());
}

// Each refusal comes before any work and changes nothing: the folder is as it was.
TEST(Outputs, AFileWithOneOfItsNamesThatPbaDidNotWriteIsRefused)
{
    const fs::path dir = freshDir("not_pbas");
    const auto refusedAndUnchanged = [&](const fs::path& folder, const std::vector<std::string>& args,
                                         const fs::path& file, const std::string& why) {
        const auto before = contents(folder);
        expectRefused(runPbaArgv(args), file, why);
        EXPECT_EQ(differences(contents(folder), before), "") << file;
    };
    // A frame a shorter run would leave among its own.
    fs::create_directories(dir / "a");
    writeText(dir / "a/frame_00009.png", "someone's");
    refusedAndUnchanged(dir / "a", renderFrames((dir / "a/").string(), 3), dir / "a/frame_00009.png",
                        "not written by pba");
    // A frame pba wrote and someone changed since.
    ASSERT_EQ(runPbaArgv(renderFrames((dir / "b/").string(), 3)).exitCode, 0);
    writeText(dir / "b/frame_00001.png", "edited");
    refusedAndUnchanged(dir / "b", renderFrames((dir / "b/").string(), 3), dir / "b/frame_00001.png",
                        "changed since pba wrote it");
    // A folder with a frame's name.
    fs::create_directories(dir / "c/frame_00000.png");
    refusedAndUnchanged(dir / "c", renderFrames((dir / "c/").string(), 3), dir / "c/frame_00000.png",
                        "not a file pba wrote");
    // The user's report where a study goes.
    fs::create_directories(dir / "d");
    writeText(dir / "d/report.md", "my report");
    refusedAndUnchanged(dir / "d", study("integrators", (dir / "d").string()), dir / "d/report.md",
                        "not written by pba");
    // A manifest pba did not write.
    fs::create_directories(dir / "e");
    writeText(dir / "e/.pba-output", "hello");
    refusedAndUnchanged(dir / "e", renderFrames((dir / "e/").string(), 3), dir / "e/.pba-output",
                        "not a list pba wrote of its files");
    EXPECT_TRUE(temporaries(dir).empty());
}

// A file that turns up while the frames are rendered is checked for too: the new frames are
// not published, and the folder is as it was.
TEST(Outputs, AFileThatAppearsWhilePbaWorksIsNotReplaced)
{
    const fs::path dir = freshDir("appears");
    ASSERT_EQ(runPbaArgv(renderFrames(dir.string(), 2)).exitCode, 0);
    const auto before = contents(dir);
    const CommandResult r = runPbaArgv(
        {"render", "spring", "--size", "64x48", "--fps", "60", "--duration", "1", "--out", dir.string()},
        {.whileRunning = [&](pid_t) {
            ASSERT_TRUE(waitFor([&] { return fs::exists(stagingFolder(dir) / "frame_00001.png"); }));
            writeText(dir / "frame_00099.png", "someone's");
        }});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("frame_00099.png: appeared or changed while pba worked"), std::string::npos) << r.err;
    auto expected = before;
    expected["frame_00099.png"] = "someone's";
    EXPECT_EQ(differences(contents(dir), expected), "");
}

// SIGTERM while frames are written into a folder of earlier frames, SIGHUP while they go into
// two new folders: the first is as it was, the folders made for the second are gone.
TEST(Outputs, AnInterruptedFolderOutputLeavesThePreviousOne)
{
    const fs::path dir = freshDir("folder_interrupted");
    fillWithUserFiles(dir);
    ASSERT_EQ(runPbaArgv(renderFrames(".", 3), {.workDir = dir}).exitCode, 0);
    const auto before = contents(dir);
    for (const auto& [out, signal] : {std::pair{dir, SIGTERM}, std::pair{dir / "new/deeper", SIGHUP}}) {
        const CommandResult r = runPbaArgv(
            {"render", "spring", "--size", "64x48", "--duration", "1000", "--out", out.string() + "/"},
            {.whileRunning = [&, out = out, signal = signal](pid_t pid) {
                EXPECT_TRUE(waitFor([&] { return fs::exists(stagingFolder(out) / "frame_00001.png"); }));
                ::kill(pid, signal);
            }});
        EXPECT_EQ(r.exitCode, 128 + signal) << r.err;
    }
    EXPECT_EQ(differences(contents(dir), before), "");
}

// The frames fill the disk part way: the previous frames, the user's file and the manifest are
// as they were, with no temporary behind.
TEST(Outputs, FramesOnAFullDiskLeaveThePreviousOnes)
{
    const fs::path dir = freshDir("frames_full_disk");
    SmallDisk disk(dir / "disk");
    if (!disk.mounted())
        GTEST_SKIP() << disk.why();
    const fs::path frames = dir / "disk/frames";
    ASSERT_EQ(runPbaArgv(renderFrames(frames.string() + "/", 3)).exitCode, 0);
    writeText(frames / "filler", std::string(40000, 'x'));
    const auto before = contents(frames);
    const CommandResult r = runPbaArgv(
        {"render", "spring", "--size", "320x240", "--fps", "30", "--duration", "1", "--out", frames.string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(differences(contents(frames), before), "");
}

// The same for a study (without gnuplot, so that only its tables count): a study of four dt
// needs more room than the one of two it would replace.
TEST(Outputs, AStudyOnAFullDiskLeavesThePreviousOne)
{
    const fs::path dir = freshDir("study_full_disk");
    SmallDisk disk(dir / "disk");
    if (!disk.mounted())
        GTEST_SKIP() << disk.why();
    fs::create_directories(dir / "bin"); // a PATH without gnuplot
    const fs::path out = dir / "disk/study";
    ASSERT_EQ(runPbaArgv(study("integrators", out.string()), {.path = (dir / "bin").string()}).exitCode, 0);
    writeText(out / "filler", std::string(40000, 'x'));
    const auto before = contents(out);
    const CommandResult r =
        runPbaArgv({"compare", "--duration", "0.5", "--dt", "0.0025,0.005,0.01,0.02", "--out", out.string()},
                   {.path = (dir / "bin").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("write failed"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(differences(contents(out), before), "");
}
