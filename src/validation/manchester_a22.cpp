#include "validation/manchester_a22.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/exact/halfspace_normal.hpp"

namespace wheel_rail_contact {

namespace {

/// The non-comment lines of a CSV after its header, split at commas; the header must be `header`.
std::vector<std::vector<std::string>> readCsv(const std::string& path, const std::string& header) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  bool seen = false;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    if (!seen) {
      if (line != header)
        throw std::runtime_error(path + ":" + std::to_string(number) + ": expected the header " +
                                 header);
      seen = true;
      continue;
    }
    std::vector<std::string> fields;
    std::istringstream ls(line);
    for (std::string f; std::getline(ls, f, ',');) fields.push_back(f);
    if (fields.size() != static_cast<size_t>(std::count(header.begin(), header.end(), ',') + 1))
      throw std::runtime_error(path + ":" + std::to_string(number) + ": wrong field count");
    rows.push_back(fields);
  }
  if (rows.empty()) throw std::runtime_error(path + ": no rows");
  return rows;
}

double number(const std::string& s, const std::string& path) {
  size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || !std::isfinite(v))
    throw std::runtime_error(path + ": '" + s + "' is not a number");
  return v;
}

WheelSide sideOf(const std::string& s, const std::string& path) {
  if (s == "left") return WheelSide::kLeft;
  if (s == "right") return WheelSide::kRight;
  throw std::runtime_error(path + ": wheel '" + s + "' is neither left nor right");
}

/// The gap function between its samples: the gap by a natural cubic spline, the wheel's radius and
/// angle linearly. Linear interpolation of the gap itself would put a kink at every sample, and a
/// kink of the gap is a concentrated curvature under which the exact pressure peaks, more sharply
/// the finer the grid: a fine exact grid would then resolve the sampling, not the profiles.
class GapInterpolant {
 public:
  explicit GapInterpolant(const std::vector<GapSample>& f) : f_(f), m_(f.size(), 0.0) {
    const size_t n = f.size();
    if (n < 3) return;
    // Second derivatives m_i, m_0 = m_{n-1} = 0: the tridiagonal system by the Thomas algorithm.
    std::vector<double> c(n, 0.0), d(n, 0.0);
    for (size_t i = 1; i + 1 < n; ++i) {
      const double h0 = f[i].eta - f[i - 1].eta, h1 = f[i + 1].eta - f[i].eta;
      const double rhs = 6.0 * ((f[i + 1].gap - f[i].gap) / h1 - (f[i].gap - f[i - 1].gap) / h0);
      const double diag = 2.0 * (h0 + h1) - h0 * c[i - 1];
      c[i] = h1 / diag;
      d[i] = (rhs - h0 * d[i - 1]) / diag;
    }
    for (size_t i = n - 2; i >= 1; --i) m_[i] = d[i] - c[i] * m_[i + 1];
  }

  /// False outside the samples.
  bool at(double eta, GapSample* out) const {
    if (f_.size() < 2 || eta < f_.front().eta || eta > f_.back().eta) return false;
    auto it = std::lower_bound(f_.begin(), f_.end(), eta,
                               [](const GapSample& s, double e) { return s.eta < e; });
    if (it == f_.begin()) ++it;
    const size_t i = static_cast<size_t>(it - f_.begin());
    const GapSample& a = f_[i - 1];
    const GapSample& b = f_[i];
    const double h = b.eta - a.eta, t = (eta - a.eta) / h, u = 1.0 - t;
    out->eta = eta;
    out->gap = u * a.gap + t * b.gap +
               h * h / 6.0 * ((u * u * u - u) * m_[i - 1] + (t * t * t - t) * m_[i]);
    out->rolling_radius = u * a.rolling_radius + t * b.rolling_radius;
    out->contact_angle = u * a.contact_angle + t * b.contact_angle;
    return true;
  }

 private:
  const std::vector<GapSample>& f_;
  std::vector<double> m_;
};

/// The box on the contact plane where h(x, eta) < level: its eta range and largest |x|.
bool interpenetrationBox(const ContactCandidate& c, double level, double* eta_lo, double* eta_hi,
                         double* x_half) {
  const double g0 = c.gap;  // at eta = 0, where patch_normal.hpp measures first touch
  bool any = false;
  *x_half = 0.0;
  for (const GapSample& s : c.gap_function) {
    const double h = s.gap - g0;
    if (h >= level) continue;
    const double rx = s.rolling_radius / std::max(std::cos(s.contact_angle), 1e-3);
    *x_half = std::max(*x_half, std::sqrt(2.0 * rx * (level - h)));
    *eta_lo = any ? std::min(*eta_lo, s.eta) : s.eta;
    *eta_hi = any ? std::max(*eta_hi, s.eta) : s.eta;
    any = true;
  }
  return any;
}

}  // namespace

std::vector<A22State> readA22States(const std::string& path) {
  std::vector<A22State> out;
  for (const auto& f :
       readCsv(path, "wheel,case,y_mm,yaw_rad,roll_rad,fz_N,vs_mm_s,vpitch_rad_s")) {
    A22State s;
    s.side = sideOf(f[0], path);
    s.number = static_cast<int>(number(f[1], path));
    s.y_mm = number(f[2], path);
    s.yaw = number(f[3], path);
    s.roll = number(f[4], path);
    s.fz = number(f[5], path);
    s.vs_mm_s = number(f[6], path);
    s.vpitch = number(f[7], path);
    out.push_back(s);
  }
  return out;
}

WheelsetPose a22Pose(const A22State& s) {
  WheelsetPose p;
  p.y = -s.y_mm * 1e-3;
  p.yaw = -s.yaw;
  p.roll = s.roll;
  return p;
}

WheelsetMotion a22Motion(const A22State& s) {
  WheelsetMotion m;
  m.V = s.vs_mm_s * 1e-3;
  m.omega = -s.vpitch;
  return m;
}

std::vector<A22Reference> readA22Reference(const std::string& path) {
  std::vector<A22Reference> out;
  const std::string header =
      "wheel,case,y_ws_mm,yaw_ws_rad,roll_ws_rad,z_ws_mm,patch,xcp_tr_mm,ycp_tr_mm,zcp_tr_mm,"
      "deltcp_tr_rad,ycp_r_mm,zcp_r_mm,ycp_w_mm,zcp_w_mm,cksi,ceta,cphi_per_mm,fn_N,fx_N,fs_N,"
      "mn_Nmm,approach_mm,pmax_MPa";
  for (const auto& f : readCsv(path, header)) {
    A22Reference r;
    r.side = sideOf(f[0], path);
    r.number = static_cast<int>(number(f[1], path));
    r.patch = static_cast<int>(number(f[6], path));
    const double mirror = r.side == WheelSide::kLeft ? -1.0 : 1.0;
    r.y_rail = mirror * number(f[11], path) * 1e-3;
    r.z_rail = number(f[12], path) * 1e-3;
    r.contact_angle = -mirror * number(f[10], path);
    r.cksi = number(f[15], path);
    r.ceta = number(f[16], path);
    r.cphi = number(f[17], path) * 1e3;
    r.fn = number(f[18], path);
    r.approach = number(f[22], path) * 1e-3;
    r.pmax = number(f[23], path) * 1e6;
    out.push_back(r);
  }
  return out;
}

Eigen::Vector2d railFilePointAt(const ContactCandidate& c, double eta) {
  // The contact plane's lateral direction, toward the track centre, is (cos delta, -sin delta)
  // in the profile frame (y toward the centre, z up); the file's axes are that frame turned half
  // a turn about x (doc/profiles.md).
  return c.rail_file + eta * Eigen::Vector2d(-std::cos(c.contact_angle), std::sin(c.contact_angle));
}

A22Exact solveExactPatch(const ContactCandidate& c, double approach, const A22Options& o) {
  A22Exact e;
  if (!(approach > 0.0)) {
    e.solved = true;  // out of contact
    return e;
  }
  double eta_lo = 0.0, eta_hi = 0.0, x_half = 0.0;
  if (!interpenetrationBox(c, o.box_fraction * approach, &eta_lo, &eta_hi, &x_half) &&
      !interpenetrationBox(c, approach, &eta_lo, &eta_hi, &x_half)) {
    e.solved = true;
    return e;
  }
  // At least two samples' spacing across, so a narrow patch still gets a few elements.
  const double spacing =
      c.gap_function.size() > 1
          ? (c.gap_function.back().eta - c.gap_function.front().eta) / (c.gap_function.size() - 1)
          : 1e-4;
  double width = std::max(eta_hi - eta_lo, 2.0 * spacing);
  double centre = 0.5 * (eta_lo + eta_hi);
  double length = 2.0 * std::max(x_half, 1e-5);
  const double g0 = c.gap;  // at eta = 0, where patch_normal.hpp measures first touch
  for (int attempt = 0; attempt < 4; ++attempt) {
    HalfspaceGrid g;
    g.mx = o.exact_mx;
    g.my = o.exact_my;
    g.dx = length / g.mx;
    g.dy = width / g.my;
    const GapInterpolant gap(c.gap_function);
    Eigen::VectorXd h(g.size());
    bool beyond = false;  // part of the grid lies past the sampled gap function
    for (int iy = 0; iy < g.my; ++iy) {
      GapSample s;
      const bool inside = gap.at(centre + g.yc(iy), &s);
      for (int ix = 0; ix < g.mx; ++ix) {
        const double x = g.xc(ix);
        // Past the samples the gap exceeds what the search sampled: out of contact at this
        // approach unless the patch reaches there, which the edge check below reports.
        h[g.index(ix, iy)] =
            inside ? s.gap - g0 + x * x * std::cos(s.contact_angle) / (2.0 * s.rolling_radius)
                   : 1.0;
      }
      beyond = beyond || !inside;
    }
    const NormalSolution s = solveNormalGapApproach(g, o.G, o.nu, h, approach);
    if (!s.converged) {
      e.message = "exact active set did not converge";
      return e;
    }
    bool edge_x = false, edge_y = false;
    e.x_min = e.eta_min = 1e9;
    e.x_max = e.eta_max = -1e9;
    for (int ix = 0; ix < g.mx; ++ix)
      for (int iy = 0; iy < g.my; ++iy) {
        if (s.p[g.index(ix, iy)] <= 0.0) continue;
        edge_x = edge_x || ix == 0 || ix == g.mx - 1;
        edge_y = edge_y || iy == 0 || iy == g.my - 1;
        e.x_min = std::min(e.x_min, g.xc(ix) - 0.5 * g.dx);
        e.x_max = std::max(e.x_max, g.xc(ix) + 0.5 * g.dx);
        e.eta_min = std::min(e.eta_min, centre + g.yc(iy) - 0.5 * g.dy);
        e.eta_max = std::max(e.eta_max, centre + g.yc(iy) + 0.5 * g.dy);
      }
    if (edge_y && beyond) {
      e.message = "the exact patch reaches the end of the sampled gap function";
      return e;
    }
    if (edge_x) length *= 1.4;
    if (edge_y) width *= 1.4;
    if (edge_x || edge_y) continue;
    e.solved = true;
    e.fn = s.fz;
    e.pmax = s.p.maxCoeff();
    e.approach = approach;
    e.grid = g;
    e.eta_offset = centre;
    e.p = s.p;
    if (s.fz <= 0.0) e.x_min = e.x_max = e.eta_min = e.eta_max = 0.0;
    return e;
  }
  e.message = "the exact patch outgrew its grid four times";
  return e;
}

A22Wheel runA22Wheel(const ContactSearch& search, const A22State& state, const A22Options& o) {
  A22Wheel w;
  w.state = state;
  // The wheelset lowered (or raised) to first touch of this wheel: the gap functions describe the
  // profiles about where they touch, and the benchmark's vertical position is its own result.
  WheelsetPose pose = a22Pose(state);
  const std::string where = std::string(state.side == WheelSide::kLeft ? "left" : "right") +
                            " wheel, case " + std::to_string(state.number) + ": ";
  for (int k = 0; k < 3; ++k) {
    w.geometry = search.search(state.side, pose);
    if (w.geometry.closest < 0) break;
    const double vg = w.geometry.candidates[w.geometry.closest].vertical_gap;
    if (std::abs(vg) < 1e-9) break;
    pose.z -= vg;
  }
  w.geometry = search.search(state.side, pose);
  if (w.geometry.status != ContactSearchStatus::kOk)
    throw std::runtime_error(where + "contact search: " + w.geometry.message);
  w.normal = solveWheelLoad(w.geometry, state.fz, o.G, o.nu, o.normal);
  if (w.normal.status != NormalStatus::kOk) {
    w.message = "normal problem: " + w.normal.message;
    return w;
  }
  const WheelsetMotion motion = a22Motion(state);
  const size_t n = w.geometry.candidates.size();
  for (size_t i = 0; i < n; ++i) {
    A22Patch p;
    p.index = static_cast<int>(i);
    p.candidate = w.geometry.candidates[i];
    p.ours = w.normal.patches.at(i);
    p.creepages = patchCreepages(state.side, pose, motion, p.candidate, search.data());
    w.patches.push_back(p);
  }
  // The exact wheel: the vertical approach V at which sum_i fn_i n_z,i = fz, candidate i at
  // approach V n_z,i - gap_i (patch_normal.hpp's WheelNormal). fz grows about as V^1.5 (Hertz), so
  // V <- V (fz / F)^(2/3) from our own V converges in a few steps on any patch shape.
  double V = w.normal.vertical_approach;
  for (int it = 0; it < o.exact_iterations; ++it) {
    double F = 0.0;
    for (A22Patch& p : w.patches) {
      const double d = V * p.candidate.normal.y() - p.candidate.gap;  // normal: (y, z)
      p.exact = solveExactPatch(p.candidate, d, o);
      if (!p.exact.solved) throw std::runtime_error(where + p.exact.message);
      if (it == 0) p.exact_fn_at_our_approach = p.exact.fn;
      F += p.exact.fn * p.candidate.normal.y();  // the vertical component
    }
    w.exact_vertical_approach = V;
    if (std::abs(F - state.fz) <= o.exact_load_tolerance * state.fz) {
      w.exact_converged = true;
      break;
    }
    if (!(F > 0.0)) throw std::runtime_error(where + "the exact patches carry no load");
    V *= std::pow(state.fz / F, 2.0 / 3.0);
  }
  return w;
}

}  // namespace wheel_rail_contact
