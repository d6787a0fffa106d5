// libFuzzer target: makeContactModel(ContactParameters) then a sequence of step() / reset() on the
// models steady, shen-li, nss (fixed and adaptive mesh) and exact (tiny grid), parameters and
// inputs decoded from the fuzz bytes with a bias to extremes (NaN, Inf, 1e+-300, sign flips,
// dt <= 0, fz <= 0, meshes 0..61), per-step a, b, mu among them, and now and then a patch shape
// (StepInput::shape: Kalker's strips of an ellipse at a moving origin, a strip's field or the
// origin perturbed, or strips of raw values). Findings: a crash or sanitizer
// report; an exception other than std::invalid_argument from makeContactModel, or any exception
// from step()/reset(); an output breaking contact_model.hpp's contract (fuzz_checks.hpp); traction
// above mu p at a node (steady, shen-li, nss) or a total force above mu fz; reset() not giving a
// fresh model's output.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iterator>
#include <limits>
#include <memory>
#include <stdexcept>

#include "core/models/nss_model.hpp"
#include "core/models/steady_model.hpp"
#include "fuzz_checks.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/fastsim/patch_shape.hpp"

using namespace wheel_rail_contact;
using namespace wheel_rail_contact::fuzz;

namespace {

// Relative slack of the Coulomb checks: the saturation rescale and the force sums round.
constexpr double kNodeTolerance = 1e-9;
constexpr double kForceTolerance = 1e-7;
constexpr int kMaxSteps = 24;        // FastSim models
constexpr int kMaxExactSteps = 4;    // exact: every step may take 10 nx sub-steps
constexpr int kMaxFastSimMesh = 61;  // nx, ny decoded in [0, 61]: both invalid ends and beyond 60
constexpr int kMaxExactMesh = 6;

// Fuzz bytes -> values. Exhausted data decodes to the typical value, so short inputs are sane.
class Decoder {
 public:
  Decoder(const uint8_t* data, size_t size) : fdp_(data, size) {}

  int pick(int n) { return fdp_.ConsumeIntegralInRange<int>(0, n - 1); }
  bool flag() { return fdp_.ConsumeBool(); }

  /// Mostly `typical` scaled by a power of two, sometimes a special value or raw bits.
  double value(double typical) {
    static const int kExponents[] = {0, 1, -1, 2, -2, 4, -4, 10, -10, 30, -30, 100, -100, 1000};
    static const double kSpecial[] = {0.0,
                                      -0.0,
                                      std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(),
                                      DBL_MIN,
                                      std::numeric_limits<double>::denorm_min(),
                                      DBL_MAX,
                                      -DBL_MAX,
                                      1e-300,
                                      1e300,
                                      1.0,
                                      -1.0};
    switch (pick(4)) {
      case 0:
        return std::ldexp(typical, kExponents[pick(std::size(kExponents))]);
      case 1:
        return -std::ldexp(typical, kExponents[pick(std::size(kExponents))]);
      case 2:
        return kSpecial[pick(std::size(kSpecial))];
      default: {
        uint64_t bits = fdp_.ConsumeIntegral<uint64_t>();
        double v;
        std::memcpy(&v, &bits, sizeof v);
        return v;
      }
    }
  }

  /// A parameter: `typical` unless the fuzzer says otherwise, then within 2^+-60 of it (beyond
  /// validate()'s physical ranges on both sides), or one that validate() must refuse (negative,
  /// NaN, Inf) or 0.
  double param(double typical) {
    static const double kSpecial[] = {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity()};
    if (!flag()) return typical;
    switch (pick(3)) {
      case 0:
        return std::ldexp(typical, pick(121) - 60);
      case 1:
        return kSpecial[pick(std::size(kSpecial))] * typical;
      default: {
        uint64_t bits = fdp_.ConsumeIntegral<uint64_t>();
        double v;
        std::memcpy(&v, &bits, sizeof v);
        const double r = std::abs(v / typical);
        return r >= std::ldexp(1.0, -30) && r <= std::ldexp(1.0, 30) ? v : typical;
      }
    }
  }

 private:
  FuzzedDataProvider fdp_;
};

ContactParameters decodeParameters(Decoder& d) {
  static const char* kModels[] = {"steady", "shen-li", "nss", "exact"};
  ContactParameters p;
  p.model = kModels[d.pick(4)];
  p.mesh = d.flag() ? "adaptive" : "fixed";
  const int maxMesh = p.model == "exact" ? kMaxExactMesh : kMaxFastSimMesh;
  p.nx = std::min(maxMesh, 2 + d.pick(maxMesh + 1)) - (d.flag() ? d.pick(3) : 0);
  p.ny = std::min(maxMesh, 1 + d.pick(maxMesh + 1)) - (d.flag() ? d.pick(2) : 0);
  p.G = d.param(p.G);
  p.nu = d.param(p.nu);
  p.mu = d.param(p.mu);
  p.a0 = d.param(p.a0);
  p.b0 = d.param(p.b0);
  p.fz0 = d.param(p.fz0);
  p.fz_max = d.flag() ? d.param(1.2e5) : 0.0;
  if (d.pick(16) == 15) p.chi_table = "/nonexistent/chi_table.csv";
  return p;
}

// A patch shape into *shape: mostly Kalker's strips of an ellipse (semi-axes near 6 and 4 mm, up to
// 30 strips) at an origin that drifts or jumps, one strip's field now and then replaced by an
// extreme value; or a few strips of raw values.
void decodeShape(Decoder& d, PatchShape* shape) {
  shape->strips.clear();
  if (d.pick(4) == 0) {
    for (int j = d.pick(5); j > 0; --j)
      shape->strips.push_back(
          PatchStrip{d.value(1e-3), d.value(4e-4), d.value(5e-3), d.value(-5e-3), d.value(1e9)});
    shape->origin = d.value(1e-2);
    return;
  }
  const double a = std::ldexp(6e-3, d.pick(9) - 4), b = std::ldexp(4e-3, d.pick(9) - 4);
  const int n = 1 + d.pick(30);
  const double p0 = 1e9 * std::ldexp(1.0, d.pick(9) - 4);
  for (int j = 0; j < n; ++j) {
    const double yn = -1.0 + (2.0 * j + 1.0) / n, r = std::sqrt(1.0 - yn * yn);
    shape->strips.push_back(PatchStrip{b * yn, 2.0 * b / n, a * r, -a * r, p0 * r});
  }
  if (d.pick(4) == 3) {
    PatchStrip& s = shape->strips[d.pick(n)];
    double* fields[] = {&s.eta, &s.width, &s.x_lead, &s.x_trail, &s.pmax};
    *fields[d.pick(5)] = d.value(1e-3);
  }
  if (d.flag()) shape->origin += d.flag() ? d.value(1e-4) : d.value(1e-2);
}

// Each field of the next input changes with the fuzzer's say-so, else repeats: runs of steps.
// `shape`: the run's shape, decoded into when the input takes one.
StepInput decodeInput(Decoder& d, StepInput in, PatchShape* shape) {
  if (d.flag()) in.dt = d.value(1e-3);
  if (d.flag()) in.V = d.value(20.0);
  if (d.flag()) in.xi = d.value(2e-3);
  if (d.flag()) in.eta = d.value(1e-3);
  if (d.flag()) in.phi = d.value(1.0);
  if (d.flag()) in.fz = d.value(8e4);
  // Per-step geometry and friction, now and then (0 = not given); a and b mostly together.
  if (d.pick(4) == 3) {
    in.a = d.flag() ? 0.0 : d.value(6e-3);
    in.b = d.pick(8) == 7 ? 0.0 : d.value(4e-3);
  }
  if (d.pick(4) == 3) in.mu = d.flag() ? 0.0 : d.value(0.3);
  if (d.pick(4) == 3) {  // a shape, given with its equivalent ellipse (else refused), or none
    in.shape = d.pick(4) == 3 ? nullptr : shape;
    if (in.shape) {
      decodeShape(d, shape);
      if (in.a == 0.0 || d.flag()) {
        in.a = d.value(6e-3);
        in.b = d.value(4e-3);
      }
    }
  }
  return in;
}

std::unique_ptr<ContactModel> make(const ContactParameters& p) {
  try {
    return makeContactModel(p);
  } catch (const std::invalid_argument&) {
    return nullptr;  // invalid parameters are allowed to throw exactly this
  } catch (const std::exception& e) {
    finding(std::string("makeContactModel threw something else: ") + e.what());
  }
}

StepOutput safeStep(ContactModel& m, const StepInput& in, const std::string& where) {
  try {
    return m.step(in);
  } catch (const std::exception& e) {
    finding(where + ": step() threw: " + e.what() + "\n  in: " + describe(in));
  }
}

// Every node of a FastSim traction field within its Coulomb bound, every value finite.
void checkField(const TractionField& f, const std::string& where) {
  for (Eigen::Index k = 0; k < f.tx.size(); ++k) {
    if (!std::isfinite(f.tx(k)) || !std::isfinite(f.ty(k)) || !std::isfinite(f.bound(k)) ||
        f.bound(k) < 0.0)
      finding(where + ": non-finite traction or bound at node " + std::to_string(k));
    if (!withinBound(f.tx(k), f.ty(k), f.bound(k), kNodeTolerance)) {
      char s[200];
      std::snprintf(s, sizeof s, ": traction above mu p at node %ld: |t| = %.17g > %.17g",
                    static_cast<long>(k), std::hypot(f.tx(k), f.ty(k)), f.bound(k));
      finding(where + s);
    }
  }
}

void checkTraction(const ContactModel& m, const std::string& where) {
  if (const auto* s = dynamic_cast<const SteadyModel*>(&m)) checkField(s->traction(), where);
  if (const auto* n = dynamic_cast<const NssModel*>(&m)) checkField(n->traction(), where);
}

// The total force bound mu * fz, fz the largest load the forces may stem from.
void checkForce(const StepOutput& out, double mu, double fz, const std::string& where) {
  if (out.status == StepStatus::kRejected || out.status == StepStatus::kNoLoad) return;
  if (!withinBound(out.fx, out.fy, mu * fz, kForceTolerance))
    finding(where + ": force above mu fz (fz = " + std::to_string(fz) +
            ")\n  out: " + describe(out));
}

// reset() must leave the model as a fresh one: the next two outputs equal a fresh model's.
void checkReset(ContactModel& m, const ContactParameters& p, const StepInput& in) {
  m.reset();
  const auto fresh = makeContactModel(p);
  // The exact solver keeps its factorisation and normal solution across reset() (caches, not
  // state), so its iterative solve ends elsewhere within its tolerance (1e-8 of max |tau|): allow
  // 1e-6 of mu fz, mu the step's own where it gives one (p.mu may be 0 then). FastSim models must
  // agree bit for bit.
  const double mu = in.mu != 0.0 ? std::abs(in.mu) : p.mu;
  const double tol = p.model == "exact" ? 1e-6 * mu * std::abs(in.fz) : 0.0;
  const auto same = [tol](double x, double y, double length) {
    return x == y || std::abs(x - y) <= tol * length;
  };
  for (int k = 0; k < 2; ++k) {
    const StepOutput a = safeStep(m, in, "after reset"), b = safeStep(*fresh, in, "fresh");
    checkOutputContract(in, a, "after reset");
    if (a.status != b.status || !same(a.fx, b.fx, 1.0) || !same(a.fy, b.fy, 1.0) ||
        !same(a.mz, b.mz, a.a))
      finding("reset() differs from a fresh model\n  in: " + describe(in) +
              "\n  reset: " + describe(a) + "\n  fresh: " + describe(b));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Decoder d(data, size);
  const ContactParameters p = decodeParameters(d);
  const std::unique_ptr<ContactModel> model = make(p);
  if (!model) return 0;
  const bool exact = p.model == "exact";
  // WRC_FUZZ_TRACE=1 prints every step: reproducing a finding shows the sequence that led to it.
  static const bool trace = std::getenv("WRC_FUZZ_TRACE") != nullptr;
  if (trace)
    std::fprintf(stderr, "%s/%s nx=%d ny=%d G=%g nu=%g mu=%g a0=%g b0=%g fz0=%g fz_max=%g\n",
                 p.model.c_str(), p.mesh.c_str(), p.nx, p.ny, p.G, p.nu, p.mu, p.a0, p.b0, p.fz0,
                 p.fz_max);
  const int steps = d.pick((exact ? kMaxExactSteps : kMaxSteps) + 1);
  StepInput in{1e-3, 20.0, 2e-3, 0.0, 0.0, 8e4};
  PatchShape shape;    // the run's shape: StepInput::shape points here while a step takes one
  double maxFz = 0.0;  // largest load since the history was last cleared (exact's forces lag)
  double maxMu = 0.0;  // largest friction coefficient since then (p.mu or the steps' own)
  for (int k = 0; k < steps; ++k) {
    const std::string where = p.model + "/" + p.mesh + " step " + std::to_string(k);
    if (d.pick(8) == 7) {
      model->reset();
      maxFz = maxMu = 0.0;
    }
    in = decodeInput(d, in, &shape);
    const StepOutput out = safeStep(*model, in, where);
    if (trace)
      std::fprintf(stderr, "%s\n  in:  %s\n  out: %s\n", where.c_str(), describe(in).c_str(),
                   describe(out).c_str());
    checkOutputContract(in, out, where);
    if (out.status == StepStatus::kNoLoad) maxFz = maxMu = 0.0;
    if (out.status != StepStatus::kRejected && in.fz > 0.0) maxFz = std::max(maxFz, in.fz);
    // A held output (standstill, exact without a sub-step) may stem from an earlier step's mu.
    if (out.status != StepStatus::kRejected) maxMu = std::max(maxMu, in.mu != 0.0 ? in.mu : p.mu);
    checkForce(out, maxMu, exact ? maxFz : out.fz, where);
    if (out.status == StepStatus::kOk) checkTraction(*model, where);
  }
  if (steps > 0) checkReset(*model, p, in);
  return 0;
}
