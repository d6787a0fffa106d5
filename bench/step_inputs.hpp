// The step inputs shared by bench_fastsim (wall clock) and step_cost (instruction counts), so both
// measure the same scene.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "core/models/nss_model.hpp"
#include "core/models/steady_model.hpp"

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

// model: steady, shen-li or nss; mesh: fixed or adaptive; n x n nodes. Steady on "fitted" is
// SteadyModel with its mesh fitted to the patch, on "fixed" SteadyModel on NssModel's fixed mesh
// (the same-mesh reference for nss fixed). nss runs a uniform first-order chi, or with shippedChi
// config/chi_table.csv (kind 23 second order: with spin the march carries s2).
// A model name ending in "-calibrated" runs the calibrated FastSim (config/calibration.bin).
inline std::unique_ptr<ContactModel> makeModel(const std::string& model, const std::string& mesh,
                                               int n, bool shippedChi = false) {
  ContactParameters p;
  const std::string suffix = "-calibrated";
  const bool calibrated = model.size() > suffix.size() &&
                          model.compare(model.size() - suffix.size(), suffix.size(), suffix) == 0;
  p.model = calibrated ? model.substr(0, model.size() - suffix.size()) : model;
  p.mesh = mesh;
  p.nx = p.ny = n;
  const CalibrationTable cal = calibrated ? CalibrationTable::shipped() : CalibrationTable();
  if (p.model == "steady" && p.mesh == "fixed")
    return std::make_unique<SteadyModel>(p, SteadyModel::Mesh::kSizedForFzMax, cal);
  if (p.model == "steady")
    return std::make_unique<SteadyModel>(p, SteadyModel::Mesh::kFittedToPatch, cal);
  return std::make_unique<NssModel>(
      p, shippedChi ? ChiTable::shipped() : ChiTable::uniform({0.4, 1.1, 0.6}), cal);
}

}  // namespace bench
}  // namespace wheel_rail_contact
