#pragma once
// The integrator study's findings in words, each sentence stated from the measured numbers and
// only where they bear it out: a report must read true for any scene and any set of dt.
#include <optional>
#include <string>
#include <vector>

#include "exact_solution.hpp"
#include "study.hpp"

namespace pba::study {

/// The first moving particle's result for one configuration, or null.
const ParticleResult* findRun(const StudyResult& result, Integrator integrator, CollisionResponse collision, double dt);

/// True if some particle met a surface in some run. Otherwise the collision responses never
/// acted, and every response gives the same numbers.
bool anyCollision(const StudyResult& result);

/// The collision responses whose results differ: all those studied, only the first when
/// nothing collided, and without `exact` beside `reflect` when every moving body is coupled
/// (then `exact` acts as `reflect`).
std::vector<CollisionResponse> distinctResponses(const StudyConfig& config, const StudyResult& result);

/// Whether `exact` was studied but is shown as `reflect`, its runs being the same (see
/// StudyResult::exactActsAsReflect).
bool exactShownAsReflect(const StudyConfig& config, const StudyResult& result);

/// "dt = 0.3 s", "dt = 0.01 and 0.05 s", "dt from 0.0005 to 0.1 s (8 values)".
std::string describeDts(const std::vector<double>& dts);

/// The measured order as "1.02", or "not measured" when fewer than two dt were in the
/// asymptotic range.
std::string orderText(const OrderResult& order);

/// An energy ratio to four decimals ("1.0123"), or to four significant digits from 10^4 up
/// ("9.504e+49"): a run past its stability limit ends many orders of magnitude up.
std::string ratioText(double ratio);

/// The exact solution of the first moving particle, the one the report follows.
std::optional<ExactSolution> firstExact(const StudyConfig& config);

/// "a", "a and b", "a, b and c".
std::string listText(const std::vector<std::string>& parts);

/// The findings, one paragraph each, in Markdown.
std::string findings(const StudyConfig& config, const StudyResult& result);

} // namespace pba::study
