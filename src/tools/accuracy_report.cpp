// accuracy_report: every accuracy figure of NSS-FastSim against our exact half-space solver
// (issue "NSS-FastSim", item 7), written as CSV under an output folder:
//   freq_errors.csv   |C^/C_steady (nss, shen-li, steady) - exact| per kind, a/b, lambda/a
//   freq_ab1.csv      the a/b = 1 curves of every model (figure 1)
//   scenes.csv        per paper scene and model: RMS error / peak, / (mu Fz0), dFx / (mu dFz),
//                     the RMS split into the mean error and the RMS about it (/ peak)
//   scene_<name>.csv  force histories of every model (figures 2-4, 9-10)
// Options: accuracy_report --help.
// --exact-from DIR reads the exact force histories of the scenes from an earlier run's
// DIR/scene_<name>.csv instead of re-solving them (minutes instead of seconds per scene; the
// histories are written with 6 significant digits, enough for errors of 0.1 %).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tool_options.hpp"
#include "validation/paper_scenes.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"
#include "wheel_rail_contact/fastsim/chi_table.hpp"
#include "wheel_rail_contact/fastsim/fastsim_frequency.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string out = "doc/data";
  int grid = 30, nx = 20, ny = 20, periods = 3;
  int loadGrid = 30;           // the varying-load exact runs re-solve the normal problem: coarser
  std::string parts = "all";   // all | freq | scenes
  std::string scenes = "all";  // all | load | combined
  std::string exactFrom;       // folder of an earlier run's scene_*.csv; empty = solve
};

void frequencyErrors(const Options& o, const ChiTable& table) {
  std::ofstream errs = tools::writeFile(o.out + "/freq_errors.csv"),
                fig = tools::writeFile(o.out + "/freq_ab1.csv");
  errs << "a_over_b,kind,lambda_over_a,err_nss,err_shenli,err_steady\n";
  fig << "kind,lambda_over_a,model,c_real,c_imag,ratio_real,ratio_imag\n";
  std::vector<double> lambdas;
  for (int q = 0; q <= 32; ++q) lambdas.push_back(std::pow(10.0, -0.30103 + q * 2.30103 / 32));
  for (double ab : {0.5, 1.0, 2.0}) {
    for (const CreepageKind kind : kCreepageKinds) {
      const NonSteadyCoefficients exact(kind, ab, 0.28, o.grid, o.grid);
      const double ce = exact.steady();
      const double cf = fastsimSteadyCoefficient(kind, ab, 0.28, o.nx, o.ny);
      const SecondOrderChi chi = table.secondOrderAt(kind, ab);  // either order
      for (double l : lambdas) {
        const std::complex<double> re = exact.at(l) / ce;
        const auto nss = fastsimSecondOrderCoefficient(kind, ab, 0.28, o.nx, o.ny, chi, l);
        const auto sl = fastsimNonSteadyCoefficient(kind, ab, 0.28, o.nx, o.ny, {}, l);
        char line[256];
        std::snprintf(line, sizeof line, "%g,%s,%.5g,%.5f,%.5f,%.5f\n", ab, coefficientCode(kind),
                      l, std::abs(nss / cf - re), std::abs(sl / cf - re), std::abs(1.0 - re));
        errs << line;
        if (ab != 1.0) continue;
        const std::pair<const char*, std::complex<double>> rows[] = {
            {"exact", re * ce}, {"nss", nss}, {"shen-li", sl}, {"steady", cf}};
        for (const auto& r : rows) {
          const double steady = std::string(r.first) == "exact" ? ce : cf;
          std::snprintf(line, sizeof line, "%s,%.5g,%s,%.6g,%.6g,%.6g,%.6g\n",
                        coefficientCode(kind), l, r.first, r.second.real(), r.second.imag(),
                        r.second.real() / steady, r.second.imag() / steady);
          fig << line;
        }
      }
      std::cerr << "freq a/b " << ab << " kind " << coefficientCode(kind) << " done\n";
    }
  }
}

// The exact rows of an earlier run's history file (same scene and grid, so the same rows).
std::vector<StepOutput> readExact(const std::string& path, size_t rows) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<StepOutput> out;
  std::string line;
  std::getline(in, line);  // header t,fz,model,mesh,fx,fy
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string f[6];
    for (auto& c : f) std::getline(ss, c, ',');
    if (f[2] != "exact") continue;
    StepOutput o;
    o.fz = std::stod(f[1]);
    o.fx = std::stod(f[4]);
    o.fy = std::stod(f[5]);
    out.push_back(o);
  }
  if (out.size() != rows) throw std::runtime_error(path + ": exact rows do not match the scene");
  return out;
}

std::vector<StepOutput> exactHistory(const Options& o, const PaperScene& s) {
  if (!o.exactFrom.empty())
    return readExact(o.exactFrom + "/scene_" + s.name + ".csv", s.rows.size());
  ContactParameters p = s.params;
  p.model = "exact";
  p.nx = p.ny = s.name.rfind("load", 0) == 0 ? o.loadGrid : o.grid;
  auto exactModel = makeContactModel(p);
  return runScene(*exactModel, s.rows);
}

void sceneErrors(const Options& o) {
  std::vector<PaperScene> scenes;
  const double step = 2.2 * 0.02 / o.grid;  // the exact solver's element length at a = 20 mm
  if (o.scenes != "load")
    for (int c = 1; c <= 3; ++c) scenes.push_back(combinedCreepageScene(c, o.periods, step));
  const double loadStep = 2.2 * 0.02 * std::cbrt(1.25) / o.loadGrid;
  if (o.scenes != "combined")
    for (double xi : {0.002, 0.01, 0.05, 0.1})
      for (double l : {5.0, 15.0, 40.0})
        scenes.push_back(varyingLoadScene(xi, l, o.periods, loadStep));
  std::ofstream table = tools::writeFile(o.out + "/scenes.csv");
  table << "scene,model,mesh,rms_over_peak,rms_over_mu_fz0,dfx_over_mu_dfz,exact_dfx_over_mu_dfz,"
           "mean_over_peak,rms_about_mean_over_peak\n";
  // "nss": nss with fastsim: classic; "nss-calibrated": with fastsim: calibrated (both named, so
  // the table means the same whatever the default).
  const std::pair<const char*, const char*> models[] = {{"nss", "fixed"},
                                                        {"nss", "adaptive"},
                                                        {"nss-calibrated", "fixed"},
                                                        {"nss-calibrated", "adaptive"},
                                                        {"shen-li", "fixed"},
                                                        {"shen-li", "adaptive"},
                                                        {"steady", "fixed"}};
  for (const PaperScene& s : scenes) {
    ContactParameters p = s.params;
    const std::vector<StepOutput> exact = exactHistory(o, s);
    std::ofstream hist = tools::writeFile(o.out + "/scene_" + s.name + ".csv");
    hist << "t,fz,model,mesh,fx,fy\n";
    auto write = [&](const char* m, const char* mesh, const std::vector<StepOutput>& r) {
      for (size_t k = 0; k < r.size(); ++k) {
        char line[200];
        std::snprintf(line, sizeof line, "%.6g,%.6g,%s,%s,%.6g,%.6g\n", s.rows[k].t, s.rows[k].fz,
                      m, mesh, r[k].fx, r[k].fy);
        hist << line;
      }
    };
    write("exact", "grid", exact);
    for (const auto& m : models) {
      const bool calibrated = std::string(m.first) == "nss-calibrated";
      p.model = calibrated ? "nss" : m.first;
      p.fastsim = calibrated ? FastSimVariant::kCalibrated : FastSimVariant::kClassic;
      p.mesh = m.second;
      p.nx = o.nx;
      p.ny = o.ny;
      auto model = makeContactModel(p);
      const std::vector<StepOutput> r = runScene(*model, s.rows);
      write(m.first, m.second, r);
      const SceneError e = sceneError(s, r, exact);
      char line[256];
      std::snprintf(line, sizeof line, "%s,%s,%s,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f\n", s.name.c_str(),
                    m.first, m.second, e.rmsOverPeak, e.rmsOverMuFz0, e.dFxOverMuDFz,
                    e.dFxOverMuDFzExact, e.meanOverPeak, e.rmsAboutMeanOverPeak);
      table << line;
      std::cerr << line;
    }
  }
}

void addOptions(CLI::App& app, Options* o) {
  app.description(
      "Every accuracy figure of NSS-FastSim against the exact half-space solver, as CSV.");
  tools::option(app, "--out", &o->out, "output folder (must exist)");
  tools::option(app, "--grid", &o->grid,
                "exact grid N x N of the frequency curves and combined scenes");
  tools::option(app, "--load-grid", &o->loadGrid, "exact grid of the varying-load scenes");
  tools::option(app, "--nx", &o->nx, "FastSim nodes per strip");
  tools::option(app, "--ny", &o->ny, "FastSim strips");
  tools::option(app, "--periods", &o->periods, "periods of each scene");
  tools::option(app, "--parts", &o->parts, "all | freq | scenes");
  tools::option(app, "--scenes", &o->scenes, "all | load | combined");
  tools::option(app, "--exact-from", &o->exactFrom,
                "folder of an earlier run's scene_*.csv: its exact histories (empty: solve)");
}

int run(const Options& o) {
  tools::requireFolder(o.out);
  const ChiTable table = ChiTable::shipped().forMesh(o.nx);
  if (o.parts != "scenes") frequencyErrors(o, table);
  if (o.parts != "freq") sceneErrors(o);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("accuracy_report", argc, argv, addOptions, run);
}
