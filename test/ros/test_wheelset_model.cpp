// The closed-loop demo's wheelset model (src/demo/wheelset_model.hpp), without ROS or a contact
// model: creepage signs, the held-force integration, the figure fits, and the closed loop with a
// linear creep law against Klingel's wavelength and the continuous-time frequency response.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "../../src/demo/wheelset_model.hpp"

using namespace wheel_rail_contact::demo;

namespace {

/// Linear creep law (Kalker's linear theory, no spin): the contact a linear simulator would use.
struct LinearContact {
  double f11 = 8e6, f22 = 7e6;
  ContactForces operator()(const ContactKinematics& k) const {
    return {-f11 * k.xi, -f22 * k.eta, 0.0};
  }
};

struct LoopRun {
  std::vector<double> t, y, fxLeft;
};

LoopRun closedLoop(const WheelsetParameters& p, const Irregularity& track, double V, double dt,
                   double duration, double y0) {
  LinearContact contact;
  WheelsetState s;
  s.y = y0;
  LoopRun r;
  const long steps = std::lround(duration / dt);
  for (long k = 0; k <= steps; ++k) {
    ContactKinematics kl, kr;
    wheelsetCreepages(p, track, s, V, &kl, &kr);
    const ContactForces fl = contact(kl), fr = contact(kr);
    r.t.push_back(static_cast<double>(k) * dt);
    r.y.push_back(s.y);
    r.fxLeft.push_back(fl.fx);
    advanceWheelset(p, fl, fr, V, dt, &s);
  }
  return r;
}

}  // namespace

TEST(WheelsetModel, CreepageSignsFollowTheVehicleAxes) {
  WheelsetParameters p;
  p.contactAngle = 0.05;
  Irregularity none;
  WheelsetState s;
  s.y = 1e-3;  // to the left: the left wheel rolls on a larger radius and runs ahead (xi < 0)
  ContactKinematics l, r;
  wheelsetCreepages(p, none, s, 20.0, &l, &r);
  EXPECT_NEAR(l.xi, -p.conicity * 1e-3 / p.r0, 1e-15);
  EXPECT_NEAR(r.xi, p.conicity * 1e-3 / p.r0, 1e-15);
  EXPECT_EQ(l.fz, p.wheelLoad);
  s = WheelsetState();
  s.vy = 0.2;  // moving left: both contacts slide left, eta > 0 on both (same axes)
  s.psi = 0.001;
  s.vpsi = 0.5;
  wheelsetCreepages(p, none, s, 20.0, &l, &r);
  EXPECT_NEAR(l.eta, 0.2 / 20.0 - 0.001, 1e-15);
  EXPECT_EQ(l.eta, r.eta);
  EXPECT_NEAR(l.xi, -p.l0 * 0.5 / 20.0, 1e-15);  // yawing left moves the left wheel back
  EXPECT_NEAR(l.phi, 0.5 / 20.0 - 0.05 / p.r0, 1e-15);
  EXPECT_NEAR(r.phi, 0.5 / 20.0 + 0.05 / p.r0, 1e-15);
  // A track shifted left by as much as the wheelset leaves no rolling-radius difference.
  Irregularity track;
  track.amplitude = 1e-3;
  track.wavelength = 4.0;
  s = WheelsetState();
  s.x = 1.0;  // a quarter wavelength: y_t = amplitude
  s.y = 1e-3;
  wheelsetCreepages(p, track, s, 20.0, &l, &r);
  EXPECT_NEAR(l.xi, 0.0, 1e-15);
}

TEST(WheelsetModel, HeldForceIntegrationIsExactForTheSuspension) {
  // m q'' + k q = f from q = 1 mm, v = 0: q(t) = f/k + (q0 - f/k) cos(wt), in 1000 steps.
  const double m = 1800, k = 2e6, f = 500, w = std::sqrt(k / m), dt = 1e-4;
  double q = 1e-3, v = 0.0;
  for (int i = 0; i < 1000; ++i) detail::advanceOscillator(m, k, f, dt, &q, &v);
  EXPECT_NEAR(q, f / k + (1e-3 - f / k) * std::cos(w * 0.1), 1e-15);
  EXPECT_NEAR(v, -(1e-3 - f / k) * w * std::sin(w * 0.1), 1e-12);
  q = 0.0, v = 1.0;  // k = 0: uniform acceleration
  detail::advanceOscillator(m, 0.0, f, 0.5, &q, &v);
  EXPECT_NEAR(q, 0.5 + 0.5 * f / m * 0.25, 1e-15);
}

TEST(WheelsetModel, FitsRecoverSyntheticSignals) {
  std::vector<double> t, v, h;
  const double f = 5.0, zeta = 0.07, wn = 2 * M_PI * f / std::sqrt(1 - zeta * zeta);
  for (int i = 0; i < 5000; ++i) {
    const double ti = i * 5e-4;
    t.push_back(ti);
    v.push_back(std::exp(-zeta * wn * ti) * std::cos(2 * M_PI * f * ti));
    // 100 Hz, amplitude 2, phase 0.7, on a drift and a slow 5 Hz oscillation
    h.push_back(2.0 * std::cos(2 * M_PI * 100 * ti + 0.7) + 0.3 + 0.4 * ti +
                0.5 * std::sin(2 * M_PI * 5 * ti));
  }
  const DecayFit d = fitDecay(t, v);
  ASSERT_TRUE(d.ok) << d.why;
  EXPECT_NEAR(d.frequency, f, 1e-3);
  EXPECT_NEAR(d.dampingRatio, zeta, 1e-3);
  const HarmonicFit hf = fitHarmonic(t, h, 100.0, 0.5);
  ASSERT_TRUE(hf.ok);
  EXPECT_NEAR(hf.amplitude, 2.0, 0.01);
  EXPECT_NEAR(hf.phase, 0.7, 0.01);
  EXPECT_FALSE(fitDecay({0, 1, 2}, {0, 1, 0}).ok);  // one peak: no fit, and it says so
}

TEST(WheelsetModel, FreeWheelsetAtLowSpeedRunsAtKlingelsWavelength) {
  WheelsetParameters p;
  p.lateralStiffness = 0.0;
  p.yawStiffness = 0.0;
  const double V = 2.0;
  const LoopRun r = closedLoop(p, Irregularity(), V, 1e-4, 25.0, 1e-3);
  const DecayFit d = fitDecay(r.t, r.y);
  ASSERT_TRUE(d.ok) << d.why;
  EXPECT_NEAR(V / d.frequency / klingelWavelength(p), 1.0, 0.01);
}

TEST(WheelsetModel, ForcedResponseMatchesTheContinuousTimeSolution) {
  // Linear creep law: the steady-state response to y_t = A e^{i w t} solves
  //   (m s^2 + k_y + 2 f22 s / V) y - 2 f22 psi = 0
  //   2 f11 l0 lambda / r0 y + (I s^2 + k_psi + 2 f11 l0^2 s / V) psi = 2 f11 l0 lambda / r0 A
  // and Fx_L = f11 (l0 s psi / V + lambda (y - A) / r0). The loop holds each force over dt, a
  // delay of dt/2: at dt = 10 us it is 0.2 degrees at 40 Hz.
  WheelsetParameters p;
  const LinearContact c;
  const double V = 20.0, L = 0.5, A = 1e-4, dt = 1e-5;
  Irregularity track;
  track.amplitude = A;
  track.wavelength = L;
  const LoopRun r = closedLoop(p, track, V, dt, 0.5, 0.0);
  const HarmonicFit fit = fitHarmonic(r.t, r.fxLeft, V / L, 0.25);
  ASSERT_TRUE(fit.ok);

  using cd = std::complex<double>;
  const cd s(0.0, 2 * M_PI * V / L);
  const cd a11 = p.mass * s * s + p.lateralStiffness + 2 * c.f22 * s / V, a12 = -2 * c.f22;
  const cd a21 = 2 * c.f11 * p.l0 * p.conicity / p.r0;
  const cd a22 = p.yawInertia * s * s + p.yawStiffness + 2 * c.f11 * p.l0 * p.l0 * s / V;
  const cd rhs2 = a21 * A;
  const cd det = a11 * a22 - a12 * a21;
  const cd y = -a12 * rhs2 / det, psi = a11 * rhs2 / det;
  // y_t = A sin(w x / V ...) = A cos(w t - pi/2): the reference is shifted by the same -pi/2.
  const cd fx =
      c.f11 * (p.l0 * s * psi / V + p.conicity * (y - A) / p.r0) * std::polar(1.0, -M_PI / 2);
  EXPECT_NEAR(fit.amplitude / std::abs(fx), 1.0, 0.005);
  EXPECT_NEAR(std::remainder(fit.phase - std::arg(fx), 2 * M_PI), 0.0, 0.01);
}

TEST(WheelsetModel, ValidateNamesTheParameter) {
  WheelsetParameters p;
  p.yawInertia = 0.0;
  try {
    validate(p);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("yaw_inertia:", 0), 0u) << e.what();
  }
  p = WheelsetParameters();
  p.lateralStiffness = std::nan("");
  EXPECT_THROW(validate(p), std::invalid_argument);
}
