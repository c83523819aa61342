// Hardening II: no string from a scene or a path reaches a shell or becomes script text, and
// every output is written completely or not at all, whatever fails (a full disk, a helper
// program, a signal). pba runs here from an argument vector (runPbaArgv), so each hostile
// string reaches it exactly as written.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "output_checks.hpp"
#include "support/run_command.hpp"

using namespace pba::test;
namespace fs = std::filesystem;

namespace {

/// Strings that would run `touch MARKER` if they reached a shell or gnuplot's script text.
std::vector<std::string> hostile(const fs::path& marker)
{
    const std::string m = marker.string();
    return {"`touch " + m + "`", "$(touch " + m + ")", "'; system('touch " + m + "'); '",
            "\"; system \"touch " + m + "\"; \"", "a;touch " + m, "x' . system('touch " + m + "') . '"};
}

/// The blow-dryer scene under another name, written to `dir`.
fs::path sceneNamed(const fs::path& dir, const std::string& name, const std::string& file = "scene.json")
{
    nlohmann::json scene = nlohmann::json::parse(readFile(sourceDir() / "scenes/blow-dryer.json"));
    scene["name"] = name;
    const fs::path path = dir / file;
    std::ofstream(path) << scene.dump();
    return path;
}

} // namespace

TEST(Security, SceneNamesReachGnuplotOnlyAsData)
{
    const fs::path dir = freshDir("hostile_names");
    const fs::path marker = dir / "MARKER";
    for (const std::string& name : hostile(marker)) {
        const fs::path scene = sceneNamed(dir, name);
        const CommandResult r = runPbaArgv({"field", scene.string(), "--slice", "--out", (dir / "f.png").string()},
                                           {.workDir = dir});
        EXPECT_EQ(r.exitCode, 0) << name << "\n" << r.err;
        EXPECT_FALSE(fs::exists(marker)) << "ran: " << name;
        EXPECT_TRUE(fs::exists(dir / "f.png")) << name;
        fs::remove(dir / "f.png");
    }
    // A newline (gnuplot's command separator) or any control character in a name is refused.
    const fs::path scene = sceneNamed(dir, "x\nsystem \"touch " + marker.string() + "\"");
    const CommandResult r = runPbaArgv({"field", scene.string(), "--slice", "--out", (dir / "f.png").string()});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("name: contains a control character"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(marker));
}

TEST(Security, OddOutputNamesAreWrittenUnderExactlyThatName)
{
    const fs::path dir = freshDir("odd_outputs");
    const fs::path marker = dir / "MARKER";
    // Relative to the working folder (a name holds no '/'): `touch MARKER` would make dir/MARKER.
    std::vector<std::string> stems{"it's", "-starts-with-a-dash", "semi;colon $(touch MARKER)", "back`touch MARKER`tick",
                                   "quote\"d", "new\nline", "it's'; touch MARKER; '"};
    for (const std::string& stem : stems) {
        for (const char* extension : {".mp4", ".png"}) {
            const std::string name = stem + extension;
            const CommandResult r =
                runPbaArgv({"render", "integrators", "--size", "64x48", "--duration", "0.1", "--fps", "10",
                            "--time", "0.1", "--out", name},
                           {.workDir = dir});
            // --time is for a PNG only: the video is made without it.
            const CommandResult video = std::string(extension) == ".mp4"
                                            ? runPbaArgv({"render", "integrators", "--size", "64x48", "--duration",
                                                          "0.1", "--fps", "10", "--out", name},
                                                         {.workDir = dir})
                                            : r;
            EXPECT_EQ(video.exitCode, 0) << name << "\n" << video.err;
            EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;
            EXPECT_GT(fs::file_size(dir / name), 100u) << name;
        }
        const CommandResult csv =
            runPbaArgv({"sim", "integrators", "--duration", "0.1", "--out", stem + ".csv"}, {.workDir = dir});
        EXPECT_EQ(csv.exitCode, 0) << stem << "\n" << csv.err;
        EXPECT_TRUE(fs::is_regular_file(dir / (stem + ".csv"))) << stem;
    }
    EXPECT_FALSE(fs::exists(marker));
    EXPECT_TRUE(temporaries(dir).empty());
}

// A path is printed with its control characters escaped, in a "wrote" line as in an error: a
// newline in it split the line, and a reader of the output saw two.
TEST(Security, APathWithControlCharactersIsPrintedOnOneLine)
{
    const fs::path dir = freshDir("control_paths") / "new\nline\tfolder";
    fs::create_directories(dir);
    const std::string shown = (dir.parent_path() / "new\\nline\\tfolder").string();
    const std::pair<std::vector<std::string>, std::string> writes[] = {
        {{"sim", "integrators", "--duration", "0.05", "--out", (dir / "run.csv").string()},
         "wrote 18 rows to " + shown + "/run.csv\n"},
        {{"field", "--slice", "--resolution", "16", "--out", (dir / "f.png").string()}, "wrote " + shown + "/f.png ("},
        {{"render", "integrators", "--size", "64x48", "--out", (dir / "a.png").string()}, "wrote " + shown + "/a.png ("},
        {{"compare", "--dt", "0.01", "--integrators", "rk4", "--out", (dir / "study").string()},
         "wrote " + shown + "/study/report.md"}};
    for (const auto& [args, line] : writes) {
        const CommandResult r = runPbaArgv(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.out.find(line), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find(dir.string()), std::string::npos) << r.out;
    }
    fs::copy_file(sourceDir() / "scenes/rope.json", dir / "rope.json");
    const CommandResult blowUp = runPbaArgv({"sim", (dir / "rope.json").string(), "--dt", "0.05"});
    EXPECT_EQ(blowUp.exitCode, 3) << blowUp.err;
    EXPECT_EQ(blowUp.err.rfind("pba: error: " + shown + "/rope.json: the energy", 0), 0u) << blowUp.err;
    EXPECT_EQ(std::count(blowUp.err.begin(), blowUp.err.end(), '\n'), 1) << blowUp.err;
}

TEST(Outputs, AnythingButARegularFileIsRefusedAndLeftAlone)
{
    const fs::path dir = freshDir("not_regular");
    ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
    for (const fs::path& target : {fs::path("/dev/null"), dir / "fifo", dir}) {
        const CommandResult r = runPbaArgv({"sim", "integrators", "--duration", "0.1", "--out", target.string()});
        EXPECT_EQ(r.exitCode, 2) << target;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    EXPECT_TRUE(fs::is_fifo(dir / "fifo"));
    const CommandResult empty = runPbaArgv({"sim", "integrators", "--out", ""});
    EXPECT_EQ(empty.exitCode, 2);
    EXPECT_NE(empty.err.find("--out: empty; give it a value"), std::string::npos) << empty.err;
}

TEST(Outputs, ASymbolicLinkIsFollowedToTheFileItNames)
{
    const fs::path dir = freshDir("symlink_out");
    fs::create_directories(dir / "real");
    fs::create_symlink(dir / "real/run.csv", dir / "link.csv"); // names a file that does not exist yet
    const CommandResult r = runPbaArgv({"sim", "integrators", "--duration", "0.1", "--out", (dir / "link.csv").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
    EXPECT_EQ(readFile(dir / "real/run.csv").rfind("step,t,body,", 0), 0u);
}

// RLIMIT_FSIZE stands in for a full disk: a write past it fails as ENOSPC would.
TEST(Outputs, AFailedWriteLeavesThePreviousFileAndNoTemporary)
{
    const fs::path dir = freshDir("full_disk");
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"sim", "integrators", "--out", "out.csv"},
          std::vector<std::string>{"render", "integrators", "--size", "320x240", "--time", "1", "--out", "out.png"},
          std::vector<std::string>{"render", "integrators", "--size", "320x240", "--duration", "2", "--out", "out.mp4"},
          std::vector<std::string>{"render", "integrators", "--size", "320x240", "--duration", "1", "--out", "frames/"}}) {
        const fs::path target = dir / args.back();
        if (args.back() == "frames/") {
            // The previous frames are pba's, beside a file of the user's.
            ASSERT_EQ(runPbaArgv({"render", "integrators", "--size", "64x48", "--duration", "0.05", "--out", "frames/"},
                                 {.workDir = dir}).exitCode, 0);
            writeText(target / "keep.txt", "previous");
        } else {
            writeAsPba(target, "previous");
        }
        const auto before = args.back() == "frames/" ? contents(target) : std::map<std::string, std::string>{};
        const CommandResult r = runPbaArgv(args, {.fileSizeLimit = 2000, .workDir = dir});
        EXPECT_EQ(r.exitCode, 1) << args.back() << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        if (args.back() == "frames/")
            EXPECT_EQ(differences(contents(target), before), "");
        else
            EXPECT_EQ(readFile(target), "previous") << args.back();
    }
    EXPECT_TRUE(temporaries(dir).empty());
}

// Results on standard output sit in stdio's buffer until the program ends, so a write that failed
// there went unseen and the run exited 0. /dev/full fails every write as a full disk would.
TEST(Outputs, AFailedWriteToStandardOutputExitsOneNamingIt)
{
    // Linux's always-full device: every write to it fails with ENOSPC.
    ASSERT_TRUE(fs::exists("/dev/full"));
    for (const std::string args : {"scenes", "sim integrators --duration 0.1", "field blow-dryer --at 0,1,0 --json"}) {
        const CommandResult r = runPba(args + " >/dev/full");
        EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err, "pba: error: standard output: " + std::string(std::strerror(ENOSPC)) + "\n") << args;
    }
    // An error before the write keeps its status and stays the only line.
    const CommandResult bad = runPba("sim integrators --dt -1 >/dev/full");
    EXPECT_EQ(bad.exitCode, 2) << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
    EXPECT_EQ(bad.err.find("standard output"), std::string::npos) << bad.err;
}

// Bare pba with no display renders two files: a user's file at the second is refused before the
// first is rendered (it was refused after 20 s, the video written).
TEST(Outputs, BarePbaRefusesAUsersStillBeforeRenderingItsVideo)
{
    const fs::path dir = freshDir("bare_pba_users_still");
    fs::create_directories(dir / "pba-out");
    std::ofstream(dir / "pba-out" / "blow-dryer.png") << "the user's";
    const CommandResult r = runShell("cd '" + dir.string() + "' && env -u DISPLAY " + pbaBinary());
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("blow-dryer.png: a file pba did not write"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "pba-out" / "blow-dryer.mp4"));
    std::ifstream in(dir / "pba-out" / "blow-dryer.png");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "the user's");
}

// A name of the file system's longest (255 bytes) is written, and leaves no temporary: its
// temporary's name, NAME.tmp-PID, was longer than the limit.
TEST(Outputs, ANameOfTheLongestLengthIsWritten)
{
    const fs::path dir = freshDir("longest_name");
    for (const std::string extension : {".csv", ".png"}) {
        const fs::path out = dir / (std::string(255 - extension.size(), 'a') + extension);
        const std::string command = extension == ".csv" ? "sim integrators --duration 0.1 --out "
                                                        : "render integrators --time 0.1 --size 64x48 --out ";
        const CommandResult r = runPba(command + out.string());
        EXPECT_EQ(r.exitCode, 0) << extension << "\n" << r.err;
        EXPECT_TRUE(fs::is_regular_file(out)) << extension;
    }
    EXPECT_TRUE(temporaries(dir).empty());
}

TEST(Outputs, AFailingHelperProgramIsReportedInOneLineAndChangesNothing)
{
    const fs::path dir = freshDir("failing_helpers");
    writeAsPba(dir / "out.mp4", "previous");
    const fs::path bin = failingProgram(dir, "ffmpeg");
    failingProgram(dir, "gnuplot");
    const CommandResult video = runPbaArgv({"render", "integrators", "--size", "64x48", "--duration", "0.5", "--out",
                                            (dir / "out.mp4").string()},
                                           {.path = bin.string()});
    EXPECT_EQ(video.exitCode, 1);
    EXPECT_NE(video.err.find("(exit status 3): fake ffmpeg failure"), std::string::npos) << video.err;
    EXPECT_EQ(std::count(video.err.begin(), video.err.end(), '\n'), 1) << video.err;
    EXPECT_EQ(readFile(dir / "out.mp4"), "previous");

    // A study that fails leaves the previous study's folder as it was, not a mix.
    ASSERT_EQ(runPbaArgv({"compare", "--duration", "1", "--dt", "0.01,0.02", "--out", (dir / "study").string()}).exitCode,
              0);
    const std::string report = readFile(dir / "study/report.md");
    const CommandResult failed = runPbaArgv(
        {"compare", "--duration", "2", "--dt", "0.005,0.01", "--out", (dir / "study").string()}, {.path = bin.string()});
    EXPECT_EQ(failed.exitCode, 1) << failed.err;
    EXPECT_NE(failed.err.find("fake gnuplot failure"), std::string::npos) << failed.err;
    EXPECT_EQ(readFile(dir / "study/report.md"), report);
    EXPECT_TRUE(temporaries(dir).empty());
}

namespace {

// MP4 boxes as printf(1) octal escapes: a 32-bit big-endian size, then the type.
const std::string kFtyp = "\\000\\000\\000\\010ftyp", kMoov = "\\000\\000\\000\\010moov",
                  kMdat = "\\000\\000\\000\\010mdat", kMdatOf4096 = "\\000\\000\\020\\000mdat";

/// A fake ffmpeg that reads every frame, writes `boxes` to its output (its last argument,
/// file:PATH), prints `message` and exits 0, as the real one does when the disk fills.
fs::path ffmpegExitingZero(const fs::path& dir, const std::string& boxes, const std::string& message)
{
    return fakeProgram(dir, "ffmpeg",
                       "for last; do :; done\n/bin/cat >/dev/null\nprintf '" + boxes + "' >\"${last#file:}\"\n" +
                           (message.empty() ? "" : "echo '" + message + "' >&2\n") + "exit 0\n");
}

} // namespace

// ffmpeg's exit status alone passes a video cut short: its log and the file's boxes are checked.
TEST(Outputs, AVideoIsCheckedBeforeItReplacesThePreviousOne)
{
    const fs::path dir = freshDir("video_checked");
    struct Case {
        std::string boxes, message, error;
    };
    for (const Case& c : {Case{kFtyp + kMdat, "", "incomplete video: it has no index (moov box)"},
                          Case{kFtyp + kMoov + kMdatOf4096, "", "'mdat' box at byte 16 claims 4096 bytes, 8 are left"},
                          Case{kFtyp + kMoov + kMdat, "Error writing trailer of out.mp4: No space left on device",
                               "ffmpeg reported an error (exit status 0): Error writing trailer of out.mp4: No space"}}) {
        writeAsPba(dir / "out.mp4", "previous");
        const fs::path bin = ffmpegExitingZero(dir, c.boxes, c.message);
        const CommandResult r = runPbaArgv({"render", "integrators", "--size", "64x48", "--duration", "0.1", "--out",
                                            (dir / "out.mp4").string()},
                                           {.path = bin.string()});
        EXPECT_EQ(r.exitCode, 1) << c.error;
        EXPECT_NE(r.err.find(c.error), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(readFile(dir / "out.mp4"), "previous");
    }
    // The same fake with a whole file and nothing to say passes: the check reads boxes, not ffmpeg.
    const fs::path bin = ffmpegExitingZero(dir, kFtyp + kMoov + kMdat, "");
    const CommandResult r = runPbaArgv(
        {"render", "integrators", "--size", "64x48", "--duration", "0.1", "--out", (dir / "out.mp4").string()},
        {.path = bin.string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(fs::file_size(dir / "out.mp4"), 24u);
    EXPECT_TRUE(temporaries(dir).empty());
}

// The real thing: on a full disk ffmpeg 5 prints "Error writing trailer ... No space left on
// device" and exits 0, its file cut at a block's end. The disk holds a file of the user's that
// leaves 12 KiB free, less than the 20 KB video.
TEST(Outputs, AVideoOnAFullDiskKeepsThePreviousOne)
{
    const fs::path dir = freshDir("video_full_disk");
    SmallDisk disk(dir / "disk");
    if (!disk.mounted())
        GTEST_SKIP() << disk.why();
    writeText(dir / "disk/filler", std::string(52000, 'x'));
    writeAsPba(dir / "disk/out.mp4", "previous");
    const CommandResult r = runPbaArgv(
        {"render", "integrators", "--size", "320x240", "--duration", "2", "--out", (dir / "disk/out.mp4").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(readFile(dir / "disk/out.mp4"), "previous");
    EXPECT_EQ(fs::file_size(dir / "disk/filler"), 52000u);
    EXPECT_TRUE(temporaries(dir).empty());
}

// A folder that cannot be written is found before the work, as sim's was: field's slice and
// render's picture and video failed only once made, naming their temporary, with exit 1.
TEST(Outputs, AFolderThatCannotBeWrittenIsRefusedBeforeAnyWork)
{
    const fs::path dir = freshDir("read_only");
    SmallDisk disk(dir / "disk", MS_RDONLY);
    if (!disk.mounted() && ::geteuid() == 0)
        GTEST_SKIP() << disk.why();
    if (!disk.mounted())
        fs::permissions(dir / "disk", fs::perms::owner_read | fs::perms::owner_exec); // honoured but by root
    const std::vector<std::vector<std::string>> runs{
        {"field", "--slice", "--out", "disk/f.png"},
        {"render", "integrators", "--size", "64x48", "--out", "disk/a.png"},
        {"render", "integrators", "--size", "64x48", "--duration", "0.2", "--out", "disk/a.mp4"},
        {"sim", "integrators", "--duration", "0.1", "--out", "disk/run.csv"}};
    for (const auto& args : runs) {
        const CommandResult r = runPbaArgv(args, {.workDir = dir});
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(r.err.rfind("pba: error: --out: " + args.back() + ": cannot be written (", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.out, "") << r.out;
    }
    // A folder output is named as given, not by its staging folder inside; bare pba's pba-out
    // (no --out typed) by its own name.
    const std::vector<std::vector<std::string>> folders{
        {"render", "integrators", "--size", "64x48", "--duration", "0.1", "--out", "disk/"},
        {"compare", "--duration", "0.2", "--out", "disk"}};
    for (const auto& args : folders) {
        const CommandResult r = runPbaArgv(args, {.workDir = dir});
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(r.err.rfind("pba: error: " + (dir / "disk").string() + ": cannot be written: ", 0), 0u) << r.err;
        EXPECT_EQ(r.err.find("staging"), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    const CommandResult bare = runShell("cd '" + (dir / "disk").string() + "' && env -u DISPLAY " + pbaBinary());
    EXPECT_EQ(bare.exitCode, 2) << bare.err;
    EXPECT_EQ(bare.err.rfind("pba: error: pba-out: cannot be made (", 0), 0u) << bare.err;
    EXPECT_EQ(bare.err.find("--out"), std::string::npos) << bare.err;
    EXPECT_EQ(std::count(bare.err.begin(), bare.err.end(), '\n'), 1) << bare.err;
    if (!disk.mounted())
        fs::permissions(dir / "disk", fs::perms::owner_all);
    EXPECT_TRUE(fs::is_empty(dir / "disk"));
}

// SIGHUP is what a closed terminal sends.
TEST(Outputs, AnInterruptedRunLeavesNoTemporary)
{
    const fs::path dir = freshDir("interrupted");
    for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
        const CommandResult r =
            runPbaArgv({"sim", "integrators", "--dt", "1e-5", "--duration", "1000", "--out", "run.csv"},
                       {.stopAfterMs = 700, .stopSignal = signal, .workDir = dir});
        EXPECT_EQ(r.exitCode, 128 + signal);
        EXPECT_FALSE(fs::exists(dir / "run.csv"));
        EXPECT_TRUE(temporaries(dir).empty());
        // The folder made for an output goes with it while nothing else is in it.
        const CommandResult made =
            runPbaArgv({"render", "integrators", "--size", "64x48", "--duration", "1000", "--out", "made/run.mp4"},
                       {.stopAfterMs = 700, .stopSignal = signal, .workDir = dir});
        EXPECT_EQ(made.exitCode, 128 + signal);
        EXPECT_FALSE(fs::exists(dir / "made"));
    }
}

// pba replaces a file only while its folder's manifest lists it with the bytes it holds: a file of
// the user's, the scene being run, or one of pba's edited since is refused before any work.
TEST(Outputs, AFileThatPbaDidNotWriteIsNeverReplaced)
{
    const fs::path dir = freshDir("users_files");
    // (A scene under a CSV's name: a .json one is refused as an output by its name alone.)
    std::ofstream(dir / "scene.csv") << readFile(sourceDir() / "scenes/integrators.json");
    const std::string scene = readFile(dir / "scene.csv");
    for (const char* name : {"notes.csv", "mine.png", "mine.mp4", "slice.png"})
        writeText(dir / name, "the user's");
    fs::create_symlink("notes.csv", dir / "link.csv");
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"sim", "scene.csv", "--dt", "1e-5", "--duration", "1000", "--out", "scene.csv"},
          std::vector<std::string>{"sim", "integrators", "--dt", "1e-5", "--duration", "1000", "--out", "notes.csv"},
          std::vector<std::string>{"sim", "integrators", "--dt", "1e-5", "--duration", "1000", "--out", "link.csv"},
          std::vector<std::string>{"render", "integrators", "--size", "64x48", "--time", "0.1", "--out", "mine.png"},
          std::vector<std::string>{"render", "integrators", "--size", "64x48", "--duration", "100", "--out", "mine.mp4"},
          std::vector<std::string>{"field", "blow-dryer", "--slice", "--out", "slice.png"}}) {
        const CommandResult r = runPbaArgv(args, {.workDir = dir});
        EXPECT_EQ(r.exitCode, 2) << args.back() << "\n" << r.err;
        EXPECT_NE(r.err.find(args.back() + ": a file pba did not write"), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    const CommandResult list = runPbaArgv({"sim", "integrators", "--out", ".pba-output"}, {.workDir = dir});
    EXPECT_EQ(list.exitCode, 2);
    EXPECT_NE(list.err.find(".pba-output: is the name of the list pba keeps"), std::string::npos) << list.err;
    EXPECT_EQ(readFile(dir / "scene.csv"), scene);
    for (const char* name : {"notes.csv", "mine.png", "mine.mp4", "slice.png"})
        EXPECT_EQ(readFile(dir / name), "the user's") << name;
    EXPECT_FALSE(fs::exists(dir / ".pba-output"));

    // pba's own file is replaced, again and again, under any name; once edited it is the user's.
    for (const std::string name : {"run.csv", "new\nline 100%.csv"}) {
        for (int run = 0; run < 2; ++run) {
            const CommandResult r = runPbaArgv({"sim", "integrators", "--duration", "0.01", "--out", name}, {.workDir = dir});
            EXPECT_EQ(r.exitCode, 0) << name << " run " << run << "\n" << r.err;
        }
    }
    std::ofstream(dir / "run.csv", std::ios::app) << "an edit\n";
    const CommandResult edited =
        runPbaArgv({"sim", "integrators", "--duration", "0.01", "--out", "run.csv"}, {.workDir = dir});
    EXPECT_EQ(edited.exitCode, 2);
    EXPECT_NE(edited.err.find("run.csv: changed since pba wrote it"), std::string::npos) << edited.err;

    // A study's folder output and a file output in one folder keep each other's entries.
    ASSERT_EQ(runPbaArgv({"compare", "spring", "--duration", "1", "--dt", "0.01,0.02", "--out", "."}, {.workDir = dir})
                  .exitCode,
              0);
    EXPECT_EQ(runPbaArgv({"sim", "integrators", "--duration", "0.01", "--out", "new\nline 100%.csv"}, {.workDir = dir})
                  .exitCode,
              0);
    const CommandResult again =
        runPbaArgv({"compare", "spring", "--duration", "1", "--dt", "0.01,0.02", "--out", "."}, {.workDir = dir});
    EXPECT_EQ(again.exitCode, 0) << again.err;
    const std::string manifest = readFile(dir / ".pba-output");
    EXPECT_NE(manifest.find(" report.md\n"), std::string::npos) << manifest;
    EXPECT_NE(manifest.find(" new%0Aline 100%25.csv\n"), std::string::npos) << manifest;
    EXPECT_TRUE(temporaries(dir).empty());
}

// A run of 10^8 steps that is refused at once shows the path is checked before simulating.
TEST(Outputs, AFilePathEndingInASlashIsRefusedBeforeAnyWork)
{
    const fs::path dir = freshDir("slash");
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"sim", "integrators", "--dt", "1e-5", "--duration", "1000", "--out", "x.csv/"},
          std::vector<std::string>{"field", "blow-dryer-flow", "--slice", "--out", "f.png/"}}) {
        const CommandResult r = runPbaArgv(args, {.workDir = dir});
        EXPECT_EQ(r.exitCode, 2) << args.back();
        EXPECT_NE(r.err.find(args.back() + ": names a folder (it ends in '/'), expected a file path"), std::string::npos)
            << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_TRUE(fs::is_empty(dir)) << "a folder was made for a refused output";
}

TEST(Outputs, CsvQuotesNamesHoldingCommasAndQuotes)
{
    const fs::path dir = freshDir("csv_quotes");
    nlohmann::json scene = nlohmann::json::parse(readFile(sourceDir() / "scenes/integrators.json"));
    scene["particles"][1]["name"] = "a,b";
    scene["particles"][2]["name"] = "say \"hi\"";
    std::ofstream(dir / "s.json") << scene.dump();
    ASSERT_EQ(runPbaArgv({"sim", (dir / "s.json").string(), "--duration", "0.01", "--out", (dir / "r.csv").string()})
                  .exitCode,
              0);
    const std::string csv = readFile(dir / "r.csv");
    EXPECT_NE(csv.find("\n0,0,\"a,b\","), std::string::npos) << csv;
    EXPECT_NE(csv.find("\n0,0,\"say \"\"hi\"\"\","), std::string::npos) << csv;
}
