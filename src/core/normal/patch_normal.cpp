#include "wheel_rail_contact/normal/patch_normal.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include "core/normal/hertz_approach.hpp"
#include "core/normal/merge_candidates.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The candidate's gap function as the patch needs it: h(0, eta) beyond its minimum and the
/// curvature A(eta) = cos(delta) / (2 r) of h along x.
struct PatchGeometry {
  std::vector<double> eta, h;
  std::vector<double> A;  ///< curvature along x at each sample, cos(delta) / (2 r) (>= 0)
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
  double curvatureAt(int i) const { return A[i]; }
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
  g->A.resize(n);
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
    g->A[i] = std::max(std::cos(s.contact_angle), 0.0) / (2.0 * s.rolling_radius);
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

/// The half-widths of the parabola with the gap's interpenetration area at level `depth` on each
/// side of the minimum: c = 3 I / (2 depth), I = int max(0, depth - (h - h0)) d eta over that side
/// (the gap linear between samples). On a parabola they are its extent at that level; unlike the
/// extent they move smoothly as a plateau sinks below the level.
void halfDepthWidths(const PatchGeometry& g, double depth, double* cl, double* cr) {
  auto part = [&](double x0, double x1, double h0v, double h1v) {
    const double u0 = depth - h0v, u1 = depth - h1v, dx = x1 - x0;
    if (u0 >= 0.0 && u1 >= 0.0) return 0.5 * dx * (u0 + u1);
    if (u0 <= 0.0 && u1 <= 0.0) return 0.0;
    const double up = std::max(u0, u1), un = std::min(u0, u1);
    return 0.5 * dx * up * up / (up - un);
  };
  const int n = static_cast<int>(g.eta.size());
  double il = 0.0, ir = 0.0;
  const double hm = g.gap(g.eta0) - g.h0;
  for (int k = 0; k + 1 < n; ++k) {
    const double a = g.eta[k], b = g.eta[k + 1], ha = g.h[k] - g.h0, hb = g.h[k + 1] - g.h0;
    if (b <= g.eta0) {
      il += part(a, b, ha, hb);
    } else if (a >= g.eta0) {
      ir += part(a, b, ha, hb);
    } else {
      il += part(a, g.eta0, ha, hm);
      ir += part(g.eta0, b, hm, hb);
    }
  }
  *cl = 1.5 * il / depth;
  *cr = 1.5 * ir / depth;
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

/// stripLine(L[i], y[i]) into out[i], i < n, four at a time: completeEllipticIntegrals' mean
/// iterated on four strips side by side (each stopping where that function stops), so that their
/// square roots overlap instead of waiting on each other; the same operations, the same values.
void stripLines(const double* L, const double* y, int n, double* out) {
  constexpr int kW = 4;
  int i = 0;
  for (; i + kW <= n; i += kW) {
    double an[kW], bn[kW], cn2[kW], sum[kW], pow2[kW], r2[kW];
    bool ok = true;
    for (int l = 0; l < kW; ++l) {
      r2[l] = L[i + l] * L[i + l] + y[i + l] * y[i + l];
      const double m = L[i + l] * L[i + l] / r2[l];
      ok = ok && L[i + l] > 0.0 && m >= 0.0 && m < 1.0;
      an[l] = 1.0;
      bn[l] = std::sqrt(1.0 - m);
      cn2[l] = m;
      sum[l] = 0.5 * m;
      pow2[l] = 0.5;
    }
    if (!ok) break;  // the rest one by one (a strip out of contact, or m out of range)
    for (int it = 0; it < 64; ++it) {
      bool any = false;
      for (int l = 0; l < kW; ++l) {
        if (!(cn2[l] > 1e-32)) continue;
        any = true;
        const double a_next = 0.5 * (an[l] + bn[l]);
        const double c_next = 0.5 * (an[l] - bn[l]);
        bn[l] = std::sqrt(an[l] * bn[l]);
        an[l] = a_next;
        cn2[l] = c_next * c_next;
        pow2[l] *= 2.0;
        sum[l] += pow2[l] * cn2[l];
      }
      if (!any) break;
    }
    for (int l = 0; l < kW; ++l) {
      const double K = M_PI / (2.0 * an[l]), E = K * (1.0 - sum[l]);
      out[i + l] = 2.0 * std::sqrt(r2[l]) * (K - E);
    }
  }
  for (; i < n; ++i) out[i] = stripLine(L[i], y[i]);
}

void zeroForces(NormalPatch* p) {
  p->fn = p->pmax = p->a = p->b = p->area = 0.0;
  p->strips.clear();
}

/// Concavity of the gap, as spacing^2 h'' over the deepest interpenetration, below which the
/// strips' patch is flagged.
constexpr double kConcave = 1e-3;

/// The ellipticity ratio (solvePatchNormal) from which a patch is the strips' alone; between 1
/// and this, Hertz and the strips blended.
constexpr double kBlendEnd = 2.0;

/// Why a patch outgrew its gap function: at an end whose gap lies within the interpenetration the
/// function stopped at a ridge to a neighbouring candidate (the two patches merge), otherwise at
/// the height the search sampled.
std::string beyondMessage(const PatchGeometry& g, double d0) {
  if (std::min(g.h.front(), g.h.back()) - g.h0 < d0)
    return "the patch reaches the ridge to a neighbouring candidate, where its gap function ends: "
           "the two patches merge (solveWheelLoad joins them once the approach crosses the ridge)";
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

/// The strips' penetration eps(eta) d0 - (h(0, eta) - h0) at the central approach d0, the factor
/// eps quadratic from A0 aa^2 / d0 at ymid to B bb^2 / d0 at ymid +- bb, (aa, bb) Hertz's ellipse
/// for A0, B at d0 (bb widened to reach eta0): on a Hertz gap the strips' region is Hertz's
/// ellipse.
class StripPenetration {
 public:
  /// held: the factor, where it grows away from ymid (A0 aa^2 < B bb^2), held at B bb^2 beyond
  /// ymid +- bb, so that it stays bounded where positiveParts looks (the whole gap function).
  StripPenetration(const PatchGeometry& g, double A0, double B, double d0, double Estar,
                   double ymid, bool held = false)
      : g_(g), ymid_(ymid), held_(held) {
    const HertzApproach hz = hertzFromApproach(A0, B, d0, Estar);
    bb_ = std::max(hz.b, 1.1 * std::abs(g.eta0 - ymid));
    ex_ = A0 * hz.a * hz.a;  // eps d0 at the centre
    ey_ = B * bb_ * bb_;     // and at bb
  }
  double operator()(double e) const { return of(e, g_.gap(e)); }
  /// The same for e strictly inside the sample interval [k, k + 1], where gap(e) is that
  /// interval's line: without gap's search for the interval.
  double inInterval(double e, int k) const {
    const double x0 = g_.eta[k], x1 = g_.eta[k + 1];
    if (!(e > x0 && e < x1)) return (*this)(e);
    const double t = std::clamp((e - x0) / (x1 - x0), 0.0, 1.0);
    return of(e, g_.h[k] + t * (g_.h[k + 1] - g_.h[k]));
  }
  /// The sample interval holding e (as gap's), for inInterval.
  int interval(double e) const {
    double t;
    return g_.interval(e, &t);
  }
  /// The parts of sample interval [k, k + 1] where the penetration is positive, appended to
  /// *pieces as (from, to) pairs in eta, continuing the last pair where it ends at the interval's
  /// start. Their ends are the roots of the quadratic the penetration is there (the factor's
  /// parabola less the gap's line; where the factor's max(0, .) clips, the penetration is <= 0),
  /// so that they move continuously with the approach.
  void positiveParts(int k, std::vector<double>* pieces) const {
    const double x0 = g_.eta[k], x1 = g_.eta[k + 1];
    const double c = (ex_ - ey_) / (bb_ * bb_);  // factor = ex - c (e - ymid)^2
    if (c >= 0.0 || !held_) {
      positiveIn(k, x0, x1, c, ex_, pieces);
      return;
    }
    // A factor growing away from ymid held at ey beyond ymid +- bb (of()).
    double cuts[4] = {x0, x1, x1, x1};
    int m = 1;
    for (const double e : {ymid_ - bb_, ymid_ + bb_})
      if (e > x0 && e < x1) cuts[m++] = e;
    cuts[m] = x1;
    for (int i = 0; i < m; ++i) {
      const bool held = std::abs(0.5 * (cuts[i] + cuts[i + 1]) - ymid_) >= bb_;
      positiveIn(k, cuts[i], cuts[i + 1], held ? 0.0 : c, held ? ey_ : ex_, pieces);
    }
  }

 private:
  /// positiveParts on [s0, s1] within sample interval k, the factor there e0 - c (e - ymid)^2.
  void positiveIn(int k, double s0, double s1, double c, double e0,
                  std::vector<double>* pieces) const {
    const double len = s1 - s0;
    if (!(len > 0.0)) return;
    const double slope = (g_.h[k + 1] - g_.h[k]) / (g_.eta[k + 1] - g_.eta[k]);
    auto gap = [&](double e) { return g_.h[k] + slope * (e - g_.eta[k]) - g_.h0; };
    auto factor = [&](double e) { return e0 - c * (e - ymid_) * (e - ymid_); };
    double top = std::max(factor(s0), factor(s1));
    if (c > 0.0 && ymid_ > s0 && ymid_ < s1) top = e0;
    if (!(top > std::min(gap(s0), gap(s1)))) return;  // the common case, cheaply
    // F(t) = a2 t^2 + a1 t + a0 over t = e - s0 in [0, len].
    const double v = s0 - ymid_;
    const double a2 = -c, a1 = -2.0 * c * v - slope, a0 = e0 - c * v * v - gap(s0);
    double cut[4] = {0.0, len, len, len};
    int nc = 1;
    auto root = [&](double t) {
      if (t > 0.0 && t < len) cut[nc++] = t;
    };
    if (std::abs(a2) * len <= 1e-12 * std::abs(a1)) {
      if (a1 != 0.0) root(-a0 / a1);
    } else {
      const double disc = a1 * a1 - 4.0 * a2 * a0;
      if (disc > 0.0) {
        const double q = -0.5 * (a1 + std::copysign(std::sqrt(disc), a1));
        if (q != 0.0) {
          root(q / a2);
          root(a0 / q);
        }
      }
    }
    cut[nc] = len;
    if (nc == 3 && cut[2] < cut[1]) std::swap(cut[1], cut[2]);
    for (int i = 0; i < nc; ++i) {
      const double t = 0.5 * (cut[i] + cut[i + 1]);
      if (!(cut[i + 1] > cut[i]) || !((a2 * t + a1) * t + a0 > 0.0)) continue;
      const double from = cut[i] > 0.0 ? s0 + cut[i] : s0;
      const double to = cut[i + 1] < len ? s0 + cut[i + 1] : s1;
      if (!pieces->empty() && pieces->back() == from) {
        pieces->back() = to;
      } else {
        pieces->push_back(from);
        pieces->push_back(to);
      }
    }
  }
  double of(double e, double gap) const {
    const double u = (e - ymid_) / bb_;
    const double u2 = held_ && ex_ < ey_ ? std::min(u * u, 1.0) : u * u;
    return std::max(0.0, ex_ - (ex_ - ey_) * u2) - (gap - g_.h0);
  }
  const PatchGeometry& g_;
  double ymid_, bb_ = 0.0, ex_ = 0.0, ey_ = 0.0;
  bool held_ = false;
};

/// Where the penetration f ends between inner (f > 0) and outer (f <= 0): bisection, then linear
/// in the last interval.
double penetrationEdge(const StripPenetration& f, double inner, double outer) {
  double p_in = f(inner), p_out = f(outer);
  // The midpoints lie between inner and outer, mostly in the first one's sample interval
  // (inInterval is f itself, and f where a midpoint is not strictly inside it).
  const int k = f.interval(0.5 * (inner + outer));
  for (int it = 0; it < 16; ++it) {
    const double mid = 0.5 * (inner + outer), p = f.inInterval(mid, k);
    if (p > 0.0) {
      inner = mid;
      p_in = p;
    } else {
      outer = mid;
      p_out = p;
    }
  }
  return inner + (outer - inner) * p_in / (p_in - p_out);
}

/// A candidate's PatchGeometry, built once for the trials of a load iteration (the candidate does
/// not change between them).
struct BuiltGeometry {
  bool built = false, ok = false;
  PatchGeometry g;
  std::string why;  ///< buildGeometry's, where not ok
};

/// solvePatchNormal on the geometry in *cache (built there on first use), or built here where
/// cache is null.
NormalPatch solvePatch(const ContactCandidate& c, BuiltGeometry* cache, double approach, double G,
                       double nu, const NormalOptions& o) {
  if (!std::isfinite(approach) || !(G > 0.0) || !std::isfinite(G) || !(nu >= 0.0 && nu < 0.5) ||
      o.strips < 3 || o.strips > 1000 || !(o.hertz_tolerance >= 0.0) ||
      !std::isfinite(o.hertz_tolerance)) {
    std::ostringstream msg;
    if (!std::isfinite(approach)) msg << "approach = " << approach << " is not finite; ";
    if (!(G > 0.0) || !std::isfinite(G)) msg << "G = " << G << " must be finite and > 0; ";
    if (!(nu >= 0.0 && nu < 0.5)) msg << "nu = " << nu << " must be in [0, 0.5); ";
    if (o.strips < 3 || o.strips > 1000) msg << "NormalOptions::strips must be in [3, 1000]; ";
    if (!(o.hertz_tolerance >= 0.0) || !std::isfinite(o.hertz_tolerance))
      msg << "NormalOptions::hertz_tolerance must be finite and >= 0; ";
    if (msg.tellp() > 0) return fail(NormalStatus::kInvalidInput, msg.str(), approach);
  }
  BuiltGeometry here;
  BuiltGeometry& built = cache ? *cache : here;
  if (!built.built) {
    built.built = true;
    built.ok = buildGeometry(c, &built.g, &built.why);
  }
  if (!built.ok) return fail(NormalStatus::kNoGapFunction, built.why, approach);
  const PatchGeometry& g = built.g;

  NormalPatch start;
  start.approach = approach;
  const double d0 = approach - g.h0;  // deepest interpenetration
  start.eta_centre = start.eta_min = start.eta_max = g.eta0;
  if (!(d0 > 0.0)) {
    start.message = "not in contact at this approach";
    return start;
  }
  const double Estar = contactModulus(G, nu);
  const double A0 = g.curvature(g.eta0);
  if (!(A0 > 0.0))
    return fail(NormalStatus::kInvalidInput, "the wheel is not convex along x", approach);

  // The equivalent ellipse (as CONTACT's KPEC): the lateral curvature B of a parabola that
  // reaches 0.5 d0 at half-widths cl, cr on either side of the minimum, centred on ymid between
  // them; Hertz's ellipse (aa, bb) for A0, B at approach d0. The half-widths: KPEC's, the extent
  // [ys, ye] of the region at 0.5 d0; with continuous_region those of the parabola with the same
  // interpenetration area at that level on each side (on a parabola, its extent), which move
  // smoothly as a plateau beside the minimum sinks below the level, where the extent runs over
  // the plateau within a fraction of a micrometre of approach and the penetration factor with it
  // (the force then falls as the approach grows). [ys, ye] bounds the samples of the Hertz test.
  double ys = 0.0, ye = 0.0;
  if (!lateralExtent(g, 0.5 * d0, &ys, &ye))
    return fail(NormalStatus::kBeyondGapFunction, beyondMessage(g, d0), approach);
  const double spacing = g.eta[1] - g.eta[0];

  // How far from elliptic (Hertz up to 1): the gap's largest departure from its least-squares
  // parabola about the minimum over the region, over hertz_tolerance d0 / 2, or R_x's largest
  // variation, over hertz_tolerance A. Samples count with a weight falling to 0 at the region's
  // edge (h - h0 = d0 / 2), so that a sample entering the region as the approach grows changes
  // neither the fit (Hertz's B) nor the ratio at once.
  double ratio = std::numeric_limits<double>::infinity();
  double B_taper = 0.0;
  {
    // The fit starts from the gap's local parabola at its minimum, with the weight of one sample
    // a spacing away, so that it goes over continuously from that parabola to the samples' fit
    // as they enter the region.
    const int m = std::clamp(g.imin, 1, static_cast<int>(g.eta.size()) - 2);
    const double B_local = (g.h[m + 1] - 2.0 * g.h[m] + g.h[m - 1]) / (2.0 * spacing * spacing);
    double num = B_local * std::pow(spacing, 4), den = std::pow(spacing, 4);
    auto taper = [&](std::size_t i) {
      return std::clamp(4.0 * (1.0 - (g.h[i] - g.h0) / (0.5 * d0)), 0.0, 1.0);
    };
    for (std::size_t i = 0; i < g.eta.size(); ++i) {
      if (g.eta[i] < ys || g.eta[i] > ye) continue;
      const double q = (g.eta[i] - g.eta0) * (g.eta[i] - g.eta0), tp = taper(i);
      num += tp * (g.h[i] - g.h0) * q;
      den += tp * q * q;
    }
    B_taper = num / den;
    if (o.allow_hertz && B_taper > 0.0) {
      double dev = 0.0, adev = 0.0;
      for (std::size_t i = 0; i < g.eta.size(); ++i) {
        if (g.eta[i] < ys || g.eta[i] > ye) continue;
        const double e = g.eta[i] - g.eta0, tp = taper(i);
        dev = std::max(dev, tp * std::abs(g.h[i] - g.h0 - B_taper * e * e));
        adev = std::max(adev, tp * std::abs(g.curvatureAt(static_cast<int>(i)) - A0));
      }
      const double tol = std::max(o.hertz_tolerance, 1e-12);
      ratio = std::max(dev / (tol * 0.5 * d0), adev / (tol * A0));
    }
  }

  const int n = o.strips;
  start.strips.resize(n);
  auto hertzPatch = [&]() {
    NormalPatch out = start;
    const double Bh = std::max(B_taper, 1e-3 * A0);
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
  };

  // Strips with the y-dependent penetration factor eps(eta), quadratic from A aa^2 / d0 at ymid
  // to B bb^2 / d0 at ymid +- bb: on a Hertz gap the strips' region is Hertz's ellipse.
  auto stripPatch = [&]() {
    NormalPatch out = start;
    out.method = NormalMethod::kNonHertzian;
    out.strip_weight = 1.0;
    double cl = g.eta0 - ys, cr = ye - g.eta0;
    if (o.continuous_region) halfDepthWidths(g, 0.5 * d0, &cl, &cr);
    const double ymid = o.continuous_region ? g.eta0 + 0.5 * (cr - cl) : 0.5 * (ys + ye);
    const double half = std::max(0.5 * (cl + cr), 1e-3 * spacing);
    const double B = std::max(0.5 * d0 / (half * half), 1e-3 * A0);
    const StripPenetration penetration(g, A0, B, d0, Estar, ymid, o.continuous_region);
    // By default the region is where the penetration is positive around the minimum, its ends by
    // bisection between samples.
    auto edge = [&](int dir, double* at) {
      double inner = g.eta0;
      for (int i = dir > 0 ? g.imin + 1 : g.imin - 1;; i += dir) {
        if (i < 0 || i >= static_cast<int>(g.eta.size())) return false;
        if (penetration(g.eta[i]) <= 0.0) {
          *at = penetrationEdge(penetration, inner, g.eta[i]);
          return true;
        }
        inner = g.eta[i];
      }
    };
    // With continuous_region, every part of the gap function where the penetration is positive,
    // the parts' ends where the penetration's quadratic crosses zero in a sample interval. Beside
    // a plateau the penetration can dip below zero between the minimum and the plateau, and a
    // region stopping at the dip jumps over the plateau (and the force with it) when it fills.
    std::vector<double> pieces;  // (from, to) pairs, ordered
    if (o.continuous_region) {
      const int last_interval = static_cast<int>(g.eta.size()) - 2;
      for (int k = 0; k <= last_interval; ++k) penetration.positiveParts(k, &pieces);
    } else {
      pieces.assign(2, 0.0);
      if (!edge(-1, &pieces[0]) || !edge(+1, &pieces[1]))
        return fail(NormalStatus::kBeyondGapFunction, beyondMessage(g, d0), approach);
    }
    if (pieces.empty()) {
      out.message = "the patch has no strip in contact";
      zeroForces(&out);
      return out;
    }
    if (pieces.front() <= g.eta.front() || pieces.back() >= g.eta.back())
      return fail(NormalStatus::kBeyondGapFunction, beyondMessage(g, d0), approach);
    const double lo = pieces.front(), hi = pieces.back();
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
    // The strips share the parts' whole length equally, laid along the parts one after the
    // other: strip j's centre lies (j + 1/2) w along them, w their total length over n. A strip
    // whose centre passes the gap between two parts has its half-length 0 at either end of the
    // gap (the penetration's zeros), so the force moves continuously as parts grow, appear or
    // join; on one part these are n equal strips from lo to hi.
    double total = 0.0;
    for (std::size_t i = 0; i < pieces.size(); i += 2) total += pieces[i + 1] - pieces[i];
    const double w = total / n;
    std::vector<double> L(n), centre(n);
    auto halfLength = [&](double e) {
      const double pen = penetration(e), Ae = g.curvature(e);
      return pen > 0.0 && Ae > 0.0 ? std::sqrt(pen / Ae) : 0.0;
    };
    if (pieces.size() == 2) {
      for (int j = 0; j < n; ++j) centre[j] = lo + (j + 0.5) * w;
    } else {
      std::size_t i = 0;
      double before = 0.0;  // the parts' length before part i
      for (int j = 0; j < n; ++j) {
        const double along = (j + 0.5) * w;
        while (i + 2 < pieces.size() && along > before + pieces[i + 1] - pieces[i]) {
          before += pieces[i + 1] - pieces[i];
          i += 2;
        }
        centre[j] = std::min(pieces[i] + (along - before), pieces[i + 1]);
      }
    }
    for (int j = 0; j < n; ++j) L[j] = halfLength(centre[j]);
    // Displacement at (0, eta0) per unit amplitude P: over each strip the integral of
    // sqrt(L^2 - x^2) / r, exact in eta (J differences) near eta0, midpoint further out.
    // The far strips' lines first, side by side (stripLines), summed in the strips' order.
    std::vector<double> farL, farY, farLine;
    farL.reserve(n);
    farY.reserve(n);
    for (int j = 0; j < n; ++j) {
      const double y1 = centre[j] - 0.5 * w - g.eta0, y2 = y1 + w;
      if (!(y2 > -3.0 * w && y1 < 3.0 * w)) {
        farL.push_back(L[j]);
        farY.push_back(0.5 * (y1 + y2));
      }
    }
    farLine.resize(farL.size());
    stripLines(farL.data(), farY.data(), static_cast<int>(farL.size()), farLine.data());
    double influence = 0.0;
    for (int j = 0, far = 0; j < n; ++j) {
      const double y1 = centre[j] - 0.5 * w - g.eta0, y2 = y1 + w;
      if (y2 > -3.0 * w && y1 < 3.0 * w) {
        if (y1 < 0.0 && y2 > 0.0)
          influence += centralStrip(L[j], -y1) + centralStrip(L[j], y2);
        else
          influence += std::abs(centralStrip(L[j], std::max(std::abs(y1), std::abs(y2))) -
                                centralStrip(L[j], std::min(std::abs(y1), std::abs(y2))));
      } else {
        influence += w * farLine[far++];
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
      s.eta = centre[j];
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
  };

  // Between Hertz (ratio up to 1) and the strips (ratio from kBlendEnd) the two solutions blended
  // with a smooth weight in the ratio, so that fn, pmax, a, b and the strips are continuous in the
  // approach where a patch leaves the elliptic regime (the strips' force on a near-Hertz gap lies
  // a little below Hertz's, a step down in the force otherwise).
  if (ratio <= 1.0) return hertzPatch();
  if (!(ratio < kBlendEnd)) return stripPatch();
  const NormalPatch hp = hertzPatch();
  NormalPatch sp = stripPatch();
  if (hp.status != NormalStatus::kOk || sp.status != NormalStatus::kOk ||
      sp.strips.size() != hp.strips.size())
    return sp;
  const double t = (ratio - 1.0) / (kBlendEnd - 1.0);
  const double ws = t * t * (3.0 - 2.0 * t);  // the strips' weight, smoothstep
  auto mix = [&](double h, double st) { return h + ws * (st - h); };
  sp.fn = mix(hp.fn, sp.fn);
  sp.pmax = mix(hp.pmax, sp.pmax);
  sp.a = mix(hp.a, sp.a);
  sp.b = mix(hp.b, sp.b);
  sp.area = mix(hp.area, sp.area);
  sp.eta_centre = mix(hp.eta_centre, sp.eta_centre);
  sp.eta_min = mix(hp.eta_min, sp.eta_min);
  sp.eta_max = mix(hp.eta_max, sp.eta_max);
  for (std::size_t j = 0; j < sp.strips.size(); ++j) {
    NormalStrip& s = sp.strips[j];
    const NormalStrip& h = hp.strips[j];
    s.eta = mix(h.eta, s.eta);
    s.width = mix(h.width, s.width);
    s.x_lead = mix(h.x_lead, s.x_lead);
    s.x_trail = mix(h.x_trail, s.x_trail);
    s.pmax = mix(h.pmax, s.pmax);
    s.force = mix(h.force, s.force);
  }
  sp.method = ws < 0.5 ? NormalMethod::kHertz : NormalMethod::kNonHertzian;
  sp.strip_weight = ws;
  return sp;
}

}  // namespace

NormalPatch solvePatchNormal(const ContactCandidate& c, double approach, double G, double nu,
                             const NormalOptions& o) {
  return solvePatch(c, nullptr, approach, G, nu, o);
}

namespace {

/// One lump of a merged patch: the strips of Kik-Piotrowski's method over its own part of the
/// gap function (between the ridges that bound it), at the shared approach.
struct Lump {
  double eta0 = 0.0, d0 = 0.0;  ///< its deepest point and interpenetration there
  double lo = 0.0, hi = 0.0, w = 0.0;
  std::vector<double> L;  ///< strips' half-lengths
  double P = 0.0;         ///< amplitude: p = P sqrt(L^2 - x^2)
};

/// The strips of one lump: KPEC's equivalent ellipse and penetration factor from the lump's own
/// gap, the patch stopping at a ridge that bounds the lump (where the neighbouring lump takes
/// over) or where the penetration ends. False if it reaches the end of the gap function.
bool lumpStrips(const PatchGeometry& g, double approach, bool ridge_lo, bool ridge_hi, double Estar,
                int n, Lump* k) {
  k->eta0 = g.eta0;
  k->d0 = approach - g.h0;
  if (!(k->d0 > 0.0)) return true;  // not in contact
  const double A0 = g.curvature(g.eta0);
  if (!(A0 > 0.0)) return false;
  const double d0 = k->d0;
  const int m = static_cast<int>(g.eta.size());
  // Extent at half the interpenetration, stopping at a bounding ridge.
  auto halfEdge = [&](int dir, double* at) {
    int i = g.imin;
    while (i + dir >= 0 && i + dir < m && g.h[i + dir] - g.h0 < 0.5 * d0) i += dir;
    if (i + dir < 0 || i + dir >= m) {
      *at = g.eta[i];
      return dir < 0 ? ridge_lo : ridge_hi;
    }
    const double u = g.h[i + dir] - g.h0 - 0.5 * d0, v = g.h[i] - g.h0 - 0.5 * d0;
    *at = g.eta[i + dir] + (g.eta[i] - g.eta[i + dir]) * u / (u - v);
    return true;
  };
  double ys = 0.0, ye = 0.0;
  if (!halfEdge(-1, &ys) || !halfEdge(+1, &ye)) return false;
  ys = std::min(ys, g.eta0);
  ye = std::max(ye, g.eta0);
  const double spacing = g.eta[1] - g.eta[0];
  const double ymid = 0.5 * (ys + ye);
  const double half = std::max(0.5 * (ye - ys), 1e-3 * spacing);
  const double B = std::max(0.5 * d0 / (half * half), 1e-3 * A0);
  const StripPenetration penetration(g, A0, B, d0, Estar, ymid);
  // The lump's extent: out to its outermost sample in contact, the strips between at zero where
  // the penetration dips below zero. Stopping at the first such dip instead would make the patch
  // jump to the ridge when the dip fills, and with it the force the load iteration needs
  // continuous in the approach.
  auto edge = [&](int dir, double* at) {
    int last = g.imin;
    for (int i = g.imin + dir; i >= 0 && i < m; i += dir)
      if (penetration(g.eta[i]) > 0.0) last = i;
    if (last + dir < 0 || last + dir >= m) {
      *at = g.eta[last];
      return dir < 0 ? ridge_lo : ridge_hi;
    }
    *at = penetrationEdge(penetration, last == g.imin ? g.eta0 : g.eta[last], g.eta[last + dir]);
    return true;
  };
  if (!edge(-1, &k->lo) || !edge(+1, &k->hi)) return false;
  k->w = (k->hi - k->lo) / n;
  k->L.assign(n, 0.0);
  for (int j = 0; j < n; ++j) {
    const double e = k->lo + (j + 0.5) * k->w;
    const double pen = penetration(e), Ae = g.curvature(e);
    k->L[j] = pen > 0.0 && Ae > 0.0 ? std::sqrt(pen / Ae) : 0.0;
  }
  return true;
}

/// Displacement at lateral position e (x = 0) per unit amplitude of lump k's strips, times
/// pi E*: exact in eta for the strips next to e, midpoint further out.
double lumpInfluence(const Lump& k, double e) {
  double s = 0.0;
  const int n = static_cast<int>(k.L.size());
  for (int j = 0; j < n; ++j) {
    const double y1 = k.lo + j * k.w - e, y2 = y1 + k.w;
    if (y2 > -3.0 * k.w && y1 < 3.0 * k.w) {
      if (y1 < 0.0 && y2 > 0.0)
        s += centralStrip(k.L[j], -y1) + centralStrip(k.L[j], y2);
      else
        s += std::abs(centralStrip(k.L[j], std::max(std::abs(y1), std::abs(y2))) -
                      centralStrip(k.L[j], std::min(std::abs(y1), std::abs(y2))));
    } else {
      s += k.w * stripLine(k.L[j], 0.5 * (y1 + y2));
    }
  }
  return s;
}

/// A merged patch (candidates joined across ridges at `ridges`, eta in the merged candidate's
/// plane) lump by lump: each lump's strips by KPEC on its own gap at the shared approach, the
/// amplitudes such that the displacement at every lump's deepest point, from all lumps' strips,
/// equals its interpenetration there. A lump whose amplitude comes out negative is lifted off.
}  // namespace

NormalPatch solveMergedPatch(const ContactCandidate& c, const std::vector<double>& ridges,
                             double approach, double G, double nu, const NormalOptions& o,
                             bool cut_lo, bool cut_hi) {
  NormalPatch out;
  out.approach = approach;
  out.method = NormalMethod::kNonHertzian;
  out.strip_weight = 1.0;
  const double Estar = contactModulus(G, nu);
  // The lumps' parts of the gap function: split at the sample nearest each ridge.
  std::vector<int> cut{0};
  for (double r : ridges) {
    int best = cut.back();
    for (int i = cut.back(); i < static_cast<int>(c.gap_function.size()); ++i)
      if (std::abs(c.gap_function[i].eta - r) < std::abs(c.gap_function[best].eta - r)) best = i;
    cut.push_back(best);
  }
  cut.push_back(static_cast<int>(c.gap_function.size()) - 1);
  const int nl = static_cast<int>(cut.size()) - 1;
  std::vector<Lump> lumps(nl);
  std::vector<ContactCandidate> parts(nl, c);
  std::vector<PatchGeometry> geos(nl);
  for (int k = 0; k < nl; ++k) {
    parts[k].gap_function.assign(c.gap_function.begin() + cut[k],
                                 c.gap_function.begin() + cut[k + 1] + 1);
    std::string why;
    if (!buildGeometry(parts[k], &geos[k], &why))
      return fail(NormalStatus::kNoGapFunction, why, approach);
    if (!lumpStrips(geos[k], approach, k > 0 || cut_lo, k + 1 < nl || cut_hi, Estar, o.strips,
                    &lumps[k]))
      return fail(NormalStatus::kBeyondGapFunction,
                  "the merged patch reaches the end of the gap function", approach);
  }
  std::vector<bool> on(nl);
  for (int k = 0; k < nl; ++k) on[k] = lumps[k].d0 > 0.0 && !lumps[k].L.empty();
  // Amplitudes: sum_l M_kl P_l = pi E* d0_k over the lumps in contact (Gauss, a few unknowns).
  for (int pass = 0; pass < nl; ++pass) {
    std::vector<int> idx;
    for (int k = 0; k < nl; ++k)
      if (on[k]) idx.push_back(k);
    const int m = static_cast<int>(idx.size());
    if (m == 0) break;
    std::vector<std::vector<double>> M(m, std::vector<double>(m + 1));
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) M[a][b] = lumpInfluence(lumps[idx[b]], lumps[idx[a]].eta0);
      M[a][m] = kPi * Estar * lumps[idx[a]].d0;
    }
    for (int a = 0; a < m; ++a)
      for (int r = a + 1; r < m; ++r) {
        const double f = M[r][a] / M[a][a];
        for (int b = a; b <= m; ++b) M[r][b] -= f * M[a][b];
      }
    std::vector<double> P(m);
    for (int a = m - 1; a >= 0; --a) {
      double s = M[a][m];
      for (int b = a + 1; b < m; ++b) s -= M[a][b] * P[b];
      P[a] = s / M[a][a];
    }
    bool lifted = false;
    for (int a = 0; a < m; ++a) {
      lumps[idx[a]].P = P[a];
      if (!(P[a] > 0.0)) {
        on[idx[a]] = false;
        lumps[idx[a]].P = 0.0;
        lifted = true;
      }
    }
    if (!lifted) break;
  }
  double fn = 0.0, area = 0.0, pmax = 0.0;
  out.eta_min = std::numeric_limits<double>::infinity();
  out.eta_max = -out.eta_min;
  for (int k = 0; k < nl; ++k) {
    if (!on[k]) continue;
    const Lump& l = lumps[k];
    out.eta_min = std::min(out.eta_min, l.lo);
    out.eta_max = std::max(out.eta_max, l.hi);
    for (std::size_t j = 0; j < l.L.size(); ++j) {
      NormalStrip s;
      s.eta = l.lo + (j + 0.5) * l.w;
      s.width = l.w;
      s.x_lead = l.L[j];
      s.x_trail = -l.L[j];
      s.pmax = l.P * l.L[j];
      s.force = 0.5 * kPi * l.P * l.L[j] * l.L[j] * l.w;
      fn += s.force;
      area += 2.0 * l.L[j] * l.w;
      pmax = std::max(pmax, s.pmax);
      out.strips.push_back(s);
    }
  }
  if (out.strips.empty()) {
    out.eta_min = out.eta_max = out.eta_centre = geos[0].eta0;
    out.message = "not in contact at this approach";
    return out;
  }
  out.fn = fn;
  out.pmax = pmax;
  out.area = area;
  out.eta_centre = 0.5 * (out.eta_min + out.eta_max);
  out.b = 0.5 * (out.eta_max - out.eta_min);
  out.a = out.b > 0.0 ? area / (kPi * out.b) : 0.0;
  return out;
}

WheelNormal solveWheelLoad(const WheelContactGeometry& geo, double load, double G, double nu,
                           const NormalOptions& o, const std::vector<double>& tangential_vertical) {
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
  const int nc = static_cast<int>(geo.candidates.size());
  // Each candidate's tangential force's vertical component per unit normal force (the header).
  std::vector<double> lift(nc, 0.0);
  if (!tangential_vertical.empty() && static_cast<int>(tangential_vertical.size()) != nc)
    return failed(NormalStatus::kInvalidInput,
                  "tangential_vertical must be empty or one value per candidate");
  for (int i = 0; i < nc; ++i) {
    const double t = tangential_vertical.empty() ? 0.0 : tangential_vertical[i];
    lift[i] = t;
    if (!std::isfinite(t) || !(geo.candidates[i].normal.y() + t > 0.0)) {
      std::ostringstream m;
      m << "candidate " << i << ": tangential_vertical = " << t
        << " with n_z = " << geo.candidates[i].normal.y()
        << ": its patch's whole force has no upward component, the load no balance";
      return failed(NormalStatus::kInvalidInput, m.str());
    }
  }
  // The vertical approach beyond which the wheel overlaps the rail across the ridge between
  // candidates i and i + 1 (infinite where their gap functions do not meet at a ridge).
  std::vector<double> ridge(nc - 1);
  for (int i = 0; i + 1 < nc; ++i)
    ridge[i] = ridgeApproach(geo.candidates[i], geo.candidates[i + 1]);
  struct Merged {
    ContactCandidate candidate;
    std::vector<double> ridges;
  };
  std::map<std::pair<int, int>, Merged> merged;  // by (first, last), built once
  std::vector<BuiltGeometry> geometry(nc);       // each candidate's, built once
  // Vertical force at a vertical approach; false on a patch's failure (its status in *bad).
  NormalStatus bad = NormalStatus::kOk;
  std::string bad_why;
  // Ridges that a patch reached before the rigid overlap crossed them (the strips' region
  // reaches beyond the interpenetration where the penetration factor exceeds 1): joined at every
  // approach from the one that reached them (the region grows with the approach).
  std::vector<double> reached(nc > 1 ? nc - 1 : 0, std::numeric_limits<double>::infinity());
  auto joined = [&](int k, double dv) { return dv > ridge[k] || dv >= reached[k]; };
  // On a patch of [i, last] outgrowing its gap function: the ridge at its lower end beyond which
  // a neighbour lies, -1 if none (then the gap function's sampled height is the limit).
  auto ridgeReached = [&](int i, int last) {
    const bool left = i > 0 && std::isfinite(ridge[i - 1]);
    const bool right = last + 1 < nc && std::isfinite(ridge[last]);
    if (left && right) {
      const ContactCandidate& a = geo.candidates[i];
      const ContactCandidate& b = geo.candidates[last];
      return a.gap_function.front().gap / a.normal.y() < b.gap_function.back().gap / b.normal.y()
                 ? i - 1
                 : last;
    }
    return left ? i - 1 : right ? last : -1;
  };
  std::function<bool(double, double*)> force = [&](double dv, double* fz) {
    *fz = 0.0;
    for (int i = 0; i < nc;) {
      int last = i;  // the candidates [i, last] joined across ridges below the approach
      while (last + 1 < nc && joined(last, dv)) ++last;
      int p = i;  // the one with the smallest vertical gap carries the merged patch
      for (int k = i + 1; k <= last; ++k)
        if (geo.candidates[k].vertical_gap < geo.candidates[p].vertical_gap) p = k;
      const ContactCandidate* c = &geo.candidates[p];
      NormalPatch& patch = out.patches[p];
      if (last > i) {
        auto it = merged.find({i, last});
        if (it == merged.end()) {
          Merged m;
          m.candidate = mergeCandidates(geo.candidates, i, last, p, &m.ridges);
          it = merged.emplace(std::make_pair(i, last), std::move(m)).first;
        }
        c = &it->second.candidate;
        patch = solveMergedPatch(*c, it->second.ridges, dv * c->normal.y() - c->gap, G, nu, o);
      } else {
        patch = solvePatch(*c, &geometry[p], dv * c->normal.y() - c->gap, G, nu, o);
      }
      if (patch.status == NormalStatus::kBeyondGapFunction) {
        const int k = ridgeReached(i, last);
        if (k >= 0 && !joined(k, dv)) {
          reached[k] = dv;
          return force(dv, fz);
        }
        // A gap function that the search cut at a neighbouring candidate where neither reaches
        // the other's ridge (a sharp kink between their contact planes): the patch stops at that
        // end, as a lump stops at a ridge, the neighbour's side left to the neighbour's patch.
        if (k < 0 && (i > 0 || last + 1 < nc) && patch.message.find("ridge") != std::string::npos) {
          static const std::vector<double> none;
          NormalPatch cut =
              solveMergedPatch(*c, last > i ? merged.at({i, last}).ridges : none,
                               dv * c->normal.y() - c->gap, G, nu, o, i > 0, last + 1 < nc);
          if (cut.status == NormalStatus::kOk) {
            cut.message = "cut where the gap function ends at a neighbouring candidate" +
                          (cut.message.empty() ? std::string() : "; " + cut.message);
            patch = cut;
          }
        }
      }
      if (patch.status != NormalStatus::kOk) {
        bad = patch.status;
        bad_why = "candidate " + std::to_string(p) +
                  (last > i ? " (merged with its neighbours)" : "") + ": " + patch.message;
        return false;
      }
      if (last > i) {
        std::string note = "merged with candidates " + std::to_string(i) + " to " +
                           std::to_string(last) + " across the ridge between them";
        patch.message = patch.message.empty() ? note : note + "; " + patch.message;
        for (int k = i; k <= last; ++k) {
          if (k == p) continue;
          const ContactCandidate& ck = geo.candidates[k];
          out.patches[k] = NormalPatch{};
          out.patches[k].approach = dv * ck.normal.y() - ck.gap;
          out.patches[k].merged_into = p;
          out.patches[k].message = "merged into candidate " + std::to_string(p) + "'s patch";
        }
      }
      *fz += patch.fn * (c->normal.y() + lift[p]);
      i = last + 1;
    }
    return true;
  };
  // Secant steps on w = ln(f / load) against u = ln(dv - first touch), a straight line for a
  // force growing as a power of the approach (Hertz: f ~ d^(3/2)): the first trial 10 um beyond
  // first touch (or at the caller's start), the second as if f ~ (dv - touch)^(3/2), then the
  // secant through the last two trials. A step that leaves the bracket [lo, hi] found so far,
  // or is more than half the step before last (the secant stalls), bisects it; a step beyond
  // every trial so far (no bracket yet) goes at most eight times as deep. The bracket closing
  // to kJumpWidth without the load met is a jump of the patches' force in the approach (two
  // patches joining across a ridge, a patch cut at a kink): the side whose force
  // is nearer the load is taken.
  constexpr double kJumpWidth = 1e-13;  // m, far below any approach the tolerance resolves
  const double inf = std::numeric_limits<double>::infinity();
  double lo = touch, hi = inf, f_lo = 0.0, f_hi = inf;
  bool lo_solved = false;
  double u0 = 0.0, w0 = 0.0, f = 0.0;  // the trial before, once there is one (have0)
  bool have0 = false;
  double step1 = inf, step2 = inf;  // the last two steps' sizes
  double dv = touch + 1e-5;
  double first_slope = 1.5;
  if (std::isfinite(o.start_beyond_touch) && o.start_beyond_touch > 0.0) {
    dv = touch + o.start_beyond_touch;
    if (std::isfinite(o.start_exponent) && o.start_exponent > 0.0) first_slope = o.start_exponent;
  }
  out.touch_approach = touch;
  int it = 0;
  for (; it < o.max_iterations; ++it) {
    if (!force(dv, &f)) return failed(bad, bad_why);
    ++out.trials;
    if (std::abs(f - load) <= o.load_tolerance * load) {
      if (have0 && f > 0.0 && dv > touch) {
        const double slope = (std::log(f / load) - w0) / (std::log(dv - touch) - u0);
        if (std::isfinite(slope) && slope > 0.0) out.load_exponent = slope;
      }
      break;
    }
    if (f > load) {
      hi = dv;
      f_hi = f;
    } else {
      lo = dv;
      f_lo = f;
      lo_solved = true;
    }
    if (hi < inf && hi - lo <= kJumpWidth) {
      if (!lo_solved) {  // first touch itself, its force taken as 0 so far
        if (!force(lo, &f_lo)) return failed(bad, bad_why);
        if (f_lo > load) {
          std::ostringstream m;
          m << "the patches carry " << f_lo
            << " N already at first touch (gap functions below their candidates' gaps), more "
               "than the load";
          return failed(NormalStatus::kNotConverged, m.str());
        }
      }
      const bool take_hi = f_hi - load < load - f_lo;
      dv = take_hi ? hi : lo;
      if (!force(dv, &f)) return failed(bad, bad_why);
      ++out.trials;
      std::ostringstream m;
      m.precision(9);
      m << "the patches' vertical force jumps from " << f_lo << " N to " << f_hi
        << " N at vertical approach " << lo
        << " m (patches joining, or a patch cut at a kink): the side nearer the "
           "load is taken, "
        << f << " N";
      out.message = m.str();
      break;
    }
    // The next trial: the secant in (u, w), or the 3/2 power from first touch.
    double next = inf;
    const double u1 = std::log(dv - touch);
    if (f > 0.0) {
      const double w1 = std::log(f / load);
      const double slope = have0 ? (w1 - w0) / (u1 - u0) : first_slope;
      if (slope > 0.0 && std::isfinite(slope)) next = touch + std::exp(u1 - w1 / slope);
      u0 = u1;
      w0 = w1;
      have0 = true;
    }
    if (hi < inf) {
      if (!(next > lo && next < hi) || std::abs(next - dv) > 0.5 * step2) next = 0.5 * (lo + hi);
    } else if (!(next > lo) || next > touch + 8.0 * (lo - touch)) {
      next = touch + 8.0 * (lo - touch);
    }
    step2 = step1;
    step1 = std::abs(next - dv);
    dv = next;
  }
  // The patches hold the last trial's solution, at dv.
  out.vertical_approach = dv;
  return out;
}

}  // namespace wheel_rail_contact
