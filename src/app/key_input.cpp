#include "key_input.hpp"

#include <optional>

#include <GLFW/glfw3.h> // the key and action codes only: nothing here calls GLFW

namespace pba::app {

namespace {

std::optional<ViewerCommand> commandFor(int key, int mods)
{
    switch (key) {
    case GLFW_KEY_SPACE: return ViewerCommand::TogglePause;
    case GLFW_KEY_PERIOD:
    case GLFW_KEY_RIGHT: return ViewerCommand::Step;
    case GLFW_KEY_R: return (mods & GLFW_MOD_SHIFT) ? ViewerCommand::ReloadScene : ViewerCommand::Reset;
    case GLFW_KEY_I: return ViewerCommand::ToggleInterpolation;
    case GLFW_KEY_C: return ViewerCommand::FrameCamera;
    case GLFW_KEY_N: return ViewerCommand::ToggleContacts;
    case GLFW_KEY_J: return ViewerCommand::ToggleJoints;
    case GLFW_KEY_A: return ViewerCommand::ToggleAxes;
    case GLFW_KEY_ESCAPE: return ViewerCommand::Quit;
    default: return std::nullopt;
    }
}

} // namespace

void KeyInput::onKey(int key, int action, int mods)
{
    const auto command = commandFor(key, mods);
    if (!command)
        return;
    // A held step key steps on at the keyboard's repeat rate; a held space or r does not flicker.
    if (action == GLFW_PRESS || (action == GLFW_REPEAT && *command == ViewerCommand::Step))
        m_queued.push_back(*command);
}

std::vector<ViewerCommand> KeyInput::take()
{
    std::vector<ViewerCommand> commands;
    commands.swap(m_queued);
    return commands;
}

} // namespace pba::app
