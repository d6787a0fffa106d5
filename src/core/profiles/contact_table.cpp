#include "wheel_rail_contact/profiles/contact_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/profiles/table_gap_function.hpp"

namespace wheel_rail_contact {

namespace {

constexpr double kSmallYaw = 1e-6;

/// One candidate of one node, as its table's wheel sees it (the right wheel's when the left
/// mirrors it).
struct TableCandidate {
  double vertical_gap0 = 0.0;  ///< vertical gap at Z = 0 (it is vertical_gap0 + Z at any Z)
  double gap_a = 0.0;          ///< gap at the node's touching height Z_a
  double gap_dz = 0.0;         ///< d gap / dZ
  double angle = 0.0, radius = 0.0, point_y = 0.0, point_z = 0.0;
  double lead_per_yaw = 0.0;  ///< lead / yaw
  double axial = 0.0;  ///< the contact circle's position along the axle (point.x = lead - axial
                       ///< sin(yaw) cos(roll))
  Eigen::Vector2d rail_file = Eigen::Vector2d::Zero(), wheel_file = Eigen::Vector2d::Zero();
  double s_rail = 0.0, s_wheel = 0.0;
  GapColumns gap_function;  ///< on Z_a and its slopes in Z (empty: the search gave none)
};

struct Node {
  ContactSearchStatus status = ContactSearchStatus::kOk;
  std::string message;
  double z_a = 0.0;  ///< the height Z at which the closest candidate about touches
  std::vector<TableCandidate> candidates;
};

/// Node coordinates of one axis: value(k) = first + k step, k = 0 .. n - 1.
struct Axis {
  double first = 0.0, step = 1.0;
  int n = 1;
  double value(int k) const { return first + k * step; }
  /// The cell [k, k + 1] holding v and its fraction; false beyond the axis (with a tolerance of
  /// rounding).
  bool locate(double v, int* k, double* t) const {
    const double u = (v - first) / step;
    if (!(u >= -1e-9) || !(u <= (n - 1) + 1e-9)) return false;
    *k = std::min(std::max(static_cast<int>(std::floor(u)), 0), n - 2);
    *t = std::min(std::max(u - *k, 0.0), 1.0);
    return true;
  }
};

Axis symmetricAxis(double max_abs, double step) {
  Axis a;
  a.n = static_cast<int>(std::lround(2.0 * max_abs / step)) + 1;
  a.n = std::max(a.n, 2);
  a.first = -max_abs;
  a.step = 2.0 * max_abs / (a.n - 1);
  return a;
}

Axis positiveAxis(double max_abs, double step) {
  Axis a;
  a.n = std::max(static_cast<int>(std::lround(max_abs / step)) + 1, 2);
  a.first = 0.0;
  a.step = max_abs / (a.n - 1);
  return a;
}

/// The wheel's place relative to its rail: see contact_table.hpp.
struct WheelPlace {
  double Y = 0.0, Z = 0.0;
};

WheelPlace placeOf(const WheelsetPose& p, double a0, double r0) {
  const double cy = std::cos(p.yaw), cr = std::cos(p.roll), sr = std::sin(p.roll);
  return {p.y + a0 * (cy * cr - 1.0) + r0 * sr * cy, p.z + a0 * sr + r0 * (1.0 - cr)};
}

WheelsetPose poseOf(double Y, double Z, double yaw, double roll, double a0, double r0) {
  const double cy = std::cos(yaw), cr = std::cos(roll), sr = std::sin(roll);
  WheelsetPose p;
  p.y = Y - a0 * (cy * cr - 1.0) - r0 * sr * cy;
  p.z = Z - a0 * sr - r0 * (1.0 - cr);
  p.yaw = yaw;
  p.roll = roll;
  return p;
}

/// A gap function (sampled uniformly from f.front().eta to f.back().eta) at eta, linearly.
GapSample lerp(const std::vector<GapSample>& f, double eta) {
  const double e0 = f.front().eta, e1 = f.back().eta;
  const int last = static_cast<int>(f.size()) - 1;
  if (!(e1 > e0)) return f.front();
  double u = (eta - e0) / (e1 - e0) * last;
  const int j = std::min(std::max(static_cast<int>(std::floor(u)), 0), last - 1);
  u -= j;
  const GapSample &p = f[j], &q = f[j + 1];
  GapSample s;
  s.eta = eta;
  s.gap = p.gap + u * (q.gap - p.gap);
  s.rolling_radius = p.rolling_radius + u * (q.rolling_radius - p.rolling_radius);
  s.contact_angle = p.contact_angle + u * (q.contact_angle - p.contact_angle);
  return s;
}

}  // namespace

struct ContactTable::Impl {
  ContactSearch search;     ///< the caller's, for the meaning of the options and poses beyond
  Axis lateral, yaw, roll;  // yaw's values are yaw^2
  double r0 = 0.0;
  bool left_mirrors_right = false;
  struct Grid {
    double sigma = 1.0, a0 = 0.0;
    std::vector<Node> nodes;  // index (roll * yaw.n + yaw) * lateral.n + lateral
  };
  std::array<Grid, 2> grids;  // [0] right, [1] left (empty when it mirrors the right)

  explicit Impl(const ContactSearch& s) : search(s) {}
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * yaw.n + j) * lateral.n + i;
  }
};

namespace {

/// Whether a and b are one candidate: within `distance` of each other on both profiles (a
/// TableCandidate or a ContactCandidate, both with the arc lengths s_wheel and s_rail).
template <class Candidate>
bool samePlace(const Candidate& a, const Candidate& b, double distance) {
  return std::abs(a.s_wheel - b.s_wheel) < distance && std::abs(a.s_rail - b.s_rail) < distance;
}

/// The candidate of `others` that is `c` (samePlace), the nearest if several, or null.
template <class Candidate>
const Candidate* match(const Candidate& c, const std::vector<Candidate>& others, double distance) {
  const Candidate* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity();
  for (const Candidate& o : others) {
    const double d = std::abs(o.s_wheel - c.s_wheel) + std::abs(o.s_rail - c.s_rail);
    if (samePlace(o, c, distance) && d < best_d) {
      best_d = d;
      best = &o;
    }
  }
  return best;
}

}  // namespace

ContactTable::ContactTable(const ContactSearch& search, const ContactTableOptions& options)
    : options_(options), impl_(std::make_unique<Impl>(search)) {
  auto positive = [](const char* name, double v, double upper) {
    if (!std::isfinite(v) || !(v > 0.0) || v > upper) {
      std::ostringstream m;
      m << "ContactTableOptions: " << name << " must be finite, > 0 and <= " << upper;
      throw std::invalid_argument(m.str());
    }
  };
  const ContactSearchOptions& so = search.options();
  positive("max_abs_lateral", options_.max_abs_lateral, so.max_abs_y);
  positive("lateral_step", options_.lateral_step, options_.max_abs_lateral);
  positive("max_abs_yaw", options_.max_abs_yaw, so.max_abs_yaw);
  positive("yaw_step", options_.yaw_step, options_.max_abs_yaw);
  positive("max_abs_roll", options_.max_abs_roll, so.max_abs_roll);
  positive("roll_step", options_.roll_step, options_.max_abs_roll);
  positive("max_overlap", options_.max_overlap, 5e-3);
  positive("match_distance", options_.match_distance, 0.1);
  if (options_.gap_samples < 3 || options_.gap_samples > 10000)
    throw std::invalid_argument("ContactTableOptions: gap_samples must be in [3, 10000]");

  Impl& im = *impl_;
  im.lateral = symmetricAxis(options_.max_abs_lateral, options_.lateral_step);
  im.yaw = positiveAxis(options_.max_abs_yaw * options_.max_abs_yaw,
                        options_.max_abs_yaw * options_.max_abs_yaw /
                            std::max(1.0, std::round(options_.max_abs_yaw / options_.yaw_step)));
  im.roll = symmetricAxis(options_.max_abs_roll, options_.roll_step);
  const WheelsetTrackData& d = search.data();
  im.r0 = d.nominal_radius;
  im.left_mirrors_right = (!d.wheel_left || d.wheel_left == d.wheel_right) &&
                          (!d.rail_left || d.rail_left == d.rail_right);

  // The table's own search: the caller's, with gap functions wide and fine enough to be cut to
  // what the caller's options give at any height up to max_overlap of overlap.
  // The caller's search, at an overlap o <= max_overlap, reaches o + max(2 max(o, gap_window),
  // gap_reach) above the gap's minimum; the table's reaches max_overlap beyond that at both
  // heights, so that the stretch both cover holds the caller's at any height between.
  ContactSearchOptions wide = so;
  wide.gap_window = options_.max_overlap;
  wide.gap_reach = std::max(so.gap_reach, 2.0 * std::max(options_.max_overlap, so.gap_window)) +
                   options_.max_overlap;
  wide.gap_samples = options_.gap_samples | 1;
  const ContactSearch table_search(d, wide);

  for (int g = 0; g < (im.left_mirrors_right ? 1 : 2); ++g) {
    Impl::Grid& grid = im.grids[g];
    const WheelSide side = g == 0 ? WheelSide::kRight : WheelSide::kLeft;
    grid.sigma = g == 0 ? 1.0 : -1.0;
    grid.a0 = -grid.sigma * 0.5 * d.gauge;
    grid.nodes.resize(static_cast<std::size_t>(im.lateral.n) * im.yaw.n * im.roll.n);
    for (int k = 0; k < im.roll.n; ++k) {
      for (int j = 0; j < im.yaw.n; ++j) {
        double z_guess = 0.0;  // the previous node's touching height: the next one's is near
        for (int i = 0; i < im.lateral.n; ++i) {
          Node& node = grid.nodes[im.index(i, j, k)];
          const double Y = im.lateral.value(i), yaw = std::sqrt(im.yaw.value(j)),
                       roll = im.roll.value(k);
          // The node at yaw 0 is searched at a yaw small enough that the even quantities do not
          // see it (yaw^2 ~ 1e-12), to give lead's slope.
          const double yaw_run = std::max(yaw, kSmallYaw);
          auto run = [&](double Z) {
            return table_search.search(side, poseOf(Y, Z, yaw_run, roll, grid.a0, im.r0));
          };
          WheelContactGeometry a = run(z_guess);
          if (a.status != ContactSearchStatus::kOk) {
            node.status = a.status;
            node.message = a.message;
            continue;
          }
          double z_a = z_guess - a.candidates[a.closest].vertical_gap;
          if (std::abs(z_a - z_guess) > 0.2 * options_.max_overlap) {
            a = run(z_a);
          } else {
            z_a = z_guess;
          }
          const double z_b = z_a - options_.max_overlap;
          const WheelContactGeometry b = run(z_b);
          if (a.status != ContactSearchStatus::kOk || b.status != ContactSearchStatus::kOk) {
            node.status = a.status != ContactSearchStatus::kOk ? a.status : b.status;
            node.message = a.status != ContactSearchStatus::kOk ? a.message : b.message;
            continue;
          }
          z_guess = z_a;
          node.z_a = z_a;
          for (const ContactCandidate& ca : a.candidates) {
            TableCandidate t;
            t.vertical_gap0 = ca.vertical_gap - z_a;
            t.gap_a = ca.gap;
            t.angle = ca.contact_angle;
            t.radius = ca.rolling_radius;
            t.point_y = ca.point.y();
            t.point_z = ca.point.z();
            // lead is odd in yaw: its slope lead / yaw is even and interpolated as the rest.
            const double sy = std::sin(yaw_run) * std::cos(roll);
            t.lead_per_yaw = ca.lead / yaw_run;
            // point.x = lead - axial sin(yaw) cos(roll): the contact circle's place on the axle.
            t.axial = -(ca.point.x() - ca.lead) / sy;
            t.rail_file = ca.rail_file;
            t.wheel_file = ca.wheel_file;
            t.s_rail = ca.s_rail;
            t.s_wheel = ca.s_wheel;
            const ContactCandidate* cb = match(ca, b.candidates, options_.match_distance);
            t.gap_dz = cb ? (cb->gap - ca.gap) / (z_b - z_a) : std::cos(ca.contact_angle);
            if (cb && ca.gap_function.size() >= 2 && cb->gap_function.size() >= 2) {
              const double lo = std::max(ca.gap_function.front().eta, cb->gap_function.front().eta);
              const double hi = std::min(ca.gap_function.back().eta, cb->gap_function.back().eta);
              if (hi > lo) {
                const int m = wide.gap_samples;
                GapColumns& f = t.gap_function;
                f.eta0 = lo;
                f.deta = (hi - lo) / (m - 1);
                f.inv_deta = 1.0 / f.deta;
                f.resize(m);
                const double inv_dz = 1.0 / (z_b - z_a);
                for (int s = 0; s < m; ++s) {
                  const double eta = lo + s * f.deta;
                  const GapSample sa = lerp(ca.gap_function, eta), sb = lerp(cb->gap_function, eta);
                  const double at_a[3] = {sa.gap, sa.rolling_radius, sa.contact_angle};
                  const double at_b[3] = {sb.gap, sb.rolling_radius, sb.contact_angle};
                  for (int x = 0; x < GapColumns::kQuantities; ++x) {
                    f.value(x)[s] = static_cast<float>(at_a[x]);
                    f.perDz(x)[s] = static_cast<float>((at_b[x] - at_a[x]) * inv_dz);
                  }
                }
              }
            }
            node.candidates.push_back(std::move(t));
          }
        }
      }
    }
  }
}

ContactTable::ContactTable(const ContactTable& o)
    : options_(o.options_), impl_(std::make_unique<Impl>(*o.impl_)) {}
ContactTable& ContactTable::operator=(const ContactTable& o) {
  if (this != &o) {
    options_ = o.options_;
    impl_ = std::make_unique<Impl>(*o.impl_);
  }
  return *this;
}
ContactTable::ContactTable(ContactTable&&) noexcept = default;
ContactTable& ContactTable::operator=(ContactTable&&) noexcept = default;
ContactTable::~ContactTable() = default;

const ContactSearch& ContactTable::contactSearch() const {
  return impl_->search;
}
std::size_t ContactTable::nodes() const {
  return static_cast<std::size_t>(impl_->lateral.n) * impl_->yaw.n * impl_->roll.n;
}
int ContactTable::tables() const {
  return impl_->left_mirrors_right ? 1 : 2;
}
std::size_t ContactTable::bytes() const {
  std::size_t b = sizeof(Impl);
  for (const Impl::Grid& g : impl_->grids)
    for (const Node& n : g.nodes) {
      b += sizeof(Node) + n.message.capacity() + n.candidates.capacity() * sizeof(TableCandidate);
      for (const TableCandidate& c : n.candidates)
        b += c.gap_function.data.capacity() * sizeof(float);
    }
  return b;
}

WheelContactGeometry ContactTable::search(WheelSide side, const WheelsetPose& pose) const {
  return lookup(side, pose, nullptr, 0.0);
}

WheelContactGeometry ContactTable::searchAtTouch(WheelSide side, WheelsetPose* pose,
                                                 double touch_tolerance) const {
  return lookup(side, *pose, pose, touch_tolerance);
}

// The direct search's answer at first touch, as searchAtTouch promises: one search at the pose,
// one more lowered or raised by the closest candidate's vertical gap.
static WheelContactGeometry searchAtTouchDirect(const ContactSearch& search, WheelSide side,
                                                WheelsetPose* pose, double touch_tolerance) {
  WheelContactGeometry g = search.search(side, *pose);
  if (g.status == ContactSearchStatus::kOk && g.closest >= 0 &&
      std::abs(g.candidates[g.closest].vertical_gap) > touch_tolerance) {
    pose->z -= g.candidates[g.closest].vertical_gap;
    g = search.search(side, *pose);
  }
  return g;
}

WheelContactGeometry ContactTable::lookup(WheelSide side, const WheelsetPose& pose,
                                          WheelsetPose* touch_pose, double touch_tolerance) const {
  const Impl& im = *impl_;
  const ContactSearchOptions& so = im.search.options();
  // The search's own checks first: a pose it refuses is refused with its message.
  if (!std::isfinite(pose.y) || !std::isfinite(pose.z) || !std::isfinite(pose.yaw) ||
      !std::isfinite(pose.roll) || std::abs(pose.y) > so.max_abs_y ||
      std::abs(pose.z) > so.max_abs_z || std::abs(pose.yaw) > so.max_abs_yaw ||
      std::abs(pose.roll) > so.max_abs_roll)
    return touch_pose ? searchAtTouchDirect(im.search, side, touch_pose, touch_tolerance)
                      : im.search.search(side, pose);

  // The left wheel of a mirrored pair is the right one in the mirrored pose.
  const bool mirror = side == WheelSide::kLeft && im.left_mirrors_right;
  WheelsetPose p = pose;
  if (mirror) {
    p.y = -p.y;
    p.yaw = -p.yaw;
    p.roll = -p.roll;
  }
  const Impl::Grid& grid = im.grids[side == WheelSide::kRight || mirror ? 0 : 1];
  const WheelPlace place = placeOf(p, grid.a0, im.r0);
  const double abs_yaw = std::abs(p.yaw);

  auto beyond = [&](const std::string& why) {
    if (options_.beyond == ContactTableOptions::Beyond::kSearch)
      return touch_pose ? searchAtTouchDirect(im.search, side, touch_pose, touch_tolerance)
                        : im.search.search(side, pose);
    WheelContactGeometry out;
    out.status = ContactSearchStatus::kOutOfRange;
    out.message = why;
    return out;
  };
  int ci = 0, cj = 0, ck = 0;
  double ti = 0.0, tj = 0.0, tk = 0.0;
  if (!im.lateral.locate(place.Y, &ci, &ti) || !im.yaw.locate(abs_yaw * abs_yaw, &cj, &tj) ||
      !im.roll.locate(p.roll, &ck, &tk)) {
    std::ostringstream m;
    m << "pose beyond the contact table: the wheel's lateral displacement " << place.Y
      << " m (table +-" << options_.max_abs_lateral << "), |yaw| " << abs_yaw << " rad (table "
      << options_.max_abs_yaw << "), roll " << p.roll << " rad (table +-" << options_.max_abs_roll
      << ")";
    return beyond(m.str());
  }

  struct Corner {
    const Node* node;
    double w;
  };
  std::array<Corner, 8> corners;
  int master = 0;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const double wi = di ? ti : 1.0 - ti, wk = dk ? tk : 1.0 - tk;
    const double wj = dj ? tj : 1.0 - tj;
    corners[c] = {&grid.nodes[im.index(ci + di, cj + dj, ck + dk)], wi * wj * wk};
    if (corners[c].node->status != ContactSearchStatus::kOk)
      return beyond("pose next to a contact-table node without contact: " +
                    corners[c].node->message);
    if (corners[c].w > corners[master].w) master = c;
  }

  // Quadratic in yaw^2 on the three yaw nodes around the nearest one, where the axis has three:
  // the flange's geometry curves in yaw^2 (the lift of the contact point under yaw grows with
  // the lead, which grows with the contact angle), which linear interpolation misses by several
  // micrometres of gap at the default nodes.
  std::array<Corner, 12> quad;
  std::array<double, 12> quad_linear{};  // the linear cell's weights of the same nodes
  bool quad_ok = im.yaw.n >= 3;
  if (quad_ok) {
    const double x_abs = cj + tj;
    const int b = std::min(std::max(static_cast<int>(std::lround(x_abs)) - 1, 0), im.yaw.n - 3);
    const double x = x_abs - b;
    const double lagrange[3] = {0.5 * (x - 1.0) * (x - 2.0), -x * (x - 2.0), 0.5 * x * (x - 1.0)};
    for (int q = 0; q < 12 && quad_ok; ++q) {
      const int di = q & 1, dk = (q >> 1) & 1, l = q >> 2;
      const double wi = di ? ti : 1.0 - ti, wk = dk ? tk : 1.0 - tk;
      quad[q] = {&grid.nodes[im.index(ci + di, b + l, ck + dk)], wi * lagrange[l] * wk};
      quad_linear[q] = wi * wk * (b + l == cj ? 1.0 - tj : b + l == cj + 1 ? tj : 0.0);
      quad_ok = quad[q].node->status == ContactSearchStatus::kOk;
    }
  }

  WheelContactGeometry out;
  // The normal's lateral sign: a mirrored left wheel is computed as the right one (its candidates
  // are mirrored at the end), a left wheel with a table of its own as the left.
  const double sigma = side == WheelSide::kRight || mirror ? 1.0 : -1.0;
  const double sy = std::sin(p.yaw) * std::cos(p.roll);
  // Pass one: each candidate's nodes and weights, and what does not depend on the height.
  struct Interpolated {
    std::array<const TableCandidate*, 12> m{};
    std::array<const Node*, 12> at{};
    std::array<double, 12> w{}, w_linear{};
    int nm = 0;
    double sw_gf = 0.0;
    ContactCandidate c;
    bool tread_before = false, tread_after = false;  ///< a tread neighbour of a tread candidate
  };
  // The candidate set: the nearest node's, and each tread candidate of another node of the
  // cell (of non-negligible weight) that the nearest node lacks. Near a centred tread two tread
  // candidates lie across a ridge of a micrometre or so, which one node's search still sees and
  // its neighbour's no longer does; with the nearest node's set alone the other candidate is
  // lost while the kept one's gap function ends at the ridge (where the node that has both cut
  // it), and a load whose approach crosses the ridge has no patch to merge with.
  struct Member {
    const TableCandidate* t;
    int owner;  // the corner whose candidate it is
  };
  std::vector<Member> set;
  for (const TableCandidate& mc : corners[master].node->candidates) set.push_back({&mc, master});
  for (int q = 0; q < 8; ++q) {
    if (q == master || !(corners[q].w > 1e-9)) continue;
    for (const TableCandidate& t : corners[q].node->candidates) {
      if (!(t.angle < so.tread_max_angle)) continue;
      const bool known = std::any_of(set.begin(), set.end(), [&](const Member& s) {
        return samePlace(*s.t, t, options_.match_distance);
      });
      if (!known) set.push_back({&t, q});
    }
  }
  std::vector<Interpolated> cands;
  cands.reserve(set.size());
  for (std::size_t ms = 0; ms < set.size(); ++ms) {
    const TableCandidate& mc = *set[ms].t;
    const int owner = set[ms].owner;
    cands.emplace_back();
    Interpolated& ic = cands.back();
    auto& m = ic.m;
    auto& at = ic.at;
    auto& w = ic.w;
    auto& w_linear = ic.w_linear;
    int& nm = ic.nm;
    // The nodes that interpolate this candidate, its match at each, and their weights: the
    // quadratic stencil where every one of its nodes has the candidate, else the linear cell's
    // nodes that have it, their weights renormalised.
    if (quad_ok) {
      for (int q = 0; q < 12; ++q) {
        m[q] = quad[q].node == corners[owner].node
                   ? &mc
                   : match(mc, quad[q].node->candidates, options_.match_distance);
        if (!m[q]) break;
        at[q] = quad[q].node;
        w[q] = quad[q].w;
        w_linear[q] = quad_linear[q];
        nm = q + 1;
      }
      if (nm < 12) nm = 0;
    }
    if (nm == 0) {
      // A tread candidate that one lateral node of a yaw-roll pair has and the other lacks (the
      // search sees a low ridge, and with it the candidate, on one side only) is extrapolated
      // linearly in Y from that node and the next one beyond it, where that one has it too: its
      // vertical gap, place and gap function move smoothly with Y up to where the ridge vanishes,
      // and one node's values alone would be a lateral step off. Elsewhere the nodes that have
      // it, their weights renormalised.
      const bool extrapolate = mc.angle < so.tread_max_angle;
      double sw = 0.0;
      auto add = [&](const TableCandidate* t, const Node* n, double weight) {
        m[nm] = t;
        at[nm] = n;
        w[nm] = weight;
        sw += weight;
        ++nm;
      };
      for (int pair = 0; pair < 4; ++pair) {
        const int c0 = pair << 1, c1 = c0 | 1;  // the pair's corners at lateral ci and ci + 1
        const TableCandidate* t0 =
            c0 == owner ? &mc : match(mc, corners[c0].node->candidates, options_.match_distance);
        const TableCandidate* t1 =
            c1 == owner ? &mc : match(mc, corners[c1].node->candidates, options_.match_distance);
        const double wp = corners[c0].w + corners[c1].w;  // the pair's share of the cell
        if (!extrapolate || (t0 && t1)) {
          if (t0) add(t0, corners[c0].node, corners[c0].w);
          if (t1) add(t1, corners[c1].node, corners[c1].w);
          continue;
        }
        if (!t0 && !t1) continue;
        const bool upper = t1 != nullptr;
        const TableCandidate* ts = upper ? t1 : t0;
        const int outer = upper ? ci + 2 : ci - 1;
        const TableCandidate* to = nullptr;
        const Node* no = nullptr;
        if (outer >= 0 && outer < im.lateral.n) {
          no = &grid.nodes[im.index(outer, cj + (pair & 1), ck + (pair >> 1))];
          if (no->status == ContactSearchStatus::kOk)
            to = match(*ts, no->candidates, options_.match_distance);
        }
        const Node* ns = corners[upper ? c1 : c0].node;
        if (!to) {
          add(ts, ns, wp);
        } else {
          const double ls = upper ? 2.0 - ti : 1.0 + ti;  // Lagrange's weight of ns; to's 1 - ls
          add(ts, ns, wp * ls);
          add(to, no, wp * (1.0 - ls));
        }
      }
      for (int q = 0; q < nm; ++q) {
        w[q] = sw > 0.0 ? w[q] / sw : (m[q] == &mc ? 1.0 : 0.0);
        w_linear[q] = w[q];
      }
    }
    // The gap function's shape from the linear cell (it changes slowly with yaw), put at the
    // gap the stencil gives.
    double& sw_gf = ic.sw_gf;
    for (int q = 0; q < nm; ++q)
      if (!m[q]->gap_function.empty()) sw_gf += w_linear[q];
    ContactCandidate& c = ic.c;
    double vg0 = 0.0, angle = 0.0, lead = 0.0, axial = 0.0;
    for (int q = 0; q < nm; ++q) {
      const TableCandidate& t = *m[q];
      vg0 += w[q] * t.vertical_gap0;
      angle += w[q] * t.angle;
      c.rolling_radius += w[q] * t.radius;
      c.point.y() += w[q] * t.point_y;
      c.point.z() += w[q] * t.point_z;
      axial += w[q] * t.axial;
      c.rail_file += w[q] * t.rail_file;
      c.wheel_file += w[q] * t.wheel_file;
      c.s_rail += w[q] * t.s_rail;
      c.s_wheel += w[q] * t.s_wheel;
      lead += w[q] * t.lead_per_yaw;
    }
    c.vertical_gap = vg0 + place.Z;
    c.contact_angle = angle;
    c.zone = angle < so.tread_max_angle     ? ContactZone::kTread
             : angle >= so.flange_min_angle ? ContactZone::kFlange
                                            : ContactZone::kGaugeCorner;
    c.lead = lead * p.yaw;
    c.point.x() = c.lead - axial * sy;
    c.normal = Eigen::Vector2d(sigma * std::sin(angle), std::cos(angle));
  }
  // At first touch: the height moves every candidate's vertical gap alike (exactly), so the
  // touching height follows from this pose's and the rest is interpolated there once.
  if (touch_pose && !cands.empty()) {
    double closest = std::numeric_limits<double>::infinity();
    for (const Interpolated& ic : cands) closest = std::min(closest, ic.c.vertical_gap);
    if (std::abs(closest) > touch_tolerance) {
      touch_pose->z -= closest;
      if (std::abs(touch_pose->z) > so.max_abs_z) return im.search.search(side, *touch_pose);
      for (Interpolated& ic : cands) ic.c.vertical_gap -= closest;
    }
  }

  // Each tread candidate's tread neighbours, by s_wheel (growing from the field side to the
  // flange, as eta does).
  for (Interpolated& ic : cands)
    for (const Interpolated& o : cands)
      if (&o != &ic && ic.c.zone == ContactZone::kTread && o.c.zone == ContactZone::kTread) {
        ic.tread_before = ic.tread_before || o.c.s_wheel < ic.c.s_wheel;
        ic.tread_after = ic.tread_after || o.c.s_wheel > ic.c.s_wheel;
      }

  // Pass two: the gap and the gap function at the candidate's height.
  for (Interpolated& ic : cands) {
    const auto& m = ic.m;
    const auto& at = ic.at;
    const auto& w = ic.w;
    const auto& w_linear = ic.w_linear;
    const int nm = ic.nm;
    const double sw_gf = ic.sw_gf;
    ContactCandidate& c = ic.c;
    double gap = 0.0;
    // Each node's gap and gap function at the candidate's vertical gap here, not at this height:
    // the nodes' candidates then overlap alike, where each node's linearisation in the height
    // holds, while at one height they would differ by the vertical gap's change from node to node
    // (half a millimetre per lateral step on a flange).
    auto heightAt = [&](int q) { return c.vertical_gap - m[q]->vertical_gap0 - at[q]->z_a; };
    for (int q = 0; q < nm; ++q) gap += w[q] * (m[q]->gap_a + m[q]->gap_dz * heightAt(q));
    c.gap = gap;

    if (sw_gf > 0.0) {
      // The gap function: the nodes' functions at this height, weighted, on the stretch all of
      // them cover; cut where the search would cut it and sampled as the search samples it. An end
      // toward a neighbouring tread candidate (another tread candidate on that side: a tread
      // candidate's tread_before, tread_after) is where the nodes' searches cut the function at the
      // ridge between the two, which moves from node to node, and which a load's approach can cross
      // (the two patches merge, normal/patch_normal.hpp): there the stretch ends where the nodes'
      // ends do, weighted alike (each node's function continued linearly beyond its own end), so
      // that the two neighbours' functions keep meeting at their ridge between the nodes. The
      // shortest node's end would jump where its weight leaves zero (0.1 um off a node at a centred
      // tread, 2 mm short of the neighbour's start): the two would no longer meet, and their
      // patches not merge.
      const bool ridge_lo = ic.tread_before, ridge_hi = ic.tread_after;
      double lo = -std::numeric_limits<double>::infinity(), hi = -lo, lo_w = 0.0, hi_w = 0.0;
      struct Term {
        const GapColumns* f;
        double w, dZ;
      };
      std::array<Term, 12> terms;
      int nt = 0;
      // Nodes of negligible weight (a pose on a node's face, up to rounding) are left out: their
      // stretch would cut the function short for nothing.
      double sw_terms = 0.0;
      for (int q = 0; q < nm; ++q)
        if (!m[q]->gap_function.empty() && std::abs(w_linear[q]) > 1e-9 * sw_gf) {
          terms[nt++] = {&m[q]->gap_function, w_linear[q], heightAt(q)};
          sw_terms += w_linear[q];
        }
      for (int q = 0; q < nt; ++q) {
        terms[q].w /= sw_terms;
        lo = std::max(lo, terms[q].f->eta0);
        hi = std::min(hi, terms[q].f->etaEnd());
        lo_w += terms[q].w * terms[q].f->eta0;
        hi_w += terms[q].w * terms[q].f->etaEnd();
      }
      if (nt > 0 && ridge_lo) lo = lo_w;
      if (nt > 0 && ridge_hi) hi = hi_w;
      // The nodes' functions at their heights, weighted (the buffers reused from lookup to
      // lookup on this thread).
      thread_local GapFunctionSum sum;
      sum.clear();
      for (int q = 0; q < nt; ++q) sum.add(*terms[q].f, terms[q].w, terms[q].dZ);
      // The gap shifted by `offset` so that eta = 0 gives the candidate's gap.
      double offset = 0.0;
      auto G = [&](double eta) { return sum.gapAt(eta, offset); };
      if (nt > 0 && lo <= 0.0 && hi >= 0.0 && hi > lo) {
        offset = c.gap - G(0.0);
        // The search's level and march (contact_search.cpp): steps growing from 0.1 mm by half
        // each out to where the gap reaches the level, then bisection; the stretch's end (where
        // the nodes' searches stopped: a ridge, the curves' end, max_gap_extent) else.
        const double level =
            c.gap + std::max(2.0 * std::max(std::abs(c.gap), so.gap_window), so.gap_reach);
        double edge[2] = {lo, hi};
        for (int dir = 0; dir < 2; ++dir) {
          const double end = dir == 0 ? lo : hi, sign = dir == 0 ? -1.0 : 1.0;
          double inside = 0.0, reach = 0.0;
          for (double step = 1e-4; reach < std::abs(end); step *= 1.5) {
            reach = std::min(reach + step, std::abs(end));
            double outside = sign * reach;
            if (G(outside) < level) {
              inside = outside;
              continue;
            }
            for (int it = 0; it < 16; ++it) {
              const double mid = 0.5 * (inside + outside);
              (G(mid) < level ? inside : outside) = mid;
            }
            edge[dir] = inside;
            break;
          }
        }
        const int ns = so.gap_samples;
        c.gap_function.resize(ns);
        sum.sample(edge[0], (edge[1] - edge[0]) / (ns - 1), ns, offset, c.gap_function.data());
      }
    }
    if (mirror) {
      c.point.y() = -c.point.y();
      c.normal.x() = -c.normal.x();
    }
    out.candidates.push_back(std::move(c));
  }
  // As the search: drop candidates more than candidate_window above the closest.
  double best = std::numeric_limits<double>::infinity();
  for (const ContactCandidate& c : out.candidates) best = std::min(best, c.vertical_gap);
  out.candidates.erase(std::remove_if(out.candidates.begin(), out.candidates.end(),
                                      [&](const ContactCandidate& c) {
                                        return c.vertical_gap > best + so.candidate_window;
                                      }),
                       out.candidates.end());
  // In the search's order (field side to flange, s_wheel growing), which the normal problem's
  // merging of neighbours across their ridge relies on.
  // An insertion sort: stable, and no temporary buffer for a handful of candidates (a lookup
  // allocates nothing beyond its answer).
  if (set.size() > corners[master].node->candidates.size()) {
    const auto by_s = [](const ContactCandidate& a, const ContactCandidate& b) {
      return a.s_wheel < b.s_wheel;
    };
    for (auto it = out.candidates.begin(); it != out.candidates.end(); ++it)
      std::rotate(std::upper_bound(out.candidates.begin(), it, *it, by_s), it, std::next(it));
  }
  for (std::size_t k = 0; k < out.candidates.size(); ++k)
    if (out.closest < 0 ||
        out.candidates[k].vertical_gap < out.candidates[out.closest].vertical_gap)
      out.closest = static_cast<int>(k);
  if (out.candidates.empty()) {
    out.status = ContactSearchStatus::kOutOfRange;
    out.message = std::string("no contact candidate on the ") +
                  (side == WheelSide::kLeft ? "left" : "right") + " wheel";
  }
  return out;
}

}  // namespace wheel_rail_contact
