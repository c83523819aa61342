#pragma once
// The panel's sections about the scene's bodies (viewer_rows.cpp), apart from its time, view and
// blow dryer sections (viewer_panel.cpp).
#include "viewer_state.hpp"

namespace pba::app {


/// A row per group: a rope or cloth as one (its count, total energy, one integrator menu for the
/// system), every other body with its own controls; the scene's energy and momentum above them.
void bodiesSection(ViewerState& state);

/// The first groups' plots, each line in its group's colour.
void plotsSection(const ViewerState& state);

} // namespace pba::app
