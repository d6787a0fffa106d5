// A Hertzian ellipse as the true-patch models and the exact solver take it: its strips (a
// PatchShape) and its pressure moved sideways on a half-space grid. Shared by the true-patch
// tests and src/tools/true_patch_accuracy.cpp so both check the same patch.
#pragma once

#include <Eigen/Dense>

#include "core/exact/halfspace_solver.hpp"
#include "wheel_rail_contact/fastsim/patch_shape.hpp"

namespace wheel_rail_contact {

/// The ellipse of semi-axes a (rolling) and b (lateral) carrying fz as `ny` equal strips across
/// y in [-b, b]: strip j at y_j = b yn_j, yn_j = -1 + (2 j + 1)/ny, edges +-a sqrt(1 - yn_j^2),
/// pressure weight p0 sqrt(1 - yn_j^2), p0 = 3 fz / (2 pi a b); `origin` as PatchShape::origin.
PatchShape ellipseStrips(double a, double b, double fz, int ny, double origin = 0.0);

/// The grid for the ellipse (a, b) moved `travel` sideways: mx square elements over 2.2 a
/// along x, across 2.2 b + travel (rounded up) along y.
HalfspaceGrid ellipseSlideGrid(double a, double b, double travel, int mx = 24);

/// The Hertzian pressure p0 sqrt(1 - (x/a)^2 - ((y - s)/b)^2) of the ellipse moved `s`
/// sideways, at the centres of `g`'s elements, scaled so that its sum over the grid is fz.
Eigen::VectorXd movedEllipsePressure(const HalfspaceGrid& g, double a, double b, double fz,
                                     double s);

}  // namespace wheel_rail_contact
