#pragma once
// The interactive viewer: a window, the fixed-timestep clock fed by real frame time, the
// scene drawn at the interpolated state, and a Dear ImGui control panel.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "pba/clock.hpp"
#include "pba/scene/scene.hpp"
#include "render/camera.hpp"
#include "render/draw_list.hpp"
#include "render/world_view.hpp"

namespace pba::app {

/// Recent samples of one quantity per body, for ImGui's plots.
class History {
public:
    static constexpr std::size_t kLength = 600;
    void resize(std::size_t bodies) { m_values.assign(bodies, {}); }
    void push(std::size_t body, float value);
    void clear();
    const std::vector<float>& values(std::size_t body) const { return m_values[body]; }
    std::size_t bodies() const { return m_values.size(); }

private:
    std::vector<std::vector<float>> m_values;
};

/// Everything the panel can change and show. Kept apart from the window so that the
/// physics-facing logic (stepping, reset, errors) reads as one unit.
struct ViewerState {
    Scene scene;
    World initial;
    FixedTimestepClock clock{0.01};
    render::ViewSettings settings;
    render::Trails trails;
    render::OrbitCamera camera;
    History heights;
    History energies;
    bool paused = false;
    bool stepOnce = false;
    float timeScale = 1.0f;
    int stepsThisFrame = 0;
    float frameRate = 0.0f;
    std::optional<std::string> error; ///< a non-finite state: shown in the panel, the viewer pauses
    std::string scenePath;            ///< the panel's text box

    void load(Scene newScene);
    void reset();
    /// Feeds one frame of real time (scaled by timeScale) to the clock and steps the world.
    void advance(double frameSeconds);
    void stepWorld(int steps);
    void record();
};

/// Draws the control panel; may load another scene into `state`.
void drawPanel(ViewerState& state);

/// Runs the window until it is closed, or for `frames` frames if given, then saves the
/// last frame to `screenshot` if given. Returns an exit code.
int runViewer(Scene scene, std::optional<int> frames, std::optional<std::string> screenshot, bool lanes = false);

} // namespace pba::app
