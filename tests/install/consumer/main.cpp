// Drops a ball with velocity Verlet and the exact response: after 0.5 s it must be where
// the analytic bounce puts it, or the installed library is not the one we built. Then the
// installed scene loader builds a built-in scene and one from JSON text, and a run of the
// first is watched for blow-ups (it has none): pba/scene/scene.hpp is installed with its library.
// Last, the README's example (readmeExample, its lines as printed) runs.
#include <cmath>
#include <cstdio>

#include <pba/pba.hpp>
#include <pba/scene/scene.hpp>

int readmeExample();

namespace {

int sceneLoaderWorks()
{
    pba::Scene spring = pba::loadScene("spring");
    pba::BlowUpWatch watch(spring.world);
    for (int i = 0; i < 100; ++i) {
        spring.world.step(spring.dt);
        watch.check(spring.world);
    }
    const pba::Scene parsed = pba::parseScene(R"({"ground": {"height": 0},
        "particles": [{"name": "ball", "position": [0, 2, 0]}]})", "consumer.json");
    std::printf("spring: %zu body, t = %g; parsed: '%s'\n", spring.world.bodyCount(), spring.world.time(),
                parsed.world.body(0).getName().c_str());
    return spring.world.bodyCount() == 1 && parsed.world.body(0).getName() == "ball" ? 0 : 1;
}

} // namespace

int main()
{
    pba::World world;
    world.addForce(std::make_unique<pba::Gravity>(pba::dvec3(0, -9.81, 0)));
    world.setGround(0.0);
    pba::Particle ball;
    ball.setPos({0, 2, 0});
    ball.setIntegrator(pba::Integrator::VelocityVerlet);
    world.addParticle(ball);
    for (int i = 0; i < 50; ++i)
        world.step(0.01);
    const double expected = 2.0 - 0.5 * 9.81 * 0.25;
    std::printf("y = %.12f (expected %.12f)\n", world.body(0).getPos().y, expected);
    if (std::abs(world.body(0).getPos().y - expected) >= 1e-9)
        return 1;
    if (const int failed = sceneLoaderWorks())
        return failed;
    return readmeExample();
}
