/// The closed-loop demo's vehicle: one wheelset (lateral displacement y, yaw psi) on tangent track,
/// tied by its primary suspension to a bogie frame that runs straight at constant speed V, with
/// linearised wheel-rail geometry (equivalent conicity) and a lateral track irregularity. ROS-free
/// and contact-model-free: it gives the creepages of the left and right contact, the simulator
/// asks any creep-force model for their forces and hands them back. Equations and parameters:
/// doc/wheelset_demo.md.
///
/// Axes (both contacts and the wheelset): vehicle-fixed, x forward (rolling direction), y to the
/// left, z up (REP 103). Both contacts report their creepages and forces in these same axes, so
/// the right wheel's lateral creepage and force have the same sign convention as the left one's
/// (positive to the left); the contact planes' tilt (contact angle) is neglected.
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace wheel_rail_contact {
namespace demo {

struct WheelsetParameters {
  double r0 = 0.46;               ///< nominal rolling radius [m]
  double l0 = 0.75;               ///< half distance between the contact points [m]
  double conicity = 0.2;          ///< equivalent conicity lambda_e [-]
  double mass = 1800.0;           ///< wheelset mass [kg]
  double yawInertia = 1100.0;     ///< wheelset yaw moment of inertia [kg m^2]
  double lateralStiffness = 2e6;  ///< primary lateral stiffness, both sides together [N/m]
  double yawStiffness = 1e7;      ///< primary yaw stiffness to the frame [N m/rad]
  double wheelLoad = 8e4;         ///< normal load on each wheel [N]
  double contactAngle = 0.0;      ///< gamma0: spin -/+ gamma0/r0 on the left/right wheel [rad]
};

/// Lateral alignment of the track: y_t(x) = amplitude sin(2 pi (x - start) / wavelength) for
/// start <= x <= start + cycles wavelength (cycles = 0: to the end), 0 elsewhere.
struct Irregularity {
  double amplitude = 0.0;   ///< [m]
  double wavelength = 1.0;  ///< [m]
  double start = 0.0;       ///< distance travelled where it begins [m]
  double cycles = 0.0;      ///< number of wavelengths; 0 = unbounded

  double lateral(double x) const {
    if (amplitude == 0.0 || x < start) return 0.0;
    if (cycles > 0.0 && x > start + cycles * wavelength) return 0.0;
    return amplitude * std::sin(2.0 * M_PI * (x - start) / wavelength);
  }
  /// dy_t/dx and d^2y_t/dx^2 (the track's local direction and curvature).
  double slope(double x) const {
    if (amplitude == 0.0 || x < start) return 0.0;
    if (cycles > 0.0 && x > start + cycles * wavelength) return 0.0;
    const double k = 2.0 * M_PI / wavelength;
    return amplitude * k * std::cos(k * (x - start));
  }
  double curvature(double x) const {
    const double k = 2.0 * M_PI / wavelength;
    return -k * k * lateral(x);
  }
};

struct WheelsetState {
  double x = 0.0;     ///< distance travelled [m]
  double y = 0.0;     ///< lateral displacement (to the left) [m]
  double psi = 0.0;   ///< yaw angle (about z up) [rad]
  double vy = 0.0;    ///< dy/dt [m/s]
  double vpsi = 0.0;  ///< dpsi/dt [rad/s]
};

/// Creepages and load of one contact, in the vehicle-fixed axes.
struct ContactKinematics {
  double xi = 0.0, eta = 0.0, phi = 0.0, fz = 0.0;
};

/// Creep forces on one wheel, in the vehicle-fixed axes (the package's sign: on the wheel).
struct ContactForces {
  double fx = 0.0, fy = 0.0, mz = 0.0;
};

/// Linearised creepages (Garg & Dukkipati 1984; Wickens 2003) of the left and right contact, with
/// the wheelset's displacement taken relative to the track, y_r = y - y_t(x):
///   xi_L,R = -/+ (l0 psi'/V + lambda_e y_r / r0)   (the left wheel rolls on r0 + lambda_e y_r)
///   eta_L = eta_R = y'/V - psi                      (the irregularity enters through y_r only)
///   phi_L,R = psi'/V -/+ gamma0 / r0
inline void wheelsetCreepages(const WheelsetParameters& p, const Irregularity& track,
                              const WheelsetState& s, double V, ContactKinematics* left,
                              ContactKinematics* right) {
  const double yr = s.y - track.lateral(s.x);
  const double longitudinal = p.l0 * s.vpsi / V + p.conicity * yr / p.r0;
  left->xi = -longitudinal;
  right->xi = longitudinal;
  left->eta = right->eta = s.vy / V - s.psi;
  left->phi = s.vpsi / V - p.contactAngle / p.r0;
  right->phi = s.vpsi / V + p.contactAngle / p.r0;
  left->fz = right->fz = p.wheelLoad;
}

namespace detail {
/// m q'' + k q = f with f held: exact over dt (k = 0: uniform acceleration).
inline void advanceOscillator(double m, double k, double f, double dt, double* q, double* v) {
  if (k <= 0.0) {
    *q += *v * dt + 0.5 * f / m * dt * dt;
    *v += f / m * dt;
    return;
  }
  const double w = std::sqrt(k / m), c = std::cos(w * dt), s = std::sin(w * dt);
  const double q0 = *q - f / k, v0 = *v;
  *q = f / k + q0 * c + v0 / w * s;
  *v = -q0 * w * s + v0 * c;
}
}  // namespace detail

/// One step of the equations of motion with the creep forces held over [t, t + dt]:
///   m y''   = F_yL + F_yR - k_y y
///   I psi'' = l0 (F_xR - F_xL) + M_zL + M_zR - k_psi psi
/// Given the held force, the suspension part is integrated exactly, so the only discretisation
/// error left is the hold itself (the one any lock-step simulator has: a contact step advances the
/// contact's own state, so it cannot be re-evaluated at intermediate stages as Runge-Kutta would).
inline void advanceWheelset(const WheelsetParameters& p, const ContactForces& left,
                            const ContactForces& right, double V, double dt, WheelsetState* s) {
  const double fy = left.fy + right.fy;
  const double mz = p.l0 * (right.fx - left.fx) + left.mz + right.mz;
  detail::advanceOscillator(p.mass, p.lateralStiffness, fy, dt, &s->y, &s->vy);
  detail::advanceOscillator(p.yawInertia, p.yawStiffness, mz, dt, &s->psi, &s->vpsi);
  s->x += V * dt;
}

/// Klingel's kinematic wavelength 2 pi sqrt(r0 l0 / lambda_e) [m].
inline double klingelWavelength(const WheelsetParameters& p) {
  return 2.0 * M_PI * std::sqrt(p.r0 * p.l0 / p.conicity);
}

/// Throws std::invalid_argument naming the first parameter out of its range.
inline void validate(const WheelsetParameters& p) {
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0 && std::isfinite(v)))
      throw std::invalid_argument(std::string(name) + ": must be > 0 and finite");
  };
  auto nonNegative = [](const char* name, double v) {
    if (!(v >= 0.0 && std::isfinite(v)))
      throw std::invalid_argument(std::string(name) + ": must be >= 0 and finite");
  };
  positive("r0", p.r0);
  positive("l0", p.l0);
  positive("conicity", p.conicity);
  positive("mass", p.mass);
  positive("yaw_inertia", p.yawInertia);
  nonNegative("lateral_stiffness", p.lateralStiffness);
  nonNegative("yaw_stiffness", p.yawStiffness);
  positive("wheel_load", p.wheelLoad);
  if (!(std::fabs(p.contactAngle) < 1.0))
    throw std::invalid_argument("contact_angle: must be in (-1, 1) rad");
}

// ---- Figures from a time history -------------------------------------------------------------

/// A decaying oscillation read from its successive positive peaks (parabola through each local
/// maximum and its neighbours): frequency from their mean spacing, damping ratio from the
/// logarithmic decrement (least-squares slope of ln peak against peak index).
struct DecayFit {
  bool ok = false;
  std::string why;  ///< when !ok
  size_t peaks = 0;
  double frequency = 0.0;     ///< [Hz]
  double dampingRatio = 0.0;  ///< [-]
};

inline DecayFit fitDecay(const std::vector<double>& t, const std::vector<double>& v,
                         size_t maxPeaks = 8) {
  DecayFit fit;
  std::vector<double> pt, pv;
  for (size_t i = 1; i + 1 < v.size() && pt.size() < maxPeaks; ++i) {
    if (!(v[i] > 0.0 && v[i] > v[i - 1] && v[i] >= v[i + 1])) continue;
    // Vertex of the parabola through the three samples (uniform spacing h).
    const double h = t[i + 1] - t[i];
    const double den = v[i - 1] - 2.0 * v[i] + v[i + 1];
    const double off = den < 0.0 ? 0.5 * (v[i - 1] - v[i + 1]) / den : 0.0;
    pt.push_back(t[i] + off * h);
    pv.push_back(v[i] - 0.25 * (v[i - 1] - v[i + 1]) * off);
  }
  fit.peaks = pt.size();
  if (pt.size() < 3) {
    fit.why = "fewer than 3 positive peaks";
    return fit;
  }
  const double n = static_cast<double>(pt.size());
  fit.frequency = (n - 1.0) / (pt.back() - pt.front());
  double sk = 0, sl = 0, skk = 0, skl = 0;
  for (size_t k = 0; k < pt.size(); ++k) {
    const double l = std::log(pv[k]);
    sk += static_cast<double>(k);
    sl += l;
    skk += static_cast<double>(k * k);
    skl += static_cast<double>(k) * l;
  }
  const double decrement = -(n * skl - sk * sl) / (n * skk - sk * sk);
  fit.dampingRatio = decrement / std::sqrt(4.0 * M_PI * M_PI + decrement * decrement);
  fit.ok = std::isfinite(fit.frequency) && std::isfinite(fit.dampingRatio);
  if (!fit.ok) fit.why = "non-finite fit";
  return fit;
}

/// Amplitude and phase of the component of v at `frequency` over the samples with t >= t0: least
/// squares of v = A cos(w t) + B sin(w t) + C + D (t - tm), so a slow drift (the lightly damped
/// kinematic mode) does not leak into it. phase = atan2(-B, A): v ~ amplitude cos(w t + phase).
struct HarmonicFit {
  bool ok = false;
  double amplitude = 0.0;
  double phase = 0.0;  ///< [rad]
};

inline HarmonicFit fitHarmonic(const std::vector<double>& t, const std::vector<double>& v,
                               double frequency, double t0) {
  HarmonicFit fit;
  const double w = 2.0 * M_PI * frequency;
  double tm = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0) tm += t[i], ++count;
  if (count < 8) return fit;
  tm /= static_cast<double>(count);
  double M[4][5] = {};
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] < t0) continue;
    const double row[4] = {std::cos(w * t[i]), std::sin(w * t[i]), 1.0, t[i] - tm};
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) M[r][c] += row[r] * row[c];
      M[r][4] += row[r] * v[i];
    }
  }
  for (int c = 0; c < 4; ++c) {  // Gauss-Jordan with partial pivoting on the 4x4 normal equations
    int best = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(M[r][c]) > std::fabs(M[best][c])) best = r;
    if (!(std::fabs(M[best][c]) > 0.0)) return fit;
    for (int k = 0; k < 5; ++k) std::swap(M[c][k], M[best][k]);
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = M[r][c] / M[c][c];
      for (int k = c; k < 5; ++k) M[r][k] -= f * M[c][k];
    }
  }
  const double A = M[0][4] / M[0][0], B = M[1][4] / M[1][1];
  fit.amplitude = std::hypot(A, B);
  fit.phase = std::atan2(-B, A);
  fit.ok = std::isfinite(fit.amplitude) && std::isfinite(fit.phase);
  return fit;
}

}  // namespace demo
}  // namespace wheel_rail_contact
