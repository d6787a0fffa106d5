#include "core/exact/halfspace_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/exact/halfspace_normal.hpp"

namespace wheel_rail_contact {

namespace {

// Slip solve of one element: tau = -g e with the slip s = c + D tau parallel to e, |e| = 1,
// D = diag(dx, dy) > 0. Writing s = k e (k >= 0) gives e_i = c_i / (k + g d_i); k is the root of
// sum e_i^2 = 1, decreasing and convex in k, so Newton from k = 0 converges monotonically.
void slipDirection(double cx, double cy, double g, double dx, double dy, double* ex, double* ey) {
  double k = 0.0;
  for (int it = 0; it < 60; ++it) {
    const double qx = k + g * dx, qy = k + g * dy;
    const double f = cx * cx / (qx * qx) + cy * cy / (qy * qy) - 1.0;
    const double df = -2.0 * (cx * cx / (qx * qx * qx) + cy * cy / (qy * qy * qy));
    const double step = -f / df;
    k += step;
    if (std::abs(step) <= 1e-15 * (k + g * std::max(dx, dy))) break;
  }
  double x = cx / (k + g * dx), y = cy / (k + g * dy);
  const double n = std::hypot(x, y);
  *ex = x / n;
  *ey = y / n;
}

// u += M(:, element at (ix, iy)) (dx, dy) over the runs of loaded elements, u planar (x of every
// element, then y at ux + n): the Gauss-Seidel hot loop, unit stride in the kernel tables. On
// x86-64 also compiled for AVX2 and chosen at run time (same results up to rounding).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void addRuns(const InfluenceKernel& k, const std::vector<detail::ContactRun>& runs, int ix, int iy,
             double dx, double dy, double* ux, double* uy) {
  const double *kxx = k.xxData(), *kxy = k.xyData(), *kyy = k.yyData();
  for (const detail::ContactRun& r : runs) {
    const int o = k.offset(r.ix - ix, r.lo - iy);
    double *px = ux + r.first, *py = uy + r.first;
    for (int t = 0; t < r.len; ++t) {
      px[t] += kxx[o + t] * dx + kxy[o + t] * dy;
      py[t] += kxy[o + t] * dx + kyy[o + t] * dy;
    }
  }
}

}  // namespace

HalfspaceSolver::HalfspaceSolver(const HalfspaceGrid& grid, double G, double nu,
                                 SolverControl control)
    : kernel_(grid, G, nu), G_(G), nu_(nu), control_(control) {
  histX_ = Eigen::VectorXd::Zero(grid.size());
  histY_ = Eigen::VectorXd::Zero(grid.size());
  sol_.tx = Eigen::VectorXd::Zero(grid.size());
  sol_.ty = Eigen::VectorXd::Zero(grid.size());
  sol_.sx = Eigen::VectorXd::Zero(grid.size());
  sol_.sy = Eigen::VectorXd::Zero(grid.size());
  sol_.state.assign(grid.size(), ElementState::kExterior);
}

void HalfspaceSolver::setPressure(const Eigen::VectorXd& p) {
  const HalfspaceGrid& g = grid();
  if (p.size() != g.size()) throw std::invalid_argument("pressure: size must be mx*my");
  std::vector<int> elems;
  for (int k = 0; k < g.size(); ++k)
    if (p[k] > 0.0) elems.push_back(k);
  if (elems != elems_) {
    elems_ = elems;
    systemKind_ = -1;
  }
  p_.resize(elems_.size());
  for (size_t i = 0; i < elems_.size(); ++i) p_[i] = p[elems_[i]];
}

void HalfspaceSolver::setHertzPressure(double a, double b, double fz) {
  setPressure(hertzianGridPressure(grid(), a, b, fz, G_, nu_));
}

void HalfspaceSolver::clearHistory() {
  histX_.setZero();
  histY_.setZero();
}

void HalfspaceSolver::mirrorHistoryAlongX() {
  const HalfspaceGrid& g = grid();
  for (int ix = 0; ix < g.mx / 2; ++ix)
    for (int iy = 0; iy < g.my; ++iy) {
      std::swap(histX_[g.index(ix, iy)], histX_[g.index(g.mx - 1 - ix, iy)]);
      std::swap(histY_[g.index(ix, iy)], histY_[g.index(g.mx - 1 - ix, iy)]);
    }
  histX_ = -histX_;
}

void HalfspaceSolver::buildSystem(bool steady) {
  const HalfspaceGrid& g = grid();
  const int n = static_cast<int>(elems_.size());
  m_.resize(2 * n, 2 * n);
  for (int j = 0; j < n; ++j) {
    const int jx = elems_[j] / g.my, jy = elems_[j] % g.my;
    for (int i = 0; i < n; ++i) {
      const int di = elems_[i] / g.my - jx, dj = elems_[i] % g.my - jy;
      double xx = kernel_.xx(di, dj), xy = kernel_.xy(di, dj), yy = kernel_.yy(di, dj);
      if (steady) {  // minus the displacement at the upstream neighbour, now
        xx -= kernel_.xx(di + 1, dj);
        xy -= kernel_.xy(di + 1, dj);
        yy -= kernel_.yy(di + 1, dj);
      }
      m_(2 * i, 2 * j) = xx;
      m_(2 * i + 1, 2 * j) = xy;
      m_(2 * i, 2 * j + 1) = xy;
      m_(2 * i + 1, 2 * j + 1) = yy;
    }
  }
  runs_.clear();
  for (int i = 0; i < n; ++i) {
    const int ix = elems_[i] / g.my, iy = elems_[i] % g.my;
    if (!runs_.empty() && runs_.back().ix == ix && runs_.back().lo + runs_.back().len == iy)
      ++runs_.back().len;
    else
      runs_.push_back({ix, iy, 1, i});
  }
  systemKind_ = steady ? 1 : 0;
  systemUsed_ = false;
  factored_ = false;
}

void HalfspaceSolver::previousDisplacement(RollingMode mode, Eigen::VectorXd* c) const {
  const HalfspaceGrid& g = grid();
  const int n = static_cast<int>(elems_.size());
  c->setZero(2 * n);
  if (mode == RollingMode::kSteady) return;
  // The loaded part of each grid column is one run of y-neighbours: walk the kernel tables along
  // it with unit stride.
  struct Run {
    int ix, lo, len;
  };
  std::vector<Run> runs;
  for (int ix = 0; ix < g.mx; ++ix) {
    int lo = g.my, hi = -1;
    for (int iy = 0; iy < g.my; ++iy)
      if (histX_[g.index(ix, iy)] != 0.0 || histY_[g.index(ix, iy)] != 0.0) {
        lo = std::min(lo, iy);
        hi = iy;
      }
    if (hi >= lo) runs.push_back({ix, lo, hi - lo + 1});
  }
  const int shift = mode == RollingMode::kTransient ? 1 : 0;
  const double *kxx = kernel_.xxData(), *kxy = kernel_.xyData(), *kyy = kernel_.yyData();
  for (int i = 0; i < n; ++i) {
    const int ix = elems_[i] / g.my + shift, iy = elems_[i] % g.my;
    double ux = 0.0, uy = 0.0;
    for (const Run& r : runs) {
      // source iy = r.lo + t sits at dj = iy - r.lo - t: table entries go down with t.
      const int o = kernel_.offset(ix - r.ix, iy - r.lo);
      const double *hx = histX_.data() + g.index(r.ix, r.lo),
                   *hy = histY_.data() + g.index(r.ix, r.lo);
      for (int t = 0; t < r.len; ++t) {
        ux += kxx[o - t] * hx[t] + kxy[o - t] * hy[t];
        uy += kxy[o - t] * hx[t] + kyy[o - t] * hy[t];
      }
    }
    (*c)[2 * i] = ux;
    (*c)[2 * i + 1] = uy;
  }
}

bool HalfspaceSolver::directAdhesion(bool steady, const Eigen::VectorXd& rhs,
                                     Eigen::VectorXd* tau) {
  if (!factored_) {
    if (steady)
      lu_.compute(m_);
    else
      llt_.compute(m_);
    factored_ = true;
  }
  *tau = steady ? Eigen::VectorXd(lu_.solve(rhs)) : Eigen::VectorXd(llt_.solve(rhs));
  for (int i = 0; i < p_.size(); ++i)
    if (std::hypot((*tau)[2 * i], (*tau)[2 * i + 1]) > bound_[i] * (1.0 + 1e-12)) return false;
  return true;
}

double HalfspaceSolver::sweep(const Eigen::VectorXd& c, const Creepages& w, double dq,
                              Eigen::VectorXd* tau, Eigen::VectorXd* v) const {
  const HalfspaceGrid& g = grid();
  const int n = static_cast<int>(elems_.size());
  double maxd = 0.0, maxt = 0.0;
  // Leading edge first: upstream elements settle before the ones they feed.
  for (int i = n - 1; i >= 0; --i) {
    const int ix = elems_[i] / g.my, iy = elems_[i] % g.my;
    const double dxx = m_(2 * i, 2 * i) / dq, dyy = m_(2 * i + 1, 2 * i + 1) / dq;
    double& tx = (*tau)[2 * i];
    double& ty = (*tau)[2 * i + 1];
    // Slip with this element's traction removed.
    const double cx = w.xi - w.phi * g.yc(iy) + ((*v)[i] - c[2 * i]) / dq - dxx * tx;
    const double cy =
        w.eta + w.phi * (g.xc(ix) + spinOffset_) + ((*v)[n + i] - c[2 * i + 1]) / dq - dyy * ty;
    const double gb = bound_[i];
    double nx = -cx / dxx, ny = -cy / dyy;  // adhesion: s = 0
    if (std::hypot(nx, ny) > gb) {          // slip at the bound
      double ex = 0.0, ey = 0.0;
      if (gb > 0.0) slipDirection(cx, cy, gb, dxx, dyy, &ex, &ey);
      nx = -gb * ex;
      ny = -gb * ey;
    }
    const double ddx = nx - tx, ddy = ny - ty;
    if (ddx != 0.0 || ddy != 0.0) {
      addInfluence(i, ddx, ddy, v);
      tx = nx;
      ty = ny;
    }
    maxd = std::max(maxd, std::hypot(ddx, ddy));
    maxt = std::max(maxt, std::hypot(nx, ny));
  }
  return maxt > 0.0 ? maxd / maxt : 0.0;
}

void HalfspaceSolver::addInfluence(int i, double dx, double dy, Eigen::VectorXd* v) const {
  // From the kernel tables, small enough to stay in cache, unlike M.
  const int n = static_cast<int>(elems_.size()), my = grid().my;
  addRuns(kernel_, runs_, elems_[i] / my, elems_[i] % my, dx, dy, v->data(), v->data() + n);
}

void HalfspaceSolver::projectOntoDiscs(Eigen::VectorXd* tau, Eigen::VectorXd* v) const {
  for (int i = 0; i < static_cast<int>(elems_.size()); ++i) {
    const double t = std::hypot((*tau)[2 * i], (*tau)[2 * i + 1]);
    if (t <= bound_[i]) continue;
    const double f = t > 0.0 ? bound_[i] / t - 1.0 : 0.0;
    const double dx = f * (*tau)[2 * i], dy = f * (*tau)[2 * i + 1];
    (*tau)[2 * i] += dx;
    (*tau)[2 * i + 1] += dy;
    addInfluence(i, dx, dy, v);
  }
}

void HalfspaceSolver::gaussSeidel(const Eigen::VectorXd& c, const Creepages& w, double dq,
                                  Eigen::VectorXd* tau) {
  // Block Gauss-Seidel sweeps G, accelerated by Anderson mixing of the last few sweeps: the next
  // input is G(x_k) - dG gamma with gamma the least-squares fit of the sweep change f = G(x) - x
  // by its recent differences dF. v = M tau is mixed alongside (it is linear in tau), and the
  // mixed traction is put back into the Coulomb discs. Convergence is judged on a plain sweep.
  // v = M tau, kept planar (x of every element, then y) for unit-stride updates.
  const int n = static_cast<int>(elems_.size());
  const Eigen::VectorXd mt = m_ * (*tau);
  Eigen::VectorXd v(2 * n);
  for (int i = 0; i < n; ++i) {
    v[i] = mt[2 * i];
    v[n + i] = mt[2 * i + 1];
  }
  const int depth = control_.andersonDepth;
  std::vector<Eigen::VectorXd> dG, dF, dV;
  Eigen::VectorXd gPrev, fPrev, vPrev;
  double best = std::numeric_limits<double>::infinity();
  sol_.converged = false;
  for (int it = 1; it <= control_.maxIterations; ++it) {
    const Eigen::VectorXd x = *tau;
    sol_.iterations = it;
    sol_.residual = sweep(c, w, dq, tau, &v);
    if (sol_.residual <= control_.tolerance) {
      sol_.converged = true;
      break;
    }
    if (depth == 0) continue;
    const Eigen::VectorXd f = *tau - x;
    if (sol_.residual > 10.0 * best) {  // mixing went astray: restart from this sweep
      dG.clear();
      dF.clear();
      dV.clear();
    } else if (gPrev.size() == tau->size()) {
      dG.push_back(*tau - gPrev);
      dF.push_back(f - fPrev);
      dV.push_back(v - vPrev);
      if (static_cast<int>(dF.size()) > depth) {
        dG.erase(dG.begin());
        dF.erase(dF.begin());
        dV.erase(dV.begin());
      }
    }
    best = std::min(best, sol_.residual);
    gPrev = *tau;
    fPrev = f;
    vPrev = v;
    const int k = static_cast<int>(dF.size());
    if (k == 0) continue;
    Eigen::MatrixXd F(f.size(), k);
    for (int j = 0; j < k; ++j) F.col(j) = dF[j];
    const Eigen::VectorXd gamma = F.colPivHouseholderQr().solve(f);
    for (int j = 0; j < k; ++j) {
      *tau -= gamma[j] * dG[j];
      v -= gamma[j] * dV[j];
    }
    projectOntoDiscs(tau, &v);
  }
  recordSlip(c, w, dq, v);
}

const HalfspaceSolution& HalfspaceSolver::solve(RollingMode mode, const Creepages& w, double mu,
                                                double dq) {
  const HalfspaceGrid& g = grid();
  if (mode != RollingMode::kShift) dq = g.dx;
  if (!(dq > 0.0) || !(mu >= 0.0)) throw std::invalid_argument("solve: need dq > 0, mu >= 0");
  const bool steady = mode == RollingMode::kSteady;
  const int n = static_cast<int>(elems_.size());
  spinOffset_ = mode == RollingMode::kShift ? 0.0 : kSpinOffset * dq;
  if (systemKind_ != (steady ? 1 : 0)) buildSystem(steady);
  bound_ = mu * p_;
  Eigen::VectorXd c;
  previousDisplacement(mode, &c);
  Eigen::VectorXd rhs(2 * n);
  for (int i = 0; i < n; ++i) {  // adhesion: u_I - u'_I = -dq w_I
    rhs[2 * i] = c[2 * i] - dq * (w.xi - w.phi * g.yc(elems_[i] % g.my));
    rhs[2 * i + 1] = c[2 * i + 1] - dq * (w.eta + w.phi * (g.xc(elems_[i] / g.my) + spinOffset_));
  }
  sol_.iterations = 0;
  sol_.converged = true;
  sol_.residual = 0.0;
  sol_.steadySteps = 0;
  Eigen::VectorXd tau;
  slip_.setZero(2 * n);  // the direct adhesion solve leaves s = 0
  if (steady) {
    if (n > 0 && !directAdhesion(true, rhs, &tau)) return steadyByMarching(w, mu, tau);
  } else if (n > 0) {
    // Direct adhesion solve when it is likely to hold (the last step was in full adhesion);
    // otherwise Gauss-Seidel from the last traction at the same elements: in rolling the traction
    // field is nearly stationary in the patch frame, so this start is close.
    const bool tryDirect = systemUsed_ && lastFullAdhesion_;
    if (!(tryDirect && directAdhesion(false, rhs, &tau))) {
      if (!tryDirect) {
        tau.resize(2 * n);
        for (int i = 0; i < n; ++i) {
          tau[2 * i] = histX_[elems_[i]];
          tau[2 * i + 1] = histY_[elems_[i]];
        }
      }
      for (int i = 0; i < n; ++i) {  // project onto the Coulomb disc
        const double t = std::hypot(tau[2 * i], tau[2 * i + 1]);
        if (t > bound_[i]) tau.segment<2>(2 * i) *= bound_[i] / t;
      }
      gaussSeidel(c, w, dq, &tau);
    }
  }
  systemUsed_ = true;
  output(tau);
  lastFullAdhesion_ = sol_.adhesionFraction == 1.0;
  if (!steady) {
    histX_ = sol_.tx;
    histY_ = sol_.ty;
  }
  return sol_;
}

const HalfspaceSolution& HalfspaceSolver::steadyByMarching(const Creepages& w, double mu,
                                                           Eigen::VectorXd tau) {
  // Steady partial slip as the limit of transient rolling with constant inputs, started from the
  // adhesion solution clamped to the Coulomb disc. The transient start-up decays over about 1.1a,
  // i.e. mx/2 steps per e-folding; the user's traction history is kept aside and restored.
  const HalfspaceGrid& g = grid();
  const Eigen::VectorXd keepX = histX_, keepY = histY_;
  histX_.setZero();
  histY_.setZero();
  for (size_t i = 0; i < elems_.size(); ++i) {
    const double t = std::hypot(tau[2 * i], tau[2 * i + 1]);
    const double f = t > bound_[i] ? bound_[i] / t : 1.0;
    histX_[elems_[i]] = f * tau[2 * i];
    histY_[elems_[i]] = f * tau[2 * i + 1];
  }
  const int maxSteps = 40 * g.mx;
  int sweeps = 0, steps = 0;
  bool converged = false;
  while (steps < maxSteps && !converged) {
    const Eigen::VectorXd px = histX_, py = histY_;
    solve(RollingMode::kTransient, w, mu);
    sweeps += sol_.iterations;
    ++steps;
    const double change =
        std::max((histX_ - px).cwiseAbs().maxCoeff(), (histY_ - py).cwiseAbs().maxCoeff());
    const double scale = std::max(histX_.cwiseAbs().maxCoeff(), histY_.cwiseAbs().maxCoeff());
    converged = sol_.converged && change <= control_.steadyTolerance * scale;
  }
  histX_ = keepX;
  histY_ = keepY;
  sol_.iterations = sweeps;
  sol_.converged = converged;
  sol_.steadySteps = steps;
  return sol_;
}

void HalfspaceSolver::recordSlip(const Eigen::VectorXd& c, const Creepages& w, double dq,
                                 const Eigen::VectorXd& v) {
  const HalfspaceGrid& g = grid();
  const int n = static_cast<int>(elems_.size());
  slip_.resize(2 * n);
  for (int i = 0; i < n; ++i) {
    const int ix = elems_[i] / g.my, iy = elems_[i] % g.my;
    slip_[2 * i] = w.xi - w.phi * g.yc(iy) + (v[i] - c[2 * i]) / dq;
    slip_[2 * i + 1] = w.eta + w.phi * (g.xc(ix) + spinOffset_) + (v[n + i] - c[2 * i + 1]) / dq;
  }
}

void HalfspaceSolver::output(const Eigen::VectorXd& tau) {
  const HalfspaceGrid& g = grid();
  const int n = static_cast<int>(elems_.size());
  const double dA = g.dx * g.dy;
  sol_.tx.setZero(g.size());
  sol_.ty.setZero(g.size());
  sol_.sx.setZero(g.size());
  sol_.sy.setZero(g.size());
  sol_.state.assign(g.size(), ElementState::kExterior);
  sol_.fx = sol_.fy = sol_.mz = 0.0;
  int adhesion = 0;
  for (int i = 0; i < n; ++i) {
    const int k = elems_[i];
    const double tx = tau[2 * i], ty = tau[2 * i + 1];
    sol_.tx[k] = tx;
    sol_.ty[k] = ty;
    sol_.sx[k] = slip_[2 * i];
    sol_.sy[k] = slip_[2 * i + 1];
    const bool slip = std::hypot(tx, ty) >= bound_[i] * (1.0 - 1e-9);
    sol_.state[k] = slip ? ElementState::kSlip : ElementState::kAdhesion;
    adhesion += slip ? 0 : 1;
    sol_.fx += tx * dA;
    sol_.fy += ty * dA;
    sol_.mz += (g.xc(k / g.my) * ty - g.yc(k % g.my) * tx) * dA;
  }
  sol_.adhesionFraction = n > 0 ? static_cast<double>(adhesion) / n : 1.0;
}

}  // namespace wheel_rail_contact
