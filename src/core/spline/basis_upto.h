// Basis functions with their first and second derivatives, fast on uniform spans (defined in
// basis.cpp beside eval_basis(), whose span search it shares).
#pragma once

#include "basis.h"

namespace sfit {

/// The same values as eval_basis_derivatives() for nderiv 0 ... 2, computed faster where the
/// knots around t are uniform (every span of a periodic curve, the inner spans of an open
/// one): ders[0 .. degree] are eval_basis()'s values bit for bit, and the derivatives are
/// differences of the lower-degree basis (N'_{i,p} = N_{i,p-1} - N_{i+1,p-1} on unit
/// spacing, N'' likewise from degree p - 2). Near a clamped end the derivatives are
/// eval_basis_derivatives()'s. `ders` must hold (nderiv + 1) * (degree + 1) values.
int eval_basis_upto(int degree, int count, bool periodic, double t, int nderiv, double* ders);

}  // namespace sfit
