#pragma once
// What the viewer runs and shows, apart from the window: the scene, the start of the run, the
// fixed-timestep clock, the panel's settings and the plots' history. Everything here works
// without a display, so the viewer's logic (reset, reload, keys, capture at a time) is tested
// without one.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "key_input.hpp"
#include "picture_options.hpp"
#include "pba/blow_dryer.hpp"
#include "pba/blow_up_watch.hpp"
#include "pba/clock.hpp"
#include "pba/frame_clock.hpp"
#include "pba/scene/scene.hpp"
#include "render/body_groups.hpp"
#include "render/camera.hpp"
#include "render/world_view.hpp"

namespace pba::app {

/// Recent samples of one quantity, for ImGui's plots.
class Series {
public:
    static constexpr std::size_t kLength = 600;
    void push(float value);
    void clear() { m_values.clear(); }
    const std::vector<float>& values() const { return m_values; }

private:
    std::vector<float> m_values;
};

/// What the panel plots of a group: a body's height (where there is gravity), its energy over
/// its start (a rope's or cloth's total over its start), and a rigid body's angular velocity in
/// its own frame, whose components show a tumble or the tennis racket's flip where height and
/// energy stay flat.
enum class PlotKind { Height, EnergyRatio, BodySpin };
std::vector<PlotKind> plotKinds(const World& world, const render::BodyGroup& group);

/// The plotted history of one group.
struct GroupPlots {
    Series height;
    Series energyRatio;
    std::array<Series, 3> spin; ///< omega's x, y and z in the body's frame, rad/s
    double startEnergy = 0.0;
};

/// The first groups of a scene are plotted (the panel has room for a few plots, and recording
/// every box of a pyramid would cost more than its step).
inline constexpr std::size_t kPlottedGroups = 4;
/// The plots sample the run every 1/60 s of simulated time, whatever dt: their 600 samples
/// span 10 s, long enough to show the tennis racket's flips (2.9 s apart) at dt = 0.002 s.
inline constexpr double kPlotInterval = 1.0 / 60.0;

struct ViewerState {
    Scene scene;
    Scene loaded;  ///< the scene as loaded (file and command-line options): what reload restores
    World initial; ///< where reset restarts: the loaded world with the panel's settings applied
    FixedTimestepClock clock{0.01};
    /// `--clock`: fixed steps the world by `clock`; semi-fixed and variable by frameSteps, with
    /// clock.dt() as their dt and nothing left over to interpolate.
    ClockKind clockKind = ClockKind::Fixed;
    render::ViewSettings settings;
    render::Trails trails;
    render::OrbitCamera camera;
    /// `--camera`: where the camera starts, and where `c` puts it back (for every scene loaded).
    std::optional<CameraChoice> cameraChoice;
    /// Set when the camera is framed (not placed by `--camera X,Y,Z,...`): once the legend's size
    /// is known, the camera moves so that the room keeps out of its corner.
    bool clearLegend = false;
    float panelWidth = 430.0f;   ///< the panel's width on the last frame
    glm::vec2 lastLegend{0.0f}; ///< the legend's size on the last frame
    /// Each rope, cloth and other body of the scene: the panel's rows, the colours, the plots.
    render::BodyGroups groups;
    std::vector<GroupPlots> plots; ///< of the first kPlottedGroups groups
    double nextPlotSample = 0.0;   ///< the simulated time of the plots' next sample
    bool paused = false;
    int pendingSteps = 0; ///< single steps asked for and not yet taken: each press is one
    bool quit = false;
    float timeScale = 1.0f;
    int stepsThisFrame = 0;
    float frameRate = 0.0f;
    /// `pba view --duration`: the simulated time at which the run pauses (play goes on past it).
    std::optional<double> pauseAt;
    /// The drawn state's alpha when the clock's does not apply: after a synthetic frame, or at
    /// the pause at pauseAt, the state shown is exactly at that time.
    std::optional<double> shownAlpha;
    std::optional<std::string> error; ///< a blow-up (BlowUpError): shown in the panel, the viewer pauses
    BlowUpWatch watch;                ///< the run's, from its start (made anew by reset)
    std::string scenePath;            ///< the panel's text box

    void load(Scene newScene);
    /// Restarts the run from `initial`: the scene's start with the panel's settings (integrators,
    /// restitutions, collision response, blow dryers, dt) kept.
    void reset();
    /// The scene as loaded, the panel's changes undone.
    void reload();

    // Panel edits: applied to the live world and to `initial`, so a reset keeps them.
    void setIntegrator(std::size_t body, Integrator integrator);
    void setRestitution(std::size_t body, double cor);
    /// Every moving body of group g (a rope's or cloth's particles, one menu for the system).
    void setGroupIntegrator(std::size_t g, Integrator integrator);
    void setGroupRestitution(std::size_t g, double cor);
    /// A rigid body's Coulomb friction (nothing for a particle).
    void setFriction(std::size_t body, double friction);
    void setCollisionResponse(CollisionResponse response);
    void setDt(double dt);
    /// The blow dryer that is force `force` (its floor hole follows the nozzle).
    void setDryerField(std::size_t force, const BlowDryerField& field);

    /// Feeds one frame of real time (scaled by timeScale) to the clock and steps the world.
    void advance(double frameSeconds);
    /// A synthetic frame: steps to exactly simulated time t (from the start of the run) and
    /// shows the state at t, whatever the clock.
    void advanceTo(double t);
    void stepWorld(std::uint64_t steps);
    /// Steps of these lengths, as the semi-fixed or variable clock takes a frame.
    void stepWorld(const std::vector<double>& lengths);
    /// `count` steps, the n-th of length(n), each checked and recorded; a blow-up pauses with
    /// its message.
    void takeSteps(std::uint64_t count, const std::function<double(std::uint64_t)>& length);
    void record();
    void apply(ViewerCommand command);
    /// The alpha the world is drawn with.
    double alpha() const { return shownAlpha.value_or(clock.alpha()); }
};

} // namespace pba::app
