// The samples of a sweep design (docs/sweeps.md, "Designs"). Every parameter is a dimension of the
// design and maps a unit coordinate u in [0, 1] to a value: a range linearly (lo + u (hi - lo)) or
// geometrically on a log scale; a values list by index floor(u k) (clamped). A tied parameter's
// coordinate gives its ratio, and its value is that ratio times its target's value.
//
//   grid   every combination of `levels` points per range (u = i / (levels - 1); one level: the
//          middle) or of a list's values; the first parameter varies slowest
//   lhs    Latin hypercube (McKay, Beckman & Conover 1979): `samples` points, each parameter's
//          [0, 1] cut into `samples` strata, one point per stratum at a uniform position, strata
//          paired by seeded random permutations (std::mt19937_64)
//   sobol  Saltelli's design for Sobol' indices: base N = `samples` points of a 2d-dimensional
//          Sobol' sequence (sobol_sequence.h; A = first d coordinates, B = last d), and per point
//          A, B and AB_1..AB_d (A with coordinate j from B): N (d + 2) samples, in that order
//   table  the rows of a CSV file: a header naming every parameter's path (any order), one row
//          per sample in SI units (a tied parameter: its ratio)
#pragma once

#include "workflows/sweep_spec.h"

#include <string>
#include <vector>

namespace tissuemesh {

struct SweepSample {
  int index = 0;               ///< 0-based position in the design
  std::vector<double> values;  ///< one per spec parameter (file order), SI
  std::vector<double> unit;    ///< one per parameter: its coordinate in [0, 1] (for distances)
  std::string group;           ///< sobol: "A", "B" or "AB<j>" (1-based free parameter); else empty
  int base = -1;               ///< sobol: the base point this sample belongs to (0..N-1)
};

/// The design's samples. InputError for a table that cannot be read (naming file and line), lacks
/// a free parameter's column or holds a non-number; a grid or design over 1,000,000 samples; a
/// sobol design over more than 10 free parameters.
std::vector<SweepSample> make_design(const SweepSpec& spec);

}  // namespace tissuemesh
