#pragma once
// The viewer's keys as events. GLFW reports every press to its key callback, however slow the
// frame; sampling the key state once a frame loses a press and release that both fall between
// two frames (at 3 fps, most of them). The callback feeds a KeyInput; each frame takes the
// commands queued since the last one, in order, one per press.
#include <vector>

namespace pba::app {

enum class ViewerCommand {
    TogglePause,         ///< space
    Step,                ///< '.' or right arrow (held: repeats)
    Reset,               ///< r: restart with the panel's settings
    ReloadScene,         ///< shift+r: the scene as loaded, the panel's changes undone
    ToggleInterpolation, ///< i
    FrameCamera,         ///< c: back to the start's camera
    ToggleContacts,      ///< n: contact points and normals
    ToggleJoints,        ///< j: joint frames
    ToggleAxes,          ///< a: rigid bodies' axes with omega and L
    Quit,                ///< Esc
};

class KeyInput {
public:
    /// GLFW's key callback arguments (GLFW_KEY_*, GLFW_PRESS / GLFW_REPEAT / GLFW_RELEASE,
    /// GLFW_MOD_* bits). Releases and unbound keys queue nothing.
    void onKey(int key, int action, int mods);
    /// The commands queued since the last call, oldest first.
    std::vector<ViewerCommand> take();

private:
    std::vector<ViewerCommand> m_queued;
};

} // namespace pba::app
