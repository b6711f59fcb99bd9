#pragma once
// [run] material = FILE: a study's material from an Abaqus card or pyvisco's
// CSV (material/card.hpp). The card gives the columns G, G1, tau1, ... (one
// value each, their option run.material) and, from its *TRS, the WLF
// constants of a temperature column; the study records the card's text
// (canonical(), the map's /provenance/material_card). A card beside [grid]
// G, Gk, tauk or [run] wlf is refused, naming both.
#include <string>
#include <vector>

#include "study/config.hpp"

namespace mdrmap::study::detail {

/// Reads the card `value` (relative to base_dir unless absolute; "" is the
/// working directory) into `c.run` (path, text, the card's WLF) and returns
/// its columns. Replaces an earlier card and its WLF. Throws
/// ConfigError("run.material") without location.
std::vector<Axis> read_material_columns(StudyConfig& c, const std::string& value,
                                        const std::string& base_dir);

/// Refuses `a` beside the card's columns: a G, Gk or tauk of the study's own
/// beside a card, or a card's beside the study's own. Throws ConfigError(a.option()).
void refuse_beside_card(const StudyConfig& c, const Axis& a);

/// Refuses [run] wlf beside the card's *TRS. Throws ConfigError("run.wlf").
void refuse_wlf_beside_card(const RunSettings& r);

} // namespace mdrmap::study::detail
