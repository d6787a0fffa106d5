#include "core/fastsim/fastsim.hpp"

#include <algorithm>
#include <cmath>

#include "core/fastsim/steady_march.hpp"
#include "core/fastsim/strip_lanes.hpp"

namespace wheel_rail_contact {

Flexibilities kalkerFlexibilities(double a, double b, double G, const CreepCoefficients& c) {
  Flexibilities L;
  L.L1 = 8.0 * a / (3.0 * c.c11 * G);
  L.L2 = 8.0 * a / (3.0 * c.c22 * G);
  L.L3 = M_PI * a * std::sqrt(a / b) / (4.0 * c.c23 * G);
  return L;
}

StepOutput stepOutput(const CreepForces& f, double fz, double a, double b) {
  StepOutput out;
  out.fx = f.fx;
  out.fy = f.fy;
  out.mz = f.mz;
  out.fz = fz;
  out.a = a;
  out.b = b;
  out.adhesionFraction = f.adhesionFraction;
  return out;
}

void TractionField::resize(int n) {
  tx.setZero(n);
  ty.setZero(n);
  bound.setZero(n);
  slip.setConstant(n, false);
}

namespace {

// Where the patch begins on a strip of nx nodes whose shape is max(0, ry - (c u)^2) at
// u = nx - 1 - 2i (element length dx): the nodes with |u| < U = sqrt(ry) / c are loaded, the
// patch's edge is at u = U, the mesh's at u = nx (one u is half an element).
// (The per-strip helpers are forced inline: each bound instance calls them, and as calls they
// cost a tenth of the classic step on a fixed mesh.)
[[gnu::always_inline]] inline StripEntry stripEntry(int nx, double ry, double c, double dx) {
  StripEntry e{nx, 0.0, 0.0};
  if (!(ry > 0.0)) return e;
  const double U = std::sqrt(ry) / c, below = 0.5 * (nx - 1.0 - U);
  e.first = below < 0.0 ? 0 : static_cast<int>(below) + 1;  // floor(below) + 1
  if (2 * e.first >= nx + (nx % 2)) {                       // no node inside the patch
    e.first = nx;
    return e;
  }
  const double hu = std::min(std::max(std::min(U, double(nx)) - (nx - 1.0 - 2.0 * e.first), 0.0),
                             e.first == 0 ? 1.0 : 2.0);
  e.h = 0.5 * hu * dx;
  e.w = 0.5 * hu - 0.5;
  return e;
}

// The mean of u^2 over the part of the strip an end node stands for: from the patch's edge
// (u = U = L + 2w + 1, or the mesh's edge if the patch is clipped) to half an element inwards of
// the node (u = L - 1), or over the whole strip [-U, U] when one node (L = 0) stands for it:
// (U^3 - lo^3) / (3 (U - lo)). The end node's bound is the shape's mean there, ry - c^2 times this:
// saturated at it, the node carries the bound's own integral over its part wherever the edge falls
// between nodes. At the node's own shape it carried h (h + dx/2) of the (h + dx/2)^2 / 2 that a
// bound rising linearly from the edge holds, so the trailing slip zone's force swung with the load
// as the edge passed from node to node.
[[gnu::always_inline]] inline double endMeanU2(double L, const StripEntry& e) {
  const double U = L + 2.0 * e.w + 1.0, lo = L > 0.0 ? L - 1.0 : -U;
  return (U * U + U * lo + lo * lo) * (1.0 / 3.0);
}

// The quadrature of that shape over the strip's loaded nodes, u = L, L - 2, ..., -L
// (L = nx - 1 - 2 first), the two end nodes weighted 1 + w at their mean *endShape: the interior
// nodes' sum (L - 1) ry - c^2 (L - 2) (L - 1) L / 3 and the end parts' exact integral.
[[gnu::always_inline]] inline double stripShapeSum(int nx, double ry, double c, const StripEntry& e,
                                                   double* endShape) {
  *endShape = 0.0;
  if (e.first >= nx) return 0.0;
  const double L = nx - 1.0 - 2.0 * e.first, c2 = c * c;
  *endShape = ry - c2 * endMeanU2(L, e);
  if (L == 0.0) return (1.0 + 2.0 * e.w) * *endShape;
  const double inner = L < 2.0 ? 0.0 : (L - 1.0) * ry - c2 * (L - 2.0) * (L - 1.0) * L / 3.0;
  return inner + 2.0 * (1.0 + e.w) * *endShape;
}

// The flattening's factor on the bound q, q (ca - cb q) (flattenedBound), from the parabolic
// bound's node sums: sum1 = Sum_j (a_j / a) Sum_i w_i q, sum2 the same of q^2 (w_i the force
// quadrature's weights, dy being common). The rescale keeps sum1, so the bound still integrates to
// mu fz.
struct Flattening {
  double ca = 1.0, cb = 0.0;
  // perPeak: 1 / p0, p0 the parabola's peak (inversePeak).
  Flattening(double s, double perPeak, double sum1, double sum2) {
    // p (2 - p / p0) is 1 - r^4 on the parabola's 1 - r^2: flatter, zero at the same edge, with
    // three quarters of the integral of 2 p, and needs no square root. Blended:
    // q (1 + s/2 - (3 s / 4 p0) q), then rescaled to the parabolic node sum.
    const double alpha = 1.0 + 0.5 * s, beta = 0.75 * s * perPeak;
    const double after = alpha * sum1 - beta * sum2;
    if (!(after > 0.0)) return;
    const double scale = sum1 / after;
    ca = scale * alpha;
    cb = scale * beta;
  }
  double operator()(double q) const { return q * (ca - cb * q); }
};

// 1 / p0, p0 = 2 mu fz / (pi a b) the parabolic bound's peak (one division, not two in a row).
double inversePeak(double a, double b, double fz, double mu) {
  return M_PI * a * b / (2.0 * mu * fz);
}

// parabolicBound, flattened (kFlat, s > 0) in the same pass. The classic bound (kFlat false) is
// its own instance: no flattening arithmetic touches it.
template <bool kFlat>
void writeBound(const PatchMesh& mesh, double a, double b, double fz, double mu, double s,
                TractionField* field) {
  Eigen::ArrayXd* const bound = &field->bound;
  std::vector<StripEntry>& entry = field->entry;
  entry.resize(mesh.ny());
  // The patch fills the mesh (or the mesh is the patch's own strips): precomputed shape.
  if (mesh.onStrips() || (a == mesh.a() && b == mesh.b())) {
    a = mesh.a();
    b = mesh.b();
    const double k = mu * fz / (mesh.shapeIntegral() * a * b);
    if constexpr (kFlat) {
      // The node sums are the mesh's shape sums S1, S2 times k and k^2, and 1 / p0 = pi / (2 I k)
      // (I its shape integral): the rescale sum1 / (alpha sum1 - beta sum2) is 1 / (alpha - s R),
      // R = (3 pi / 8) S2 / (I S1), free of the step's load and size; then q (ca - cb q) with
      // q = k shape, folded: shape (lo - hi shape). (As Flattening; the mesh keeps 1 / I and
      // S2 / S1, so the step divides once.)
      // On strips the parabolas' peak is the shape's largest value, not the ellipse's 2 I / pi.
      const double perI = mesh.onStrips() ? 0.75 / mesh.shapePeak()
                                          : (3.0 * M_PI / 8.0) * mesh.inverseShapeIntegral(),
                   alpha = 1.0 + 0.5 * s;
      const double after = alpha - s * perI * mesh.shapeSquareRatio();
      double lo = k, hi = 0.0;
      if (after > 0.0) {
        const double kc = mu * fz / (mesh.shapeIntegral() * a * b * after);
        lo = kc * alpha;
        hi = kc * s * perI;
      }
      *bound = mesh.pressureShape() * (lo - hi * mesh.pressureShape());
    } else {
      *bound = mesh.pressureShape() * k;
    }
    for (int j = 0; j < mesh.ny(); ++j) entry[j] = {0, 0.5 * mesh.stripStep(j), 0.0};
    return;
  }
  // The ellipse differs from the mesh's (fixed mesh sized for another load): node (x/a, y/b) on
  // the mesh is (ka x/a_mesh, kb y/b_mesh), its shape 1 - (kb y/b_mesh)^2 - (ka x/a_mesh)^2. Per
  // strip in closed form where the patch begins and the quadrature sum (the end nodes weighted as
  // the march's sums weight them), and with kFlat the node sums the flattening keeps; then the
  // bound, scale (ry - (ka x/a_mesh)^2) clipped at zero.
  const int nx = mesh.nx(), ny = mesh.ny();
  const double ka = mesh.a() / a, kb = mesh.b() / b;
  double* const out = bound->data();
  double sum = 0.0, shapeSum = 0.0, shapeSquareSum = 0.0;
  // kFlat: the node sums of the shape, Sum shape and Sum shape^2 times a_j / a, in closed form per
  // strip: the interior nodes' shape is ry - c^2 u^2 (stripEntry), their moments the mesh's; the
  // end nodes at their parked shape, clipped at zero as the bound is, and weighted as the force's
  // quadrature weights them (stripShapeSum). Unweighted, the flattened bound's quadrature could
  // exceed mu fz where the patch covers few nodes of a fixed mesh (found by fuzzing).
  const double perU2 = (ka / nx) * (ka / nx);
  for (int j = 0; j < ny; ++j) {
    const double yn = mesh.yNorm(j) * kb, ry = 1.0 - yn * yn, c = ka * mesh.halfNorm(j) / nx;
    entry[j] = stripEntry(nx, ry, c, mesh.stripStep(j));
    double endShape;
    sum += stripShapeSum(nx, ry, c, entry[j], &endShape) * mesh.nodeArea(j);
    out[mesh.index(0, j)] = endShape;  // parked until the scale is known
    if constexpr (kFlat) {
      const int first = entry[j].first;
      if (first >= nx) continue;
      const PatchMesh::InteriorMoments& m = mesh.interiorMoments(first);
      const double h = mesh.halfNorm(j);
      const double c2 = perU2 * h * h, c2u2 = c2 * m.u2, end = std::max(endShape, 0.0);
      // One loaded node (weight 1 + 2w), or two ends (1 + w each).
      const double ends = (2 * first == nx - 1 ? 1.0 : 2.0) + 2.0 * entry[j].w;
      shapeSum += h * (m.count * ry - c2u2 + ends * end);
      shapeSquareSum += h * (ry * (m.count * ry - 2.0 * c2u2) + c2 * c2 * m.u4 + ends * end * end);
    }
  }
  const double scale = (sum > 0.0) ? mu * fz / sum : 0.0, perXn2 = scale * ka * ka;
  const double* const xn = mesh.xNorms().data();
  if constexpr (kFlat) {
    // Flattened relative to the parabola's peak p0, q (ca - cb q) turns negative where q exceeds
    // (1 + s/2) / (3 s / 4) p0 (4/3 p0 at the largest shape). The bound of a patch clipped to the
    // mesh (ka or kb below 1), scaled to carry mu fz on the part left, can exceed that (found by
    // fuzzing: a patch four times the mesh's length): it is flattened relative to its own peak,
    // scale (the shape is at most 1), and stays above (1 - s/4) q.
    const bool clipped = ka < 1.0 || kb < 1.0;
    const double perParabolaPeak = inversePeak(a, b, fz, mu);
    const double perPeak =
        clipped && scale > 0.0 ? std::min(perParabolaPeak, 1.0 / scale) : perParabolaPeak;
    const Flattening flat(s, perPeak, scale * shapeSum, scale * scale * shapeSquareSum);
    // On a strip the flattened parabola q (ca - cb q), q = top - perXn2 x^2, is a polynomial in
    // x^2, lo + x^2 (mid + hi x^2): two operations a node more than the parabola (q's form took
    // three). Outside the patch q < 0 gives a negative value, clipped at zero as q is.
    const double hi = -flat.cb * perXn2 * perXn2;
    for (int j = 0; j < ny; ++j) {
      const int k0 = mesh.index(0, j), first = entry[j].first;
      const double yn = mesh.yNorm(j) * kb, top = scale * (1.0 - yn * yn);
      // Clipped at zero as the other nodes are: a bound is never negative.
      const double end = std::max(flat(std::max(scale * out[k0], 0.0)), 0.0);
      const double lo = flat(top), mid = perXn2 * (2.0 * flat.cb * top - flat.ca);
      for (int k = k0; k < k0 + nx; ++k) {
        const double x2 = xn[k] * xn[k];
        out[k] = std::max(lo + x2 * (mid + hi * x2), 0.0);
      }
      if (first < nx) out[k0 + first] = out[k0 + nx - 1 - first] = end;
    }
  } else {
    for (int j = 0; j < ny; ++j) {
      const int k0 = mesh.index(0, j), first = entry[j].first;
      const double yn = mesh.yNorm(j) * kb, top = scale * (1.0 - yn * yn);
      const double end = std::max(scale * out[k0], 0.0);
      for (int k = k0; k < k0 + nx; ++k) out[k] = std::max(top - perXn2 * xn[k] * xn[k], 0.0);
      if (first < nx) out[k0 + first] = out[k0 + nx - 1 - first] = end;
    }
  }
}

}  // namespace

void parabolicBound(const PatchMesh& mesh, double a, double b, double fz, double mu,
                    TractionField* field) {
  writeBound<false>(mesh, a, b, fz, mu, 0.0, field);
}

void flattenedBound(const PatchMesh& mesh, double a, double b, double fz, double mu, double s,
                    TractionField* field) {
  if (s > 0.0)
    writeBound<true>(mesh, a, b, fz, mu, s, field);
  else
    writeBound<false>(mesh, a, b, fz, mu, 0.0, field);
}

void ForceSums::addStrip(const PatchMesh& mesh, int j, StripSums s) {
  const double dA = mesh.nodeArea(j);
  f_.fx += s.tx * dA;
  f_.fy += s.ty * dA;
  f_.mz += (mesh.a() * s.xnTy - mesh.stripY(j) * s.tx) * dA;
  stuck_ += s.stuck * dA;
  loaded_ += s.loaded * dA;
}

void ForceSums::addStrip(const PatchMesh& mesh, int j, StripSums s, const StripEntry& e,
                         const double* tx, const double* ty) {
  if (e.w != 0.0 && e.first < mesh.nx()) {
    const int kf = mesh.index(e.first, j), kl = mesh.index(mesh.nx() - 1 - e.first, j);
    s.tx += e.w * (tx[kf] + tx[kl]);
    s.ty += e.w * (ty[kf] + ty[kl]);
    s.xnTy += e.w * (mesh.xNorms()(kf) * ty[kf] + mesh.xNorms()(kl) * ty[kl]);
  }
  addStrip(mesh, j, s);
}

CreepForces ForceSums::forces() const {
  CreepForces out = f_;
  out.adhesionFraction = loaded_ > 0.0 ? stuck_ / loaded_ : 0.0;
  return out;
}

CreepForces integrateTraction(const PatchMesh& mesh, const TractionField& f) {
  ForceSums sums;
  for (int j = 0; j < mesh.ny(); ++j) {
    StripSums strip;
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      strip.tx += f.tx(k);
      strip.ty += f.ty(k);
      strip.xnTy += mesh.xNorms()(k) * f.ty(k);
      strip.loaded += f.bound(k) > 0.0;
      strip.stuck += f.bound(k) > 0.0 && !f.slip(k);
    }
    if (j < static_cast<int>(f.entry.size()))
      sums.addStrip(mesh, j, strip, f.entry[j], f.tx.data(), f.ty.data());
    else
      sums.addStrip(mesh, j, strip);
  }
  return sums.forces();
}

namespace {

// The scalar reference: one strip at a time, in strip order.
template <bool kCoupled>
CreepForces steadyMarch(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                        TractionField* f) {
  const steady::SteadyMarch<kCoupled> m(mesh, L, c, f);
  ForceSums sums;
  for (int j = 0; j < m.ny; ++j) {
    auto s = m.strip(j);
    m.march(j, s, f->entry[j].first);
    m.unloadedEnds(j);
    sums.addStrip(mesh, j, s.sums, f->entry[j], m.out.tx, m.out.ty);
  }
  return sums.forces();
}

}  // namespace

CreepForces steadyFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                          TractionField* f, StripLanes lanes) {
  const bool inLanes = lanes == StripLanes::kOn ||
                       (lanes == StripLanes::kAuto && mesh.nx() >= kSteadyLanesFromNodes);
  if (inLanes && stripLanesAvailable()) return steadyFastSimInLanes(mesh, L, c, f);
  if (L.lateralCoupling != 0.0) return steadyMarch<true>(mesh, L, c, f);
  return steadyMarch<false>(mesh, L, c, f);
}

}  // namespace wheel_rail_contact
