/// The non-steady FastSim step (paper eqs. 12-14): FastSim with the time term of the slip equation
/// s = w - du/dx + (1/V) du/dt kept, the time term passed through the dynamic-flexibility filter
/// (nss_filter.hpp). With F == 1 this is Shen & Li (1996).
/// Units: tractions Pa, filter states Pa/s, V m/s, dt s; shapes: every array has mesh.size()
/// entries indexed by PatchMesh::index(i, j).
#pragma once

#include <Eigen/Core>

#include "wheel_rail_contact/fastsim.hpp"
#include "wheel_rail_contact/nss_filter.hpp"

namespace wheel_rail_contact {

/// Traction history at fixed contact coordinates: what one step leaves for the next.
struct TransientState {
  Eigen::ArrayXd tx, ty;  ///< traction at the previous step [Pa]
  Eigen::ArrayXd sx, sy;  ///< filter state (transposed direct form II) [Pa/s]
  void resize(int n);
  void clear();
};

/// One step of length dt > 0 at speed V > 0. Marches each strip from the leading edge solving the
/// discretised slip equation with s = 0 for the adhesion guess, saturates at field->bound, then
/// updates `state` from the saturated traction. field->bound must be filled (parabolicBound).
CreepForces transientFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                             double V, double dt, const FilterZ& zx, const FilterZ& zy,
                             TransientState* state, TractionField* field);

/// A step of dt = 0: no time has passed, so the traction history stands, except that it is
/// saturated at field->bound (filled for the current load): a load that fell since must not leave
/// traction above mu p. Writes the field (saturated nodes marked slipping, the rest keep their
/// flag) and the saturated traction back to `state`; returns the integrated forces.
CreepForces holdTraction(const PatchMesh& mesh, TransientState* state, TractionField* field);

/// Paper eq. 19: carry the history from the patch (from.a(), from.b()) to the patch
/// (to.a(), to.b()) of the same normalised layout by bilinear interpolation at fixed physical
/// coordinates (linear along each strip, then across strips); traction falls to zero at the old
/// patch's edge and is zero outside it.
void remapState(const PatchMesh& from, const TransientState& in, const PatchMesh& to,
                TransientState* out);

}  // namespace wheel_rail_contact
