// A combined-creepage step on a patch's strips, as the true-patch and auto tests drive a model
// (tests only).
#pragma once

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/fastsim/patch_shape.hpp"

namespace wheel_rail_contact {

/// xi 2e-4, eta 3e-4, spin 0.3 1/m at 20 m/s, dt 0.1 ms: all three creepages and partial slip on
/// a 10 kN patch, on `shape`'s strips (nullptr: the ellipse a, b).
inline StepInput combinedCreepageStep(const PatchShape* shape, double a, double b, double fz) {
  StepInput in;
  in.dt = 1e-4;
  in.V = 20.0;
  in.xi = 2e-4;
  in.eta = 3e-4;
  in.phi = 0.3;
  in.fz = fz;
  in.a = a;
  in.b = b;
  in.shape = shape;
  return in;
}

}  // namespace wheel_rail_contact
