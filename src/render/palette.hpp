#pragma once
// The colours of every picture pba makes, defined once. The viewer and `pba render` draw each
// body (and each rope, cloth and swarm) in a colour of its own, which its legend bullet and its
// plots share, so a reader follows one thing by one colour; the legend's text names its
// integrator. The integrator study's gnuplot figures (`pba compare`) compare integrators, so
// they draw each integrator's line in the integrator's colour. Plain numbers, no OpenGL: the
// plotting code includes this header too.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "pba/integrator.hpp"

namespace pba::palette {

/// An sRGB colour as 0xrrggbb.
using Rgb = std::uint32_t;

inline constexpr Rgb kForwardEuler = 0xed5445;      // red: gains energy
inline constexpr Rgb kSemiImplicitEuler = 0x4cbf61; // green
inline constexpr Rgb kVelocityVerlet = 0x458cf2;    // blue
inline constexpr Rgb kRK4 = 0xf2b233;               // amber
inline constexpr Rgb kImplicitGyroscopic = 0xa66bd9; // violet
inline constexpr Rgb kSplitting = 0x1fb5c4;          // teal
inline constexpr Rgb kImplicitEuler = 0x9c6b4e;      // brown: damps
inline constexpr Rgb kXpbd = 0xe0609f;               // pink
inline constexpr Rgb kFixed = 0xb2b2b8;             // grey: a body that does not move

/// The bodies' colours, in the order bodies take them: saturated enough to read on the dark
/// background and on the light floor, neighbours far apart in hue, none grey (grey is a fixed
/// body's).
inline constexpr std::array<Rgb, 10> kBodies = {
    0xf28e2b, // orange
    0x4e9ff0, // blue
    0x59c26b, // green
    0xe8484b, // red
    0xb483e0, // violet
    0xedc948, // yellow
    0x4fc9c0, // teal
    0xff8fc0, // pink
    0xb8875a, // brown
    0xa8d93a, // lime
};

/// An sRGB colour from hue (degrees), saturation and value (0 to 1).
constexpr Rgb fromHsv(double hue, double saturation, double value)
{
    const double c = value * saturation, h = hue / 60.0;
    const double m = value - c;
    const double hm2 = h - 2.0 * double(int(h / 2.0)); // h mod 2
    const double x = c * (1.0 - (hm2 > 1.0 ? hm2 - 1.0 : 1.0 - hm2));
    double r = 0, g = 0, b = 0;
    switch (int(h) % 6) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
    }
    const auto byte = [](double v) { return Rgb(v * 255.0 + 0.5); };
    return (byte(r + m) << 16) | (byte(g + m) << 8) | byte(b + m);
}

/// The colour of the body (or rope, cloth or swarm) with this index: the same on every run, so
/// a picture, its legend and its plots agree, and so do two pictures of one scene. Past the ten
/// picked ones, hues a golden angle apart at three shades, so that a row of dominoes or a chain's
/// links does not repeat its colours every ten.
constexpr Rgb bodyRgb(std::size_t index)
{
    if (index < kBodies.size())
        return kBodies[index];
    const std::size_t k = index - kBodies.size();
    const double hue = double((k * 137508) % 360000) / 1000.0 + 15.0;
    constexpr double kSaturation[3] = {0.62, 0.45, 0.75}, kValue[3] = {0.78, 0.95, 0.62};
    return fromHsv(hue >= 360.0 ? hue - 360.0 : hue, kSaturation[k % 3], kValue[k % 3]);
}

constexpr Rgb integratorRgb(Integrator integrator)
{
    switch (integrator) {
    case Integrator::ForwardEuler: return kForwardEuler;
    case Integrator::SemiImplicitEuler: return kSemiImplicitEuler;
    case Integrator::VelocityVerlet: return kVelocityVerlet;
    case Integrator::RK4: return kRK4;
    case Integrator::ImplicitGyroscopic: return kImplicitGyroscopic;
    case Integrator::Splitting: return kSplitting;
    case Integrator::ImplicitEuler: return kImplicitEuler;
    case Integrator::Xpbd: return kXpbd;
    }
    return 0xffffff;
}

/// The colour's channels from 0 to 1.
constexpr std::array<float, 3> channels(Rgb rgb)
{
    return {float((rgb >> 16) & 0xff) / 255.0f, float((rgb >> 8) & 0xff) / 255.0f, float(rgb & 0xff) / 255.0f};
}

/// "#rrggbb", as gnuplot's `lc rgb '#rrggbb'` and HTML take it.
inline std::string hex(Rgb rgb)
{
    std::string out = "#";
    for (int shift = 20; shift >= 0; shift -= 4)
        out += "0123456789abcdef"[(rgb >> shift) & 0xf];
    return out;
}

/// The colour moved towards black (amount < 0) or white (amount > 0), amount in [-1, 1]: shades
/// of one integrator's colour for its lines at several dt.
constexpr Rgb shade(Rgb rgb, double amount)
{
    Rgb out = 0;
    for (int shift : {16, 8, 0}) {
        const double c = double((rgb >> shift) & 0xff);
        const double target = amount < 0 ? 0.0 : 255.0;
        const double a = amount < 0 ? -amount : amount;
        out |= Rgb(c + (target - c) * a + 0.5) << shift;
    }
    return out;
}

} // namespace pba::palette
