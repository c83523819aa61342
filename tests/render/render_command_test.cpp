// `pba render` and `pba view` end to end: an MP4 probed with ffprobe, numbered frames, the
// window under a virtual X server, and a blow-up's exit 3.
#include <gtest/gtest.h>

#include <algorithm>

#include <stb_image.h>

#include "support/run_command.hpp"

using namespace pba::test;

TEST(PbaRender, WritesAnH264Mp4WithOneFramePerTick)
{
    const auto dir = freshDir("render_mp4");
    const auto mp4 = dir / "spring.mp4";
    const CommandResult r = runPba("render spring --duration 1 --fps 30 --size 320x240 --out " + mp4.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const CommandResult probe = runShell("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                         "stream=codec_name,width,height,pix_fmt,nb_read_frames -of csv=p=0 " +
                                         mp4.string());
    ASSERT_EQ(probe.exitCode, 0) << probe.err;
    EXPECT_EQ(probe.out, "h264,320,240,yuv420p,31\n"); // frames at t = 0, 1/30, ..., 1
    // Beside it only pba's list of the files it wrote there (.pba-output): no temporary left.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 2);
    EXPECT_TRUE(std::filesystem::exists(dir / ".pba-output"));
}

TEST(PbaRender, WritesNumberedFramesAndOnePng)
{
    const auto dir = freshDir("render_frames");
    ASSERT_EQ(runPba("render integrators --duration 0.1 --fps 20 --size 160x120 --out " + (dir / "frames/").string())
                  .exitCode,
              0);
    EXPECT_TRUE(std::filesystem::exists(dir / "frames/frame_00000.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "frames/frame_00002.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "frames/frame_00003.png"));
    const auto png = dir / "one.png";
    ASSERT_EQ(runPba("render integrators --time 0.5 --size 200x100 --out " + png.string()).exitCode, 0);
    int w = 0, h = 0, channels = 0;
    unsigned char* data = stbi_load(png.c_str(), &w, &h, &channels, 4);
    ASSERT_NE(data, nullptr);
    EXPECT_EQ(w, 200);
    EXPECT_EQ(h, 100);
    stbi_image_free(data);
}

TEST(PbaRender, BadOutputIsBadInputAndLeavesNothing)
{
    const auto dir = freshDir("render_bad");
    EXPECT_EQ(runPba("render integrators --out " + (dir / "x.gif").string()).exitCode, 2);
    // A missing last folder is made (pba-out/ in a fresh clone); two missing are refused.
    EXPECT_EQ(runPba("render integrators --out " + (dir / "missing/deeper/x.png").string()).exitCode, 2);
    // Found before any frame is drawn: a long video into a missing folder fails at once.
    EXPECT_EQ(runPba("render integrators --duration 1000 --out " + (dir / "missing/deeper/x.mp4").string()).exitCode,
              2);
    EXPECT_EQ(runPba("render integrators --out " + (dir / "missing/deeper/frames/").string()).exitCode, 2);
    EXPECT_EQ(runPba("render integrators --size 12 --out " + (dir / "x.png").string()).exitCode, 2);
    const CommandResult fraction = runPba("render integrators --fps 0.5 --out " + (dir / "x.mp4").string());
    EXPECT_EQ(fraction.exitCode, 2);
    EXPECT_EQ(fraction.err, "pba: error: --fps: expected a whole number, got '0.5'\n");
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 0);
}

// The extension is read in any case: IMG.PNG is a PNG.
TEST(PbaRender, AnExtensionInCapitalsIsTheSameKind)
{
    const auto dir = freshDir("render_capitals");
    ASSERT_EQ(runPba("render integrators --time 0.1 --size 64x48 --out " + (dir / "IMG.PNG").string()).exitCode, 0);
    int w = 0, h = 0, channels = 0;
    unsigned char* data = stbi_load((dir / "IMG.PNG").c_str(), &w, &h, &channels, 4);
    ASSERT_NE(data, nullptr);
    EXPECT_EQ(w, 64);
    stbi_image_free(data);
}

namespace {

/// `pba view ARGS` in a window on a virtual X server.
CommandResult runView(const std::string& args)
{
    return runShell("xvfb-run -a -s '-screen 0 1280x720x24' " + pbaBinary() + " view " + args);
}

std::vector<unsigned char> loadRgba(const std::filesystem::path& png, int& w, int& h)
{
    int channels = 0;
    unsigned char* data = stbi_load(png.c_str(), &w, &h, &channels, 4);
    if (!data)
        return {};
    std::vector<unsigned char> pixels(data, data + static_cast<std::size_t>(w) * h * 4);
    stbi_image_free(data);
    return pixels;
}

} // namespace

// The real window, on a virtual X server: the panel and the particles are in the screenshot,
// the particles left of the panel, which is docked at the right and covers none of the scene.
TEST(PbaView, WindowUnderXvfbShowsThePanelAndTheParticles)
{
    const auto dir = freshDir("view_xvfb");
    const auto png = dir / "view.png";
    const CommandResult r = runView("integrators --time 0.5 --screenshot " + png.string());
    ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
    EXPECT_NE(r.out.find("t = 0.5 s"), std::string::npos) << r.out;
    int w = 0, h = 0;
    const std::vector<unsigned char> data = loadRgba(png, w, h);
    ASSERT_FALSE(data.empty());
    int blue = 0, green = 0, panelBlue = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const unsigned char* p = data.data() + (static_cast<std::size_t>(y) * w + x) * 4;
            const bool scene = x < w - 440 && y < h - 150; // left of the panel, above the legend
            if (scene && p[2] > 150 && p[0] < 110 && p[2] > p[1] + 40)
                ++blue; // the forward Euler particle, in its own colour
            if (scene && p[1] > 130 && p[0] < 110 && p[2] < 130)
                ++green; // the semi-implicit Euler particle
            if (x > w - 440 && p[2] > p[0] + 40 && p[2] > 80)
                ++panelBlue; // ImGui's blue widgets in the panel on the right
        }
    }
    EXPECT_GT(blue, 30);
    EXPECT_GT(green, 30);
    EXPECT_GT(panelBlue, 2000);
}

// Synthetic frames to exactly the time asked for: the same picture on every run and machine,
// whatever the frame rate (`--frames N` reached a different simulated time on each).
TEST(PbaView, TimeAndScreenshotAreReproducible)
{
    const auto dir = freshDir("view_repro");
    ASSERT_EQ(runView("blow-dryer --time 1.5 --screenshot " + (dir / "a.png").string()).exitCode, 0);
    ASSERT_EQ(runView("blow-dryer --time 1.5 --screenshot " + (dir / "b.png").string()).exitCode, 0);
    int wa = 0, ha = 0, wb = 0, hb = 0;
    const std::vector<unsigned char> a = loadRgba(dir / "a.png", wa, ha), b = loadRgba(dir / "b.png", wb, hb);
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(wa, 1280);
    EXPECT_EQ(ha, 720);
    EXPECT_TRUE(a == b) << "two captures at 1.5 s differ";
}

// The time said is the state drawn: without interpolation, the last state the steps made (at
// dt 0.01, 2.01 s for 2.005), as the picture's legend says.
TEST(PbaView, AScreenshotSaysTheTimeOfTheStateItDraws)
{
    const auto dir = freshDir("view_state_time");
    const CommandResult last = runView("integrators --no-interpolation --time 2.005 --screenshot " + (dir / "a.png").string());
    ASSERT_EQ(last.exitCode, 0) << last.err;
    EXPECT_NE(last.out.find("(t = 2.01 s)"), std::string::npos) << last.out;
    const CommandResult blended = runView("integrators --time 2.005 --screenshot " + (dir / "b.png").string());
    EXPECT_NE(blended.out.find("(t = 2.005 s)"), std::string::npos) << blended.out;
}

TEST(PbaView, ScreenshotNeedsTimeAndBadTimesAreRefused)
{
    const auto dir = freshDir("view_usage");
    const std::string png = (dir / "x.png").string();
    EXPECT_EQ(runPba("view integrators --frames 10 --screenshot " + png).exitCode, 2);
    EXPECT_EQ(runPba("view integrators --time -1 --screenshot " + png).exitCode, 2);
    EXPECT_EQ(runPba("view integrators --time 1 --frames 10").exitCode, 2);
    EXPECT_EQ(runPba("view integrators --duration 1 --time 2 --screenshot " + png).exitCode, 2);
    EXPECT_EQ(runPba("view integrators --time 1 --screenshot " + (dir / "missing/deeper/x.png").string()).exitCode, 2);
    const CommandResult jpeg = runPba("view integrators --time 1 --screenshot " + (dir / "x.jpg").string());
    EXPECT_EQ(jpeg.exitCode, 2);
    EXPECT_NE(jpeg.err.find("--screenshot: expected FILE.png"), std::string::npos) << jpeg.err;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 0);
}

// Without ffmpeg on the PATH the error names the package to install, and nothing is left behind.
TEST(PbaRender, MissingFfmpegNamesThePackageAndWritesNothing)
{
    const auto dir = freshDir("render_noffmpeg");
    const auto mp4 = dir / "x.mp4";
    const CommandResult r =
        runShell("PATH=/nonexistent " + pbaBinary() + " render spring --duration 0.1 --out " + mp4.string());
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("install the Debian package ffmpeg"), std::string::npos) << r.err;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 0);
}

// Synthetic frames cover exactly the time asked for: no real-time clamp (0.25 s a frame)
// shortens a slow frame rate, and --time T shows the state at T, not a step before it.
TEST(PbaRender, FramesCoverExactlyTheTimeAskedFor)
{
    const auto dir = freshDir("render_time");
    const CommandResult slow = runPba("render integrators --fps 1 --time 10 --size 64x48 --out " + (dir / "a.png").string());
    ASSERT_EQ(slow.exitCode, 0) << slow.err;
    EXPECT_NE(slow.out.find("t = 10 s"), std::string::npos) << slow.out;
    const CommandResult at = runPba("render integrators --time 1.2 --size 64x48 --out " + (dir / "b.png").string());
    EXPECT_NE(at.out.find("t = 1.2 s"), std::string::npos) << at.out;
    // Between two frames of 1/60 s: still exactly the time asked for.
    const CommandResult between = runPba("render integrators --time 0.64 --size 64x48 --out " + (dir / "d.png").string());
    EXPECT_NE(between.out.find("t = 0.64 s"), std::string::npos) << between.out;
    const CommandResult video =
        runPba("render integrators --fps 2 --duration 20 --size 64x48 --out " + (dir / "c.mp4").string());
    ASSERT_EQ(video.exitCode, 0) << video.err;
    EXPECT_NE(video.out.find("41 frames, 64x48, t = 20 s"), std::string::npos) << video.out;
}

// A thumbnail's legend would hide most of it (hanging-crate's, 88% of 320x180): it is left out,
// the picture is the one --no-legend draws, and a note says so; a picture it fits keeps it.
TEST(PbaRender, AThumbnailLeavesTheLegendOutAndSaysSo)
{
    const auto dir = freshDir("render_thumbnail");
    const std::string common = "render hanging-crate --time 0.5 --size 320x180 --out ";
    const CommandResult small = runPba(common + (dir / "a.png").string());
    ASSERT_EQ(small.exitCode, 0) << small.err;
    EXPECT_NE(small.err.find("pba: note: the legend was left out: it would have covered"), std::string::npos)
        << small.err;
    ASSERT_EQ(runPba(common + (dir / "b.png").string() + " --no-legend").exitCode, 0);
    EXPECT_EQ(readFile(dir / "a.png"), readFile(dir / "b.png"));
    const CommandResult large = runPba("render hanging-crate --time 0.5 --size 640x360 --out " + (dir / "c.png").string());
    EXPECT_EQ(large.err.find("legend"), std::string::npos) << large.err;
}

// A scene's own camera is where its pictures look from by default: the same picture as
// --camera with its numbers, and another than the framing view's.
TEST(PbaRender, AScenesOwnCameraIsTheDefault)
{
    const auto dir = freshDir("render_scene_camera");
    const std::string common = "render newtons-cradle --time 0.5 --size 160x90 --no-legend --out ";
    ASSERT_EQ(runPba(common + (dir / "own.png").string()).exitCode, 0);
    ASSERT_EQ(runPba(common + (dir / "flag.png").string() + " --camera 0.1,1.3,2.4,0.1,1.05,0").exitCode, 0);
    ASSERT_EQ(runPba(common + (dir / "corner.png").string() + " --camera corner").exitCode, 0);
    EXPECT_EQ(readFile(dir / "own.png"), readFile(dir / "flag.png"));
    EXPECT_NE(readFile(dir / "own.png"), readFile(dir / "corner.png"));
}

// The camera's distance is kept in single precision: 0.1 m apart is its least, not below it.
TEST(PbaRender, ACameraAtItsLeastAndMostDistanceIsTaken)
{
    const auto dir = freshDir("render_camera_edges");
    for (const char* camera : {"0,0,0,0,0,0.1", "0,1,0,0,1,1000"}) {
        const CommandResult r = runPbaArgv({"render", "spring", "--camera", camera, "--size", "64x48", "--out",
                                            (dir / "c.png").string()});
        EXPECT_EQ(r.exitCode, 0) << camera << ": " << r.err;
    }
    const CommandResult far = runPbaArgv({"render", "spring", "--camera", "0,1,0,0,1,1000.4", "--size", "64x48",
                                          "--out", (dir / "c.png").string()});
    EXPECT_EQ(far.exitCode, 2);
    EXPECT_NE(far.err.find("got 1000.4 m"), std::string::npos) << far.err;
}

// H.264 needs even sizes: an odd --size is padded, and the summary says the video's real size.
TEST(PbaRender, AnOddSizedVideoSaysItWasPadded)
{
    const auto dir = freshDir("render_odd_video");
    const CommandResult r =
        runPba("render integrators --fps 10 --duration 0.2 --size 65x49 --out " + (dir / "x.mp4").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("3 frames, 66x50, padded from 65x49 as H.264 needs even sizes"), std::string::npos) << r.out;
    const CommandResult probe = runShell("ffprobe -v error -show_entries stream=width,height -of csv=p=0 " +
                                         (dir / "x.mp4").string());
    if (probe.exitCode == 0) {
        EXPECT_EQ(probe.out, "66,50\n");
    }
}

// `pba render` stops at a blow-up with exit 3 naming the body, and writes no picture: here the
// built-in rope at dt = 0.05, whose energy the room's walls keep finite as it explodes.
TEST(PbaRender, ABlowUpIsExitThreeNamingTheBodyAndWritesNothing)
{
    const auto dir = freshDir("render_blow_up");
    const auto png = dir / "rope.png";
    const CommandResult r = runPba("render rope --dt 0.05 --time 1 --size 64x48 --out " + png.string());
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_EQ(r.err.rfind("pba: error: builtin:rope: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("body 'rope["), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("no energy source"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(png));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 0) << "no temporary files left";
}

// --camera and --show: a named view or a position and a target, and the marks by name; a bad
// value is one line naming the flag, exit 2, before any picture (and no file).
TEST(PbaRender, CameraAndShowFlags)
{
    const auto dir = freshDir("render_camera");
    const CommandResult side =
        runPba("render pendulum --camera side --show joints,axes --time 0.3 --size 160x90 --out " + (dir / "a.png").string());
    ASSERT_EQ(side.exitCode, 0) << side.err;
    const CommandResult at = runPba("render dominoes --camera=-3,1.5,3,-1,0.3,0 --show contacts --time 0.5 --size 160x90 "
                                    "--out " + (dir / "b.png").string());
    ASSERT_EQ(at.exitCode, 0) << at.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "a.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "b.png"));
    const std::pair<const char*, const char*> bad[] = {
        {"--camera frnt", "--camera: expected a view (front, side, top, corner)"},
        {"--camera 1,2,3", "--camera: expected a view"},
        {"--camera 0,2,0,0,2,0", "--camera: the position and the target must be 0.1 to 1000 m apart"},
        {"--camera 0,9,0,0,1,0", "--camera: the position is straight above the target"},
        {"--show contact", "--show: unknown mark 'contact' (expected a comma-separated list of contacts, joints, axes)"},
    };
    for (const auto& [flags, message] : bad) {
        const CommandResult r = runPba(std::string("render dice --size 64x48 ") + flags + " --out " + (dir / "x.png").string());
        EXPECT_EQ(r.exitCode, 2) << flags;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
    const CommandResult view = runPba("view dice --camera top,1 --time 1 --screenshot " + (dir / "y.png").string());
    EXPECT_EQ(view.exitCode, 2) << "checked before the window opens: " << view.err;
    EXPECT_NE(view.err.find("--camera:"), std::string::npos) << view.err;
}
