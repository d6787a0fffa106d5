#include "core/models/rolling_direction.hpp"

#include <cmath>

namespace wheel_rail_contact {

StepInput mirroredInput(const StepInput& in) {
  StepInput m = in;
  m.V = std::abs(in.V);
  m.eta = -in.eta;
  return m;
}

void mirrorForces(StepOutput* out) {
  out->fx = -out->fx;
  out->mz = -out->mz;
}

namespace {

// Reverses each strip of one per-node array (x -> -x) and scales it by `sign`.
template <typename Array>
void reverseStrips(const PatchMesh& mesh, Array&& v, double sign) {
  for (int j = 0; j < mesh.ny(); ++j) {
    auto strip = v.segment(mesh.index(0, j), mesh.nx());
    strip.reverseInPlace();
    if (sign < 0.0) strip = -strip;
  }
}

}  // namespace

void mirrorAlongX(const PatchMesh& mesh, TransientState* s) {
  reverseStrips(mesh, s->tx(), -1.0);
  reverseStrips(mesh, s->sx(), -1.0);
  reverseStrips(mesh, s->ty(), 1.0);
  reverseStrips(mesh, s->sy(), 1.0);
  reverseStrips(mesh, s->s2x(), -1.0);
  reverseStrips(mesh, s->s2y(), 1.0);
}

void mirrorAlongX(const PatchMesh& mesh, TractionField* f) {
  reverseStrips(mesh, f->tx, -1.0);
  reverseStrips(mesh, f->ty, 1.0);
  reverseStrips(mesh, f->bound, 1.0);
  for (int j = 0; j < mesh.ny(); ++j) f->slip.segment(mesh.index(0, j), mesh.nx()).reverseInPlace();
}

}  // namespace wheel_rail_contact
