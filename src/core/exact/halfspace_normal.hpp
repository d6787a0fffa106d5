/// Normal problem of two elastically identical half-spaces (G [Pa], nu) on a HalfspaceGrid:
/// piecewise-constant pressure [Pa] per element, an undeformed gap h given per element (or
/// the Hertz gap h = A x^2 + B y^2, A, B [1/m]), a prescribed total load fz [N] or a prescribed
/// rigid approach [m]. Solved like Kalker's NORM: active set with a direct solve on the loaded
/// elements, where the deformed gap h + u - approach vanishes; elsewhere it is >= 0 and p = 0.
/// Pressure and gap vectors have size mx*my (HalfspaceGrid::index).
#pragma once

#include <Eigen/Core>

#include "core/exact/halfspace_influence.hpp"

namespace wheel_rail_contact {

/// Curvatures A (along x) and B (along y) [1/m] whose Hertz ellipse at load fz is (a, b).
void hertzCurvatures(double a, double b, double fz, double G, double nu, double* A, double* B);

struct NormalSolution {
  Eigen::VectorXd p;      ///< pressure per element [Pa], 0 outside contact
  double approach = 0.0;  ///< rigid approach of the bodies [m]
  double fz = 0.0;        ///< total load sum p dx dy [N]
  int iterations = 0;     ///< active-set iterations
  bool converged = false;
};

/// Active set: start from the elements inside the ellipse (a_guess, b_guess); drop elements with
/// p < 0, add elements that interpenetrate; at most 50 iterations.
NormalSolution solveNormalProblem(const HalfspaceGrid& grid, double G, double nu, double A,
                                  double B, double fz, double a_guess, double b_guess);

/// Any undeformed gap h [m] per element (size mx*my), prescribed total load fz > 0 [N]. The
/// active set starts from the elements of least gap, a quarter of the gap's range above its
/// minimum.
NormalSolution solveNormalGapLoad(const HalfspaceGrid& grid, double G, double nu,
                                  const Eigen::VectorXd& h, double fz);

/// Any undeformed gap h [m] per element, prescribed rigid approach [m]: contact where the bodies
/// would interpenetrate, h < approach, is where the active set starts. An approach at or below
/// min(h) gives p = 0, fz = 0, converged.
NormalSolution solveNormalGapApproach(const HalfspaceGrid& grid, double G, double nu,
                                      const Eigen::VectorXd& h, double approach);

/// The discrete Hertz problem whose continuous solution is the ellipse (a, b) at load fz.
/// Symmetric in y by construction (the mean of p and its mirror), as CONTACT's grids are.
Eigen::VectorXd hertzianGridPressure(const HalfspaceGrid& grid, double a, double b, double fz,
                                     double G, double nu);

}  // namespace wheel_rail_contact
