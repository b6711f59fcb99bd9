#pragma once
// --material FILE: a material from an Abaqus input's material block
// (docs/master-curve.md, DESIGN section 9):
//   *ELASTIC [, MODULI=LONG TERM | INSTANTANEOUS]   E, nu
//   *VISCOELASTIC, TIME=PRONY                       g_i, k_i, tau_i (one term a line)
//   *TRS, DEFINITION=WLF                            Tref, C1, C2
// The Prony moduli are normalised by the instantaneous modulus G0:
// G_i = g_i G0 and the long-term modulus G = G0 (1 - sum g_i); E maps to a
// shear modulus by G = E / (4 (1 - nu^2)) (LONG TERM: E gives G, INSTANTANEOUS:
// G0). Bulk terms k_i do not enter an incompressible foundation: nonzero ones
// are reported in `notes`. *MATERIAL and comment lines (**) are skipped; any
// other keyword or option is refused in one line naming the file and line.
#include <optional>
#include <string>
#include <vector>

#include "core/model/rheology.hpp"
#include "core/model/temperature.hpp"

namespace mdrmap::material {

struct MaterialCard {
  double G = 0.0;                 ///< long-term shear modulus
  std::vector<Branch> branches;   ///< absolute shear moduli g_i G0 and times tau_i
  std::optional<UnitWlf> wlf;     ///< *TRS, DEFINITION=WLF
  std::vector<std::string> notes; ///< what was read but does not enter (nonzero k_i)
  std::string text;               ///< the file's text as read (what a study's map records)
};

/// Reads `path` (a regular file of at most 1 MiB). Throws
/// InvalidInput("material") with "FILE:LINE: " where a line is at fault.
MaterialCard read_material(const std::string& path);

} // namespace mdrmap::material
