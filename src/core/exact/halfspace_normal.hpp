/// Normal problem of two elastically identical half-spaces (G [Pa], nu) on a HalfspaceGrid:
/// piecewise-constant pressure [Pa] per element, undeformed gap h = A x^2 + B y^2 (A, B [1/m]),
/// prescribed total load fz [N]. Solved like Kalker's NORM: active set with a direct solve on the
/// loaded elements. Pressure vectors have size mx*my (HalfspaceGrid::index).
#pragma once

#include <Eigen/Core>

#include "core/exact/halfspace_influence.hpp"

namespace wheel_rail_contact {

/// Curvatures A (along x) and B (along y) [1/m] whose Hertz ellipse at load fz is (a, b).
void hertzCurvatures(double a, double b, double fz, double G, double nu, double* A, double* B);

struct NormalSolution {
  Eigen::VectorXd p;      ///< pressure per element [Pa], 0 outside contact
  double approach = 0.0;  ///< rigid approach of the bodies [m]
  int iterations = 0;     ///< active-set iterations
  bool converged = false;
};

/// Active set: start from the elements inside the ellipse (a_guess, b_guess); drop elements with
/// p < 0, add elements that interpenetrate; at most 50 iterations.
NormalSolution solveNormalProblem(const HalfspaceGrid& grid, double G, double nu, double A,
                                  double B, double fz, double a_guess, double b_guess);

/// The discrete Hertz problem whose continuous solution is the ellipse (a, b) at load fz.
/// Symmetric in y by construction (the mean of p and its mirror), as CONTACT's grids are.
Eigen::VectorXd hertzianGridPressure(const HalfspaceGrid& grid, double a, double b, double fz,
                                     double G, double nu);

}  // namespace wheel_rail_contact
