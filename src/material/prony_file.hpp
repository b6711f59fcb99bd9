#pragma once
// --prony-file FILE: a relaxation spectrum's terms from a CSV file whose
// header names its columns, in any order: tau and one modulus column,
//   G   absolute shear moduli,
//   E   absolute Young's moduli, G = E / (4 (1 - nu^2)) (docs/master-curve.md;
//       nu from --nu, 0.5 by default: G = E / 3),
//   g   moduli normalised by the instantaneous (glassy) modulus G0, given in
//       the file by a comment line `# G0 = VALUE` (or `# E0 = VALUE`, mapped
//       like E); then G_k = g_k G0 and the long-term modulus is
//       G = G0 (1 - sum g_k), the Abaqus and pyvisco convention.
// Blank lines and other '#' comments are skipped. A message names the file,
// the line and, for a value, the column.
#include <optional>
#include <string>
#include <vector>

#include "core/model/rheology.hpp"

namespace mdrmap::material {

/// What a spectrum file gives.
struct SpectrumFile {
  std::vector<Branch> branches; ///< absolute shear moduli and times
  std::optional<double> G;      ///< long-term modulus G0 (1 - sum g_k): a file of column g
  bool uses_nu = false;         ///< a Young's modulus (E or E0) was mapped with nu
};

/// Reads `path` (a regular file of at most 1 MiB); `nu` maps Young's moduli.
/// Throws InvalidInput("prony-file") with "FILE:LINE: " where a line is at fault.
SpectrumFile read_prony_file(const std::string& path, double nu);

} // namespace mdrmap::material
