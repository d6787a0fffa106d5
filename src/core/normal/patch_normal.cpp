#include "wheel_rail_contact/normal/patch_normal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/normal/hertz_approach.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The candidate's gap function as the patch needs it: h(0, eta) beyond its minimum and the
/// curvature A(eta) = cos(delta) / (2 r) of h along x.
struct PatchGeometry {
  std::vector<double> eta, h;
  const ContactCandidate* c = nullptr;
  int imin = 0;
  double eta0 = 0.0, h0 = 0.0;  ///< the minimum, refined by a parabola through three samples

  /// The sample interval [i, i+1] holding e (clamped) and the fraction t within it.
  int interval(double e, double* t) const {
    const int n = static_cast<int>(eta.size());
    const double de = eta[1] - eta[0];
    int i = std::clamp(static_cast<int>((e - eta[0]) / de), 0, n - 2);
    while (i > 0 && eta[i] > e) --i;
    while (i < n - 2 && eta[i + 1] < e) ++i;
    *t = std::clamp((e - eta[i]) / (eta[i + 1] - eta[i]), 0.0, 1.0);
    return i;
  }
  /// h(0, e) by linear interpolation between samples.
  double gap(double e) const {
    double t;
    const int i = interval(e, &t);
    return h[i] + t * (h[i + 1] - h[i]);
  }
  /// Curvature along x at sample i: cos(delta) / (2 r).
  double curvatureAt(int i) const {
    const GapSample& s = c->gap_function[i];
    return std::max(std::cos(s.contact_angle), 0.0) / (2.0 * s.rolling_radius);
  }
  double curvature(double e) const {
    double t;
    const int i = interval(e, &t);
    return curvatureAt(i) + t * (curvatureAt(i + 1) - curvatureAt(i));
  }
};

bool buildGeometry(const ContactCandidate& c, PatchGeometry* g, std::string* why) {
  const auto& f = c.gap_function;
  const int n = static_cast<int>(f.size());
  if (n < 5) {
    *why = "the candidate has no gap function (fewer than 5 samples)";
    return false;
  }
  g->c = &c;
  g->eta.resize(n);
  g->h.resize(n);
  for (int i = 0; i < n; ++i) {
    const GapSample& s = f[i];
    if (!std::isfinite(s.eta) || !std::isfinite(s.gap) || !(s.rolling_radius > 0.0) ||
        !std::isfinite(s.rolling_radius) || !std::isfinite(s.contact_angle) ||
        (i > 0 && !(s.eta > f[i - 1].eta))) {
      *why =
          "the candidate's gap function has a sample not finite, out of order or without a "
          "wheel radius";
      return false;
    }
    g->eta[i] = s.eta;
    g->h[i] = s.gap - c.gap;
  }
  g->imin = static_cast<int>(std::min_element(g->h.begin(), g->h.end()) - g->h.begin());
  g->eta0 = g->eta[g->imin];
  g->h0 = g->h[g->imin];
  if (g->imin > 0 && g->imin < n - 1) {
    const int i = g->imin;
    const double d1 = g->eta[i] - g->eta[i - 1], d2 = g->eta[i + 1] - g->eta[i];
    const double s1 = (g->h[i] - g->h[i - 1]) / d1, s2 = (g->h[i + 1] - g->h[i]) / d2;
    const double curv = (s2 - s1) / (0.5 * (d1 + d2));  // h''
    if (curv > 0.0) {
      // vertex of the parabola through the three samples
      const double slope_i = s1 + 0.5 * curv * d1;  // h' at eta[i]
      const double shift = std::clamp(-slope_i / curv, -0.5 * d1, 0.5 * d2);
      g->eta0 = g->eta[i] + shift;
      g->h0 = g->h[i] + slope_i * shift + 0.5 * curv * shift * shift;
    }
  }
  return true;
}

/// Lateral extent of {h(0, eta) - h0 < depth} around the minimum by linear interpolation;
/// false if it reaches the gap function's end.
bool lateralExtent(const PatchGeometry& g, double depth, double* lo, double* hi) {
  const int n = static_cast<int>(g.eta.size());
  int i = g.imin;
  while (i > 0 && g.h[i - 1] - g.h0 < depth) --i;
  if (i == 0) return false;
  {
    const double u = g.h[i - 1] - g.h0 - depth, v = g.h[i] - g.h0 - depth;  // u >= 0 > v
    *lo = g.eta[i - 1] + (g.eta[i] - g.eta[i - 1]) * u / (u - v);
  }
  int j = g.imin;
  while (j < n - 1 && g.h[j + 1] - g.h0 < depth) ++j;
  if (j == n - 1) return false;
  {
    const double u = g.h[j] - g.h0 - depth, v = g.h[j + 1] - g.h0 - depth;  // u < 0 <= v
    *hi = g.eta[j] + (g.eta[j + 1] - g.eta[j]) * u / (u - v);
  }
  *lo = std::min(*lo, g.eta0);
  *hi = std::max(*hi, g.eta0);
  return true;
}

/// Least-squares B of h - h0 = B (eta - eta0)^2 over the samples inside [lo, hi]; the number of
/// samples in *count.
double fitLateralCurvature(const PatchGeometry& g, double lo, double hi, int* count) {
  double num = 0.0, den = 0.0;
  int k = 0;
  for (std::size_t i = 0; i < g.eta.size(); ++i) {
    if (g.eta[i] < lo || g.eta[i] > hi) continue;
    const double q = (g.eta[i] - g.eta0) * (g.eta[i] - g.eta0);
    num += (g.h[i] - g.h0) * q;
    den += q * q;
    ++k;
  }
  *count = k;
  return den > 0.0 ? num / den : 0.0;
}

/// Gauss-Legendre nodes and weights on [0, 1], 6 points.
constexpr double kGx[6] = {0.033765242898423986, 0.16939530676686776, 0.38069040695840156,
                           0.61930959304159845,  0.83060469323313224, 0.96623475710157603};
constexpr double kGw[6] = {0.085662246189585178, 0.18038078652406930, 0.23395696728634552,
                           0.23395696728634552,  0.18038078652406930, 0.085662246189585178};

/// Q(q) = int_0^{pi/2} cos^2 t ln(q + sqrt(q^2 + sin^2 t)) dt by Gauss-Legendre on geometric
/// panels from t = 0 (the integrand varies on the scale q there).
double quadratureQ(double q) {
  auto f = [&](double t) {
    const double s = std::sin(t), co = std::cos(t);
    return co * co * std::log(q + std::sqrt(q * q + s * s));
  };
  double sum = 0.0, t0 = 0.0, t1 = std::min(q, 0.5 * kPi);
  while (true) {
    for (int k = 0; k < 6; ++k) sum += kGw[k] * (t1 - t0) * f(t0 + kGx[k] * (t1 - t0));
    if (t1 >= 0.5 * kPi) break;
    t0 = t1;
    t1 = std::min(4.0 * t1, 0.5 * kPi);
  }
  return sum;
}

/// Q tabulated once on u = ln q in [kUlo, kUhi] (Catmull-Rom between nodes, relative error below
/// 1e-6 of J); beyond, its limits: Q(0) and Q ~ (pi/4) ln(2q) + pi / (64 q^2).
class QTable {
 public:
  static constexpr double kUlo = -16.0, kUhi = 8.0, kDu = 0.05;
  QTable() {
    const int n = static_cast<int>(std::lround((kUhi - kUlo) / kDu)) + 3;
    v_.resize(n);
    for (int i = 0; i < n; ++i) v_[i] = quadratureQ(std::exp(kUlo + (i - 1) * kDu));
  }
  double operator()(double q) const {
    const double u = std::log(q);
    if (u >= kUhi) return 0.25 * kPi * std::log(2.0 * q) + kPi / (64.0 * q * q);
    const double s = (u - kUlo) / kDu;
    const int i = static_cast<int>(s);
    const double t = s - i;
    const double p0 = v_[i], p1 = v_[i + 1], p2 = v_[i + 2], p3 = v_[i + 3];
    return p1 + 0.5 * t *
                    (p2 - p0 +
                     t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0)));
  }

 private:
  std::vector<double> v_;  // node i at u = kUlo + (i - 1) kDu
};

/// int_0^c d eta int_{-L}^{L} sqrt(L^2 - x^2) / sqrt(x^2 + eta^2) dx, c >= 0: with x = L sin t it
/// is 2 L^2 int_0^{pi/2} cos^2 t [ln(c/L + sqrt(c^2/L^2 + sin^2 t)) - ln sin t] dt
/// = 2 L^2 (Q(c/L) + (pi/8)(1 + 2 ln 2)), as int_0^{pi/2} cos^2 t ln sin t dt = -(pi/8)(1 + 2 ln
/// 2).
double centralStrip(double L, double c) {
  if (!(L > 0.0) || !(c > 0.0)) return 0.0;
  static const QTable table;
  const double q = c / L;
  const double Q =
      q < std::exp(QTable::kUlo) ? -0.125 * kPi * (1.0 + 2.0 * std::log(2.0)) : table(q);
  return std::max(0.0, 2.0 * L * L * (Q + 0.125 * kPi * (1.0 + 2.0 * std::log(2.0))));
}

/// int_{-L}^{L} sqrt(L^2 - x^2) / sqrt(x^2 + y^2) dx = 2 sqrt(L^2 + y^2) (K(m) - E(m)),
/// m = L^2 / (L^2 + y^2), y != 0.
double stripLine(double L, double y) {
  if (!(L > 0.0)) return 0.0;
  const double r2 = L * L + y * y;
  double K, E;
  completeEllipticIntegrals(L * L / r2, &K, &E);
  return 2.0 * std::sqrt(r2) * (K - E);
}

void zeroForces(NormalPatch* p) {
  p->fn = p->pmax = p->a = p->b = p->area = 0.0;
  p->strips.clear();
}

/// Concavity of the gap, as spacing^2 h'' over the deepest interpenetration, below which the
/// strips' patch is flagged.
constexpr double kConcave = 1e-3;

/// Why a patch outgrew its gap function: at an end whose gap lies within the interpenetration the
/// function stopped at a ridge to a neighbouring candidate (the two patches merge), otherwise at
/// the height the search sampled.
std::string beyondMessage(const PatchGeometry& g, double d0) {
  if (std::min(g.h.front(), g.h.back()) - g.h0 < d0)
    return "the patch reaches the ridge to a neighbouring candidate, where its gap function ends: "
           "the two patches merge (ContactSearchOptions::min_ridge keeps them apart)";
  return "the patch reaches the end of the gap function: the approach is deeper than the contact "
         "search sampled (ContactSearchOptions::gap_reach)";
}

NormalPatch fail(NormalStatus s, const std::string& why, double approach) {
  NormalPatch p;
  p.status = s;
  p.message = why;
  p.approach = approach;
  return p;
}

}  // namespace

NormalPatch solvePatchNormal(const ContactCandidate& c, double approach, double G, double nu,
                             const NormalOptions& o) {
  {
    std::ostringstream msg;
    if (!std::isfinite(approach)) msg << "approach = " << approach << " is not finite; ";
    if (!(G > 0.0) || !std::isfinite(G)) msg << "G = " << G << " must be finite and > 0; ";
    if (!(nu >= 0.0 && nu < 0.5)) msg << "nu = " << nu << " must be in [0, 0.5); ";
    if (o.strips < 3 || o.strips > 1000) msg << "NormalOptions::strips must be in [3, 1000]; ";
    if (!(o.hertz_tolerance >= 0.0) || !std::isfinite(o.hertz_tolerance))
      msg << "NormalOptions::hertz_tolerance must be finite and >= 0; ";
    if (msg.tellp() > 0) return fail(NormalStatus::kInvalidInput, msg.str(), approach);
  }
  PatchGeometry g;
  std::string why;
  if (!buildGeometry(c, &g, &why)) return fail(NormalStatus::kNoGapFunction, why, approach);

  NormalPatch out;
  out.approach = approach;
  const double d0 = approach - g.h0;  // deepest interpenetration
  out.eta_centre = out.eta_min = out.eta_max = g.eta0;
  if (!(d0 > 0.0)) {
    out.message = "not in contact at this approach";
    return out;
  }
  const double Estar = contactModulus(G, nu);
  const double A0 = g.curvature(g.eta0);
  if (!(A0 > 0.0))
    return fail(NormalStatus::kInvalidInput, "the wheel is not convex along x", approach);

  // The equivalent ellipse (as CONTACT's KPEC): the lateral extent [ys, ye] of Kik-Piotrowski's
  // region at penetration factor 1/2 gives the lateral curvature B of a parabola centred on it
  // that reaches 0.5 d0 at its edges; Hertz's ellipse (aa, bb) for A0, B at approach d0.
  double ys = 0.0, ye = 0.0;
  if (!lateralExtent(g, 0.5 * d0, &ys, &ye))
    return fail(NormalStatus::kBeyondGapFunction, beyondMessage(g, d0), approach);
  const double spacing = g.eta[1] - g.eta[0];
  const double ymid = 0.5 * (ys + ye);
  const double half = std::max(0.5 * (ye - ys), 1e-3 * spacing);
  const double B = std::max(0.5 * d0 / (half * half), 1e-3 * A0);
  int inside = 0;
  const double B_fit = fitLateralCurvature(g, ys, ye, &inside);

  // Elliptic enough for Hertz: the gap departs from its least-squares parabola about the minimum
  // by little over the region, and R_x hardly varies; a patch within a few samples of the gap
  // function is taken as elliptic (its samples cannot show more than a parabola).
  bool elliptic = inside < 3;
  if (!elliptic && o.allow_hertz && B_fit > 0.0) {
    double dev = 0.0, adev = 0.0;
    for (std::size_t i = 0; i < g.eta.size(); ++i) {
      if (g.eta[i] < ys || g.eta[i] > ye) continue;
      const double e = g.eta[i] - g.eta0;
      dev = std::max(dev, std::abs(g.h[i] - g.h0 - B_fit * e * e));
      adev = std::max(adev, std::abs(g.curvatureAt(static_cast<int>(i)) - A0));
    }
    elliptic = dev <= o.hertz_tolerance * 0.5 * d0 && adev <= o.hertz_tolerance * A0;
  }

  const int n = o.strips;
  out.strips.resize(n);
  if (elliptic) {
    double Bh = B_fit;
    if (inside < 3) {  // the gap's local parabola at its minimum
      const int i = std::clamp(g.imin, 1, static_cast<int>(g.eta.size()) - 2);
      Bh = (g.h[i + 1] - 2.0 * g.h[i] + g.h[i - 1]) / (2.0 * spacing * spacing);
    }
    Bh = std::max(Bh, 1e-3 * A0);
    const HertzApproach hz = hertzFromApproach(A0, Bh, d0, Estar);
    out.method = NormalMethod::kHertz;
    out.a = hz.a;
    out.b = hz.b;
    out.fn = hz.fn;
    out.pmax = hz.p0;
    out.area = kPi * hz.a * hz.b;
    out.eta_centre = g.eta0;
    out.eta_min = g.eta0 - hz.b;
    out.eta_max = g.eta0 + hz.b;
    if (out.eta_min < g.eta.front() || out.eta_max > g.eta.back())
      return fail(NormalStatus::kBeyondGapFunction, beyondMessage(g, d0), approach);
    const double w = 2.0 * hz.b / n;
    for (int j = 0; j < n; ++j) {
      NormalStrip& s = out.strips[j];
      s.eta = out.eta_min + (j + 0.5) * w;
      s.width = w;
      const double u = (s.eta - g.eta0) / hz.b;
      const double r = std::sqrt(std::max(0.0, 1.0 - u * u));
      s.x_lead = hz.a * r;
      s.x_trail = -s.x_lead;
      s.pmax = hz.p0 * r;
      s.force = 0.5 * kPi * hz.p0 * hz.a * r * r * w;  // midpoint in eta
    }
    return out;
  }

  // Strips with the y-dependent penetration factor eps(eta), quadratic from A aa^2 / d0 at ymid
  // to B bb^2 / d0 at ymid +- bb: on a Hertz gap the strips' region is Hertz's ellipse.
  out.method = NormalMethod::kNonHertzian;
  const HertzApproach hz = hertzFromApproach(A0, B, d0, Estar);
  const double bb = std::max(hz.b, 1.1 * std::abs(g.eta0 - ymid));
  const double ex = A0 * hz.a * hz.a, ey = B * bb * bb;  // eps d0 at the centre and at bb
  auto penetration = [&](double e) {                     // eps(eta) d0 - (h(0, eta) - h0)
    const double u = (e - ymid) / bb;
    return std::max(0.0, ex - (ex - ey) * u * u) - (g.gap(e) - g.h0);
  };
  // Lateral extent: where the penetration is positive, connected to the minimum, by bisection
  // between samples.
  auto edge = [&](int dir, double* at) {
    double inner = g.eta0;
    for (int i = dir > 0 ? g.imin + 1 : g.imin - 1;; i += dir) {
      if (i < 0 || i >= static_cast<int>(g.eta.size())) return false;
      if (penetration(g.eta[i]) <= 0.0) {
        double outer = g.eta[i], p_in = penetration(inner), p_out = penetration(outer);
        for (int it = 0; it < 16; ++it) {
          const double mid = 0.5 * (inner + outer), p = penetration(mid);
          if (p > 0.0) {
            inner = mid;
            p_in = p;
          } else {
            outer = mid;
            p_out = p;
          }
        }
        *at = inner + (outer - inner) * p_in / (p_in - p_out);  // the last interval: linear
        return true;
      }
      inner = g.eta[i];
    }
  };
  double lo = 0.0, hi = 0.0;
  if (!edge(-1, &lo) || !edge(+1, &hi))
    return fail(NormalStatus::kBeyondGapFunction, beyondMessage(g, d0), approach);
  {
    // A gap that turns concave under the patch (a plateau, a second lump beside the minimum) is
    // where the strips are weak: say so.
    double worst = 0.0;
    for (int i = 1; i + 1 < static_cast<int>(g.eta.size()); ++i)
      if (g.eta[i] > lo && g.eta[i] < hi)
        worst = std::min(worst, g.h[i + 1] - 2.0 * g.h[i] + g.h[i - 1]);  // spacing^2 h''
    if (worst < -kConcave * d0)
      out.message =
          "the gap turns concave under the patch: the strips may miss part of the "
          "contact (doc/normal_problem.md)";
  }
  const double w = (hi - lo) / n;
  std::vector<double> L(n);
  auto halfLength = [&](double e) {
    const double pen = penetration(e), Ae = g.curvature(e);
    return pen > 0.0 && Ae > 0.0 ? std::sqrt(pen / Ae) : 0.0;
  };
  for (int j = 0; j < n; ++j) L[j] = halfLength(lo + (j + 0.5) * w);
  // Displacement at (0, eta0) per unit amplitude P: over each strip the integral of
  // sqrt(L^2 - x^2) / r, exact in eta (J differences) near eta0, midpoint further out.
  double influence = 0.0;
  for (int j = 0; j < n; ++j) {
    const double y1 = lo + j * w - g.eta0, y2 = y1 + w;
    if (y2 > -3.0 * w && y1 < 3.0 * w) {
      if (y1 < 0.0 && y2 > 0.0)
        influence += centralStrip(L[j], -y1) + centralStrip(L[j], y2);
      else
        influence += std::abs(centralStrip(L[j], std::max(std::abs(y1), std::abs(y2))) -
                              centralStrip(L[j], std::min(std::abs(y1), std::abs(y2))));
    } else {
      influence += w * stripLine(L[j], 0.5 * (y1 + y2));
    }
  }
  if (!(influence > 0.0)) {
    out.message = "the patch has no strip in contact";
    zeroForces(&out);
    return out;
  }
  // (1 - nu) / (pi G) = 1 / (pi E*): both bodies' Boussinesq displacement.
  const double P = d0 * kPi * Estar / influence;
  double fn = 0.0, area = 0.0, pmax = P * halfLength(g.eta0);
  for (int j = 0; j < n; ++j) {
    NormalStrip& s = out.strips[j];
    s.eta = lo + (j + 0.5) * w;
    s.width = w;
    s.x_lead = L[j];
    s.x_trail = -L[j];
    s.pmax = P * L[j];
    s.force = 0.5 * kPi * P * L[j] * L[j] * w;
    fn += s.force;
    area += 2.0 * L[j] * w;
    pmax = std::max(pmax, s.pmax);
  }
  out.fn = fn;
  out.pmax = pmax;
  out.area = area;
  out.eta_min = lo;
  out.eta_max = hi;
  out.eta_centre = 0.5 * (lo + hi);
  out.b = 0.5 * (hi - lo);
  out.a = out.b > 0.0 ? area / (kPi * out.b) : 0.0;
  return out;
}

WheelNormal solveWheelLoad(const WheelContactGeometry& geo, double load, double G, double nu,
                           const NormalOptions& o) {
  WheelNormal out;
  auto failed = [&](NormalStatus s, const std::string& why) {
    out.status = s;
    out.message = why;
    for (NormalPatch& p : out.patches) zeroForces(&p);
    return out;
  };
  out.patches.resize(geo.candidates.size());
  if (!(load > 0.0) || !std::isfinite(load)) {
    std::ostringstream m;
    m << "vertical_load = " << load << " must be finite and > 0";
    return failed(NormalStatus::kInvalidInput, m.str());
  }
  if (!(G > 0.0) || !std::isfinite(G) || !(nu >= 0.0 && nu < 0.5))
    return failed(NormalStatus::kInvalidInput, "G must be finite and > 0, nu in [0, 0.5)");
  if (!(o.load_tolerance > 0.0 && o.load_tolerance < 0.1) || o.max_iterations < 1)
    return failed(NormalStatus::kInvalidInput,
                  "NormalOptions::load_tolerance must be in (0, 0.1), max_iterations >= 1");
  if (geo.status != ContactSearchStatus::kOk || geo.candidates.empty())
    return failed(NormalStatus::kNoContact,
                  "no contact candidate" + (geo.message.empty() ? "" : ": " + geo.message));
  double touch = std::numeric_limits<double>::infinity();  // first touch of any candidate
  for (const ContactCandidate& c : geo.candidates) {
    if (!(c.normal.y() > 0.0) || !std::isfinite(c.gap))
      return failed(NormalStatus::kInvalidInput, "a candidate's normal does not point up");
    touch = std::min(touch, c.gap / c.normal.y());
  }
  // Vertical force at a vertical approach; false on a patch's failure (its status in *bad).
  NormalStatus bad = NormalStatus::kOk;
  std::string bad_why;
  auto force = [&](double dv, double* fz) {
    *fz = 0.0;
    for (std::size_t i = 0; i < geo.candidates.size(); ++i) {
      const ContactCandidate& c = geo.candidates[i];
      out.patches[i] = solvePatchNormal(c, dv * c.normal.y() - c.gap, G, nu, o);
      if (out.patches[i].status != NormalStatus::kOk) {
        bad = out.patches[i].status;
        bad_why = "candidate " + std::to_string(i) + ": " + out.patches[i].message;
        return false;
      }
      *fz += out.patches[i].fn * c.normal.y();
    }
    return true;
  };
  // Secant steps on r = f^(2/3) - load^(2/3), nearly linear in the approach (Hertz: f ~
  // d^(3/2)), from first touch (r = -load^(2/3)) and a probe 10 um beyond; a step that leaves
  // the bracket found so far bisects it, one beyond every trial so far (no bracket yet) goes at
  // most eight times as deep.
  const double target = std::cbrt(load * load);
  const double inf = std::numeric_limits<double>::infinity();
  double lo = touch, hi = inf;
  double x0 = touch, r0 = -target, x1 = touch + 1e-5, f = 0.0;
  double dv = x1;
  int it = 0;
  for (; it < o.max_iterations; ++it) {
    if (!force(dv, &f)) return failed(bad, bad_why);
    if (std::abs(f - load) <= o.load_tolerance * load) break;
    const double r = std::cbrt(f * f) - target;
    (r > 0.0 ? hi : lo) = dv;
    x1 = dv;
    double next = r != r0 ? x1 - r * (x1 - x0) / (r - r0) : inf;
    x0 = x1;
    r0 = r;
    if (hi < inf) {
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    } else if (!(next > lo) || next > touch + 8.0 * (lo - touch)) {
      next = touch + 8.0 * (lo - touch);
    }
    dv = next;
  }
  if (it >= o.max_iterations)
    return failed(NormalStatus::kNotConverged, hi < inf ? "the approach iteration did not converge"
                                                        : "no approach carries the load");
  // The patches hold the last trial's solution, at dv.
  out.vertical_approach = dv;
  return out;
}

}  // namespace wheel_rail_contact
