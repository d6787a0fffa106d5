/// A step's own contact geometry and friction (StepInput::a, b, mu) where given, else the
/// parameters'. Units as in contact_model.hpp.
#pragma once

#include <algorithm>
#include <cmath>

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

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

/// The a/b Kalker's coefficients and chi are taken at: the step's (in.a / in.b where given, else
/// the reference's, a0/b0 for every load), held in Kalker's table [0.1, 10] for a shape's
/// equivalent ellipse (StepInput::shape), the only step whose a/b may lie beyond it.
inline double stepAOverB(const StepInput& in, double referenceAOverB) {
  if (in.a == 0.0) return referenceAOverB;
  const double ab = in.a / in.b;
  return in.shape ? std::min(std::max(ab, kKalkerMinAOverB), kKalkerMaxAOverB) : ab;
}

/// Whether a shape's a/b lies beyond Kalker's table (stepAOverB held it at the table's end).
inline bool aOverBHeld(const StepInput& in) {
  return in.shape && stepAOverB(in, 1.0) != in.a / in.b;
}

/// The message of a step on a shape whose a/b was held.
constexpr const char* kAOverBHeldMessage =
    "the patch's equivalent a/b lies beyond Kalker's table [0.1, 10]: flexibilities and chi at "
    "the table's end";

}  // namespace wheel_rail_contact
