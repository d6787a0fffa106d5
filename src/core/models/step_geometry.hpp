/// A step's own contact geometry and friction (StepInput::a, b, mu) where given, else the
/// parameters'. Units as in contact_model.hpp.
#pragma once

#include <cmath>

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

/// The patch of a screened step: (in.a, in.b) with Hertz's peak pressure for in.fz where given,
/// else ref's Hertz scaling of the load.
inline HertzEllipse stepPatch(const StepInput& in, const ReferencePatch& ref) {
  if (in.a == 0.0) return ref.at(in.fz);
  HertzEllipse h;
  h.a = in.a;
  h.b = in.b;
  h.p0 = 3.0 * in.fz / (2.0 * M_PI * h.a * h.b);
  return h;
}

/// The step's friction coefficient: in.mu where given, else the parameter's.
inline double stepMu(const StepInput& in, double mu) {
  return in.mu != 0.0 ? in.mu : mu;
}

/// The step's a/b: in.a / in.b where given, else the reference's (a0/b0 for every load).
inline double stepAOverB(const StepInput& in, double referenceAOverB) {
  return in.a != 0.0 ? in.a / in.b : referenceAOverB;
}

}  // namespace wheel_rail_contact
