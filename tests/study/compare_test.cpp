// The integrator study's numbers against oracles, and `pba compare`'s files.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <stb_image.h>

#include "study/study.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;

namespace {

/// The default study on the integrators scene, shortened to 6 s (four bounces) to stay fast.
const study::StudyResult& defaultStudy()
{
    static const study::StudyResult result = [] {
        study::StudyConfig config;
        config.scene = loadScene("integrators");
        config.duration = 6.0;
        config.jobs = 2;
        return study::runStudy(config);
    }();
    return result;
}

std::vector<const study::ParticleResult*> select(Integrator integrator, CollisionResponse collision)
{
    std::vector<const study::ParticleResult*> rows;
    for (const auto& r : defaultStudy().runs)
        if (r.integrator == integrator && r.collision == collision && r.particle == "forward-euler")
            rows.push_back(&r);
    return rows; // in increasing dt
}

} // namespace

TEST(IntegratorStudy, ForwardEulerGainsMoreEnergyTheLargerDtInEveryResponse)
{
    for (CollisionResponse collision : kAllCollisionResponses) {
        const auto rows = select(Integrator::ForwardEuler, collision);
        ASSERT_EQ(rows.size(), 8u);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            EXPECT_GT(rows[i]->energyRatioEnd, 1.0) << collisionResponseName(collision) << " dt " << rows[i]->dt;
            if (i > 0) {
                EXPECT_GT(rows[i]->energyRatioEnd, rows[i - 1]->energyRatioEnd) << collisionResponseName(collision);
            }
        }
    }
}

TEST(IntegratorStudy, SemiImplicitEulerKeepsItsEnergyWithReflect)
{
    for (const auto* r : select(Integrator::SemiImplicitEuler, CollisionResponse::Reflect))
        if (r->dt <= 0.05) {
            EXPECT_NEAR(r->meanEnergyRatio, 1.0, 0.05) << "dt " << r->dt;
        }
}

TEST(IntegratorStudy, VerletAndRK4ReproduceTheBouncePeriodAndApexWithExactImpacts)
{
    for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4}) {
        for (const auto* r : select(integrator, CollisionResponse::Exact)) {
            EXPECT_GE(r->bounces, 4u);
            EXPECT_NEAR(r->periodError, 0.0, 1e-9) << integratorName(integrator) << " dt " << r->dt;
            EXPECT_NEAR(r->apexRatioLast, 1.0, 1e-9) << integratorName(integrator) << " dt " << r->dt;
            EXPECT_LT(r->maxPositionError, 1e-9) << integratorName(integrator) << " dt " << r->dt;
            EXPECT_NEAR(r->energyRatioEnd, 1.0, 1e-9);
        }
    }
}

TEST(IntegratorStudy, MeasuredOrdersAreWithinAThirdOfTheTheory)
{
    ASSERT_EQ(defaultStudy().orders.size(), 4u);
    for (const auto& o : defaultStudy().orders)
        EXPECT_NEAR(o.measured, o.expected, 0.3) << integratorName(o.integrator);
}

TEST(PbaCompare, WritesEveryRowAndPlotsAndIsTheSameWhateverTheJobs)
{
    const auto dir = freshDir("compare");
    const std::string common = "compare --duration 3 --dt 0.001,0.01,0.05 ";
    const CommandResult one = runPba(common + "--jobs 1 --out " + (dir / "one").string());
    ASSERT_EQ(one.exitCode, 0) << one.err;
    const CommandResult two = runPba(common + "--jobs 2 --out " + (dir / "two").string());
    ASSERT_EQ(two.exitCode, 0) << two.err;
    for (const char* file : {"results.csv", "orders.csv", "report.md"})
        EXPECT_EQ(readFile(dir / "one" / file), readFile(dir / "two" / file)) << file;

    // One row per integrator, collision response, dt and moving particle.
    std::istringstream csv(readFile(dir / "one/results.csv"));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line.rfind("integrator,collision,dt,particle,", 0), 0u);
    std::set<std::string> keys;
    while (std::getline(csv, line)) {
        std::vector<std::string> cells;
        std::stringstream fields(line);
        for (std::string cell; std::getline(fields, cell, ',');)
            cells.push_back(cell);
        ASSERT_EQ(cells.size(), 12u) << line;
        for (std::size_t i = 4; i < cells.size(); ++i)
            EXPECT_NO_THROW((void)std::stod(cells[i])) << line;
        keys.insert(cells[0] + cells[1] + cells[2] + cells[3]);
    }
    EXPECT_EQ(keys.size(), 4u * 3u * 3u * 2u);

    for (const char* plot : {"height.png", "energy.png", "convergence.png"}) {
        int w = 0, h = 0, n = 0;
        unsigned char* data = stbi_load((dir / "one" / plot).c_str(), &w, &h, &n, 3);
        ASSERT_NE(data, nullptr) << plot;
        std::set<int> colours;
        for (int i = 0; i < w * h; i += 7)
            colours.insert(data[3 * i] << 16 | data[3 * i + 1] << 8 | data[3 * i + 2]);
        stbi_image_free(data);
        EXPECT_GT(colours.size(), 8u) << plot << " is blank";
    }
    const std::string report = readFile(dir / "one/report.md");
    EXPECT_NE(report.find("## Findings"), std::string::npos);
    EXPECT_NE(report.find("![height](height.png)"), std::string::npos);
    EXPECT_NE(one.out.find("order of accuracy"), std::string::npos);
}

TEST(PbaCompare, BadOptionsAreBadInput)
{
    EXPECT_EQ(runPba("compare --integrators leapfrog --out /tmp/x").exitCode, 2);
    EXPECT_EQ(runPba("compare --collisions bounce --out /tmp/x").exitCode, 2);
    EXPECT_EQ(runPba("compare --dt 0.01,-1 --out /tmp/x").exitCode, 2);
}
