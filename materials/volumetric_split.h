// The shear part of a law: W_rest(C) = W(C) - U(J), with U the law's volumetric part
// (HyperelasticLaw::volumetric), J = sqrt(det C). The solver's nodal-pressure tet4
// (solver_check/nodal_pressure.h) integrates W_rest per element and U per node.
//   S_rest  = S  - J U'(J) C^-1                                       (S_vol = 2 dU/dC)
//   CC_rest = CC - [J (U' + J U'') C^-1 (x) C^-1 - 2 J U' C^-1 (.) C^-1]   (CC_vol = 2 dS_vol/dC)
// with (.) the symmetrised product of materials/tensor4.h. The subtraction costs about
// log10(lambda / mu) digits (2.5 at nu = 0.4985), far below the solver's tolerances.
#pragma once

#include "materials/hyperelastic_law.h"

#include <memory>

namespace tissuemesh {

/// W - U(J) of `full` as a law of its own (its volumetric() is zero). References `full`, which
/// must outlive it.
std::unique_ptr<HyperelasticLaw> make_shear_part(const HyperelasticLaw& full);

}  // namespace tissuemesh
