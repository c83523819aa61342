// Drops a ball with velocity Verlet and the exact response: after 0.5 s it must be where
// the analytic bounce puts it, or the installed library is not the one we built.
#include <cmath>
#include <cstdio>

#include <pba/pba.hpp>

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
    return std::abs(world.body(0).getPos().y - expected) < 1e-9 ? 0 : 1;
}
