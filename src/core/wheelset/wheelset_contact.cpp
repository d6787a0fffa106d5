#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "wheel_rail_contact/fastsim/patch_shape.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

namespace wheel_rail_contact {

const char* toString(WheelStatus s) {
  switch (s) {
    case WheelStatus::kOk:
      return "ok";
    case WheelStatus::kNoLoad:
      return "no_load";
    case WheelStatus::kNoContact:
      return "no_contact";
    case WheelStatus::kInvalidInput:
      return "invalid_input";
    case WheelStatus::kNormalFailed:
      return "normal_failed";
  }
  return "unknown";
}

namespace {

const char* zoneName(ContactZone z) {
  switch (z) {
    case ContactZone::kTread:
      return "tread";
    case ContactZone::kGaugeCorner:
      return "gauge_corner";
    case ContactZone::kFlange:
      return "flange";
  }
  return "unknown";
}

bool finite(const WheelsetPose& p) {
  return std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.yaw) && std::isfinite(p.roll);
}

bool finite(const WheelsetMotion& m) {
  return std::isfinite(m.V) && std::isfinite(m.omega) && std::isfinite(m.vy) &&
         std::isfinite(m.yaw_rate) && std::isfinite(m.curvature) && std::isfinite(m.cant) &&
         std::isfinite(m.vz) && std::isfinite(m.roll_rate);
}

bool sameProfile(const std::shared_ptr<const Profile>& a, const std::shared_ptr<const Profile>& b) {
  if (a == b) return true;
  return a && b && a->kind() == b->kind() && a->smoothingLength() == b->smoothingLength() &&
         a->points() == b->points();
}

// The same placement of the same profiles (as ContactSearch holds them: null right profiles
// resolved to the standard ones).
bool sameTrack(const WheelsetTrackData& a, const WheelsetTrackData& b) {
  return a.nominal_radius == b.nominal_radius && a.flange_back_distance == b.flange_back_distance &&
         a.flange_back_position == b.flange_back_position && a.gauge == b.gauge &&
         a.gauge_depth == b.gauge_depth && a.rail_inclination == b.rail_inclination &&
         sameProfile(a.wheel_right, b.wheel_right) && sameProfile(a.rail_right, b.rail_right) &&
         sameProfile(a.wheel_left, b.wheel_left) && sameProfile(a.rail_left, b.rail_left);
}

// A slot's model (null while its patch is absent) and whether its patch was present this step.
struct Slot {
  std::unique_ptr<ContactModel> model;
  double a_cover = 0.0, b_cover = 0.0;  // the patch the model's fixed mesh or grid covers [m]
  PatchShape shape;  // the patch's strips, kept for the step (its storage reused)
  bool present = false;
  double fs_per_fn = 0.0;  // the last step's fs / fn, within +-mu (whole_force_balance)
};

// A patch's slot name: its zone, with "_k" for the k-th patch of that zone from the field side.
std::string slotName(ContactZone zone, int k) {
  return std::string(zoneName(zone)) + (k > 1 ? "_" + std::to_string(k) : "");
}

// How far from first touch the search may leave a wheel before it is searched again there [m]: a
// tenth of a 10 kN wheel's elastic approach.
constexpr double kTouchTolerance = 1e-5;

// The patch's forces in track axes about the wheel's centre c (TrackWrench's formula).
TrackWrench trackWrench(const PatchResult& p, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n =
      Eigen::Vector3d(0.0, p.geometry.normal.x(), p.geometry.normal.y()).normalized();
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d f = p.fx * ex + p.fs * n.cross(ex) + p.normal.fn * n;
  const Eigen::Vector3d m = (p.geometry.point - c).cross(f) + p.mz * n;
  return {f.x(), f.y(), f.z(), m.x(), m.y(), m.z()};
}

void add(TrackWrench* sum, const TrackWrench& w) {
  sum->fx += w.fx;
  sum->fy += w.fy;
  sum->fz += w.fz;
  sum->mx += w.mx;
  sum->my += w.my;
  sum->mz += w.mz;
}

// The share of the reference patch a fixed mesh covers: fz_max = 1.5 fz0 (fz_max 0), a ~ fz^(1/3).
const double kCover = std::cbrt(1.5);

}  // namespace

struct WheelsetContact::Impl {
  WheelsetTrackData track;
  ContactParameters parameters;
  WheelsetContactOptions options;
  ContactSearch search;
  std::shared_ptr<const ContactTable> table;
  std::size_t direct_search_fallbacks = 0;           // directSearchFallbacks()
  std::array<std::map<std::string, Slot>, 2> slots;  // [0] left, [1] right, by slot name
  // Each wheel's previous normal solution for the warm start, with its candidates' zones; empty
  // zones: none (cold start).
  struct Previous {
    std::vector<ContactZone> zones;
    double beyond_touch = 0.0, exponent = 1.5;
  };
  std::array<Previous, 2> previous;
  std::array<double, 2> centre_axial{};  // each wheel's centre along the axle [m] (WheelResult)
  // Per side, +1 or -1: the rail profile's arc length grows toward the track centre (as a patch's
  // eta does) or away from it; 0: not found, the contact point's lateral track coordinate toward
  // the centre is the patch's origin instead (PatchShape::origin).
  std::array<double, 2> arcSign = {0.0, 0.0};

  Impl(const WheelsetTrackData& t, const ContactParameters& p, const WheelsetContactOptions& o)
      : track(t), parameters(p), options(o), search(t, o.search) {
    validate(parameters);
    makeContactModel(parameters);  // throws now for a model this build does not provide
    if (options.whole_force_balance && !options.tangential)
      throw std::invalid_argument(
          "whole_force_balance: needs the tangential forces (WheelsetContactOptions::tangential)");
    if (options.contact_table) {
      if (!sameTrack(options.contact_table->contactSearch().data(), search.data()))
        throw std::invalid_argument(
            "contact_table: the shared table tabulates other track data or profiles than this "
            "wheelset's");
      table = std::move(options.contact_table);  // one reference per object: `table`
    } else if (options.use_contact_table) {
      table = std::make_shared<const ContactTable>(search, options.table);
    }
    // The wheel profile file's lateral origin placed on the axle as the search places the
    // profile: sigma (y_p - flange back) - sigma flange_back_distance / 2 (contact_search.cpp).
    const WheelsetTrackData& d = search.data();
    for (int k = 0; k < 2; ++k) {
      const double sigma = k == 0 ? -1.0 : 1.0;
      const Profile& w = k == 0 && d.wheel_left ? *d.wheel_left : *d.wheel_right;
      const double back = w.fromFile(Eigen::Vector2d(d.flange_back_position, 0.0)).x();
      centre_axial[k] = sigma * (w.fromFile(Eigen::Vector2d::Zero()).x() - back) -
                        sigma * 0.5 * d.flange_back_distance;
    }
    for (WheelSide side : {WheelSide::kLeft, WheelSide::kRight})
      arcSign[side == WheelSide::kLeft ? 0 : 1] = railArcSign(side);
  }

  // Whether the rail profile's arc length s_rail grows toward the track centre on `side`: the
  // contact point of the centred wheelset shifted 1 mm either way moves along the rail both in s
  // and in y; +1, -1, or 0 where the search finds no single tread candidate to tell.
  double railArcSign(WheelSide side) const {
    double s[2], y[2];
    for (int k = 0; k < 2; ++k) {
      WheelsetPose pose;
      pose.y = k == 0 ? -1e-3 : 1e-3;
      const WheelContactGeometry g = search.search(side, pose);
      if (g.status != ContactSearchStatus::kOk || g.closest < 0) return 0.0;
      s[k] = g.candidates[g.closest].s_rail;
      y[k] = g.candidates[g.closest].point.y();
    }
    const double toCentre = (y[1] - y[0]) * (side == WheelSide::kLeft ? -1.0 : 1.0);
    const double ds = s[1] - s[0];
    if (!(std::abs(ds) > 1e-7) || !(std::abs(toCentre) > 1e-7)) return 0.0;
    return ds * toCentre > 0.0 ? 1.0 : -1.0;
  }

  // The patch's reference point on the rail's profile, growing with eta (PatchShape::origin).
  double profileOrigin(WheelSide side, const ContactCandidate& c) const {
    const int w = side == WheelSide::kLeft ? 0 : 1;
    if (arcSign[w] != 0.0) return arcSign[w] * c.s_rail;
    return c.point.y() * (side == WheelSide::kLeft ? -1.0 : 1.0);
  }

  // The geometry at first touch; the table finds the touching height within one lookup.
  WheelContactGeometry geometryAtTouch(WheelSide side, WheelsetPose* pose) const {
    if (table) return table->searchAtTouch(side, pose, kTouchTolerance);
    return searchAtTouchDirect(side, pose);
  }
  WheelContactGeometry searchAtTouchDirect(WheelSide side, WheelsetPose* pose) const {
    WheelContactGeometry g = search.search(side, *pose);
    if (g.status == ContactSearchStatus::kOk && g.closest >= 0 &&
        std::abs(g.candidates[g.closest].vertical_gap) > kTouchTolerance) {
      pose->z -= g.candidates[g.closest].vertical_gap;
      g = search.search(side, *pose);
    }
    return g;
  }

  // Drops the models of one wheel's slots whose patch was not present this step: the patch
  // starts from rest when it comes back.
  void resetAbsent(std::map<std::string, Slot>& wheel) {
    for (auto& kv : wheel) {
      if (!kv.second.present) {
        kv.second.model.reset();
        kv.second.fs_per_fn = 0.0;
      }
      kv.second.present = false;
    }
  }

  // A model for a patch that appears. The reference patch a0, b0, fz0 has no other use here (each
  // step gives a, b): it is set to the patch's, so that a fixed mesh (fz_max 0: 1.5 fn) fits the
  // patch instead of a reference patch of another scale. Null, with the reason, if the patch is
  // outside the model's ranges (a/b beyond Kalker's table).
  // `onStrips`: the patch reaches the model as its strips (StepInput::shape), whose a/b may lie
  // beyond Kalker's table: the reference patch is then held at the table's end (a FastSim model
  // takes its coefficients there, with a note); the exact model, on the ellipse, refuses it.
  std::unique_ptr<ContactModel> modelFor(const NormalPatch& np, bool onStrips,
                                         std::string* why) const {
    const bool inTable = np.a >= kKalkerMinAOverB * np.b && np.a <= kKalkerMaxAOverB * np.b;
    // As checkStepInput would refuse the step: said in the patch's own terms, not as a0/b0.
    if (!inTable && (!onStrips || parameters.model == "exact")) {
      *why = "the patch's a/b = " + std::to_string(np.a / np.b) +
             " is outside Kalker's table [0.1, 10], which the elliptic-patch models take";
      return nullptr;
    }
    ContactParameters q = parameters;
    // Held just inside the table's ends: a0 / b0 rounds back onto them.
    q.a0 = std::min(std::max(np.a, kKalkerMinAOverB * (1.0 + 1e-12) * np.b),
                    kKalkerMaxAOverB * (1.0 - 1e-12) * np.b);
    q.b0 = np.b;
    q.fz0 = np.fn;
    q.fz_max = 0.0;
    try {
      return makeContactModel(q);
    } catch (const std::exception& e) {
      *why = e.what();
      return nullptr;
    }
  }

  WheelResult stepWheel(WheelSide side, const WheelsetState& s, double dt) {
    const int w = side == WheelSide::kLeft ? 0 : 1;
    std::map<std::string, Slot>& wheel = slots[w];
    Previous& prev = previous[w];
    WheelResult r;
    r.side = side;
    const double load = side == WheelSide::kLeft ? s.fz_left : s.fz_right;
    const auto finish = [&](WheelStatus status, std::string message, bool clear) {
      r.status = status;
      r.message = std::move(message);
      r.patches.clear();
      r.centre.setZero();
      if (clear) {
        resetAbsent(wheel);  // no patch present: every slot of the wheel
        prev.zones.clear();
      }
      return r;
    };
    // Rejected input leaves the history as it was, as a model's kRejected step does.
    if (!finite(s.pose) || !finite(s.motion) || !std::isfinite(load) || !std::isfinite(dt))
      return finish(WheelStatus::kInvalidInput, "a state value or dt is not finite", false);
    if (dt < 0.0) return finish(WheelStatus::kInvalidInput, "dt < 0", false);
    if (!(std::abs(s.motion.cant) <= kMaxCant)) {
      std::ostringstream m;
      m << "cant = " << s.motion.cant << " rad is beyond +-" << kMaxCant << " rad";
      return finish(WheelStatus::kInvalidInput, m.str(), false);
    }
    if (!(load > 0.0)) return finish(WheelStatus::kNoLoad, "vertical load <= 0", true);

    // The load sets the approach, so the wheel is searched at first touch: from z = 0 lowered or
    // raised by the closest candidate's vertical gap (a vertical shift moves every vertical gap
    // alike, so one more search lands on it) when that is more than kTouchTolerance. The normal
    // problem's approach then starts where its gap functions were sampled.
    WheelsetPose pose = s.pose;
    pose.z = 0.0;
    WheelContactGeometry g = geometryAtTouch(side, &pose);
    if (g.status == ContactSearchStatus::kInvalidInput)
      return finish(WheelStatus::kInvalidInput, g.message, false);
    if (g.status != ContactSearchStatus::kOk || g.candidates.empty())
      return finish(WheelStatus::kNoContact, g.message.empty() ? "no candidate" : g.message, true);

    std::vector<ContactZone> zones;
    for (const ContactCandidate& c : g.candidates) zones.push_back(c.zone);
    NormalOptions no = options.normal;
    if (options.warm_start && zones == prev.zones) {
      no.start_beyond_touch = prev.beyond_touch;
      no.start_exponent = prev.exponent;
    }
    // whole_force_balance: each candidate's tangential force's vertical component per unit fn
    // from its slot's previous step. The slot a candidate takes counts only the candidates that
    // carry load (a merged one does not): first guessed as all, solved again if that was wrong.
    const auto lift = [&](const WheelNormal* solved) {
      std::vector<double> t;
      std::map<ContactZone, int> count;
      for (size_t i = 0; i < g.candidates.size(); ++i) {
        const ContactCandidate& c = g.candidates[i];
        if (solved && !(solved->patches[i].fn >= kMinLoad)) {
          t.push_back(0.0);
          continue;
        }
        const auto it = wheel.find(slotName(c.zone, ++count[c.zone]));
        t.push_back(it == wheel.end() ? 0.0 : -it->second.fs_per_fn * c.normal.x());
      }
      return t;
    };
    const bool whole = options.whole_force_balance && options.tangential;
    std::vector<double> guess = whole ? lift(nullptr) : std::vector<double>{};
    WheelNormal n = solveWheelLoad(g, load, parameters.G, parameters.nu, no, guess);
    if (table && n.status != NormalStatus::kOk && n.status != NormalStatus::kNoContact) {
      // Where the table's geometry leaves the normal problem no solution, the direct search's
      // answers this step (the table keeps the tread candidates across a low ridge that it once
      // dropped near a centred tread, contact_table.hpp; this remains for what it still misses).
      ++direct_search_fallbacks;
      WheelsetPose direct = s.pose;
      direct.z = 0.0;
      WheelContactGeometry d = searchAtTouchDirect(side, &direct);
      if (d.status == ContactSearchStatus::kOk && !d.candidates.empty()) {
        std::swap(g, d);  // lift() reads g
        std::vector<double> dguess = whole ? lift(nullptr) : std::vector<double>{};
        WheelNormal nd = solveWheelLoad(g, load, parameters.G, parameters.nu, no, dguess);
        if (nd.status == NormalStatus::kOk) {
          n = std::move(nd);
          guess = std::move(dguess);
          pose = direct;
          zones.clear();
          for (const ContactCandidate& c : g.candidates) zones.push_back(c.zone);
        } else {
          std::swap(g, d);
        }
      }
    }
    if (whole && n.status == NormalStatus::kOk && n.patches.size() == guess.size()) {
      const std::vector<double> t = lift(&n);
      for (size_t i = 0; i < t.size(); ++i)
        if (n.patches[i].fn >= kMinLoad && t[i] != guess[i]) {
          n = solveWheelLoad(g, load, parameters.G, parameters.nu, no, t);
          break;
        }
    }
    if (whole && n.status != NormalStatus::kOk && n.status != NormalStatus::kNoContact) {
      r.message = "the tangential forces' vertical components leave the load no balance (" +
                  n.message + "): the normal forces alone carry it this step";
      n = solveWheelLoad(g, load, parameters.G, parameters.nu, no);
    }
    prev.zones.clear();
    if (n.status == NormalStatus::kOk && std::isfinite(n.vertical_approach - n.touch_approach) &&
        n.vertical_approach > n.touch_approach && std::isfinite(n.load_exponent)) {
      prev.zones = std::move(zones);
      prev.beyond_touch = n.vertical_approach - n.touch_approach;
      prev.exponent = n.load_exponent;
    }
    if (n.status == NormalStatus::kNoContact)
      return finish(WheelStatus::kNoContact, n.message, true);
    if (n.status != NormalStatus::kOk || n.patches.size() != g.candidates.size())
      return finish(WheelStatus::kNormalFailed,
                    n.message.empty() ? "the normal problem found no solution" : n.message, true);

    // The wheel's centre at its loaded height: the searched pose lowered by the vertical approach.
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(pose.yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pose.roll, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    r.centre = Eigen::Vector3d(0.0, pose.y, track.nominal_radius + pose.z - n.vertical_approach) +
               centre_axial[w] * R.col(1);
    std::map<ContactZone, int> rank;
    for (size_t i = 0; i < g.candidates.size(); ++i) {
      const NormalPatch& np = n.patches[i];
      if (!(np.fn >= kMinLoad)) continue;  // out of contact
      PatchResult p;
      p.geometry = g.candidates[i];
      p.zone = p.geometry.zone;
      const int k = ++rank[p.zone];
      p.slot = slotName(p.zone, k);
      p.normal = np;
      p.creepages = patchCreepages(side, pose, s.motion, p.geometry, track);

      if (!options.tangential) {
        p.message = "tangential forces not computed (WheelsetContactOptions::tangential false)";
        r.patches.push_back(std::move(p));
        continue;
      }
      Slot& slot = wheel[p.slot];
      slot.present = true;
      slot.fs_per_fn = 0.0;  // until the model gives a force
      if (p.creepages.status == CreepageStatus::kInvalidInput) {
        // No creepages, no tangential forces; the slot is kept as a refused step keeps a model.
        p.tangential_status = StepStatus::kRejected;
        p.message = "creepages: " + p.creepages.message;
        r.patches.push_back(std::move(p));
        continue;
      }
      // The exact model refuses a patch beyond its grid (the FastSim models grow their mesh): a
      // patch that outgrows it restarts from rest on a grid for the patch, saying so.
      const bool outgrown =
          slot.model && parameters.model == "exact" && (np.a > slot.a_cover || np.b > slot.b_cover);
      // A non-Hertzian or blended patch reaches the model as its strips; a Hertz one as its
      // ellipse (the normal problem's rule: no more model than the patch needs), unless its a/b
      // lies beyond Kalker's table, which the ellipse's models refuse: then as its strips (Kalker's
      // strips of the ellipse), the coefficients held at the table's end.
      const bool inTable = np.a >= kKalkerMinAOverB * np.b && np.a <= kKalkerMaxAOverB * np.b;
      const bool onStrips =
          np.method == NormalMethod::kNonHertzian || np.strip_weight > 0.0 || !inTable;
      if (!slot.model || outgrown) {  // appears: from rest
        slot.model = modelFor(np, onStrips, &p.message);
        slot.a_cover = kCover * np.a;
        slot.b_cover = kCover * np.b;
      }
      if (!slot.model) {
        p.tangential_status = StepStatus::kRejected;
        p.message = "tangential model: " + p.message;
        r.patches.push_back(std::move(p));
        continue;
      }
      StepInput in;
      in.dt = dt;
      in.V = s.motion.V;  // patchCreepages divides by it; at V = 0 the model stands still
      in.xi = p.creepages.xi;
      in.eta = p.creepages.eta;
      in.phi = p.creepages.phi;
      in.fz = np.fn;
      in.a = np.a;
      in.b = np.b;
      if (onStrips) {
        // The strips' eta runs toward the track centre; the contact frame's y (the creepages',
        // the models') is the same on both wheels (y = z x x): toward the centre on the right
        // wheel, away from it on the left, whose strips are mirrored.
        slot.shape = patchShapeOf(np, profileOrigin(side, p.geometry));
        if (side == WheelSide::kLeft) {
          slot.shape.origin = -slot.shape.origin;
          for (PatchStrip& st : slot.shape.strips) st.eta = -st.eta;
          std::reverse(slot.shape.strips.begin(), slot.shape.strips.end());
        }
        in.shape = &slot.shape;
      }
      const StepOutput out = slot.model->step(in);
      p.fx = out.fx;
      p.fs = out.fy;
      p.mz = out.mz;
      p.tangential_status = out.status;
      p.message = out.message;
      if (out.status == StepStatus::kOk && std::isfinite(out.fy / np.fn))
        slot.fs_per_fn = std::max(-parameters.mu, std::min(parameters.mu, out.fy / np.fn));
      if (outgrown && out.status == StepStatus::kOk)
        p.message =
            "the patch outgrew the exact model's grid: restarted from rest on a grid for it";
      r.patches.push_back(std::move(p));
    }
    resetAbsent(wheel);
    if (r.patches.empty()) return finish(WheelStatus::kNoContact, "no patch carries load", false);
    r.status = WheelStatus::kOk;
    for (PatchResult& p : r.patches) {
      p.wrench = trackWrench(p, r.centre);
      add(&r.wrench, p.wrench);
    }
    return r;
  }
};

WheelsetContact::WheelsetContact(const WheelsetTrackData& track,
                                 const ContactParameters& parameters,
                                 const WheelsetContactOptions& options)
    : impl_(std::make_unique<Impl>(track, parameters, options)) {}

WheelsetContact::~WheelsetContact() = default;
WheelsetContact::WheelsetContact(WheelsetContact&&) noexcept = default;
WheelsetContact& WheelsetContact::operator=(WheelsetContact&&) noexcept = default;

WheelsetResult WheelsetContact::step(const WheelsetState& state, double dt) {
  WheelsetResult r;
  r.left = impl_->stepWheel(WheelSide::kLeft, state, dt);
  r.right = impl_->stepWheel(WheelSide::kRight, state, dt);
  return r;
}

WheelsetResult WheelsetContact::settle(const WheelsetState& state, double dt, double tolerance,
                                       int max_steps) {
  if (!(tolerance > 0.0 && tolerance < 0.1) || max_steps < 2) {
    WheelsetResult r;
    r.left.side = WheelSide::kLeft;
    for (WheelResult* w : {&r.left, &r.right}) {
      w->status = WheelStatus::kInvalidInput;
      w->message = "settle: tolerance must be in (0, 0.1), max_steps >= 2";
    }
    return r;
  }
  // Settled: the same patches as the step before, each fn within tolerance of the load.
  const auto settled = [tolerance](const WheelResult& a, const WheelResult& b, double load) {
    if (a.status != b.status || a.patches.size() != b.patches.size()) return false;
    for (size_t i = 0; i < a.patches.size(); ++i)
      if (a.patches[i].slot != b.patches[i].slot ||
          !(std::abs(a.patches[i].normal.fn - b.patches[i].normal.fn) <= tolerance * load))
        return false;
    return true;
  };
  WheelsetResult before = step(state, dt);
  for (int k = 1; k < max_steps; ++k) {
    WheelsetResult r = step(state, dt);
    const bool left = settled(r.left, before.left, state.fz_left);
    const bool right = settled(r.right, before.right, state.fz_right);
    if (left && right) return r;
    if (k + 1 == max_steps) {
      for (WheelResult* w : {left ? nullptr : &r.left, right ? nullptr : &r.right})
        if (w && w->status == WheelStatus::kOk)
          w->message += std::string(w->message.empty() ? "" : "; ") + "not settled after " +
                        std::to_string(max_steps) + " steps";
      return r;
    }
    before = std::move(r);
  }
  return before;
}

void WheelsetContact::reset() {
  for (auto& wheel : impl_->slots) wheel.clear();
  for (auto& prev : impl_->previous) prev.zones.clear();
}

const ContactSearch& WheelsetContact::search() const {
  return impl_->search;
}
const ContactParameters& WheelsetContact::parameters() const {
  return impl_->parameters;
}
std::size_t WheelsetContact::directSearchFallbacks() const {
  return impl_->direct_search_fallbacks;
}

}  // namespace wheel_rail_contact
