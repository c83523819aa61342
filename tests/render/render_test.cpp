// Headless rendering checked by meaning, not against golden images: what should be at a
// pixel is known from the camera's projection of the world.
#include <gtest/gtest.h>

#include "pba/scene/scene.hpp"
#include "render/offscreen.hpp"

using namespace pba;
using namespace pba::render;

namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 360;

struct Rgb {
    int r, g, b;
};

Rgb pixel(const std::vector<std::uint8_t>& image, int x, int y)
{
    const std::size_t i = (static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x)) * 4;
    return {image[i], image[i + 1], image[i + 2]};
}

Rgb pixelAt(const std::vector<std::uint8_t>& image, const OrbitCamera& camera, const glm::vec3& world)
{
    const glm::vec3 p = camera.project(world, kWidth, kHeight);
    return pixel(image, static_cast<int>(p.x), static_cast<int>(p.y));
}

/// The renderer and the scene, without the legend so that every pixel is the scene's.
struct Fixture {
    Scene scene = loadScene("integrators");
    World initial = scene.world;
    OffscreenRenderer renderer{kWidth, kHeight, false};
    ViewSettings settings;

    std::vector<std::uint8_t> draw() { return renderer.render(scene.world, initial, 0.0, settings, nullptr, "", 0.01); }
};

} // namespace

TEST(HeadlessRender, BackgroundWhereNothingIsDrawn)
{
    Fixture f;
    const auto image = f.draw();
    const Rgb sky = pixel(image, 2, 2); // above the floor's far edge
    EXPECT_NEAR(sky.r, 0.11 * 255, 2);
    EXPECT_NEAR(sky.g, 0.12 * 255, 2);
    EXPECT_NEAR(sky.b, 0.15 * 255, 2);
}

TEST(HeadlessRender, ParticlesInTheirIntegratorColoursAboveAVisibleFloor)
{
    Fixture f;
    const auto image = f.draw();
    const OrbitCamera& camera = f.renderer.camera();
    const glm::vec3 forward(f.scene.world.body(1).getPos());   // forward Euler: red
    const glm::vec3 semiImplicit(f.scene.world.body(2).getPos()); // semi-implicit Euler: green
    const Rgb red = pixelAt(image, camera, forward);
    EXPECT_GT(red.r, red.g + 60) << red.r << "," << red.g << "," << red.b;
    EXPECT_GT(red.r, red.b + 60);
    const Rgb green = pixelAt(image, camera, semiImplicit);
    EXPECT_GT(green.g, green.r + 40) << green.r << "," << green.g << "," << green.b;
    EXPECT_GT(green.g, green.b + 40);
    // Straight below the particle lies the checkered floor: light grey.
    const Rgb floor = pixelAt(image, camera, glm::vec3(forward.x, 0.0f, forward.z + 0.3f));
    EXPECT_GT(floor.r, 120);
    EXPECT_NEAR(floor.r, floor.g, 20);
    EXPECT_NEAR(floor.g, floor.b, 25);
}

TEST(HeadlessRender, DifferentTimesGiveDifferentFramesAndTheSameTimeTheSameFrame)
{
    Fixture f;
    const auto start = f.draw();
    EXPECT_EQ(start, f.draw());
    for (int n = 0; n < 50; ++n)
        f.scene.world.step(0.01);
    const auto later = f.draw();
    EXPECT_NE(start, later);
    // The falling particle has left its start pixel: the background shows there now.
    const Rgb vacated = pixelAt(later, f.renderer.camera(), glm::vec3(f.initial.body(1).getPos()) + glm::vec3(0, 0.05f, 0));
    EXPECT_LT(vacated.r, 200);
}

TEST(HeadlessRender, InterpolationDrawsBetweenThePreviousAndCurrentState)
{
    Fixture f;
    for (int n = 0; n < 30; ++n)
        f.scene.world.step(0.01);
    const auto atPrevious = f.renderer.render(f.scene.world, f.initial, 0.0, f.settings, nullptr, "", 0.01);
    const auto halfway = f.renderer.render(f.scene.world, f.initial, 0.5, f.settings, nullptr, "", 0.01);
    EXPECT_NE(atPrevious, halfway);
    f.settings.interpolate = false;
    const auto current = f.renderer.render(f.scene.world, f.initial, 0.5, f.settings, nullptr, "", 0.01);
    const auto alsoCurrent = f.renderer.render(f.scene.world, f.initial, 0.0, f.settings, nullptr, "", 0.01);
    EXPECT_EQ(current, alsoCurrent);
}

TEST(HeadlessRender, ShaderErrorsNameTheShaderAndCarryTheDriverLog)
{
    Fixture f; // a current context
    try {
        Shader broken("broken-example", "#version 330 core\nvoid main() { gl_Position = vec4(1.0) }\n",
                      "#version 330 core\nout vec4 c; void main() { c = vec4(1.0); }\n");
        FAIL() << "compiled";
    } catch (const RenderError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("broken-example"), std::string::npos) << what;
        EXPECT_NE(what.find("vertex"), std::string::npos) << what;
        EXPECT_GT(what.size(), 60u) << "the driver's log is included: " << what;
    }
}

TEST(HeadlessRender, TheBlowDryerConeIsDrawn)
{
    Scene scene = loadScene("blow-dryer");
    const World initial = scene.world;
    OffscreenRenderer renderer(kWidth, kHeight, false);
    ViewSettings settings;
    settings.trails = false;
    const auto with = renderer.render(scene.world, initial, 0.0, settings, nullptr, "", 0.01);
    settings.cone = false;
    const auto without = renderer.render(scene.world, initial, 0.0, settings, nullptr, "", 0.01);
    // Halfway up the axis the translucent cone tints the picture blue.
    const Rgb inCone = pixelAt(with, renderer.camera(), glm::vec3(0.0f, 1.75f, 0.0f));
    const Rgb plain = pixelAt(without, renderer.camera(), glm::vec3(0.0f, 1.75f, 0.0f));
    EXPECT_GT(inCone.b, plain.b + 5);
}

// A cloth is drawn as a surface: at the middle of one of its cells (no particle there), the
// picture shows the sheet's red, lit, not the room behind it.
TEST(HeadlessRender, TheClothIsASurfaceWhereItHangs)
{
    Scene scene = loadScene("cloth");
    for (int n = 0; n < 1000; ++n) // 2 s: fallen and hanging from its pins
        scene.world.step(scene.dt);
    const World initial = scene.world;
    OffscreenRenderer renderer(kWidth, kHeight, false);
    ViewSettings settings;
    settings.trails = false;
    settings.fabric = scene.fabric;
    const auto image = renderer.render(scene.world, initial, 1.0, settings, nullptr, "", 0.01);
    const ClothLayout& sheet = scene.fabric.cloths.at(0);
    for (const auto& [i, j] : {std::pair{5, 5}, std::pair{2, 8}, std::pair{8, 2}}) {
        glm::vec3 centre(0.0f);
        for (const std::size_t k : {sheet.at(i, j), sheet.at(i + 1, j), sheet.at(i, j + 1), sheet.at(i + 1, j + 1)})
            centre += 0.25f * glm::vec3(scene.world.body(k).getPos());
        const Rgb cloth = pixelAt(image, renderer.camera(), centre);
        EXPECT_GT(cloth.r, cloth.g + 60) << i << "," << j;
        EXPECT_GT(cloth.r, cloth.b + 60) << i << "," << j;
        EXPECT_GT(cloth.r, 90) << i << "," << j; // lit, not a dark silhouette
    }
}
