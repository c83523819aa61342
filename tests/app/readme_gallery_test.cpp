// The README's gallery: every built-in scene appears in it with a small picture, and every
// picture it shows is a file in the repository of the gallery's size (a PNG 640 wide), so a scene
// added without a picture, or a picture renamed, is caught here rather than by a reader.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <filesystem>
#include <regex>
#include <string>

#include "pba/scene/scene.hpp"
#include "support/run_command.hpp"

using namespace pba::test;

namespace {

const std::filesystem::path kSource = sourceDir();

/// The README's section "The built-in scenes", up to the next section.
std::string gallerySection()
{
    const std::string readme = readFile(kSource / "README.md");
    const std::size_t start = readme.find("\n## The built-in scenes\n");
    const std::size_t end = readme.find("\n## ", start + 1);
    EXPECT_NE(start, std::string::npos);
    return readme.substr(start, end - start);
}

/// A PNG's width and height, from its IHDR chunk (bytes 16 to 23, big-endian); zeros if not a PNG.
std::pair<std::uint32_t, std::uint32_t> pngSize(const std::string& bytes)
{
    if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0 || bytes.compare(12, 4, "IHDR") != 0)
        return {0, 0};
    const auto be32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (std::size_t i = 0; i < 4; ++i)
            v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
        return v;
    };
    return {be32(16), be32(20)};
}

} // namespace

TEST(ReadmeGallery, EveryBuiltInSceneHasACellWithAPicture)
{
    const std::string gallery = gallerySection();
    for (const auto& name : pba::builtinSceneNames()) {
        // A cell is "![alt](docs/images/X.png) `name`...", or a swarm named beside another's picture.
        const std::regex cell(R"(!\[[^\]]*\]\(docs/images/[^)]+\.png\) [^|]*`)" + name + "`");
        EXPECT_TRUE(std::regex_search(gallery, cell)) << name << " has no picture in the README's gallery";
    }
}

TEST(ReadmeGallery, EveryPictureExistsAtTheGallerysSizeAndStaysSmall)
{
    const std::string gallery = gallerySection();
    const std::regex picture(R"(\]\((docs/images/[^)]+\.png)\))");
    int count = 0;
    for (std::sregex_iterator it(gallery.begin(), gallery.end(), picture), end; it != end; ++it, ++count) {
        const std::filesystem::path file = kSource / (*it)[1].str();
        ASSERT_TRUE(std::filesystem::is_regular_file(file)) << file;
        // 640 x 360; blow-dryer-flow's is taller, to keep its five balls in view under the legend.
        const auto [width, height] = pngSize(readFile(file));
        EXPECT_EQ(width, 640u) << file;
        EXPECT_TRUE(height == 360u || height == 480u) << file << ": " << height;
        // The swarm's hundred thousand specks are the largest picture; a few tens of KB is the rest.
        EXPECT_LT(std::filesystem::file_size(file), 128u * 1024u) << file;
    }
    EXPECT_GE(count, static_cast<int>(pba::builtinSceneNames().size()) - 1) << "one picture for the two swarms";
}

// "The lines are the scenes' own summaries": each cell's words after its name are the scene's
// summary without its "Task 3: ", "Rigid bodies: " or "The bonus: " and with a lower-case start,
// then at most a `--show` hint. They had drifted apart in five scenes.
TEST(ReadmeGallery, EachCellSaysItsScenesSummary)
{
    const std::string gallery = gallerySection();
    for (const auto& name : pba::builtinSceneNames()) {
        const std::regex cell("`" + name + R"(`: ([^|]*?)( \(`--show [a-z,]+`\))? \|)");
        std::smatch m;
        if (!std::regex_search(gallery, m, cell))
            continue; // a swarm named beside another's picture (EveryBuiltInSceneHasACellWithAPicture)
        std::string summary = pba::builtinSceneSummary(name);
        summary = std::regex_replace(summary, std::regex("^(Task [0-9]+|Rigid bodies|The bonus): "), "");
        if (summary.rfind("Newton", 0) != 0)
            summary[0] = char(std::tolower(static_cast<unsigned char>(summary[0])));
        EXPECT_EQ(m[1].str(), summary) << name;
    }
}
