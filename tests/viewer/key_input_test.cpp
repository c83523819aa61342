// The viewer's keys as events: what GLFW's key callback reports becomes one command a press,
// however many presses fall between two frames.
#include <gtest/gtest.h>

#include <GLFW/glfw3.h> // key and action codes only

#include "key_input.hpp"

using namespace pba::app;

namespace {

void press(KeyInput& keys, int key, int mods = 0)
{
    keys.onKey(key, GLFW_PRESS, mods);
    keys.onKey(key, GLFW_RELEASE, mods);
}

} // namespace

// A frame sampling key state would see neither the press nor the release of a 100 ms tap at
// 3 fps; the callback saw both.
TEST(KeyInput, APressAndReleaseWithinOneFrameCountsOnce)
{
    KeyInput keys;
    press(keys, GLFW_KEY_SPACE);
    EXPECT_EQ(keys.take(), std::vector<ViewerCommand>{ViewerCommand::TogglePause});
    EXPECT_TRUE(keys.take().empty()) << "taken once";
}

TEST(KeyInput, RepeatedPressesEachCountInOrder)
{
    KeyInput keys;
    press(keys, GLFW_KEY_PERIOD);
    press(keys, GLFW_KEY_PERIOD);
    press(keys, GLFW_KEY_RIGHT);
    press(keys, GLFW_KEY_ESCAPE);
    const std::vector<ViewerCommand> expected{ViewerCommand::Step, ViewerCommand::Step, ViewerCommand::Step,
                                              ViewerCommand::Quit};
    EXPECT_EQ(keys.take(), expected);
}

TEST(KeyInput, HeldStepRepeatsButOtherKeysDoNot)
{
    KeyInput keys;
    keys.onKey(GLFW_KEY_PERIOD, GLFW_PRESS, 0);
    keys.onKey(GLFW_KEY_PERIOD, GLFW_REPEAT, 0);
    keys.onKey(GLFW_KEY_PERIOD, GLFW_REPEAT, 0);
    keys.onKey(GLFW_KEY_SPACE, GLFW_PRESS, 0);
    keys.onKey(GLFW_KEY_SPACE, GLFW_REPEAT, 0); // a held space does not flicker pause and play
    EXPECT_EQ(keys.take().size(), 4u);
}

TEST(KeyInput, ShiftRReloadsTheSceneAndOtherKeysAreIgnored)
{
    KeyInput keys;
    press(keys, GLFW_KEY_R);
    press(keys, GLFW_KEY_R, GLFW_MOD_SHIFT);
    press(keys, GLFW_KEY_Q);
    press(keys, GLFW_KEY_I);
    press(keys, GLFW_KEY_C);
    const std::vector<ViewerCommand> expected{ViewerCommand::Reset, ViewerCommand::ReloadScene,
                                              ViewerCommand::ToggleInterpolation, ViewerCommand::FrameCamera};
    EXPECT_EQ(keys.take(), expected);
}
