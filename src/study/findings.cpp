#include "findings.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "exact_solution.hpp"

namespace pba::study {

namespace {

bool has(const std::vector<Integrator>& list, Integrator x) { return std::find(list.begin(), list.end(), x) != list.end(); }
bool has(const std::vector<CollisionResponse>& list, CollisionResponse x)
{
    return std::find(list.begin(), list.end(), x) != list.end();
}

/// One integrator's rows for one response, in increasing dt.
std::vector<const ParticleResult*> rowsOf(const StudyConfig& config, const StudyResult& result, Integrator integrator,
                                          CollisionResponse collision)
{
    std::vector<const ParticleResult*> rows;
    for (double dt : config.dts)
        if (const ParticleResult* r = findRun(result, integrator, collision, dt))
            rows.push_back(r);
    return rows;
}


/// Whether the bounce findings' mechanisms (the shadow energy, the mirror's gain) are the whole
/// story: gravity is the only force, the ground the only surface, and every moving particle
/// bounces elastically. A dryer, drag, a restitution below 1 or a room's walls and ceiling (a
/// bounce off the ceiling takes what one off the floor gives) change the energy too, and then
/// only the figures are quoted.
bool elasticBouncesUnderGravity(const StudyConfig& config)
{
    const World& world = config.scene.world;
    if (!forceKinds(world).onlyGravity || world.gravity() == dvec3(0.0) || world.room() || world.planes().size() > 1)
        return false;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed() && world.body(i).getCor() != 1.0)
            return false;
    return true;
}

/// "at dt = 0.3", "at dt = 0.01 and 0.05", "over every dt from 0.0005 to 0.1".
std::string overDts(const std::vector<double>& dts)
{
    if (dts.size() == 1)
        return fmt::format("at dt = {}", dts.front());
    if (dts.size() == 2)
        return fmt::format("at dt = {} and {}", dts.front(), dts.back());
    return fmt::format("over every dt from {} to {}", dts.front(), dts.back());
}

/// "1.0123 times the start at dt = 0.01" or "... at dt = 0.01 and 1.5 times at dt = 0.1".
std::string endRatios(const std::vector<const ParticleResult*>& rows)
{
    std::string text = fmt::format("{} times the start at dt = {}", ratioText(rows.front()->energyRatioEnd), rows.front()->dt);
    if (rows.size() > 1)
        text += fmt::format(" and {} times at dt = {}", ratioText(rows.back()->energyRatioEnd), rows.back()->dt);
    return text;
}

/// "its energy after 10 s is 0.9737 times the start at dt = 0.0005 and 1.2 times at dt = 0.1", or
/// "... and it blew up at t = 0.21 s at dt = 0.1": a run that blew up has no end energy to quote,
/// only when it blew up. The energy is named once.
std::string endClauses(const std::vector<const ParticleResult*>& rows, double duration, bool lessSourceWork)
{
    const auto one = [&](const ParticleResult& r, bool named) {
        if (!std::isnan(r.blewUpAt))
            return fmt::format("it blew up at t = {:.3g} s at dt = {}", r.blewUpAt, r.dt);
        // Below zero, less the dryer's work: the bounces and the integration took more than the
        // start's energy, the dryer having put it in.
        const bool below = lessSourceWork && r.energyRatioEnd < 0.0;
        const std::string subject = named ? "" : fmt::format("its energy{} after {} s is ",
                                                             lessSourceWork ? " less the dryer's work" : "", duration);
        return fmt::format("{}{} times {}at dt = {}{}", subject, ratioText(r.energyRatioEnd), named ? "" : "the start ",
                           r.dt,
                           below ? " (below zero: what the bounces and the integration took is more than the start's "
                                   "energy, the dryer's work having put it in)"
                                 : "");
    };
    const ParticleResult& first = *rows.front();
    if (rows.size() == 1)
        return one(first, false);
    // The second names the energy only if the first did not (it blew up).
    return one(first, false) + " and " + one(*rows.back(), std::isnan(first.blewUpAt));
}

std::string capitalised(std::string text)
{
    if (!text.empty())
        text[0] = char(std::toupper(static_cast<unsigned char>(text[0])));
    return text;
}

std::string nothingCollides(const StudyConfig& config, const StudyResult& result)
{
    if (anyCollision(result) || config.collisions.size() < 2)
        return "";
    std::string names;
    for (CollisionResponse c : config.collisions)
        names += fmt::format("{}`{}`", names.empty() ? "" : ", ", collisionResponseName(c));
    return fmt::format("**Nothing collides.** No particle met a surface in any run, so the collision responses ({}) "
                       "never acted and give the same numbers: the tables and plots show them once.\n\n",
                       names);
}

std::string exactAsReflect(const StudyConfig& config, const StudyResult& result)
{
    if (!exactShownAsReflect(config, result))
        return "";
    return "**`exact` is `reflect` here.** Every moving particle is joined to others by springs, and a coupled "
           "particle has no path of its own along which to find a time of impact (its group moves as one), so the "
           "`exact` response acts as `reflect` on it (docs/scenes.md): the two give the same runs, to the bit, and "
           "the tables and plots show them once, as `reflect`.\n\n";
}

/// For a system: which methods kept it finite at every dt, and the largest dt each survived.
std::string survivors(const StudyConfig& config, const StudyResult& result)
{
    if (!result.followsSystem)
        return "";
    const CollisionResponse c = distinctResponses(config, result).front();
    std::string text;
    for (Integrator integrator : config.integrators) {
        double largest = 0.0;
        bool all = true;
        for (const auto* r : rowsOf(config, result, integrator, c)) {
            if (std::isnan(r->blewUpAt))
                largest = std::max(largest, r->dt);
            else
                all = false;
        }
        text += fmt::format("{}{} ", text.empty() ? "" : "; ", integratorName(integrator));
        text += all ? "at every dt" : largest > 0 ? fmt::format("up to dt = {}", largest) : "at none";
    }
    // Only what the scene has is named: its springs' mode, their damping, drag, bounces.
    const ForceKinds kinds = forceKinds(config.scene.world);
    std::vector<std::string> losses;
    if (kinds.dampedSprings)
        losses.emplace_back("the springs' damping");
    if (kinds.drag)
        losses.emplace_back("the drag");
    if (anyCollision(result))
        losses.emplace_back("the bounces");
    std::string why = result.omegaMax ? " Past a method's stability limit the stiffest springs' mode grows "
                                        "geometrically: the run blows up, or gains energy (the stability limits below)."
                                      : "";
    if (!losses.empty())
        why += fmt::format(" Where it stays finite the total energy falls, to {}.", listText(losses));
    return fmt::format("**Which dt keep the system finite** (`{}` response, {} s): {}.{}\n\n",
                       collisionResponseName(c), config.duration, text, why);
}

/// endClauses for each response that gave different runs, "With the `exact` response ... . "
/// for each when there are several; empty when the integrator has no runs.
std::string endClausesByResponse(const StudyConfig& config, const StudyResult& result, Integrator integrator)
{
    const auto responses = distinctResponses(config, result);
    std::string text;
    bool said = false; // after the first response's sentence, the others' figures alone
    for (CollisionResponse c : responses) {
        const auto rows = rowsOf(config, result, integrator, c);
        if (rows.empty())
            continue;
        const bool finite = std::all_of(rows.begin(), rows.end(), [](const ParticleResult* r) {
            return std::isnan(r->blewUpAt) && !(r->energyRatioEnd < 0.0);
        });
        if (said && finite && rows.size() > 1) {
            text += fmt::format("With `{}`, {} and {} times. ", collisionResponseName(c),
                                ratioText(rows.front()->energyRatioEnd), ratioText(rows.back()->energyRatioEnd));
            continue;
        }
        const std::string clauses = endClauses(rows, config.duration, result.lessSourceWork);
        text += responses.size() > 1 ? fmt::format("With the `{}` response {}. ", collisionResponseName(c), clauses)
                                     : capitalised(clauses) + ". ";
        said = finite && rows.size() > 1;
    }
    return text;
}

std::string forwardEuler(const StudyConfig& config, const StudyResult& result)
{
    if (!has(config.integrators, Integrator::ForwardEuler))
        return "";
    bool gains = true, growing = true;
    for (CollisionResponse c : distinctResponses(config, result)) {
        const auto rows = rowsOf(config, result, Integrator::ForwardEuler, c);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            gains = gains && rows[i]->energyRatioEnd > 1.0;
            growing = growing && rows.size() > 1 && (i == 0 || rows[i]->energyRatioEnd > rows[i - 1]->energyRatioEnd);
        }
    }
    const std::string numbers = endClausesByResponse(config, result, Integrator::ForwardEuler);
    if (numbers.empty())
        return "";
    std::string text = gains ? "**Forward Euler gains energy.** " : "**Forward Euler.** ";
    text += numbers;
    if (gains) {
        // dE per step, unit mass: gravity g dt (v_n) + (v_{n+1}^2 - v_n^2)/2 = g^2 dt^2 / 2; spring:
        // E_{n+1} = E_n (1 + w^2 dt^2). Both from moving with the start's velocity and force.
        const auto exact = firstExact(config);
        text += "It moves each step with the velocity, and accelerates it with the force, of the step's start";
        if (exact && exact->kind() == ExactSolution::Kind::Bounce)
            text += ": in flight under gravity alone that adds exactly m g² dt² / 2 of energy every step, whichever "
                    "way the particle moves";
        else if (exact && exact->kind() == ExactSolution::Kind::Oscillator)
            text += ": on an undamped spring that multiplies the energy by 1 + ω² dt² every step, for as long as "
                    "the swing stays short of the anchor";
        text += growing ? ", so the larger dt, the more it gains.\n\n" : ".\n\n";
    } else {
        text += "\n\n";
    }
    return text;
}

/// With collisions: how the response decides whether semi-implicit Euler keeps its bounce.
std::string semiImplicitEulerBounces(const StudyConfig& config, const StudyResult& result)
{
    std::string reflectText, exactText;
    if (has(config.collisions, CollisionResponse::Reflect) && elasticBouncesUnderGravity(config)) {
        double worst = 0, largest = 0;
        for (const auto* r : rowsOf(config, result, Integrator::SemiImplicitEuler, CollisionResponse::Reflect))
            if (r->dt <= 0.05 + 1e-12) {
                worst = std::max(worst, std::abs(r->meanEnergyRatio - 1));
                largest = r->dt;
            }
        if (largest > 0 && worst <= 0.05)
            reflectText = fmt::format("With the classic `reflect` response its energy, averaged over the run, stays "
                                      "within {:.1f}% of the start {} (at any one instant it swings by about "
                                      "g |v| dt / 2 per unit mass around that): the practical's observation that it "
                                      "keeps its bounce. ",
                                      100 * worst, largest < 0.05 ? fmt::format("up to dt = {}", largest)
                                                                  : "for every dt up to 0.05");
    }
    if (has(config.collisions, CollisionResponse::Exact)) {
        // The row nearest dt = 0.05 from below, else the smallest dt: the loss at a typical large dt.
        const ParticleResult* chosen = nullptr;
        for (const auto* r : rowsOf(config, result, Integrator::SemiImplicitEuler, CollisionResponse::Exact))
            if (!chosen || r->dt <= 0.05 + 1e-12)
                chosen = r;
        if (chosen && chosen->bounces > 0 && chosen->energyRatioEnd < 1.0 && elasticBouncesUnderGravity(config))
            exactText = fmt::format("With the `exact` time-of-impact response it loses energy at every bounce and "
                                    "ends at {:.3f} of its start energy at dt = {}{}: between bounces it conserves "
                                    "the shadow energy E - m g v dt / 2, and each bounce, by reversing v, lowers that "
                                    "level by m g |v| dt{}.",
                                    chosen->energyRatioEnd, chosen->dt,
                                    chosen->energyRatioEnd < 0.01 ? " (it has come to rest on the ground)" : "",
                                    reflectText.empty() ? "" : "; the mirror of `reflect` happens to undo the shift");
    }
    if (reflectText.empty() && exactText.empty())
        return "";
    const bool both = !reflectText.empty() && !exactText.empty();
    return (both ? "**Semi-implicit Euler: the collision response decides the verdict.** " : "**Semi-implicit Euler.** ") +
           reflectText + exactText + "\n\n";
}

/// Whether a run's gain can be the mirror's: it stayed finite and its dt is below the
/// integrator's measured stability limit (past it, springs gain energy whatever the response).
bool belowStabilityLimit(const StudyResult& result, const ParticleResult& run)
{
    if (!std::isnan(run.blewUpAt))
        return false;
    for (const auto& limit : result.stability)
        if (limit.integrator == run.integrator && !std::isnan(limit.measuredDt) && run.dt >= limit.measuredDt)
            return false;
    return true;
}

/// The measured stability limit of an integrator, as "its stability limit (dt = 0.0666 s,
/// measured below)", or "its stability limit" when the study did not measure one.
std::string stabilityLimitText(const StudyResult& result, Integrator integrator)
{
    for (const auto& limit : result.stability)
        if (limit.integrator == integrator && !std::isnan(limit.measuredDt))
            return fmt::format("its stability limit (dt = {:.4g} s, measured below)", limit.measuredDt);
    return "its stability limit";
}

std::string semiImplicitEuler(const StudyConfig& config, const StudyResult& result)
{
    if (!has(config.integrators, Integrator::SemiImplicitEuler))
        return "";
    // The bounce findings are a single particle's (its shadow energy, the mirror's gain): a
    // system's energy is spread over modes the bounces do not speak for.
    if (anyCollision(result) && !result.followsSystem)
        if (std::string bounces = semiImplicitEulerBounces(config, result); !bounces.empty())
            return bounces;
    const auto rows = rowsOf(config, result, Integrator::SemiImplicitEuler, distinctResponses(config, result).front());
    if (rows.empty())
        return "";
    const auto exact = firstExact(config);
    if (!exact || exact->kind() != ExactSolution::Kind::Oscillator)
        return fmt::format("**Semi-implicit Euler.** {}\n\n",
                           endClausesByResponse(config, result, Integrator::SemiImplicitEuler));
    // Symplectic only below its stability limit: past it the energy grows geometrically.
    std::vector<const ParticleResult*> stable, unstable;
    for (const auto* r : rows)
        (belowStabilityLimit(result, *r) ? stable : unstable).push_back(r);
    std::string text = "**Semi-implicit Euler.** ";
    if (!stable.empty())
        text += fmt::format("Its energy after {} s is {}: on the undamped spring it is symplectic, it keeps a shadow "
                            "energy close to the true one, so its error swings but does not grow as forward Euler's "
                            "does.",
                            config.duration, endRatios(stable));
    if (!unstable.empty())
        text += fmt::format("{}Above {} its energy grows without bound: {}.", stable.empty() ? "" : " ",
                            stabilityLimitText(result, Integrator::SemiImplicitEuler),
                            endClauses(unstable, config.duration, result.lessSourceWork));
    return text + "\n\n";
}

std::string exactWithExactImpacts(const StudyConfig& config, const StudyResult& result, Integrator integrator)
{
    if (!has(config.integrators, integrator) || !has(config.collisions, CollisionResponse::Exact))
        return "";
    double period = 0, apex = 0;
    std::vector<double> dts;
    for (const auto* r : rowsOf(config, result, integrator, CollisionResponse::Exact))
        if (!std::isnan(r->periodError) && !std::isnan(r->apexRatioLast)) {
            period = std::max(period, std::abs(r->periodError));
            apex = std::max(apex, std::abs(r->apexRatioLast - 1));
            dts.push_back(r->dt);
        }
    if (dts.empty() || period > 1e-6 || apex > 1e-6)
        return "";
    return fmt::format("**{} with exact impacts is exact.** Its bounce period is off by at most {:.1e} and its last "
                       "apex by at most {:.1e} (relative) {}: it integrates constant gravity exactly and the time of "
                       "impact adds no error.\n\n",
                       integratorName(integrator), period, apex, overDts(dts));
}

/// The largest dt up to which a run of this integrator ends within kKept of its start energy with
/// every response, each smaller dt too; 0 if not at the smallest.
constexpr double kKept = 0.01;
double keptUpTo(const StudyConfig& config, const StudyResult& result, Integrator integrator)
{
    double largest = 0.0;
    for (double dt : config.dts) {
        for (CollisionResponse c : distinctResponses(config, result)) {
            const ParticleResult* r = findRun(result, integrator, c, dt);
            if (!r || !std::isnan(r->blewUpAt) || !(std::abs(r->energyRatioEnd - 1.0) <= kKept))
                return largest;
        }
        largest = dt;
    }
    return largest;
}

/// Where neither an exact solution nor a system's survival speaks for the scene (a ball in a
/// dryer's jet): the four methods side by side, by the largest step each keeps the energy at.
std::string energyKeptUpTo(const StudyConfig& config, const StudyResult& result)
{
    if (firstExact(config) || result.followsSystem || config.integrators.size() < 2 || config.dts.size() < 2)
        return "";
    std::vector<std::pair<double, std::vector<std::string>>> byDt; // in the order first met
    for (Integrator m : config.integrators) {
        const double dt = keptUpTo(config, result, m);
        const auto same = std::find_if(byDt.begin(), byDt.end(), [&](const auto& g) { return g.first == dt; });
        (same != byDt.end() ? same->second : byDt.emplace_back(dt, std::vector<std::string>{}).second)
            .emplace_back(integratorName(m));
    }
    if (std::all_of(byDt.begin(), byDt.end(), [](const auto& g) { return g.first == 0.0; }))
        return "";
    std::string groups; // "a and b up to dt = 0.005; c up to dt = 0.05"
    for (const auto& [dt, names] : byDt)
        groups += (groups.empty() ? "" : "; ") + (dt > 0.0 ? fmt::format("{} up to dt = {}", listText(names), dt)
                                                           : fmt::format("{} at no dt given", listText(names)));
    return fmt::format("**The largest step that keeps the energy.** Within {:g}% of the start after {} s{}, with {}: "
                       "{}.\n\n",
                       100 * kKept, config.duration, result.lessSourceWork ? " (less the dryer's work)" : "",
                       distinctResponses(config, result).size() > 1 ? "every response" : "its response", groups);
}

/// Whether a reflect run gained energy over its bounces where the mirror, not the step's
/// stability, can be the cause.
bool gainedByMirror(const StudyResult& result, const ParticleResult& run)
{
    return run.bounces > 0 && run.energyRatioEnd > 1.0 + 1e-6 && belowStabilityLimit(result, run);
}

/// The runs reflectGain quotes, of the first integrator that gained: the dt nearest 0.01 and
/// the largest, a typical step and the worst.
std::vector<const ParticleResult*> typicalAndWorst(const std::vector<const ParticleResult*>& rows)
{
    const auto typical = std::min_element(rows.begin(), rows.end(), [](const auto* a, const auto* b) {
        return std::abs(std::log(a->dt / 0.01)) < std::abs(std::log(b->dt / 0.01));
    });
    std::vector<const ParticleResult*> shown{*typical};
    if (rows.back() != *typical)
        shown.push_back(rows.back());
    return shown;
}

/// Whether the second gaining integrator ended each shown run with the first's energy.
bool sameGain(const StudyResult& result, const std::vector<Integrator>& gaining,
              const std::vector<const ParticleResult*>& shown)
{
    if (gaining.size() != 2)
        return false;
    for (const auto* r : shown) {
        const auto* other = findRun(result, gaining[1], CollisionResponse::Reflect, r->dt);
        if (!other || std::abs(other->energyRatioEnd - r->energyRatioEnd) > 1e-6)
            return false;
    }
    return true;
}

/// "X ends at 1.0123 times the start at dt = 0.01 (9 bounces) ... after T s. " for each
/// gaining integrator, or once for both when they ended alike.
std::string gainFigures(const StudyConfig& config, const StudyResult& result, const std::vector<Integrator>& gaining,
                        const std::vector<const ParticleResult*>& shown, bool same)
{
    std::string text;
    for (std::size_t k = 0; k < gaining.size(); ++k) {
        if (k == 1 && same)
            break;
        std::string numbers;
        for (const auto* first : shown) {
            const auto* r = findRun(result, gaining[k], CollisionResponse::Reflect, first->dt);
            if (r && gainedByMirror(result, *r))
                numbers += fmt::format("{}{:.4f} times the start at dt = {} ({} bounces)", numbers.empty() ? "" : " and ",
                                       r->energyRatioEnd, r->dt, r->bounces);
        }
        const std::string subject = same ? "both end" : fmt::format("{} ends", integratorName(gaining[k]));
        if (!numbers.empty())
            text += fmt::format("{}{} at {} after {} s. ", k > 0 ? "With it " : "", subject, numbers, config.duration);
    }
    return text;
}

/// For the bounce, whose flight velocity Verlet and RK4 follow exactly: the measured gain per
/// bounce against the mirror's mean, |v| dt / h.
std::string mirrorAgainstPrediction(const ExactSolution& exact, const std::vector<const ParticleResult*>& shown)
{
    const double h = exact.height(), v = std::sqrt(2.0 * exact.gravity() * h);
    std::string measured, predicted;
    for (const auto* r : shown) {
        const std::string sep = measured.empty() ? "" : " and ";
        measured += fmt::format("{}{:.1f}% at dt = {}", sep, 100 * (std::pow(r->energyRatioEnd, 1.0 / double(r->bounces)) - 1),
                                r->dt);
        predicted += fmt::format("{}{:.1f}%", sep, 100 * v * r->dt / h);
    }
    return fmt::format(". Velocity Verlet and RK4 follow the flight under gravity exactly, so here the mirror is the "
                       "whole story: the measured gain per bounce, (E(end)/E(0))^(1/bounces) - 1, is {}, against "
                       "|v| dt / h = {} for the first impact speed |v| = √(2 g h) = {:.2f} m/s and drop height "
                       "h = {} m.\n\n",
                       measured, predicted, v, h);
}

/// The gain of an integrator exact in flight, with the reflect response: the response's own.
std::string reflectGain(const StudyConfig& config, const StudyResult& result)
{
    if (!has(config.collisions, CollisionResponse::Reflect) || !anyCollision(result) || result.followsSystem ||
        !elasticBouncesUnderGravity(config))
        return "";
    std::vector<Integrator> gaining;
    std::vector<const ParticleResult*> shown; // of the first gaining integrator
    for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4}) {
        if (!has(config.integrators, integrator))
            continue;
        std::vector<const ParticleResult*> rows;
        for (const auto* r : rowsOf(config, result, integrator, CollisionResponse::Reflect))
            if (gainedByMirror(result, *r))
                rows.push_back(r);
        if (rows.empty())
            continue;
        if (gaining.empty())
            shown = typicalAndWorst(rows);
        gaining.push_back(integrator);
    }
    if (gaining.empty())
        return "";
    const bool same = sameGain(result, gaining, shown);
    std::string who = std::string(integratorName(gaining[0]));
    if (gaining.size() == 2)
        who += fmt::format(" and {}", integratorName(gaining[1]));
    std::string text = fmt::format("**{} {} energy with `reflect`.** With the `reflect` response ", who,
                                   gaining.size() == 2 ? "gain" : "gains");
    text += gainFigures(config, result, gaining, shown, same);
    // A step that ends a depth d below the floor is mirrored to d above it with its velocity
    // reversed; the time spent below is not given back, so the bounce starts at height d with
    // the end-of-step speed, v^2 = v_c^2 + 2 g d: the energy grows by 2 m g d, the next apex by
    // 2 d. d is spread over [0, |v| dt), so the mean gain is m g |v| dt a bounce.
    text += "The mirror adds it, not the integrator: a step that ends a depth d below the floor is put d above it "
            "with its velocity reversed, but the time it spent below the surface is not given back, so the bounce "
            "starts at height d with the speed it had at the end of the step, larger than the speed at contact "
            "(v² = v_c² + 2 g d). Each bounce adds 2 m g d, with d anywhere from 0 to |v| dt: about m g |v| dt on "
            "average, for any integrator";
    const auto exact = firstExact(config);
    if (!exact || exact->kind() != ExactSolution::Kind::Bounce)
        return text + ".\n\n";
    return text + mirrorAgainstPrediction(*exact, shown);
}

/// "none of the dt given is" or "of the dt given only 0.01 is", for the fit's points.
std::string inRange(const std::vector<double>& fitted)
{
    return fitted.empty() ? std::string("none of the dt given is")
                          : fmt::format("of the dt given only {} is", fitted.front());
}

std::string orders(const StudyResult& result)
{
    if (result.orders.empty())
        return "";
    std::vector<std::string> measured;
    std::vector<const OrderResult*> missing;
    for (const auto& o : result.orders) {
        if (std::isnan(o.measured))
            missing.push_back(&o);
        else
            measured.push_back(fmt::format("{} {:.2f} (expected {})", integratorName(o.integrator), o.measured, o.expected));
    }
    std::string text = "**Orders of accuracy** measured on the harmonic oscillator: ";
    for (std::size_t i = 0; i < measured.size(); ++i)
        text += measured[i] + (i + 1 < measured.size() ? "; " : ". Each halving of dt divides the error by 2 to the order.");
    if (missing.empty())
        return text + "\n";
    const bool alike = std::all_of(missing.begin(), missing.end(), [&](const OrderResult* o) { return o->fitted == missing.front()->fitted; });
    std::string why;
    if (alike) {
        why = inRange(missing.front()->fitted);
    } else {
        for (const OrderResult* o : missing)
            why += fmt::format("{}for {} {}", why.empty() ? "" : "; ", integratorName(o->integrator), inRange(o->fitted));
    }
    std::string names;
    for (const OrderResult* o : missing)
        names += fmt::format("{}{}", names.empty() ? "" : ", ", integratorName(o->integrator));
    const std::string rule = fmt::format("an order is the slope of log(error) against log(dt) and needs at least two "
                                         "dt in the asymptotic range, dt ≤ {} s with an error above rounding ({:g} m), "
                                         "and {}",
                                         kOrderMaxDt, kOrderRoundingError, why);
    if (measured.empty())
        return fmt::format("**Orders of accuracy** on the harmonic oscillator are not measured: {}.\n", rule);
    text += fmt::format(" {} {} no order: {}{}.", names, missing.size() > 1 ? "have" : "has", rule,
                        missing.size() > 1 && alike ? " for them" : "");
    return text + "\n";
}

} // namespace

const ParticleResult* findRun(const StudyResult& result, Integrator integrator, CollisionResponse collision, double dt)
{
    for (const auto& r : result.runs)
        if (r.integrator == integrator && r.collision == collision && r.dt == dt)
            return &r;
    return nullptr;
}

bool anyCollision(const StudyResult& result)
{
    return std::any_of(result.runs.begin(), result.runs.end(), [](const ParticleResult& r) { return r.bounces > 0; });
}

std::vector<CollisionResponse> distinctResponses(const StudyConfig& config, const StudyResult& result)
{
    if (config.collisions.empty())
        return config.collisions;
    if (!anyCollision(result))
        return {config.collisions.front()};
    if (!result.exactActsAsReflect || !has(config.collisions, CollisionResponse::Reflect))
        return config.collisions;
    std::vector<CollisionResponse> distinct;
    for (CollisionResponse c : config.collisions)
        if (c != CollisionResponse::Exact)
            distinct.push_back(c);
    return distinct;
}

bool exactShownAsReflect(const StudyConfig& config, const StudyResult& result)
{
    return anyCollision(result) && result.exactActsAsReflect && has(config.collisions, CollisionResponse::Exact) &&
           has(config.collisions, CollisionResponse::Reflect);
}

std::string describeDts(const std::vector<double>& dts)
{
    if (dts.size() == 1)
        return fmt::format("dt = {} s", dts.front());
    if (dts.size() == 2)
        return fmt::format("dt = {} and {} s", dts.front(), dts.back());
    return fmt::format("dt from {} to {} s ({} values)", dts.front(), dts.back(), dts.size());
}

std::string orderText(const OrderResult& order)
{
    return std::isnan(order.measured) ? "not measured" : fmt::format("{:.2f}", order.measured);
}

std::string ratioText(double ratio)
{
    return std::abs(ratio) < 1e4 ? fmt::format("{:.4f}", ratio) : fmt::format("{:.4g}", ratio);
}

std::optional<ExactSolution> firstExact(const StudyConfig& config)
{
    const World& world = config.scene.world;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed())
            return ExactSolution::find(world, i);
    return std::nullopt;
}

std::string listText(const std::vector<std::string>& parts)
{
    std::string text;
    for (std::size_t i = 0; i < parts.size(); ++i)
        text += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
    return text;
}

std::string findings(const StudyConfig& config, const StudyResult& result)
{
    return nothingCollides(config, result) + exactAsReflect(config, result) + survivors(config, result) +
           forwardEuler(config, result) + semiImplicitEuler(config, result) + energyKeptUpTo(config, result) +
           exactWithExactImpacts(config, result, Integrator::VelocityVerlet) +
           exactWithExactImpacts(config, result, Integrator::RK4) + reflectGain(config, result) + orders(result);
}

} // namespace pba::study
