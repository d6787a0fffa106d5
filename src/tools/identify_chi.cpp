// identify_chi: fits the NSS-FastSim dynamic-flexibility table chi (config/chi_table.csv) against
// our exact half-space solver (doc/method.md#chi-identification). For each creepage kind and a/b of
// the grid it computes the exact C^(lambda/a) / C_steady curve, fits chi (chi_fit.hpp) at each
// FastSim mesh and writes the table, plus every exact curve for plots. Options: identify_chi
// --help.
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

#include "tool_options.hpp"
#include "validation/chi_fit.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string out = "config/chi_table.csv", curves = "doc/data/exact_curves.csv", spinOut;
  std::vector<int> meshes = {5, 10, 20, 30, 40};
  int grid = 30, points = 25;
  double nu = 0.28;
  std::vector<double> ratios = {0.2, 0.3, 0.5, 0.7, 1, 1.4, 2, 3, 5};
  bool secondOrderSpin = false;
};

void addOptions(CLI::App& app, Options* o) {
  app.description("Fits the NSS-FastSim chi table against the exact half-space solver.");
  tools::option(app, "--out", &o->out, "the chi table written");
  tools::option(app, "--curves", &o->curves, "every exact curve, for plots");
  tools::option(app, "--meshes", &o->meshes,
                "the FastSim meshes N x N to fit at (chi absorbs the march's discretisation; the "
                "table's fastsim_nx column, NssModel takes the mesh nearest its nx)");
  tools::option(app, "--grid", &o->grid, "exact grid N x N");
  tools::option(app, "--nu", &o->nu, "Poisson ratio");
  tools::option(app, "--points", &o->points, "lambda/a points in [1, 100], log-spaced");
  tools::option(app, "--ab", &o->ratios, "a/b of the table's rows");
  tools::option(app, "--spin-out", &o->spinOut,
                "also fit a second-order F to kind 23 and write it here (empty: no)");
  tools::flag(app, "--second-order-spin", &o->secondOrderSpin,
              "the second-order fit of kind 23 in the table itself (columns chi4, chi5)");
}

std::string meshList(const std::vector<int>& meshes) {
  std::string s;
  for (int n : meshes) s += (s.empty() ? "" : ", ") + std::to_string(n) + "x" + std::to_string(n);
  return s;
}

// One row: a/b, kind, chi (second order: five), the mesh, then the errors.
std::string row(double ab, const char* kind, const SecondOrderChi& c, bool fiveChi, int nx,
                double errLog, double errLinear, double errMax, const double* shenLi) {
  char line[320];
  int n =
      std::snprintf(line, sizeof line, "%g,%s,%.6f,%.6f,%.6f", ab, kind, c.chi1, c.chi2, c.chi3);
  if (fiveChi && c.chi4 == 0.0 && c.chi5 == 0.0)  // a first-order row
    n += std::snprintf(line + n, sizeof line - n, ",0,0");
  else if (fiveChi)
    n += std::snprintf(line + n, sizeof line - n, ",%.6f,%.6f", c.chi4, c.chi5);
  n +=
      std::snprintf(line + n, sizeof line - n, ",%d,%.5f,%.5f,%.5f", nx, errLog, errLinear, errMax);
  if (shenLi) std::snprintf(line + n, sizeof line - n, ",%.5f", *shenLi);
  return std::string(line) + "\n";
}

int run(const Options& o) {
  const int grid = o.grid, points = o.points;
  const double nu = o.nu;
  const std::vector<double>& ratios = o.ratios;
  if (points < 2) throw std::invalid_argument("--points must be >= 2");
  if (o.meshes.empty()) throw std::invalid_argument("--meshes: at least one mesh");
  for (int n : o.meshes)
    if (n < 2 || n > 400) throw std::invalid_argument("--meshes: each N in [2, 400]");
  std::vector<double> lambdas;
  for (int q = 0; q < points; ++q) lambdas.push_back(std::pow(100.0, q / (points - 1.0)));

  std::ofstream table = tools::writeFile(o.out), curves = tools::writeFile(o.curves);
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  table << "# NSS-FastSim dynamic flexibility F(k) = (chi2 + i k chi1) / (1 + i k chi3), k = 2 pi "
           "a / lambda; chi dimensionless.\n"
        << "# Fitted by identify_chi on " << date << " against the exact half-space solver on a "
        << grid << "x" << grid << " grid, nu = " << nu << ", FastSim meshes " << meshList(o.meshes)
        << " (column fastsim_nx;\n# NssModel interpolates in 1/nx between the meshes around its "
           "nx), on "
           "C^/C_steady over lambda/a in [1, 100] ("
        << points << " log-spaced points), measure d(ln lambda/a).\n"
        << "# err_log, err_linear: mean |r_exact - r_nss| in d(ln lambda/a) and d(lambda/a); "
           "err_max: max over lambda/a >= 2.\n"
        << (o.secondOrderSpin
                ? "# Kind 23: second order, F(k) = (chi2 + s chi1 + s^2 chi4) / (1 + s chi3 + s^2 "
                  "chi5), s = i k, cost err_log + 10 err_max, |F(inf)| <= 5.\n"
                  "a_over_b,kind,chi1,chi2,chi3,chi4,chi5,fastsim_nx,err_log,err_linear,err_max,"
                  "shenli_err_log\n"
                : "a_over_b,kind,chi1,chi2,chi3,fastsim_nx,err_log,err_linear,err_max,"
                  "shenli_err_log\n");
  curves << "a_over_b,kind,lambda_over_a,c_real,c_imag,c_steady\n";
  std::ofstream spin;
  if (!o.spinOut.empty()) {
    spin = tools::writeFile(o.spinOut);
    spin << "# Second-order F(k) = (chi2 + s chi1 + s^2 chi4) / (1 + s chi3 + s^2 chi5), s = i k, "
            "kind 23, fitted by identify_chi on "
         << date << ",\n# exact " << grid << "x" << grid << ", FastSim " << meshList(o.meshes)
         << ", cost err_log + 10 err_max, |F(inf)| <= 5. Columns as chi_table.csv.\n"
         << "a_over_b,kind,chi1,chi2,chi3,chi4,chi5,fastsim_nx,err_log,err_linear,err_max\n";
  }
  // Rows gathered per mesh (the exact curve is computed once for all meshes), written mesh by mesh.
  std::vector<std::string> tableRows(o.meshes.size()), spinRows(o.meshes.size());
  for (double ab : ratios) {
    for (const CreepageKind kind : kCreepageKinds) {
      const auto t0 = std::chrono::steady_clock::now();
      const NonSteadyCoefficients exact(kind, ab, nu, grid, grid);
      const double steady = exact.steady();
      std::vector<FrequencyPoint> curve;
      for (double l : lambdas) {
        const std::complex<double> c = exact.at(l);
        curve.push_back({l, c / steady});
        char line[256];
        std::snprintf(line, sizeof line, "%g,%s,%.6g,%.9g,%.9g,%.9g\n", ab, coefficientCode(kind),
                      l, c.real(), c.imag(), steady);
        curves << line;
      }
      const bool second = kind == CreepageKind::kPhi && (spin.is_open() || o.secondOrderSpin);
      for (std::size_t m = 0; m < o.meshes.size(); ++m) {
        const int n = o.meshes[m];
        const double shenLi = evaluateChi(kind, ab, nu, n, n, ChiParameters{}, curve).meanErrorLog;
        std::string line;
        if (!(second && o.secondOrderSpin)) {  // else the second-order fit below is the row
          const ChiFit f = fitChi(kind, ab, nu, n, n, curve);
          line = row(ab, coefficientCode(kind), SecondOrderChi::fromFirstOrder(f.chi),
                     o.secondOrderSpin, n, f.meanErrorLog, f.meanErrorLinear, f.maxError, &shenLi);
        }
        if (second) {
          const SecondOrderFit f2 = fitSecondOrderChi(kind, ab, nu, n, n, curve);
          spinRows[m] += row(ab, "23", f2.chi, true, n, f2.meanErrorLog, f2.meanErrorLinear,
                             f2.maxError, nullptr);
          if (o.secondOrderSpin)
            line = row(ab, "23", f2.chi, true, n, f2.meanErrorLog, f2.meanErrorLinear, f2.maxError,
                       &shenLi);
        }
        tableRows[m] += line;
        std::cerr << "a/b " << ab << " kind " << coefficientCode(kind) << " mesh " << n << ": "
                  << line;
      }
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cerr << "  (" << secs << " s)\n";
    }
  }
  for (std::size_t m = 0; m < o.meshes.size(); ++m) {
    const std::string title = "# FastSim mesh " + meshList({o.meshes[m]}) + "\n";
    table << title << tableRows[m];
    if (spin.is_open()) spin << title << spinRows[m];
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("identify_chi", argc, argv, addOptions, run);
}
