/// Rolling backwards (V < 0) as rolling forwards in the mirror x -> -x (doc/conventions.md).
/// Creepages are relative velocities divided by the signed rolling speed V, so the slip equation
/// s = w - du/dx + (1/V) du/dt, w = (xi - phi y, eta + phi x), holds for either sign of V; only its
/// boundary condition moves: material enters at x = -a when V < 0. With x' = -x, u'_x = -u_x,
/// u'_y = u_y (a reflection: the spin, a z pseudo-vector, changes sign with V and so phi keeps it)
/// the same equation reads, in primed quantities, as forward rolling at V' = |V| with
///   xi' = xi, eta' = -eta, phi' = phi,   and   Fx = -Fx', Fy = Fy', Mz = -Mz',
/// tau_x(x, y) = -tau'_x(-x, y), tau_y(x, y) = tau'_y(-x, y).
/// A model marches the primed problem; its history is mirrored whenever the direction changes, so
/// the traction that stands in the material at a reversal is carried on (nothing jumps).
#pragma once

#include "core/fastsim/fastsim.hpp"
#include "core/fastsim/transient_fastsim.hpp"
#include "wheel_rail_contact/contact_model.hpp"

namespace wheel_rail_contact {

/// The forward-rolling input of the mirrored problem: V -> |V|, eta -> -eta (xi, phi, fz, dt kept).
StepInput mirroredInput(const StepInput& in);

/// The mirrored problem's forces back in the contact frame: Fx -> -Fx, Mz -> -Mz (Fy kept).
void mirrorForces(StepOutput* out);

/// Per-node arrays reflected x -> -x on `mesh`: node i of each strip swaps with node nx-1-i (the
/// centre nodes are symmetric about x = 0); the x components change sign.
void mirrorAlongX(const PatchMesh& mesh, TransientState* state);
void mirrorAlongX(const PatchMesh& mesh, TractionField* field);

/// The frame a model's history is in: the mirror while rolling backwards. face() turns a step's
/// input into the forward-rolling one, first calling `reverse` (which mirrors the model's history)
/// when the direction changes; V = 0 keeps the frame.
class RollingFrame {
 public:
  template <class Reverse>
  StepInput face(const StepInput& in, Reverse&& reverse) {
    const bool backwards = in.V < 0.0;
    if (in.V != 0.0 && backwards != mirrored_) {
      reverse();
      mirrored_ = backwards;
    }
    return inFrame(in);
  }
  /// `in` as the frame sees it, the frame kept (a side calculation at the current direction).
  StepInput inFrame(const StepInput& in) const { return mirrored_ ? mirroredInput(in) : in; }
  /// Forces of the frame back in the contact frame.
  void toContact(StepOutput* out) const {
    if (mirrored_) mirrorForces(out);
  }
  void reset() { mirrored_ = false; }

 private:
  bool mirrored_ = false;
};

}  // namespace wheel_rail_contact
