// libFuzzer target: any bytes given to the scene loader either load or raise SceneError, and
// a loaded scene survives a few steps. Anything else (a crash, a sanitizer report, another
// exception, a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "pba/particle.hpp"
#include "pba/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        pba::Scene scene = pba::parseScene(text, "fuzz.json");
        std::size_t swarmParticles = 0, grains = 0;
        for (std::size_t i = 0; i < scene.world.swarmCount(); ++i) {
            swarmParticles += scene.world.swarm(i).size();
            grains += scene.world.swarm(i).desc().collide ? scene.world.swarm(i).size() : 0;
        }
        // A valid but huge scene: stepping it proves nothing and takes long. Colliding grains
        // count sooner: their pairs grow with how tightly the region packs them (80,800 grains of
        // 1 cm in a 12 cm column, each overlapping hundreds, took over 10 s a step here; 2 s
        // without the fuzzer's tracing, which the replay of fuzz/regressions/ steps).
        if (swarmParticles > 100000 || grains > 10000)
            return 0;
        // Likewise a large cloth of balls: its lists of neighbours along the springs grow as
        // (radius / spacing)^2 (docs/scenes.md), seconds for a few thousand under the fuzzer.
        // And a large implicit system: its Newton and conjugate-gradient loops run thousands of
        // sweeps over the springs in a step of large dt, which the fuzzer's comparison tracing
        // makes 150 times slower (a 20 x 20 cloth at dt 0.2: 0.1 s a step, 13 s under the fuzzer).
        std::size_t balls = 0, implicit = 0;
        for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
            if (const auto* p = dynamic_cast<const pba::Particle*>(&scene.world.body(i))) {
                balls += p->getRadius() > 0.0 ? 1 : 0;
                implicit += p->getIntegrator() == pba::Integrator::ImplicitEuler ? 1 : 0;
            }
        if (balls > 2000 || implicit > 100)
            return 0;
        for (int n = 0; n < 3; ++n)
            scene.world.step(scene.dt);
    } catch (const pba::SceneError&) {
    } catch (const pba::BlowUpError&) { // a state not finite, or a rigid body left inside a wall
    }
    return 0;
}
