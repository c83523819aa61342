// `pba field`: the force at a point (text and JSON) and the slice picture.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "support/run_command.hpp"

using namespace pba::test;

TEST(PbaField, PrintsEachFieldAndTheTotalAtAPoint)
{
    // On the axis 1 m above the nozzle: 58 N (1 - 1/3.5) up, smooth radial falloff is 1 on the axis.
    const CommandResult r = runPba("field blow-dryer --at 0,1,0 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    const double lift = 58.0 * (1.0 - 1.0 / 3.5);
    EXPECT_NEAR(json["total"][1].get<double>(), lift - 9.81, 1e-9);
    ASSERT_EQ(json["forces"].size(), 2u);
    EXPECT_EQ(json["forces"][0]["type"], "gravity");
    EXPECT_EQ(json["forces"][1]["type"], "blow-dryer");
    EXPECT_NEAR(json["forces"][1]["force"][1].get<double>(), lift, 1e-9);

    const CommandResult text = runPba("field blow-dryer --at 0,1,0");
    ASSERT_EQ(text.exitCode, 0);
    EXPECT_NE(text.out.find("blow-dryer"), std::string::npos);
    EXPECT_NE(text.out.find("total"), std::string::npos);
}

TEST(PbaField, OutsideTheConeOnlyGravityActs)
{
    const CommandResult r = runPba("field blow-dryer --at 1.9,1,1.9 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["forces"][1]["force"], nlohmann::json::array({0.0, 0.0, 0.0}));
}

TEST(PbaField, DrawsTheSliceAsAPng)
{
    const auto dir = freshDir("field_slice");
    const auto png = dir / "field.png";
    const CommandResult r = runPba("field blow-dryer-flow --slice --out " + png.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string bytes = readFile(png);
    ASSERT_GT(bytes.size(), 10000u);
    EXPECT_EQ(bytes.substr(1, 3), "PNG");
    // Beside it only pba's list of the files it wrote there (.pba-output): no temporary left.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 2);
    EXPECT_TRUE(std::filesystem::exists(dir / ".pba-output"));
}

// An option the chosen output would ignore, a picture under another format's name, or a point
// that is not one, is refused before any work: exit 2, one line, nothing written.
TEST(PbaField, RefusesOptionsTheOutputWouldIgnore)
{
    const auto dir = freshDir("field_refused");
    const std::pair<std::string, const char*> cases[] = {
        {"blow-dryer --slice --out " + (dir / "f.csv").string(), "--out: --slice writes a PNG, so the file must end in .png"},
        {"blow-dryer --at 0,1,0 --slice --out " + (dir / "f.png").string(), "--at: prints the force at a point, and --slice"},
        {"blow-dryer --slice --json --out " + (dir / "f.png").string(), "--json: prints --at's forces as JSON"},
        {"blow-dryer --at 0,1,0 --out " + (dir / "f.png").string(), "--out: names --slice's picture, and there is no --slice"},
        {"blow-dryer --at nan,1,0", "--at: cannot read 'nan' as a number"},
        {"blow-dryer --at 0,inf,0 --json", "--at: cannot read 'inf' as a number"},
        {"blow-dryer --at 0,1e400,0", "--at: every coordinate must be a finite number, got inf"},
        {"blow-dryer --at 0,1,0,", "--at: item 4 of '0,1,0,' is empty"},
        {"blow-dryer --at 0,1,0 --at 0,2,0", "--at: given 2 times; give it once"}};
    for (const auto& [args, message] : cases) {
        const CommandResult r = runPba("field " + args);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(r.err.rfind(std::string("pba: error: ") + message, 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.out, "") << args;
    }
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 0) << "nothing written";
}

TEST(PbaField, TheLegendIsDarkSoTheWhiteDirectionArrowShowsInIt)
{
    const auto dir = freshDir("field_legend");
    const auto png = dir / "field.png";
    ASSERT_EQ(runPba("field blow-dryer --slice --out " + png.string()).exitCode, 0);
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(png.c_str(), &w, &h, &n, 3);
    ASSERT_NE(data, nullptr);
    // The legend's box is the one area of the legend's background colour (#2b2b3a); inside it,
    // the white arrow sample and the white text.
    int x0 = w, y0 = h, x1 = -1, y1 = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const unsigned char* p = data + 3 * (y * w + x);
            if (p[0] == 0x2b && p[1] == 0x2b && p[2] == 0x3a) {
                x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            }
        }
    int white = 0;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const unsigned char* p = data + 3 * (y * w + x);
            white += p[0] > 240 && p[1] > 240 && p[2] > 240;
        }
    stbi_image_free(data);
    ASSERT_GT(x1 - x0, 100) << "no dark legend";
    ASSERT_GT(y1 - y0, 30) << "no dark legend";
    EXPECT_GT(white, 100) << "nothing white in the legend";
}

TEST(PbaField, BadUsageIsExitTwo)
{
    EXPECT_EQ(runPba("field blow-dryer").exitCode, 2);
    EXPECT_EQ(runPba("field blow-dryer --at 1,2").exitCode, 2);
    EXPECT_EQ(runPba("field blow-dryer --slice").exitCode, 2);
    EXPECT_EQ(runPba("field integrators --slice --out /tmp/x.png").exitCode, 2);
    EXPECT_EQ(runPba("field blow-dryer --slice --out /nonexistent/dir/x.png").exitCode, 2);
}
