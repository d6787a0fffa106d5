#include "core/normal/merge_candidates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wheel_rail_contact {

namespace {

/// The lateral direction of a candidate's contact plane, toward the track centre (the search's
/// convention): the normal turned by a quarter, its sign from the wheel's side (the right wheel's
/// point has y < 0, its track centre lies toward +y).
Eigen::Vector2d lateral(const ContactCandidate& c) {
  const double sigma = c.point.y() < 0.0 ? 1.0 : -1.0;
  return sigma * Eigen::Vector2d(c.normal.y(), -c.normal.x());
}

/// Sample `s` of candidate `k` in candidate `p`'s contact plane.
GapSample moved(const GapSample& s, const ContactCandidate& k, const ContactCandidate& p) {
  const Eigen::Vector2d ok(k.point.y(), k.point.z()), op(p.point.y(), p.point.z());
  GapSample m = s;
  m.eta = (ok + s.eta * lateral(k) - op).dot(lateral(p));
  m.gap = s.gap / k.normal.normalized().dot(p.normal.normalized());
  return m;
}

/// The gap function's gap at eta (in its own samples' eta), linearly; +inf outside its range.
double gapAt(const std::vector<GapSample>& f, double eta) {
  if (f.empty() || eta < f.front().eta || eta > f.back().eta) {
    return std::numeric_limits<double>::infinity();
  }
  const auto it = std::lower_bound(f.begin(), f.end(), eta,
                                   [](const GapSample& s, double v) { return s.eta < v; });
  if (it == f.begin()) return it->gap;
  const GapSample &l = *(it - 1), &r = *it;
  return l.gap + (eta - l.eta) / (r.eta - l.eta) * (r.gap - l.gap);
}

/// Whether the gap functions of neighbours `a` and `b` (b the next toward the flange) overlap in
/// a's contact plane by more than a sample spacing. The contact search cuts both at the ridge
/// between them, so that its neighbours meet there; a contact table's interpolated gap function,
/// weighted between a node where the ridge separates the two and one where the search found one
/// candidate only, runs on past the ridge, above the neighbour's function there. Left so, the two
/// would not meet at a ridge, and whether their patches merge would depend on how far it runs on.
bool overlap(const ContactCandidate& a, const ContactCandidate& b) {
  const auto& fa = a.gap_function;
  const auto& fb = b.gap_function;
  if (fa.size() < 2 || fb.size() < 2) return false;
  const double spacing = std::max(fa[1].eta - fa[0].eta, fb[1].eta - fb[0].eta);
  return fa.back().eta - moved(fb.front(), b, a).eta > spacing;
}
/// Overlapping neighbours (above) each cut at the ridge between them: at the highest point of
/// their lower envelope over the overlap between the two candidates' points (where they cross),
/// a's samples beyond it and b's before it dropped. Others unchanged.
void cutAtOverlap(ContactCandidate* a, ContactCandidate* b) {
  if (!overlap(*a, *b)) return;  // they meet (or not at all): as the search gives them
  auto& fa = a->gap_function;
  auto& fb = b->gap_function;
  std::vector<GapSample> mb;  // b's samples in a's plane
  mb.reserve(fb.size());
  for (const GapSample& s : fb) mb.push_back(moved(s, *b, *a));
  // The ridge lies between the two candidates' points: a's at eta 0, b's at its own eta 0.
  GapSample b_point;
  const double lo = std::max(mb.front().eta, 0.0);
  const double hi = std::min(fa.back().eta, moved(b_point, *b, *a).eta);
  if (!(hi > lo)) return;
  double best = -std::numeric_limits<double>::infinity(), at = hi;
  auto consider = [&](double e) {
    const double envelope = std::min(gapAt(fa, e), gapAt(mb, e));
    if (std::isfinite(envelope) && envelope > best) {
      best = envelope;
      at = e;
    }
  };
  for (const GapSample& s : fa)
    if (s.eta >= lo && s.eta <= hi) consider(s.eta);
  for (const GapSample& s : mb)
    if (s.eta >= lo && s.eta <= hi) consider(s.eta);
  std::size_t keep_a = 0, first_b = 0;
  while (keep_a < fa.size() && fa[keep_a].eta <= at) ++keep_a;
  while (first_b < mb.size() && mb[first_b].eta < at) ++first_b;
  // Each keeps at least two samples (a uniform spacing, as the normal problem needs).
  if (keep_a < 2 || mb.size() - first_b < 2) return;
  fa.resize(keep_a);
  fb.erase(fb.begin(), fb.begin() + static_cast<std::ptrdiff_t>(first_b));
}

}  // namespace

double ridgeApproach(const ContactCandidate& a_in, const ContactCandidate& b_in) {
  const double inf = std::numeric_limits<double>::infinity();
  if (a_in.gap_function.size() < 2 || b_in.gap_function.size() < 2 || !(a_in.normal.y() > 0.0) ||
      !(b_in.normal.y() > 0.0))
    return inf;
  const bool cut = overlap(a_in, b_in);
  ContactCandidate a_cut, b_cut;
  if (cut) {
    a_cut = a_in;
    b_cut = b_in;
    cutAtOverlap(&a_cut, &b_cut);
  }
  const ContactCandidate& a = cut ? a_cut : a_in;
  const ContactCandidate& b = cut ? b_cut : b_in;
  const auto& fa = a.gap_function;
  const auto& fb = b.gap_function;
  const double spacing =
      std::max(fa[1].eta - fa[0].eta, fb[1].eta - fb[0].eta);  // both uniform, > 0
  const GapSample b_first = moved(fb.front(), b, a);
  if (!(std::abs(b_first.eta - fa.back().eta) <= 2.0 * spacing)) return inf;
  return std::min(fa.back().gap / a.normal.y(), fb.front().gap / b.normal.y());
}

ContactCandidate mergeCandidates(const std::vector<ContactCandidate>& in, int first, int last,
                                 int primary, std::vector<double>* ridges) {
  std::vector<ContactCandidate> cs(in.begin() + first, in.begin() + last + 1);
  for (std::size_t k = 0; k + 1 < cs.size(); ++k) cutAtOverlap(&cs[k], &cs[k + 1]);
  primary -= first;
  last -= first;
  first = 0;
  const ContactCandidate& p = cs[primary];
  ContactCandidate out = p;
  if (ridges) {
    ridges->clear();
    for (int k = first + 1; k <= last; ++k)
      ridges->push_back(moved(cs[k].gap_function.front(), cs[k], p).eta);
  }
  // Every sample in the primary's plane, in order of eta; the others' samples only beyond the
  // primary's own range (the ridge cuts them apart, so at most an end sample overlaps).
  const auto& own = p.gap_function;
  std::vector<GapSample> all(own.begin(), own.end());
  for (int k = first; k <= last; ++k) {
    if (k == primary) continue;
    for (const GapSample& s : cs[k].gap_function) {
      const GapSample m = moved(s, cs[k], p);
      if (m.eta < own.front().eta || m.eta > own.back().eta) all.push_back(m);
    }
  }
  std::sort(all.begin(), all.end(),
            [](const GapSample& u, const GapSample& v) { return u.eta < v.eta; });
  // Four-point (Lagrange) cubic through the samples nearest e; the wheel's radius and angle
  // linearly between the two that bracket it.
  auto at = [&](double e) {
    const int n = static_cast<int>(all.size());
    int i =
        static_cast<int>(std::lower_bound(all.begin(), all.end(), e,
                                          [](const GapSample& s, double v) { return s.eta < v; }) -
                         all.begin());
    i = std::clamp(i, 1, n - 1);  // all[i - 1].eta < e <= all[i].eta
    GapSample s;
    s.eta = e;
    const GapSample &l = all[i - 1], &r = all[i];
    const double t = std::clamp((e - l.eta) / (r.eta - l.eta), 0.0, 1.0);
    s.rolling_radius = l.rolling_radius + t * (r.rolling_radius - l.rolling_radius);
    s.contact_angle = l.contact_angle + t * (r.contact_angle - l.contact_angle);
    const int j0 = std::clamp(i - 2, 0, std::max(0, n - 4));
    const int j1 = std::min(n, j0 + 4);
    s.gap = 0.0;
    for (int j = j0; j < j1; ++j) {
      double w = 1.0;
      for (int q = j0; q < j1; ++q)
        if (q != j) w *= (e - all[q].eta) / (all[j].eta - all[q].eta);
      s.gap += w * all[j].gap;
    }
    return s;
  };
  // Drop samples closer together than a tenth of the primary's spacing (an end that meets its
  // neighbour's), which would make the interpolation ill-conditioned.
  const double de = own[1].eta - own[0].eta;
  {
    std::vector<GapSample> kept;
    for (const GapSample& s : all)
      if (kept.empty() || s.eta - kept.back().eta > 0.1 * de) kept.push_back(s);
    all.swap(kept);
  }
  std::vector<GapSample> merged;
  const int below = static_cast<int>(std::floor((own.front().eta - all.front().eta) / de));
  for (int j = below; j >= 1; --j) merged.push_back(at(own.front().eta - j * de));
  merged.insert(merged.end(), own.begin(), own.end());
  const int above = static_cast<int>(std::floor((all.back().eta - own.back().eta) / de));
  for (int j = 1; j <= above; ++j) merged.push_back(at(own.back().eta + j * de));
  out.gap_function = std::move(merged);
  return out;
}

}  // namespace wheel_rail_contact
