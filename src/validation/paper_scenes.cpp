#include "validation/paper_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wheel_rail_contact {

namespace {

ContactParameters paperMaterial(double a) {
  ContactParameters p;
  p.G = 1.0e6;
  p.nu = 0.28;
  p.mu = 0.4013;
  p.a0 = p.b0 = a;
  p.fz0 = 470.5;
  return p;
}

}  // namespace

PaperScene combinedCreepageScene(int which, int periods, double step) {
  // {xi mean, xi amplitude, eta amplitude, phi [1/m], lambda/a}
  static const double cases[3][5] = {{0.0, 0.002, 0.002, 0.1, 15.0},
                                     {0.0, 0.052, 0.052, 1.0, 10.0},
                                     {0.05, 0.002, 0.502, 1.0, 25.0}};
  if (which < 1 || which > 3) throw std::invalid_argument("combined case must be 1, 2 or 3");
  const double* c = cases[which - 1];
  PaperScene s;
  s.name = "combined" + std::to_string(which);
  s.params = paperMaterial(0.02);
  s.params.fz_max = 470.5;  // constant load: the largest patch is the patch
  const double V = 0.025, lambda = c[4] * 0.02;
  s.period = lambda / V;
  const int n = static_cast<int>(std::round(periods * lambda / step));
  for (int k = 0; k <= n; ++k) {
    const double q = k * step, w = 2.0 * M_PI * q / lambda;
    // eta is in opposite phase: cos(2 pi (q - lambda/2) / lambda) = -cos(w).
    s.rows.push_back({q / V, V, c[0] + c[1] * std::cos(w), -c[2] * std::cos(w), c[3], 470.5});
  }
  return s;
}

PaperScene varyingLoadScene(double xi, double lambda_over_a0, int periods, double step) {
  PaperScene s;
  s.name = "load_xi" + std::to_string(xi).substr(0, 5) + "_l" +
           std::to_string(static_cast<int>(lambda_over_a0));
  s.params = paperMaterial(0.02);
  s.params.fz_max = 1.25 * 470.5;
  const double V = 0.25, lambda = lambda_over_a0 * 0.02;
  s.period = lambda / V;
  const int n = static_cast<int>(std::round(periods * lambda / step));
  for (int k = 0; k <= n; ++k) {
    const double q = k * step;
    s.rows.push_back(
        {q / V, V, xi, 0.0, 0.0, 470.5 * (1.0 + 0.25 * std::sin(2.0 * M_PI * q / lambda))});
  }
  return s;
}

std::vector<StepOutput> runScene(ContactModel& model, const std::vector<ScenarioRow>& rows) {
  model.reset();
  std::vector<StepOutput> out;
  out.reserve(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) out.push_back(model.step(stepInputAt(rows, k)));
  return out;
}

SceneError sceneError(const PaperScene& scene, const std::vector<StepOutput>& model,
                      const std::vector<StepOutput>& exact) {
  SceneError e;
  const double tEnd = scene.rows.back().t, from = tEnd - scene.period * (1.0 + 1e-9);
  double sum = 0.0, peak = 0.0, meanX = 0.0, meanY = 0.0;
  double fxMin = 1e300, fxMax = -1e300, exMin = 1e300, exMax = -1e300, fzMin = 1e300,
         fzMax = -1e300;
  int n = 0;
  for (size_t k = 0; k < scene.rows.size(); ++k) {
    if (scene.rows[k].t <= from) continue;
    const double dx = model[k].fx - exact[k].fx, dy = model[k].fy - exact[k].fy;
    sum += dx * dx + dy * dy;
    meanX += dx;
    meanY += dy;
    peak = std::max(peak, std::hypot(exact[k].fx, exact[k].fy));
    fxMin = std::min(fxMin, model[k].fx);
    fxMax = std::max(fxMax, model[k].fx);
    exMin = std::min(exMin, exact[k].fx);
    exMax = std::max(exMax, exact[k].fx);
    fzMin = std::min(fzMin, scene.rows[k].fz);
    fzMax = std::max(fzMax, scene.rows[k].fz);
    ++n;
  }
  const double rms = std::sqrt(sum / std::max(n, 1));
  e.rmsOverPeak = peak > 0.0 ? rms / peak : 0.0;
  const double mean = std::hypot(meanX, meanY) / std::max(n, 1);
  e.meanOverPeak = peak > 0.0 ? mean / peak : 0.0;
  e.rmsAboutMeanOverPeak =
      peak > 0.0 ? std::sqrt(std::max(0.0, rms * rms - mean * mean)) / peak : 0.0;
  e.rmsOverMuFz0 = rms / (scene.params.mu * scene.params.fz0);
  const double dFz = scene.params.mu * (fzMax - fzMin);
  e.dFxOverMuDFz = dFz > 0.0 ? (fxMax - fxMin) / dFz : 0.0;
  e.dFxOverMuDFzExact = dFz > 0.0 ? (exMax - exMin) / dFz : 0.0;
  return e;
}

}  // namespace wheel_rail_contact
