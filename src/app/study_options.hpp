#pragma once
// The options of `mdrmap study` that override a key of the study's config:
// declared once, read by the command line (app/study_cmd.cpp) and listed by
// the help texts (app/study_help.cpp).
#include <string>
#include <vector>

namespace mdrmap::app {

struct StudyOverride {
  std::string option;      ///< without dashes, e.g. "tau"
  std::string key;         ///< the config key it sets, e.g. "grid.tau"
  std::string placeholder; ///< its value in the help, e.g. "SPEC"
};

/// The override options and the keys they set: the run's, the seed's step,
/// the temperature and its WLF constants, every case parameter of the core's
/// table as a grid column (--d, --F0, --R, --tau, --aT, --v, ...; G stays the
/// seed's [run] G; an old spelling, --FN, sets grid.FN, which the config reads
/// as its parameter) and a spectrum's terms (--G1, --tau1, ..., --G32, --tau32).
const std::vector<StudyOverride>& study_overrides();

} // namespace mdrmap::app
