// A user's program: one nss step through the installed library and its shipped chi table.
// Prints fx fy mz; exits non-zero unless the step is OK and its force finite and opposing xi.
#include <cmath>
#include <cstdio>

#include <wheel_rail_contact/wheel_rail_contact.hpp>

int main() {
  namespace wrc = wheel_rail_contact;
  wrc::ContactParameters p;  // a wheel-rail contact: a0 = 6 mm, b0 = 4 mm at fz0 = 80 kN
  p.model = "nss";
  auto model = wrc::makeContactModel(p);

  wrc::StepInput in;
  in.dt = 1e-3;   // s
  in.V = 20.0;    // m/s
  in.xi = 0.002;  // longitudinal creepage
  in.fz = 8e4;    // N
  const wrc::StepOutput out = model->step(in);

  std::printf("%s fx %.6g N fy %.6g N mz %.6g N m\n", wrc::toString(out.status), out.fx, out.fy,
              out.mz);
  const bool ok = out.status == wrc::StepStatus::kOk && std::isfinite(out.fx) && out.fx < 0.0;
  return ok ? 0 : 1;
}
