#include "viewer_state.hpp"

#include <algorithm>

#include "frame_steps.hpp"
#include "lanes.hpp"

namespace pba::app {

void Series::push(float value)
{
    if (m_values.size() == kLength)
        m_values.erase(m_values.begin());
    m_values.push_back(value);
}

std::vector<PlotKind> plotKinds(const World& world, const render::BodyGroup& group)
{
    if (render::groupFixed(world, group))
        return {};
    if (group.fabric())
        return {PlotKind::EnergyRatio};
    std::vector<PlotKind> kinds;
    if (glm::length(world.gravity()) > 0.0)
        kinds.push_back(PlotKind::Height);
    if (world.isRigid(group.members.front()))
        kinds.push_back(PlotKind::BodySpin);
    kinds.push_back(PlotKind::EnergyRatio);
    return kinds;
}

void ViewerState::load(Scene newScene)
{
    loaded = newScene;
    scene = std::move(newScene);
    scene.world.setSwarmRollback(true); // a failed step pauses on the last finite state, swarms too
    scenePath = scene.source;
    camera = cameraFor(cameraChoice, scene.world, scene.camera);
    clearLegend = framingCamera(cameraChoice, scene.camera);
    settings.fabric = scene.fabric;
    settings.dice = scene.dice;
    groups = render::BodyGroups(scene.world, scene.fabric);
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
    const std::vector<double> start = initial.energies();
    plots.assign(std::min(groups.size(), kPlottedGroups), GroupPlots{});
    for (std::size_t g = 0; g < plots.size(); ++g)
        plots[g].startEnergy = render::groupEnergy(groups[g], start);
    nextPlotSample = 0.0;
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

void ViewerState::setGroupIntegrator(std::size_t g, Integrator integrator)
{
    // Each member directly: asking each of a cloth's particles for its coupled group would walk
    // the springs once per particle. The first moving member's coupled group follows, in case a
    // spring joins the system to a body outside it.
    std::optional<std::size_t> moving;
    for (const std::size_t i : groups[g].members)
        if (!scene.world.body(i).isFixed()) {
            scene.world.body(i).setIntegrator(integrator);
            initial.body(i).setIntegrator(integrator);
            moving = moving.value_or(i);
        }
    if (moving)
        setIntegrator(*moving, integrator);
}

void ViewerState::setGroupRestitution(std::size_t g, double cor)
{
    for (const std::size_t i : groups[g].members)
        setRestitution(i, cor);
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
    if (!paused && frameSeconds > 0.0 && clockKind != ClockKind::Fixed) {
        const double before = scene.world.time();
        stepWorld(frameSteps(clockKind, clock.dt(), frameSeconds * timeScale, clock.maxFrameTime()));
        shownAlpha = 1.0; // neither clock keeps a remainder: the state drawn is the last one made
        // The frame that reaches pauseAt pauses, wherever its last step ends: these clocks' steps vary.
        if (pauseAt && before < *pauseAt && scene.world.time() >= *pauseAt - 1e-9 * clock.dt())
            paused = true;
    } else if (!paused && frameSeconds > 0.0) {
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
    // The fixed dt: the frame time only decided how many steps.
    takeSteps(steps, [&](std::uint64_t) { return clock.dt(); });
}

void ViewerState::stepWorld(const std::vector<double>& lengths)
{
    takeSteps(lengths.size(), [&](std::uint64_t n) { return lengths[n]; });
}

void ViewerState::takeSteps(std::uint64_t count, const std::function<double(std::uint64_t)>& length)
{
    try {
        for (std::uint64_t n = 0; n < count; ++n) {
            scene.world.step(length(n));
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
    // Samples on a grid of kPlotInterval: the first step at or past each point of it (a step's
    // time is a sum of dt, so half a step's slack keeps a sample from slipping a step late).
    if (plots.empty() || world.time() < nextPlotSample - 0.5 * clock.dt())
        return;
    while (nextPlotSample <= world.time() + 0.5 * clock.dt())
        nextPlotSample += kPlotInterval;
    const std::vector<double> now = world.energies();
    for (std::size_t g = 0; g < plots.size(); ++g) {
        GroupPlots& p = plots[g];
        const double energy = render::groupEnergy(groups[g], now);
        p.energyRatio.push(float(p.startEnergy != 0.0 ? energy / p.startEnergy : 1.0));
        if (groups[g].fabric())
            continue;
        const std::size_t i = groups[g].members.front();
        p.height.push(float(world.body(i).getPos().y));
        if (world.isRigid(i)) {
            const auto& body = static_cast<const RigidBody&>(world.body(i));
            const dvec3 w = glm::conjugate(body.getOrientation()) * body.getAngularVelocity(); // in its own frame
            for (int k = 0; k < 3; ++k)
                p.spin[k].push(float(w[k]));
        }
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
    case ViewerCommand::FrameCamera:
        camera = cameraFor(cameraChoice, initial, loaded.camera);
        clearLegend = framingCamera(cameraChoice, loaded.camera);
        break;
    case ViewerCommand::ToggleContacts: settings.contacts = !settings.contacts; break;
    case ViewerCommand::ToggleJoints: settings.joints = !settings.joints; break;
    case ViewerCommand::ToggleAxes: settings.axes = !settings.axes; break;
    case ViewerCommand::Quit: quit = true; break;
    }
}

} // namespace pba::app
