#pragma once
// The studies of mdrmap_spectrum_physics, one per file; each prints its table
// to stdout and writes its CSV file into o.out (docs/design.md, "What the
// spectra do").
#include "common.hpp"

namespace mdrmap::physics {

void study_sls(const Options& o);          ///< 1. sls.cpp: the SLS's friction maximum under load
void study_width(const Options& o);        ///< 2. width.cpp: width of the friction-velocity curve
void study_healing(const Options& o);      ///< 3. healing.cpp: slide-hold-slide at fixed depth
void study_direct(const Options& o);       ///< 4. direct.cpp: the direct effect without a dashpot
void study_creep(const Options& o);        ///< 5. creep.cpp: Lee-Radok creep, checked
void study_healing_load(const Options& o); ///< 6. healing_load.cpp: slide-hold-slide under load
void study_profiles(const Options& o);     ///< 7. profiles.cpp: cone and power law on Kelvin

} // namespace mdrmap::physics
