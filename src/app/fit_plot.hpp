#pragma once
// `mdrmap fit --plot FILE.png`: the figure of data, fit and residuals is the
// Python package's tool (python3 -m mdrmap plot_fit, matplotlib), run on the
// fit's JSON. The package is looked for next to the program (the build
// tree's <build>/python, an install's <prefix>/<python dir>) and then where
// the interpreter finds it.
#include <string>

namespace mdrmap::app {

/// Refuses (InvalidInput("plot")) a plot this program cannot draw (built
/// without Python) or a FILE in a directory that does not exist.
void check_plot(const std::string& png);

/// Runs the tool on `json`, writing `png`. Throws std::runtime_error when it
/// fails (its own line on stderr says why).
void draw_plot(const std::string& json, const std::string& png);

} // namespace mdrmap::app
