// The Bullet peer of pba's pile of dice (bench/peers/pile.py): the same throw, read from the CSV
// that `pba bench --pile-worker` saves, in the same room, stepped by Bullet's btDiscreteDynamicsWorld
// with its default solver and sleeping, and timed a window of steps at a time on request.
//
//   bullet_pile --state START.csv --dt 0.005 --gravity 0,-9.81,0 --room -2,0,-2,2,4,2
//               --size 0.1,0.1,0.1 --mass 0.6 --inertia 0.001,0.001,0.001 --friction 0.5
//               --restitution 0.4 [--iterations 10]
//
// pile.py passes pba's own numbers (its worker's ready line). After setting up it prints one JSON
// line, {"ready": ...} with the dice count and start_bits_sum (the checksum of the start state as
// pba's pileStateBits defines it), then answers each line of standard input with one JSON line:
//   window STEPS   step on STEPS steps of dt from where the last window ended;
//                  {"seconds", "steps", "t", "steps_per_s", "sleeping"}
//   save PATH      the current state as CSV, name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz; {"saved", "t"}
// Bad arguments or input: one line on stderr, exit 2.
//
// Built against Debian's libbullet-dev (single precision) by bench/peers/CMakeLists.txt, or by hand:
//   g++ -O2 bench/peers/bullet_pile.cpp -I/usr/include/bullet -lBulletDynamics -lBulletCollision -lLinearMath
#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <LinearMath/btThreads.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

constexpr int kBadInput = 2;

[[noreturn]] void fail(const std::string& message)
{
    std::fprintf(stderr, "bullet_pile: %s\n", message.c_str());
    std::exit(kBadInput);
}

/// A number that must be finite, all of `text`.
double number(const std::string& text, const std::string& where)
{
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value))
        fail(where + ": not a finite number: '" + text + "'");
    return value;
}

std::vector<std::string> split(const std::string& text, char separator)
{
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, separator))
        parts.push_back(part);
    if (!text.empty() && text.back() == separator)
        parts.emplace_back();
    return parts;
}

std::vector<double> numbers(const std::string& text, std::size_t count, const std::string& where)
{
    const std::vector<std::string> parts = split(text, ',');
    if (parts.size() != count)
        fail(where + ": " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
    std::vector<double> values;
    for (const std::string& part : parts)
        values.push_back(number(part, where));
    return values;
}

/// The pile: what pba's ready line gives, and the state file.
struct Options {
    std::string state;
    double dt = 0.0, mass = 0.0, friction = 0.0, restitution = 0.0;
    btVector3 gravity, roomMin, roomMax, size, inertia;
    int iterations = 10;
};

btVector3 vector3(const std::string& text, const std::string& where)
{
    const std::vector<double> v = numbers(text, 3, where);
    return btVector3(btScalar(v[0]), btScalar(v[1]), btScalar(v[2]));
}

Options parse(int argc, char** argv)
{
    std::map<std::string, std::string> given;
    for (int i = 1; i < argc; i += 2) {
        const std::string name = argv[i];
        if (name.rfind("--", 0) != 0 || i + 1 >= argc)
            fail("usage: --state FILE --dt S --gravity X,Y,Z --room X0,Y0,Z0,X1,Y1,Z1 --size X,Y,Z --mass KG "
                 "--inertia IXX,IYY,IZZ --friction MU --restitution E [--iterations N]");
        given[name] = argv[i + 1];
    }
    const auto take = [&given](const std::string& name) {
        const auto found = given.find(name);
        if (found == given.end())
            fail(name + ": missing");
        std::string value = found->second;
        given.erase(found);
        return value;
    };
    Options o;
    o.state = take("--state");
    o.dt = number(take("--dt"), "--dt");
    o.gravity = vector3(take("--gravity"), "--gravity");
    const std::vector<double> room = numbers(take("--room"), 6, "--room");
    o.roomMin = btVector3(btScalar(room[0]), btScalar(room[1]), btScalar(room[2]));
    o.roomMax = btVector3(btScalar(room[3]), btScalar(room[4]), btScalar(room[5]));
    o.size = vector3(take("--size"), "--size");
    o.mass = number(take("--mass"), "--mass");
    o.inertia = vector3(take("--inertia"), "--inertia");
    o.friction = number(take("--friction"), "--friction");
    o.restitution = number(take("--restitution"), "--restitution");
    if (given.count("--iterations") != 0) {
        const double iterations = number(take("--iterations"), "--iterations");
        if (iterations < 1 || iterations > 1000 || iterations != std::floor(iterations))
            fail("--iterations: a whole number from 1 to 1000, got " + std::to_string(iterations));
        o.iterations = int(iterations);
    }
    if (!given.empty())
        fail(given.begin()->first + ": unknown option");
    if (!(o.dt > 0.0) || !(o.mass > 0.0) || o.friction < 0.0 || o.restitution < 0.0)
        fail("--dt and --mass must be positive, --friction and --restitution not negative");
    for (int k = 0; k < 3; ++k)
        if (!(o.size[k] > 0) || !(o.inertia[k] > 0) || !(o.roomMax[k] > o.roomMin[k]))
            fail("--size and --inertia must be positive, --room's max above its min");
    return o;
}

/// A die's start: its name and pba's 13 numbers (x, y, z, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz).
struct Die {
    std::string name;
    std::array<double, 13> state;
};

constexpr const char* kHeader = "name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";

std::vector<Die> readState(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
        fail(path + ": cannot be read");
    std::string line;
    if (!std::getline(in, line) || line != kHeader)
        fail(path + ": line 1: the header must be " + kHeader);
    std::vector<Die> dice;
    for (int row = 2; std::getline(in, line); ++row) {
        const std::string where = path + ": line " + std::to_string(row);
        const std::vector<std::string> fields = split(line, ',');
        if (fields.size() != 14)
            fail(where + ": 14 fields, got " + std::to_string(fields.size()));
        if (fields[0].find('"') != std::string::npos)
            fail(where + ": a quoted name (pba's dice are named die0, die1, ...)");
        Die die{fields[0], {}};
        for (std::size_t k = 0; k < 13; ++k)
            die.state[k] = number(fields[k + 1], where + ", " + split(kHeader, ',')[k + 1]);
        dice.push_back(die);
    }
    if (dice.empty())
        fail(path + ": no dice");
    return dice;
}

/// pba's pileStateBits of the same numbers: each rounded to float, read as a 32-bit integer, summed.
std::uint64_t stateBits(const std::vector<Die>& dice)
{
    std::uint64_t bits = 0;
    for (const Die& die : dice)
        for (const double value : die.state) {
            const auto rounded = static_cast<float>(value);
            std::uint32_t word;
            std::memcpy(&word, &rounded, sizeof word);
            bits += word;
        }
    return bits;
}

/// Bullet multiplies two bodies' friction and restitution; pba's pile has one material. The room's
/// boxes carry 1, so the smaller of the two leaves a die's own values in force against the room
/// and between two dice alike.
btScalar smallerFriction(const btCollisionObject* a, const btCollisionObject* b)
{
    return std::min(a->getFriction(), b->getFriction());
}

btScalar smallerRestitution(const btCollisionObject* a, const btCollisionObject* b)
{
    return std::min(a->getRestitution(), b->getRestitution());
}

/// Bullet's world with the room (floor, walls and ceiling as static boxes a metre thick outside it)
/// and the dice, in the state file's order.
class Pile {
public:
    Pile(const Options& o, const std::vector<Die>& dice)
        : m_dispatcher(&m_configuration), m_world(&m_dispatcher, &m_broadphase, &m_solver, &m_configuration),
          m_dieShape(o.size * btScalar(0.5))
    {
        gCalculateCombinedFrictionCallback = &smallerFriction;
        gCalculateCombinedRestitutionCallback = &smallerRestitution;
        m_world.setGravity(o.gravity);
        m_world.getSolverInfo().m_numIterations = o.iterations;
        addRoom(o.roomMin, o.roomMax);
        for (const Die& die : dice)
            addDie(o, die);
    }
    Pile(const Pile&) = delete;
    Pile& operator=(const Pile&) = delete;
    ~Pile()
    {
        for (auto& body : m_dice)
            m_world.removeRigidBody(body.get());
        for (auto& body : m_room)
            m_world.removeRigidBody(body.get());
    }

    void step(btScalar dt) { m_world.stepSimulation(dt, 0); } // maxSubSteps 0: exactly one step of dt

    int sleeping() const
    {
        return int(std::count_if(m_dice.begin(), m_dice.end(), [](const std::unique_ptr<btRigidBody>& body) {
            return body->getActivationState() == ISLAND_SLEEPING;
        }));
    }

    void save(const std::string& path, const std::vector<Die>& dice) const
    {
        const std::string temporary = path + ".tmp-" + std::to_string(getpid()); // renamed when whole
        {
            std::ofstream out(temporary);
            out << kHeader << '\n';
            char row[512];
            for (std::size_t i = 0; i < m_dice.size(); ++i) {
                const btRigidBody& body = *m_dice[i];
                const btVector3 x = body.getCenterOfMassPosition(), v = body.getLinearVelocity(),
                                w = body.getAngularVelocity();
                const btQuaternion q = body.getOrientation();
                std::snprintf(row, sizeof row, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                              x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), w.x(), w.y(),
                              w.z());
                out << dice[i].name << row;
            }
            if (!out.flush())
                fail(path + ": write failed");
        }
        if (std::rename(temporary.c_str(), path.c_str()) != 0)
            fail(path + ": cannot be written");
    }

private:
    void addStatic(btCollisionShape& shape, const btVector3& centre)
    {
        btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, &shape);
        info.m_friction = 1;
        info.m_restitution = 1;
        auto body = std::make_unique<btRigidBody>(info);
        body->setCenterOfMassTransform(btTransform(btQuaternion::getIdentity(), centre));
        m_world.addRigidBody(body.get());
        m_room.push_back(std::move(body));
    }

    void addRoom(const btVector3& lo, const btVector3& hi)
    {
        const btScalar thick = 1;
        const btVector3 centre = (lo + hi) * btScalar(0.5), half = (hi - lo) * btScalar(0.5);
        for (int axis = 0; axis < 3; ++axis) {
            btVector3 extent = half + btVector3(thick, thick, thick); // past the corners: no seams
            extent[axis] = thick * btScalar(0.5);
            m_walls.push_back(std::make_unique<btBoxShape>(extent));
            for (const int side : {-1, 1}) {
                btVector3 at = centre;
                at[axis] = side < 0 ? lo[axis] - thick * btScalar(0.5) : hi[axis] + thick * btScalar(0.5);
                addStatic(*m_walls.back(), at);
            }
        }
    }

    void addDie(const Options& o, const Die& die)
    {
        const auto s = [&die](int k) { return btScalar(die.state[std::size_t(k)]); };
        btRigidBody::btRigidBodyConstructionInfo info(btScalar(o.mass), nullptr, &m_dieShape, o.inertia);
        info.m_friction = btScalar(o.friction);
        info.m_restitution = btScalar(o.restitution);
        auto body = std::make_unique<btRigidBody>(info);
        const btQuaternion q(s(4), s(5), s(6), s(3)); // Bullet's order: x, y, z, w
        body->setCenterOfMassTransform(btTransform(q, btVector3(s(0), s(1), s(2))));
        body->setLinearVelocity(btVector3(s(7), s(8), s(9)));
        body->setAngularVelocity(btVector3(s(10), s(11), s(12)));
        m_world.addRigidBody(body.get());
        m_dice.push_back(std::move(body));
    }

    btDefaultCollisionConfiguration m_configuration;
    btCollisionDispatcher m_dispatcher;
    btDbvtBroadphase m_broadphase;
    btSequentialImpulseConstraintSolver m_solver;
    btDiscreteDynamicsWorld m_world;
    btBoxShape m_dieShape;
    std::vector<std::unique_ptr<btBoxShape>> m_walls;
    std::vector<std::unique_ptr<btRigidBody>> m_room, m_dice;
};

/// A path as a JSON string.
std::string quoted(const std::string& text)
{
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\')
            out += '\\';
        if (static_cast<unsigned char>(c) < 0x20)
            continue;
        out += c;
    }
    return out + "\"";
}

} // namespace

int main(int argc, char** argv)
{
    const Options options = parse(argc, argv);
    const std::vector<Die> dice = readState(options.state);
    Pile pile(options, dice);
    // Debian's libbullet is built without BT_THREADSAFE: then there is no task scheduler and
    // btDiscreteDynamicsWorld steps on one thread, which this says rather than assumes.
    std::unique_ptr<btITaskScheduler> scheduler(btCreateDefaultTaskScheduler());
    double t = 0.0;
    std::printf("{\"ready\": true, \"n\": %zu, \"t\": 0, \"threads\": 1, \"threadsafe_build\": %s, "
                "\"iterations\": %d, \"single_precision\": %s, \"start_bits_sum\": %llu}\n",
                dice.size(), scheduler ? "true" : "false", options.iterations,
                sizeof(btScalar) == 4 ? "true" : "false", static_cast<unsigned long long>(stateBits(dice)));
    std::fflush(stdout);
    for (std::string line; std::getline(std::cin, line);) {
        std::istringstream words(line);
        std::string command;
        words >> command;
        if (command == "window") {
            long steps = 0;
            if (!(words >> steps) || steps < 1)
                fail("'window STEPS' with STEPS >= 1, got '" + line + "'");
            const auto start = std::chrono::steady_clock::now();
            for (long k = 0; k < steps; ++k)
                pile.step(btScalar(options.dt));
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            t += double(steps) * options.dt;
            std::printf("{\"seconds\": %.9g, \"steps\": %ld, \"t\": %.9g, \"steps_per_s\": %.9g, \"sleeping\": %d}\n",
                        seconds, steps, t, double(steps) / seconds, pile.sleeping());
        } else if (command == "save") {
            std::string path;
            std::getline(words >> std::ws, path);
            if (path.empty())
                fail("'save PATH', got '" + line + "'");
            pile.save(path, dice);
            std::printf("{\"saved\": %s, \"t\": %.9g}\n", quoted(path).c_str(), t);
        } else if (command.empty()) {
            continue;
        } else {
            fail("unknown command '" + line + "' (window STEPS, save PATH)");
        }
        std::fflush(stdout);
    }
    return 0;
}
