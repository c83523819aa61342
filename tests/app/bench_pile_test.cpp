// `pba bench --pile-worker`: what bench/peers/pile.py and the Bullet peer read from it.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pba/rigid_body.hpp"
#include "pba/scene/scene.hpp"
#include "support/run_command.hpp"

namespace {

/// The CSV's rows after its header, each split at its commas.
std::vector<std::vector<std::string>> csvRows(const std::string& text, std::string& header)
{
    std::istringstream lines(text);
    std::getline(lines, header);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(lines, line);) {
        std::vector<std::string> fields;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');)
            fields.push_back(cell);
        rows.push_back(fields);
    }
    return rows;
}

/// A die's 13 numbers as the worker writes them.
std::vector<double> dieNumbers(const pba::RigidBody& die)
{
    const pba::dvec3 x = die.getPos(), v = die.getVel(), w = die.getAngularVelocity();
    const pba::dquat q = die.getOrientation();
    return {x.x, x.y, x.z, q.w, q.x, q.y, q.z, v.x, v.y, v.z, w.x, w.y, w.z};
}

} // namespace

// The ready line gives manyDice's pile (a 10 cm box of 600 kg/m^3: 0.6 kg, inertia m (a^2 + a^2) / 12
// = 0.001 kg m^2 about each axis; the dice scene's friction, restitution, dt, gravity and room);
// the saved start holds every die's state to the bit and its checksum is the sum the ready line
// gives (recomputed here from the file: each number rounded to float, its bits summed); a window
// steps on from where the pile was, to the same states as the library's world stepped as often.
TEST(PbaBench, PileWorkerSavesTheThrowAndStepsItOnRequest)
{
    const auto dir = pba::test::freshDir("pile_worker");
    const std::string start = (dir / "start.csv").string(), later = (dir / "later.csv").string();
    const auto r = pba::test::runShell("printf 'save " + start + "\\nwindow 3\\nsave " + later + "\\n' | " +
                                       pba::test::pbaBinary() + " bench --pile-worker --dice 50");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::string readyLine, saved, window, savedLater;
    ASSERT_TRUE(std::getline(lines, readyLine) && std::getline(lines, saved) && std::getline(lines, window) &&
                std::getline(lines, savedLater))
        << r.out;
    const auto ready = nlohmann::json::parse(readyLine);
    EXPECT_EQ(ready["n"], 50);
    EXPECT_EQ(ready["dt"], 0.005);
    EXPECT_EQ(ready["gravity"], nlohmann::json::parse("[0.0, -9.81, 0.0]"));
    EXPECT_EQ(ready["room"]["min"], nlohmann::json::parse("[-2.0, 0.0, -2.0]"));
    EXPECT_EQ(ready["room"]["max"], nlohmann::json::parse("[2.0, 4.0, 2.0]"));
    EXPECT_EQ(ready["die"]["size"], nlohmann::json::parse("[0.1, 0.1, 0.1]"));
    EXPECT_NEAR(ready["die"]["mass"].get<double>(), 0.6, 1e-15);
    for (const auto& moment : ready["die"]["inertia"])
        EXPECT_NEAR(moment.get<double>(), 0.001, 1e-15);
    EXPECT_EQ(ready["die"]["friction"], 0.5);
    EXPECT_EQ(ready["die"]["restitution"], 0.4);
    EXPECT_EQ(nlohmann::json::parse(window)["steps"], 3);
    EXPECT_NEAR(nlohmann::json::parse(window)["t"].get<double>(), 0.015, 1e-15);
    EXPECT_NEAR(nlohmann::json::parse(savedLater)["t"].get<double>(), 0.015, 1e-15);

    pba::Scene expected = pba::manyDice(50);
    for (const auto& [path, steps] : {std::pair{start, 0}, std::pair{later, 3}}) {
        for (; expected.world.stepCount() < std::uint64_t(steps);)
            expected.world.step(expected.dt);
        std::string header;
        const auto rows = csvRows(pba::test::readFile(path), header);
        EXPECT_EQ(header, "name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
        ASSERT_EQ(rows.size(), 50u) << path;
        std::uint64_t bits = 0;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            ASSERT_EQ(rows[i].size(), 14u);
            EXPECT_EQ(rows[i][0], "die" + std::to_string(i));
            const auto& die = static_cast<const pba::RigidBody&>(expected.world.body(i));
            const std::vector<double> numbers = dieNumbers(die);
            for (std::size_t k = 0; k < 13; ++k) {
                const double value = std::stod(rows[i][k + 1]);
                ASSERT_EQ(value, numbers[k]) << path << " die " << i << " column " << k + 1;
                const auto rounded = static_cast<float>(value);
                std::uint32_t word;
                std::memcpy(&word, &rounded, sizeof word);
                bits += word;
            }
        }
        if (steps == 0) {
            EXPECT_EQ(ready["start_bits_sum"].get<std::uint64_t>(), bits);
        }
    }
}

// Bad requests are usage errors (exit 2) naming the option or the command, with nothing on stdout
// but what came before them.
TEST(PbaBench, PileWorkerRefusesBadRequests)
{
    const auto many = pba::test::runPba("bench --pile-worker --dice 10649 < /dev/null");
    EXPECT_EQ(many.exitCode, 2);
    EXPECT_NE(many.err.find("--dice: a pile of dice: the dice scene's room holds at most 10648 dice"),
              std::string::npos)
        << many.err;
    EXPECT_TRUE(many.out.empty()) << many.out;
    const auto alone = pba::test::runPba("bench --quick --dice 100");
    EXPECT_EQ(alone.exitCode, 2);
    EXPECT_EQ(alone.err, "pba: error: --dice: only with --pile-worker\n");
    const auto both = pba::test::runPba("bench --pile-worker --peer-worker --sizes 1000");
    EXPECT_EQ(both.exitCode, 2);
    EXPECT_NE(both.err.find(": not with --p"), std::string::npos) << both.err;
    const auto unknown =
        pba::test::runShell("printf 'jump 3\\n' | " + pba::test::pbaBinary() + " bench --pile-worker --dice 10");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("--pile-worker: unknown command 'jump 3' (window STEPS, save PATH)"),
              std::string::npos)
        << unknown.err;
    const auto zero =
        pba::test::runShell("printf 'window 0\\n' | " + pba::test::pbaBinary() + " bench --pile-worker --dice 10");
    EXPECT_EQ(zero.exitCode, 2);
    EXPECT_NE(zero.err.find("'window STEPS' with STEPS >= 1"), std::string::npos) << zero.err;
}
