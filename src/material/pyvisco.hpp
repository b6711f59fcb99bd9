#pragma once
// pyvisco's Prony series CSV (NREL/pyvisco, out.to_csv of a fit's df_terms):
// a header row naming the columns (an optional index column, tau_i, alpha_i,
// E_0 or G_0, E_i or G_i), a second row of units, then one term a row. The
// alpha_i are normalised by the instantaneous modulus E_0 (G_0), as Abaqus's
// g_i: G_i = alpha_i G0, G = G0 (1 - sum alpha_i); E_0 maps to G0 by
// G = E / (4 (1 - nu^2)) with nu = 0.5 (pyvisco fits an incompressible
// solid's tension modulus: G0 = E_0 / 3).
#include <string>

#include "material/card.hpp"

namespace mdrmap::material {

/// Whether `text` is a pyvisco CSV: its first line names tau_i and alpha_i.
bool is_pyvisco_csv(const std::string& text);

/// The material of pyvisco's CSV `text`, read from `path` (for messages).
/// Throws InvalidInput("material") with "FILE:LINE: " where a line is at fault.
MaterialCard read_pyvisco(const std::string& path, const std::string& text);

} // namespace mdrmap::material
