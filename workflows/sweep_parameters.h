// What a sweep parameter changes in a model (docs/sweeps.md, "Parameters"). Values in SI.
//
//   materials.<tissue>.mu       initial shear modulus, Pa: the law's shear parameters scaled
//                               together (neo-Hookean C10 = mu/2; Mooney-Rivlin C10 and C01 keep
//                               their ratio; Ogden mu_i keep theirs); K unchanged
//   materials.<tissue>.K        bulk modulus, Pa
//   materials.<tissue>.E        Young's modulus, Pa, with Poisson's ratio kept
//   materials.<tissue>.nu       Poisson's ratio, with Young's modulus kept (>= 0.5 is refused)
//   materials.<tissue>.C10, C01 Mooney-Rivlin constants, Pa (mu = 2 (C10 + C01))
//   materials.<tissue>.density  kg/m^3
//   model.gravity.acceleration  magnitude of gravity, m/s^2, direction kept
#pragma once

#include "core/model.h"
#include "core/quantity.h"

#include <string>

namespace tissuemesh {

/// The unit kind of a parameter path's values; false for a dimensionless one (nu). InputError
/// for a path that names no known parameter (listing the forms).
bool parameter_dimension(const std::string& path, Dimension& dimension);

/// Checks that `path` names a parameter of `model` (its tissue exists, its law has the constant).
/// InputError naming the path, the tissue list or the law.
void check_parameter_path(const Model& model, const std::string& path);

/// Sets the parameter in `model`. InputError naming the path and value when the result is not a
/// physical material (mu, K, E or a constant <= 0, nu outside (-1, 0.5), density outside
/// [100, 5000] kg/m^3, a non-finite value).
void apply_parameter(Model& model, const std::string& path, double value);

}  // namespace tissuemesh
