#include "viewer_state.hpp"

#include "frame_steps.hpp"
#include "lanes.hpp"

namespace pba::app {

void History::push(std::size_t body, float value)
{
    auto& v = m_values[body];
    if (v.size() == kLength)
        v.erase(v.begin());
    v.push_back(value);
}

void History::clear()
{
    for (auto& v : m_values)
        v.clear();
}

void ViewerState::load(Scene newScene)
{
    loaded = newScene;
    scene = std::move(newScene);
    scene.world.setSwarmRollback(true); // a failed step pauses on the last finite state, swarms too
    scenePath = scene.source;
    camera = render::frameWorld(scene.world);
    settings.fabric = scene.fabric;
    initial = scene.world;
    if (settings.ghost)
        settings.ghost = exactGhosts(initial);
    clock = FixedTimestepClock(scene.dt, clock.maxFrameTime(), clock.maxStepsPerFrame());
    reset();
}

void ViewerState::reset()
{
    scene.world = initial;
    watch = BlowUpWatch(scene.world);
    clock.reset();
    trails.clear();
    heights.resize(scene.world.bodyCount());
    energies.resize(scene.world.bodyCount());
    error.reset();
    shownAlpha.reset();
    pendingSteps = 0;
    record();
}

void ViewerState::reload()
{
    const render::OrbitCamera kept = camera; // where the student looks from is not the scene's
    load(Scene(loaded));
    camera = kept;
}

void ViewerState::setIntegrator(std::size_t body, Integrator integrator)
{
    // Bodies joined by springs share one integrator: the whole group changes with this one.
    for (const std::size_t i : scene.world.coupledGroup(body)) {
        scene.world.body(i).setIntegrator(integrator);
        initial.body(i).setIntegrator(integrator);
    }
}

void ViewerState::setRestitution(std::size_t body, double cor)
{
    scene.world.body(body).setCor(cor);
    initial.body(body).setCor(cor);
}

void ViewerState::setFriction(std::size_t body, double friction)
{
    if (!scene.world.isRigid(body))
        return; // a particle has no friction
    static_cast<RigidBody&>(scene.world.body(body)).setFriction(friction);
    static_cast<RigidBody&>(initial.body(body)).setFriction(friction);
}

void ViewerState::setCollisionResponse(CollisionResponse response)
{
    scene.world.setCollisionResponse(response);
    initial.setCollisionResponse(response);
}

void ViewerState::setDt(double dt)
{
    clock.setDt(dt);
    scene.dt = dt;
}

namespace {

/// The hole in the floor follows the nozzle (it is the nozzle's opening).
void setDryer(World& world, std::size_t force, const BlowDryerField& field)
{
    struct Setter final : ForceEditor {
        const BlowDryerField& field;
        bool set = false;
        explicit Setter(const BlowDryerField& f) : field(f) {}
        void visit(BlowDryer& dryer) override
        {
            dryer.setField(field);
            set = true;
        }
    } setter(field);
    world.force(force).accept(setter);
    if (!setter.set)
        return;
    const auto& hole = world.floorHole();
    if (hole && field.nozzleRadius > 0.0)
        world.setFloorHole(FloorHole{field.nozzle, field.nozzleRadius, hole->depth});
}

} // namespace

void ViewerState::setDryerField(std::size_t force, const BlowDryerField& field)
{
    setDryer(scene.world, force, field);
    setDryer(initial, force, field);
}

void ViewerState::advance(double frameSeconds)
{
    stepsThisFrame = 0;
    if (error)
        return;
    if (!paused && frameSeconds > 0.0) {
        shownAlpha.reset();
        std::uint64_t steps = static_cast<std::uint64_t>(clock.advance(frameSeconds * timeScale));
        // At pauseAt the run stops on the step that reaches it, and shows the state at exactly it.
        const std::uint64_t toPause = pauseAt ? stepsToReach(scene.world, *pauseAt, clock.dt()) : 0;
        const bool pausing = toPause > 0 && steps >= toPause;
        stepWorld(pausing ? toPause : steps);
        if (pausing && !error) {
            paused = true;
            shownAlpha = alphaAt(scene.world, *pauseAt);
        }
    }
    if (pendingSteps > 0) {
        stepWorld(static_cast<std::uint64_t>(pendingSteps));
        pendingSteps = 0;
        shownAlpha = 1.0; // a single step shows the state it made, the one the panel's t names
    }
}

void ViewerState::advanceTo(double t)
{
    stepsThisFrame = 0;
    if (error)
        return;
    stepWorld(stepsToReach(scene.world, t, clock.dt()));
    if (!error)
        shownAlpha = alphaAt(scene.world, t);
}

void ViewerState::stepWorld(std::uint64_t steps)
{
    try {
        for (std::uint64_t n = 0; n < steps; ++n) {
            scene.world.step(clock.dt()); // the fixed dt: the frame time only decided how many steps
            ++stepsThisFrame;
            watch.check(scene.world);
            record();
        }
    } catch (const BlowUpError& e) {
        error = e.what();
        paused = true;
    }
}

void ViewerState::record()
{
    const World& world = scene.world;
    const std::vector<double> now = world.energies(), start = initial.energies();
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        heights.push(i, float(world.body(i).getPos().y));
        energies.push(i, float(start[i] != 0.0 ? now[i] / start[i] : 1.0));
    }
}

void ViewerState::apply(ViewerCommand command)
{
    switch (command) {
    case ViewerCommand::TogglePause: paused = !paused; break;
    case ViewerCommand::Step:
        paused = true;
        ++pendingSteps;
        break;
    case ViewerCommand::Reset: reset(); break;
    case ViewerCommand::ReloadScene: reload(); break;
    case ViewerCommand::ToggleInterpolation: settings.interpolate = !settings.interpolate; break;
    case ViewerCommand::FrameCamera: camera = render::frameWorld(initial); break;
    case ViewerCommand::Quit: quit = true; break;
    }
}

} // namespace pba::app
