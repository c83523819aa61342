// Headless rendering checked by meaning, not against golden images: what should be at a
// pixel is known from the camera's projection of the world.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>

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

/// Whether a lit pixel is of this colour's hue: its largest and smallest channels are the
/// colour's, well apart (light and shade change the levels, not their order).
testing::AssertionResult ofHue(const Rgb& p, const glm::vec4& colour)
{
    const int channels[3] = {p.r, p.g, p.b};
    const auto most = [](const auto& c) { return c[0] >= c[1] && c[0] >= c[2] ? 0 : c[1] >= c[2] ? 1 : 2; };
    const auto least = [](const auto& c) { return c[0] <= c[1] && c[0] <= c[2] ? 0 : c[1] <= c[2] ? 1 : 2; };
    const float expected[3] = {colour.r, colour.g, colour.b};
    if (most(channels) == most(expected) && least(channels) == least(expected) &&
        channels[most(channels)] - channels[least(channels)] > 40)
        return testing::AssertionSuccess();
    return testing::AssertionFailure() << "pixel " << p.r << "," << p.g << "," << p.b << " is not of the hue of "
                                       << colour.r << "," << colour.g << "," << colour.b;
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

// Each body in its own colour, the one its legend bullet and plots take: the forward Euler and
// semi-implicit Euler balls are told apart by colour, their integrators by the legend's text.
TEST(HeadlessRender, ParticlesInTheirOwnColoursAboveAVisibleFloor)
{
    Fixture f;
    const auto image = f.draw();
    const OrbitCamera& camera = f.renderer.camera();
    const BodyGroups groups(f.scene.world, f.scene.fabric);
    const glm::vec3 forward(f.scene.world.body(1).getPos());
    const glm::vec3 semiImplicit(f.scene.world.body(2).getPos());
    EXPECT_TRUE(ofHue(pixelAt(image, camera, forward), groups.bodyColour(1)));
    EXPECT_TRUE(ofHue(pixelAt(image, camera, semiImplicit), groups.bodyColour(2)));
    EXPECT_FALSE(ofHue(pixelAt(image, camera, semiImplicit), groups.bodyColour(1))) << "two colours";
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

// With interpolation a frame draws each body alpha of the way from its state before the last
// step to its current one: after a last step of 0.3 s (the ball falls about 0.9 m in it, several
// of its radii) the ball is drawn halfway between where it was and where it is, and at neither
// end; without interpolation, where it is, whatever alpha.
TEST(HeadlessRender, InterpolationDrawsBetweenThePreviousAndCurrentState)
{
    Fixture f;
    f.settings.trails = false;
    for (int n = 0; n < 30; ++n)
        f.scene.world.step(0.01);
    f.scene.world.step(0.3);
    const glm::vec3 before(f.scene.world.interpolatedState(1, 0.0).pos), now(f.scene.world.body(1).getPos());
    ASSERT_GT(before.y - now.y, 0.6f);
    const glm::vec3 halfway = 0.5f * (before + now);
    const glm::vec4 colour = BodyGroups(f.scene.world, f.scene.fabric).bodyColour(1);
    const OrbitCamera& camera = f.renderer.camera();
    const auto blended = f.renderer.render(f.scene.world, f.initial, 0.5, f.settings, nullptr, "", 0.01);
    EXPECT_TRUE(ofHue(pixelAt(blended, camera, halfway), colour));
    EXPECT_FALSE(ofHue(pixelAt(blended, camera, before), colour));
    EXPECT_FALSE(ofHue(pixelAt(blended, camera, now), colour));
    f.settings.interpolate = false;
    const auto current = f.renderer.render(f.scene.world, f.initial, 0.5, f.settings, nullptr, "", 0.01);
    EXPECT_TRUE(ofHue(pixelAt(current, camera, now), colour));
    EXPECT_FALSE(ofHue(pixelAt(current, camera, halfway), colour));
    EXPECT_EQ(current, f.renderer.render(f.scene.world, f.initial, 0.0, f.settings, nullptr, "", 0.01));
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

// The cone is a translucent surface of its fill colour (0.35, 0.75, 1.0) at alpha 0.1: seen
// through on its axis, halfway up, the picture is the plain one behind it blended with that
// colour, once for the cone's near side and at most once more for its far side.
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
    const glm::vec3 onAxis(0.0f, 1.75f, 0.0f);
    const Rgb inCone = pixelAt(with, renderer.camera(), onAxis);
    const Rgb plain = pixelAt(without, renderer.camera(), onAxis);
    const double alpha = 0.1, fill[3] = {0.35 * 255, 0.75 * 255, 1.0 * 255};
    const int seen[3] = {inCone.r, inCone.g, inCone.b}, behind[3] = {plain.r, plain.g, plain.b};
    for (int c = 0; c < 3; ++c) {
        const double once = (1 - alpha) * behind[c] + alpha * fill[c];
        const double twice = (1 - alpha) * once + alpha * fill[c];
        EXPECT_GE(seen[c], std::min(once, twice) - 2) << "channel " << c;
        EXPECT_LE(seen[c], std::max(once, twice) + 2) << "channel " << c;
    }
    EXPECT_GT(inCone.b, plain.b + 5); // and visibly so
}

// A cloth is drawn as a surface: at the middle of one of its cells (no particle there), the
// picture shows the sheet in its colour, lit, not the room behind it.
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
        EXPECT_TRUE(ofHue(cloth, BodyGroups(scene.world, scene.fabric)[0].colour)) << i << "," << j;
        EXPECT_GT(std::max({cloth.r, cloth.g, cloth.b}), 90) << i << "," << j; // lit, not a dark silhouette
    }
}

namespace {

/// How much greener (green over red) the greenest pixel within one of `at` is in `after` than in
/// `before`: a line is one pixel wide, antialiased, and a projected point rounds to either side.
int greener(const std::vector<std::uint8_t>& before, const std::vector<std::uint8_t>& after, const glm::vec3& at)
{
    int most = -255;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const Rgb a = pixel(before, int(at.x) + dx, int(at.y) + dy), b = pixel(after, int(at.x) + dx, int(at.y) + dy);
            most = std::max(most, (b.g - b.r) - (a.g - a.r));
        }
    return most;
}

} // namespace

// The three faces of an unturned box the camera sees (+x, +y, +z) are three shades of the box's
// one colour, far enough apart to tell (so a die's faces, and its turning, can be seen).
TEST(HeadlessRender, ABoxsFacesAreShadesOfItsColour)
{
    Scene scene = parseScene(R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "rigid_bodies": [{"name": "die",
        "shape": {"type": "box", "size": [1, 1, 1]}, "density": 100, "position": [0, 0.5, 0]}]})", "die.json");
    OffscreenRenderer renderer(kWidth, kHeight, false);
    renderer.setCamera(OrbitCamera::lookingFrom(glm::vec3(2.5f, 3.0f, 3.5f), glm::vec3(0.0f, 0.5f, 0.0f)));
    ViewSettings settings;
    const auto image = renderer.render(scene.world, scene.world, 1.0, settings, nullptr, "", 0.01);
    const glm::vec4 colour = BodyGroups(scene.world, scene.fabric).bodyColour(0);
    std::vector<Rgb> faces;
    for (const glm::vec3& centre : {glm::vec3(0.5f, 0.5f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, 0.5f, 0.5f)}) {
        faces.push_back(pixelAt(image, renderer.camera(), centre));
        EXPECT_TRUE(ofHue(faces.back(), colour));
    }
    for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t b = a + 1; b < 3; ++b)
            EXPECT_GT(std::abs(faces[a].r - faces[b].r) + std::abs(faces[a].g - faces[b].g) +
                          std::abs(faces[a].b - faces[b].b), 30)
                << a << " and " << b;
}

// The marks are drawn over the bodies: the racket's y axis, inside its box, shows green through
// the box's orange when the axes are on.
TEST(HeadlessRender, AxesAreDrawnOverTheBodyTheyDescribe)
{
    Scene scene = loadScene("tennis-racket"); // unturned at the start: its y axis is the world's
    OffscreenRenderer renderer(kWidth, kHeight, false);
    const glm::vec3 centre(scene.world.body(0).getPos());
    renderer.setCamera(OrbitCamera::lookingFrom(centre + glm::vec3(0.6f, 0.4f, 1.5f), centre));
    ViewSettings settings;
    settings.trails = false;
    const glm::vec3 inside = renderer.camera().project(centre + glm::vec3(0.0f, 0.2f, 0.0f), kWidth, kHeight);
    const auto without = renderer.render(scene.world, scene.world, 1.0, settings, nullptr, "", 0.01);
    const Rgb racket = pixel(without, int(inside.x), int(inside.y));
    EXPECT_GT(racket.r, racket.g) << "the racket's orange is there, in front of its axis";
    settings.axes = true;
    const auto with = renderer.render(scene.world, scene.world, 1.0, settings, nullptr, "", 0.01);
    EXPECT_GT(greener(without, with, inside), 60);
}

// A die's top face, seen from above, shows its number of pips (1 on +x, 2 on +y, 3 on +z, the
// opposite faces making 7), set apart from the face's own shade, and nothing else on the face.
TEST(HeadlessRender, EachFaceOfADieShowsItsNumberOfPips)
{
    const std::pair<std::string, int> upwards[] = {
        {"[0.70710678, 0, 0, 0.70710678]", 1}, {"[0.70710678, 0, 0, -0.70710678]", 6},
        {"[1, 0, 0, 0]", 2},                   {"[0, 1, 0, 0]", 5},
        {"[0.70710678, -0.70710678, 0, 0]", 3}, {"[0.70710678, 0.70710678, 0, 0]", 4}};
    OffscreenRenderer renderer(kWidth, kHeight, false);
    renderer.setCamera(OrbitCamera::lookingFrom(glm::vec3(0.0f, 3.0f, 0.2f), glm::vec3(0.0f, 0.5f, 0.0f)));
    const auto apart = [](const Rgb& a, const Rgb& b) { return std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b); };
    for (const auto& [orientation, pips] : upwards) {
        const Scene scene = parseScene(R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "rigid_bodies": [{"name":
            "die", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0.5, 0], "die": true, "orientation": )" +
                                           orientation + "}]}",
                                       "die.json");
        ViewSettings settings;
        settings.dice = scene.dice;
        const auto image = renderer.render(scene.world, scene.world, 1.0, settings, nullptr, "", 0.01);
        // u and v in half sides across the top face (a pip's centre is at 0 or +-0.5 of them).
        const auto at = [&](float u, float v) { return pixelAt(image, renderer.camera(), glm::vec3(0.5f * u, 1.0f, 0.5f * v)); };
        const Rgb face = at(0.25f, 0.75f); // no face has a pip there
        int seen = 0;
        for (const float u : {-0.5f, 0.0f, 0.5f})
            for (const float v : {-0.5f, 0.0f, 0.5f})
                seen += apart(at(u, v), face) > 90 ? 1 : 0;
        EXPECT_EQ(seen, pips) << orientation;
        for (const float s : {-1.0f, 1.0f})
            for (const float t : {-1.0f, 1.0f}) {
                EXPECT_LT(apart(at(0.25f * s, 0.75f * t), face), 12) << orientation << ": a plain face";
                EXPECT_LT(apart(at(0.75f * s, 0.25f * t), face), 12) << orientation << ": a plain face";
            }
    }
}
