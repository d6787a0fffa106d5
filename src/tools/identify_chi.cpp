// identify_chi: fits the NSS-FastSim dynamic-flexibility table chi (config/chi_table.csv) against
// our exact half-space solver (method-notes section 5). For each creepage kind and a/b of the grid
// it computes the exact C^(lambda/a) / C_steady curve, fits chi (chi_fit.hpp) at the FastSim mesh
// and writes the table, plus every exact curve for plots.
// Options: identify_chi --help.
// --spin-out also fits a second-order F to kind 23 (second_order_flexibility.hpp) and writes its
// chi1..chi5 with the same error measures to its own file. --second-order-spin puts that fit in
// the table itself (columns chi4, chi5, zero for kinds 11 and 22): what NssModel then marches.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "tool_args.hpp"
#include "wheel_rail_contact/chi_fit.hpp"
#include "wheel_rail_contact/nonsteady_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string out = "config/chi_table.csv", curves = "doc/data/exact_curves.csv", spinOut;
  int nx = 20, ny = 20, grid = 30, points = 25;
  double nu = 0.28;
  std::vector<double> ratios = {0.2, 0.3, 0.5, 0.7, 1, 1.4, 2, 3, 5};
  bool secondOrderSpin = false;
};

const char* const kUsage =
    "usage: identify_chi [--out config/chi_table.csv] [--curves doc/data/exact_curves.csv]\n"
    "                    [--nx 20 --ny 20] [--grid 30] [--nu 0.28] [--points 25]\n"
    "                    [--ab 0.2,0.3,0.5,0.7,1,1.4,2,3,5] [--spin-out FILE]\n"
    "                    [--second-order-spin]\n";

void readOption(tools::Args& a, Options* o) {
  if (a.is("--out"))
    o->out = a.text();
  else if (a.is("--curves"))
    o->curves = a.text();
  else if (a.is("--spin-out"))
    o->spinOut = a.text();
  else if (a.is("--second-order-spin"))
    o->secondOrderSpin = true;
  else if (a.is("--nx"))
    o->nx = a.integer();
  else if (a.is("--ny"))
    o->ny = a.integer();
  else if (a.is("--grid"))
    o->grid = a.integer();
  else if (a.is("--points"))
    o->points = a.integer();
  else if (a.is("--nu"))
    o->nu = a.real();
  else if (a.is("--ab"))
    o->ratios = a.reals();
  else
    a.unknown();
}

int run(const Options& o) {
  const int nx = o.nx, ny = o.ny, grid = o.grid, points = o.points;
  const double nu = o.nu;
  const std::vector<double>& ratios = o.ratios;
  if (points < 2) throw std::invalid_argument("--points must be >= 2");
  std::vector<double> lambdas;
  for (int q = 0; q < points; ++q) lambdas.push_back(std::pow(100.0, q / (points - 1.0)));

  std::ofstream table = tools::writeFile(o.out), curves = tools::writeFile(o.curves);
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  table << "# NSS-FastSim dynamic flexibility F(k) = (chi2 + i k chi1) / (1 + i k chi3), k = 2 pi "
           "a / "
           "lambda; chi dimensionless.\n"
        << "# Fitted by identify_chi on " << date << " against the exact half-space solver on a "
        << grid << "x" << grid << " grid, nu = " << nu << ", FastSim mesh " << nx << "x" << ny
        << ",\n# on C^/C_steady over lambda/a in [1, 100] (" << points
        << " log-spaced points), measure d(ln lambda/a).\n"
        << "# err_log, err_linear: mean |r_exact - r_nss| in d(ln lambda/a) and d(lambda/a); "
           "err_max: max over lambda/a >= 2.\n"
        << (o.secondOrderSpin
                ? "# Kind 23: second order, F(k) = (chi2 + s chi1 + s^2 chi4) / (1 + s chi3 + s^2 "
                  "chi5), s = i k, cost err_log + 10 err_max, |F(inf)| <= 5.\n"
                  "a_over_b,kind,chi1,chi2,chi3,chi4,chi5,err_log,err_linear,err_max,"
                  "shenli_err_log\n"
                : "a_over_b,kind,chi1,chi2,chi3,err_log,err_linear,err_max,shenli_err_log\n");
  curves << "a_over_b,kind,lambda_over_a,c_real,c_imag,c_steady\n";
  std::ofstream spin;
  if (!o.spinOut.empty()) {
    spin = tools::writeFile(o.spinOut);
    spin << "# Second-order F(k) = (chi2 + s chi1 + s^2 chi4) / (1 + s chi3 + s^2 chi5), s = i k, "
            "kind 23, fitted by identify_chi on "
         << date << ",\n# exact " << grid << "x" << grid << ", FastSim " << nx << "x" << ny
         << ", cost err_log + 10 err_max, |F(inf)| <= 5. Columns as chi_table.csv.\n"
         << "a_over_b,kind,chi1,chi2,chi3,chi4,chi5,err_log,err_linear,err_max\n";
  }
  const CreepageKind kinds[3] = {CreepageKind::kXi, CreepageKind::kEta, CreepageKind::kPhi};
  const char* names[3] = {"11", "22", "23"};
  for (double ab : ratios) {
    for (int q = 0; q < 3; ++q) {
      const auto t0 = std::chrono::steady_clock::now();
      const NonSteadyCoefficients exact(kinds[q], ab, nu, grid, grid);
      const double steady = exact.steady();
      std::vector<FrequencyPoint> curve;
      for (double l : lambdas) {
        const std::complex<double> c = exact.at(l);
        curve.push_back({l, c / steady});
        char line[256];
        std::snprintf(line, sizeof line, "%g,%s,%.6g,%.9g,%.9g,%.9g\n", ab, names[q], l, c.real(),
                      c.imag(), steady);
        curves << line;
      }
      const ChiFit shenLi = evaluateChi(kinds[q], ab, nu, nx, ny, ChiParameters{}, curve);
      const bool second = kinds[q] == CreepageKind::kPhi && (spin.is_open() || o.secondOrderSpin);
      char line[256];
      if (second && o.secondOrderSpin) {  // the second-order fit below is the table's row
        line[0] = '\0';
      } else {
        const ChiFit fit = fitChi(kinds[q], ab, nu, nx, ny, curve);
        std::snprintf(line, sizeof line, "%g,%s,%.6f,%.6f,%.6f%s,%.5f,%.5f,%.5f,%.5f\n", ab,
                      names[q], fit.chi.chi1, fit.chi.chi2, fit.chi.chi3,
                      o.secondOrderSpin ? ",0,0" : "", fit.meanErrorLog, fit.meanErrorLinear,
                      fit.maxError, shenLi.meanErrorLog);
        table << line;
      }
      if (second) {
        const SecondOrderFit f2 = fitSecondOrderChi(kinds[q], ab, nu, nx, ny, curve);
        char line2[256];
        std::snprintf(line2, sizeof line2, "%g,23,%.6f,%.6f,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f\n", ab,
                      f2.chi.chi1, f2.chi.chi2, f2.chi.chi3, f2.chi.chi4, f2.chi.chi5,
                      f2.meanErrorLog, f2.meanErrorLinear, f2.maxError);
        if (spin.is_open()) spin << line2;
        std::cerr << "  second order: " << line2;
        if (o.secondOrderSpin) {
          std::snprintf(line, sizeof line, "%g,23,%.6f,%.6f,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f,%.5f\n",
                        ab, f2.chi.chi1, f2.chi.chi2, f2.chi.chi3, f2.chi.chi4, f2.chi.chi5,
                        f2.meanErrorLog, f2.meanErrorLinear, f2.maxError, shenLi.meanErrorLog);
          table << line;
        }
      }
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cerr << "a/b " << ab << " kind " << names[q] << ": " << line << "  (" << secs << " s)\n";
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("identify_chi", kUsage, argc, argv, readOption, run);
}
