// `--camera` and `--show`, parsed as `pba render` and `pba view` parse them: every bad value is
// one UsageError naming the flag, before any work.
#include <gtest/gtest.h>

#include "command.hpp"
#include "picture_options.hpp"
#include "pba/scene/scene.hpp"

using namespace pba;
using namespace pba::app;

TEST(CameraFlag, ANamedViewOrAPositionAndATarget)
{
    const World world = loadScene("dice").world;
    const CameraChoice front = parseCamera("front");
    ASSERT_TRUE(front.view);
    EXPECT_EQ(*front.view, render::NamedView::Front);
    EXPECT_EQ(cameraFor(front, world, std::nullopt).target, render::frameWorld(world).target);

    const CameraChoice at = parseCamera("0.5,2,6,-0.25,1e-1,0");
    EXPECT_FALSE(at.view);
    const render::OrbitCamera camera = cameraFor(at, world, std::nullopt);
    EXPECT_NEAR(glm::length(camera.eye() - glm::vec3(0.5f, 2.0f, 6.0f)), 0.0f, 1e-5f);
    EXPECT_EQ(camera.target, glm::vec3(-0.25f, 0.1f, 0.0f));
    EXPECT_EQ(cameraFor(std::nullopt, world, std::nullopt).distance, render::frameWorld(world).distance)
        << "the default: framing";
    EXPECT_TRUE(framingCamera(std::nullopt, std::nullopt));
    EXPECT_TRUE(framingCamera(front, std::nullopt));
    EXPECT_FALSE(framingCamera(at, std::nullopt));
}

// A scene's own camera is the default, placed as --camera would place it; --camera, a named view
// or a position, overrides it. Neither moves to clear the legend.
TEST(CameraFlag, AScenesOwnCameraIsTheDefault)
{
    const World world = loadScene("dice").world;
    const SceneCamera own{dvec3(0.5, 2.0, 6.0), dvec3(-0.25, 0.1, 0.0)};
    const render::OrbitCamera fromScene = cameraFor(std::nullopt, world, own);
    const render::OrbitCamera fromFlag = cameraFor(parseCamera("0.5,2,6,-0.25,0.1,0"), world, std::nullopt);
    EXPECT_EQ(fromScene.target, fromFlag.target);
    EXPECT_EQ(fromScene.eye(), fromFlag.eye());
    EXPECT_FALSE(framingCamera(std::nullopt, own));
    EXPECT_EQ(cameraFor(parseCamera("front"), world, own).target, render::frameWorld(world).target);
    EXPECT_TRUE(framingCamera(parseCamera("front"), own));
    EXPECT_EQ(cameraFor(parseCamera("1,2,3,0,1,0"), world, own).target, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(CameraFlag, BadValuesAreOneLineNamingTheFlag)
{
    for (const char* bad : {"frnt", "", "1,2,3", "1,2,3,4,5,6,7", "1,2,3,4,5,x", "1,2,3,4,5,nan", "1,2,3,4,5,inf",
                            "1,2,3,4,5, 6", "1,2,3,1,2,3", "0,9,0,0,1,0", "0,-5,0,0,1,0", "1e9,0,0,0,0,0"}) {
        try {
            parseCamera(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const UsageError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("--camera: ", 0), 0u) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
    try {
        parseCamera("0,9,0,0,1,0");
    } catch (const UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("straight above the target"), std::string::npos) << e.what();
    }
    try {
        parseCamera("frnt");
    } catch (const UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("front, side, top, corner"), std::string::npos) << e.what();
    }
}

TEST(ShowFlag, TurnsOnTheMarksNamedAndRefusesOthers)
{
    render::ViewSettings settings;
    applyShow("axes,contacts", settings);
    EXPECT_TRUE(settings.axes);
    EXPECT_TRUE(settings.contacts);
    EXPECT_FALSE(settings.joints);
    applyShow("joints", settings);
    EXPECT_TRUE(settings.joints);
    for (const char* bad : {"", "contact", "axes,", "joints,,axes", "all"})
        try {
            render::ViewSettings unchanged;
            applyShow(bad, unchanged);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const UsageError& e) {
            EXPECT_EQ(std::string(e.what()).rfind("--show: ", 0), 0u) << e.what();
        }
}
