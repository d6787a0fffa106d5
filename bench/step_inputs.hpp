// The step inputs shared by bench_fastsim (wall clock) and step_cost (instruction counts), so both
// measure the same scene.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "wheel_rail_contact/nss_model.hpp"
#include "wheel_rail_contact/rolling_direction.hpp"
#include "wheel_rail_contact/steady_model.hpp"

namespace wheel_rail_contact {
namespace bench {

// Partial slip, combined creepages, and (when varyLoad) a load that changes every step.
inline StepInput input(int k, bool varyLoad) {
  const double q = 20.0 * 5e-5 * k;
  return {5e-5,
          20.0,
          1.5e-3 * std::cos(2 * M_PI * q / 0.09),
          0.8e-3 * std::sin(2 * M_PI * q / 0.05),
          1.0,
          8e4 * (varyLoad ? 1.0 + 0.25 * std::sin(2 * M_PI * q / 0.12) : 1.0)};
}

// Steady FastSim on the mesh NssModel's fixed mesh uses (sized for fz_max, the patch from the
// load clipped onto it, the nodes outside it skipped): the same-mesh reference for nss on the
// fixed mesh. SteadyModel instead fits its mesh to the patch, so every node is loaded. The step
// does what SteadyModel::step does apart from fitting the mesh.
class SteadyOnFixedMesh : public ContactModel {
 public:
  explicit SteadyOnFixedMesh(const ContactParameters& p)
      : p_(p), ref_{p.a0, p.b0, p.fz0}, c_(kalkerCoefficients(p.a0 / p.b0, p.nu)) {
    const HertzEllipse largest = ref_.at(effectiveFzMax(p));
    mesh_ = PatchMesh(p.nx, p.ny, largest.a, largest.b);
    field_.resize(mesh_.size());
  }
  StepOutput step(const StepInput& in) override {
    StepOutput out;
    if (screenStep(in, &out) || in.V == 0.0) return out;
    const bool backwards = in.V < 0.0;
    const StepInput fwd = backwards ? mirroredInput(in) : in;
    const HertzEllipse h = ref_.at(fwd.fz);
    parabolicBound(mesh_, h.a, h.b, fwd.fz, p_.mu, &field_);
    const CreepForces f = steadyFastSim(mesh_, kalkerFlexibilities(h.a, h.b, p_.G, c_),
                                        {fwd.xi, fwd.eta, fwd.phi}, &field_);
    out = stepOutput(f, fwd.fz, h.a, h.b);
    if (backwards) mirrorForces(&out);
    return out;
  }
  void reset() override {}
  std::string name() const override { return "steady on the fixed mesh"; }

 private:
  ContactParameters p_;
  ReferencePatch ref_;
  CreepCoefficients c_;
  PatchMesh mesh_;
  TractionField field_;
};

// model: steady, shen-li or nss; mesh: fixed or adaptive; n x n nodes. Steady on "fitted" is
// SteadyModel (mesh fitted to the patch), on "fixed" SteadyOnFixedMesh.
inline std::unique_ptr<ContactModel> makeModel(const std::string& model, const std::string& mesh,
                                               int n) {
  ContactParameters p;
  p.model = model;
  p.mesh = mesh;
  p.nx = p.ny = n;
  if (p.model == "steady" && p.mesh == "fixed") return std::make_unique<SteadyOnFixedMesh>(p);
  if (p.model == "steady") return std::make_unique<SteadyModel>(p);
  return std::make_unique<NssModel>(p, ChiTable::uniform({0.4, 1.1, 0.6}));
}

}  // namespace bench
}  // namespace wheel_rail_contact
