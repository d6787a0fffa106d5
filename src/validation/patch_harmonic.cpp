#include "validation/patch_harmonic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "validation/manchester_a22.hpp"

namespace wheel_rail_contact {

namespace {

constexpr double kWarmUp = 8.0;  // rolling before the scored period, in a [-]
constexpr double kV = 1.0;       // the models' rolling speed [m/s] (only dq matters)

const char* zoneName(ContactZone z) {
  return z == ContactZone::kTread ? "tread" : z == ContactZone::kGaugeCorner ? "corner" : "flange";
}

PatchShape exactStripsOf(const ExactPatch& e) {
  PatchShape s;
  const HalfspaceGrid& g = e.grid;
  for (int iy = 0; iy < g.my; ++iy) {
    double half = 0.0, pmax = 0.0;
    for (int ix = 0; ix < g.mx; ++ix) {
      const double p = e.solution.p[g.index(ix, iy)];
      if (p > 0.0) {
        half = std::max(half, std::abs(g.xc(ix)) + 0.5 * g.dx);
        pmax = std::max(pmax, p);
      }
    }
    if (half > 0.0)
      s.strips.push_back(PatchStrip{e.eta_offset + g.yc(iy), g.dy, half, -half, pmax});
  }
  return s;
}

}  // namespace

const char* toString(PatchGeometry g) {
  return g == PatchGeometry::kEllipse  ? "ellipse"
         : g == PatchGeometry::kStrips ? "strips"
                                       : "exact_strips";
}

RealPatch a22RightPatch(const std::string& cases_csv, double y_mm, ContactZone zone, int exact_mx,
                        int exact_my) {
  const std::vector<A22State> states = readA22States(cases_csv);
  const auto s = std::find_if(states.begin(), states.end(), [&](const A22State& x) {
    return x.side == WheelSide::kRight && std::abs(x.y_mm - y_mm) < 1e-9;
  });
  if (s == states.end())
    throw std::runtime_error("a22RightPatch: no right-wheel state at y = " + std::to_string(y_mm));
  A22Options o;
  o.exact_mx = exact_mx;
  o.exact_my = exact_my;
  const A22Wheel w = runA22Wheel(ContactSearch{WheelsetTrackData{}}, *s, o);
  if (!w.message.empty()) throw std::runtime_error("a22RightPatch: " + w.message);
  for (const A22Patch& p : w.patches) {
    if (p.candidate.zone != zone || !(p.ours.fn > 0.0) || p.ours.merged_into >= 0) continue;
    if (!p.exact.solved || !(p.exact.fn > 0.0))
      throw std::runtime_error("a22RightPatch: the exact solution failed: " + p.exact.message);
    RealPatch r;
    char name[64];
    std::snprintf(name, sizeof name, "%s_y%g", zoneName(zone), y_mm);
    r.name = name;
    r.normal = p.ours;
    r.shape = patchShapeOf(p.ours);
    r.exact.grid = p.exact.grid;
    r.exact.eta_offset = p.exact.eta_offset;
    r.exact.solution.p = p.exact.p;
    r.exact.solution.converged = true;
    r.exact.fn = p.exact.fn;
    r.exact.pmax = p.exact.pmax;
    r.exact.eta_min = p.exact.eta_min;
    r.exact.eta_max = p.exact.eta_max;
    r.exact_shape = exactStripsOf(r.exact);
    r.creepages = {p.creepages.xi, p.creepages.eta, p.creepages.phi};
    r.G = o.G;
    r.nu = o.nu;
    const NormalPatch& n = p.ours;
    const bool in_table = n.a >= kKalkerMinAOverB * n.b && n.a <= kKalkerMaxAOverB * n.b;
    r.strips_by_default =
        n.method == NormalMethod::kNonHertzian || n.strip_weight > 0.0 || !in_table;
    return r;
  }
  throw std::runtime_error(std::string("a22RightPatch: no ") + zoneName(zone) +
                           " patch at y = " + std::to_string(y_mm));
}

PatchHarmonicScene patchHarmonicScene(const RealPatch& patch, double lambda_over_a, double mu,
                                      double amplitude, const Creepages& mean) {
  if (!(lambda_over_a > 0.0)) throw std::invalid_argument("patch harmonic: need lambda/a > 0");
  PatchHarmonicScene s;
  const double a = patch.normal.a, b = patch.normal.b;
  s.dq = patch.exact.grid.dx;
  s.period_steps = std::max(4, static_cast<int>(std::lround(lambda_over_a * a / s.dq)));
  s.lambda_over_a = s.period_steps * s.dq / a;
  // Linear theory's Fs ~ C22 G a b eta with C22 about 3 to 4 here: a force of 1e-3 mu fn.
  s.amplitude = amplitude > 0.0 ? amplitude : 1e-3 * mu * patch.exact.fn / (3.5 * patch.G * a * b);
  const int warm = static_cast<int>(std::ceil(kWarmUp * a / s.dq));
  const int n = warm + s.period_steps;
  for (int k = 0; k < n; ++k) {
    Creepages c = mean;
    c.eta += s.amplitude * std::sin(2.0 * M_PI * (k + 0.5) / s.period_steps);
    s.creepages.push_back(c);
  }
  return s;
}

std::vector<StepOutput> runExactHarmonic(const RealPatch& patch, const PatchHarmonicScene& scene,
                                         double mu) {
  ExactPatchTangential exact(patch.exact, WheelSide::kRight, patch.G, patch.nu);
  std::vector<StepOutput> out;
  out.reserve(scene.creepages.size());
  for (const Creepages& c : scene.creepages) {
    const ExactTangential t = exact.step(c, mu);
    StepOutput o;
    o.fx = t.fx;
    o.fy = t.fs;
    o.mz = t.mz;
    o.fz = patch.exact.fn;
    o.adhesionFraction = t.adhesion_fraction;
    o.status = t.converged ? StepStatus::kOk : StepStatus::kNotConverged;
    out.push_back(o);
  }
  return out;
}

std::vector<StepOutput> runModelHarmonic(const RealPatch& patch, const PatchHarmonicScene& scene,
                                         ContactParameters p, PatchGeometry geometry) {
  const NormalPatch& n = patch.normal;
  p.G = patch.G;
  p.nu = patch.nu;
  p.b0 = n.b;
  p.a0 = std::min(std::max(n.a, kKalkerMinAOverB * n.b), kKalkerMaxAOverB * n.b);
  p.fz0 = n.fn;
  p.fz_max = 0.0;
  auto model = makeContactModel(p);
  StepInput in;
  in.V = kV;
  in.dt = scene.dq / kV;
  in.fz = geometry == PatchGeometry::kExactStrips ? patch.exact.fn : n.fn;
  in.a = n.a;
  in.b = n.b;
  in.shape = geometry == PatchGeometry::kEllipse  ? nullptr
             : geometry == PatchGeometry::kStrips ? &patch.shape
                                                  : &patch.exact_shape;
  std::vector<StepOutput> out;
  out.reserve(scene.creepages.size());
  for (const Creepages& c : scene.creepages) {
    in.xi = c.xi;
    in.eta = c.eta;
    in.phi = c.phi;
    out.push_back(model->step(in));
  }
  return out;
}

PatchResponse harmonicResponse(const PatchHarmonicScene& scene,
                               const std::vector<StepOutput>& forces) {
  const int n = scene.period_steps, first = static_cast<int>(forces.size()) - n;
  if (first < 0 || forces.size() != scene.creepages.size())
    throw std::invalid_argument("patch harmonic: forces do not match the scene");
  std::complex<double> e, fx, fs, mz;
  for (int k = 0; k < n; ++k) {
    const std::complex<double> w = std::polar(1.0, -2.0 * M_PI * k / n);
    const StepOutput& f = forces[first + k];
    e += scene.creepages[first + k].eta * w;
    fx += f.fx * w;
    fs += f.fy * w;
    mz += f.mz * w;
  }
  return {fx / e, fs / e, mz / e};
}

PatchResponse exactSteadyResponse(const RealPatch& patch, double amplitude, const Creepages& mean,
                                  double mu) {
  ExactPatchTangential exact(patch.exact, WheelSide::kRight, patch.G, patch.nu);
  const ExactTangential hi = exact.steady({mean.xi, mean.eta + 0.5 * amplitude, mean.phi}, mu);
  const ExactTangential lo = exact.steady({mean.xi, mean.eta - 0.5 * amplitude, mean.phi}, mu);
  return {(hi.fx - lo.fx) / amplitude, (hi.fs - lo.fs) / amplitude, (hi.mz - lo.mz) / amplitude};
}

double patchHarmonicError(const PatchHarmonicScene& scene, const std::vector<StepOutput>& model,
                          const std::vector<StepOutput>& reference) {
  const int n = scene.period_steps, first = static_cast<int>(reference.size()) - n;
  if (first < 0 || model.size() != reference.size())
    throw std::invalid_argument("patch harmonic: histories of different lengths");
  double sum = 0.0, peak = 0.0;
  for (int k = first; k < first + n; ++k) {
    sum += std::pow(model[k].fx - reference[k].fx, 2) + std::pow(model[k].fy - reference[k].fy, 2);
    peak = std::max(peak, std::hypot(reference[k].fx, reference[k].fy));
  }
  return std::sqrt(sum / n) / std::max(peak, 1e-300);
}

}  // namespace wheel_rail_contact
