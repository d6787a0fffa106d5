#include "validation/manchester_a22.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/exact/halfspace_normal.hpp"
#include "core/normal/merge_candidates.hpp"
#include "validation/patch_exact.hpp"

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
    r.fx = -number(f[19], path);
    r.fs = number(f[20], path);
    r.mz = number(f[21], path) * 1e-3;
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
  e.solved = true;
  if (!(approach > 0.0)) return e;  // out of contact
  const ExactPatch x = exactPatchNormal(c, approach, o.G, o.nu, o.exact_mx, o.exact_my);
  if (x.grid.size() == 0) return e;  // no sample interpenetrates: out of contact
  if (!x.solution.converged) {
    e.solved = false;
    e.message = "exact active set did not converge";
    return e;
  }
  e.fn = x.fn;
  e.pmax = x.pmax;
  e.approach = approach;
  e.grid = x.grid;
  e.eta_offset = x.eta_offset;
  e.p = x.solution.p;
  if (e.fn <= 0.0) return e;
  e.eta_min = x.eta_min;
  e.eta_max = x.eta_max;
  const HalfspaceGrid& g = x.grid;
  e.x_min = 1e9;
  e.x_max = -1e9;
  for (int ix = 0; ix < g.mx; ++ix)
    for (int iy = 0; iy < g.my; ++iy)
      if (e.p[g.index(ix, iy)] > 0.0) {
        e.x_min = std::min(e.x_min, g.xc(ix) - 0.5 * g.dx);
        e.x_max = std::max(e.x_max, g.xc(ix) + 0.5 * g.dx);
      }
  return e;
}

namespace {

using GeometrySource = std::function<WheelContactGeometry(WheelSide, const WheelsetPose&)>;

A22Wheel runWheel(const GeometrySource& geometry, const WheelsetTrackData& data,
                  const A22State& state, const A22Options& o) {
  A22Wheel w;
  w.state = state;
  // The wheelset lowered (or raised) to first touch of this wheel: the gap functions describe the
  // profiles about where they touch, and the benchmark's vertical position is its own result.
  WheelsetPose pose = a22Pose(state);
  const std::string where = std::string(state.side == WheelSide::kLeft ? "left" : "right") +
                            " wheel, case " + std::to_string(state.number) + ": ";
  for (int k = 0; k < 3; ++k) {
    w.geometry = geometry(state.side, pose);
    if (w.geometry.closest < 0) break;
    const double vg = w.geometry.candidates[w.geometry.closest].vertical_gap;
    if (std::abs(vg) < 1e-9) break;
    pose.z -= vg;
  }
  w.geometry = geometry(state.side, pose);
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
    p.creepages = patchCreepages(state.side, pose, motion, p.candidate, data);
    p.merged_first = p.merged_last = p.index;
    w.patches.push_back(p);
  }
  for (A22Patch& p : w.patches) {
    if (p.ours.merged_into >= 0) continue;
    for (const A22Patch& q : w.patches)
      if (q.ours.merged_into == p.index) {
        p.merged_first = std::min(p.merged_first, q.index);
        p.merged_last = std::max(p.merged_last, q.index);
      }
    p.exact_candidate =
        p.merged_last > p.merged_first
            ? mergeCandidates(w.geometry.candidates, p.merged_first, p.merged_last, p.index)
            : p.candidate;
  }
  // The exact wheel: the vertical approach V at which sum_i fn_i n_z,i = fz, candidate i at
  // approach V n_z,i - gap_i (patch_normal.hpp's WheelNormal). fz grows about as V^1.5 (Hertz), so
  // V <- V (fz / F)^(2/3) from our own V converges in a few steps on any patch shape.
  double V = w.normal.vertical_approach;
  for (int it = 0; it < o.exact_iterations; ++it) {
    double F = 0.0;
    for (A22Patch& p : w.patches) {
      if (p.ours.merged_into >= 0) {  // solved on the merged gap of the patch that took it
        p.exact = A22Exact{};
        p.exact.solved = true;
        continue;
      }
      const double d = V * p.candidate.normal.y() - p.candidate.gap;  // normal: (y, z)
      p.exact = solveExactPatch(p.exact_candidate, d, o);
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

}  // namespace

A22Wheel runA22Wheel(const ContactSearch& search, const A22State& state, const A22Options& o) {
  return runWheel(
      [&search](WheelSide side, const WheelsetPose& pose) { return search.search(side, pose); },
      search.data(), state, o);
}

A22Wheel runA22Wheel(const ContactTable& table, const A22State& state, const A22Options& o) {
  return runWheel(
      [&table](WheelSide side, const WheelsetPose& pose) { return table.search(side, pose); },
      table.contactSearch().data(), state, o);
}

std::vector<A22Creep> runA22Creep(const A22Wheel& w, const A22Options& o, const A22CreepOptions& c,
                                  const std::vector<A22Reference>& refs) {
  std::vector<A22Creep> out;
  if (!w.message.empty()) return out;
  const A22State& s = w.state;
  WheelsetState state;
  state.pose = a22Pose(s);
  state.motion = a22Motion(s);
  state.fz_left = state.fz_right = s.fz;
  // The loaded patches of the exact solution (a merged patch at the candidate that took it).
  for (const A22Patch& p : w.patches)
    if (p.ours.merged_into < 0 && p.exact.fn > 0.0) {
      A22Creep k;
      k.index = p.index;
      k.zone = p.candidate.zone;
      out.push_back(k);
    }
  const auto patchOf = [&](const A22Creep& k) -> const A22Patch& {
    for (const A22Patch& p : w.patches)
      if (p.index == k.index) return p;
    throw std::logic_error("runA22Creep: no patch");
  };
  // WheelsetContact's patch on the same candidate: the same zone, the contact point on the rail
  // within 0.1 mm (it searches at first touch within 10 um of height, not 1 nm).
  const auto sameCandidate = [](const ContactCandidate& a, const ContactCandidate& b) {
    return a.zone == b.zone && (a.rail_file - b.rail_file).norm() < 1e-4;
  };
  std::vector<std::vector<NormalStrip>> strips(out.size());  // WheelsetContact's, per patch
  for (const std::string& model : c.models) {
    ContactParameters par;
    par.model = model;
    par.G = o.G;
    par.nu = o.nu;
    par.mu = c.mu;
    WheelsetContactOptions wo;
    wo.normal = o.normal;  // the same normal problem as the wheel's
    WheelsetContact wc(WheelsetTrackData{}, par, wo);
    const auto wheelOf = [&](const WheelsetResult& r) -> const WheelResult& {
      return s.side == WheelSide::kLeft ? r.left : r.right;
    };
    WheelsetResult last = wc.step(state, 0.0);
    int steps = 0;
    bool settled = false;
    while (steps < c.max_steps && !settled) {
      const WheelsetResult next = wc.step(state, c.dt);
      ++steps;
      settled = true;
      const WheelResult &a = wheelOf(last), &b = wheelOf(next);
      if (a.patches.size() != b.patches.size()) settled = false;
      for (size_t i = 0; settled && i < b.patches.size(); ++i) {
        const PatchResult &pa = a.patches[i], &pb = b.patches[i];
        const double tol = c.settle_tolerance * c.mu * pb.normal.fn;
        const double lever = std::sqrt(pb.normal.a * pb.normal.b);
        settled = std::abs(pa.fx - pb.fx) <= tol && std::abs(pa.fs - pb.fs) <= tol &&
                  std::abs(pa.mz - pb.mz) <= tol * lever;
      }
      last = next;
    }
    const WheelResult& r = wheelOf(last);
    for (A22Creep& k : out) {
      A22ModelForces f;
      f.model = model;
      f.steps = steps;
      f.settled = settled;
      for (const PatchResult& p : r.patches) {
        if (!sameCandidate(p.geometry, patchOf(k).candidate)) continue;
        f.found = true;
        f.fx = p.fx;
        f.fs = p.fs;
        f.mz = p.mz;
        f.status = p.tangential_status;
        f.message = p.message;
        if (k.fn == 0.0) {  // the same normal problem and creepages whichever the model
          k.fn = p.normal.fn;
          k.a = p.normal.a;
          k.b = p.normal.b;
          k.creepages = {p.creepages.xi, p.creepages.eta, p.creepages.phi};
          strips[&k - out.data()] = p.normal.strips;
        }
      }
      k.models.push_back(f);
    }
  }
  for (A22Creep& k : out) {
    const A22Patch& p = patchOf(k);
    if (k.fn > 0.0) {
      ExactPatch e;
      e.grid = p.exact.grid;
      e.eta_offset = p.exact.eta_offset;
      e.solution.p = p.exact.p;
      e.fn = p.exact.fn;
      k.exact = ExactPatchTangential(e, s.side, o.G, o.nu, k.fn).steady(k.creepages, c.mu);
      // Our pressure on the same grid: each strip's semi-ellipse at the element centres.
      const HalfspaceGrid& g = e.grid;
      Eigen::VectorXd ours = Eigen::VectorXd::Zero(g.size());
      for (const NormalStrip& st : strips[&k - out.data()]) {
        const double xm = 0.5 * (st.x_lead + st.x_trail), half = 0.5 * (st.x_lead - st.x_trail);
        if (!(half > 0.0)) continue;
        for (int iy = 0; iy < g.my; ++iy) {
          const double eta = e.eta_offset + g.yc(iy);
          if (std::abs(eta - st.eta) > 0.5 * st.width) continue;
          for (int ix = 0; ix < g.mx; ++ix) {
            const double u = (g.xc(ix) - xm) / half;
            if (std::abs(u) < 1.0) ours[g.index(ix, iy)] = st.pmax * std::sqrt(1.0 - u * u);
          }
        }
      }
      e.solution.p = ours;
      e.fn = ours.sum() * g.dx * g.dy;
      if (e.fn > 0.0)
        k.exact_on_ours =
            ExactPatchTangential(e, s.side, o.G, o.nu, k.fn).steady(k.creepages, c.mu);
    }
  }
  // Each of CONTACT's patches of this wheel and case beside our patch nearest on the rail.
  for (const A22Reference& ref : refs) {
    if (ref.side != s.side || ref.number != s.number) continue;
    A22Creep* best = nullptr;
    double dist = std::numeric_limits<double>::infinity();
    for (A22Creep& k : out) {
      const A22Patch& p = patchOf(k);
      const double d = std::abs(railFilePointAt(p.candidate, p.ours.eta_centre).x() - ref.y_rail);
      if (d < dist) dist = d, best = &k;
    }
    if (best) best->contact = &ref;
  }
  return out;
}

}  // namespace wheel_rail_contact
