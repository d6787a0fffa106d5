/// wheel_rail_contact: creep forces of a wheel-rail contact, one time step per call.
/// The one header a user includes: the model interface and its parameters, scenario files, Hertz
/// geometry and the tables shipped inside the library. Example (doc/method.md for the models):
///
///   wheel_rail_contact::ContactParameters p;  // defaults: a wheel-rail contact at 80 kN
///   p.model = "nss";
///   auto model = wheel_rail_contact::makeContactModel(p);
///   wheel_rail_contact::StepInput in;
///   in.dt = 1e-3; in.V = 20.0; in.xi = 0.002; in.fz = 8e4;
///   const wheel_rail_contact::StepOutput out = model->step(in);  // out.fx, out.fy, out.mz [N, N
///   m]
#pragma once

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/contact_parameters.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"
#include "wheel_rail_contact/scenario.hpp"
#include "wheel_rail_contact/shipped_tables.hpp"
