/// A non-Hertzian contact patch as the creep-force models take it (StepInput::shape): the patch's
/// strips as the normal problem gives them (normal/patch_normal.hpp), each with its own lateral
/// position, width, leading and trailing edge and pressure (doc/true_patch.md).
///
/// Coordinates: x along the rolling direction (material enters at the leading edge, +x when
/// rolling forwards), eta lateral in the contact plane from the creepages' reference point (the
/// contact candidate's point): the spin's lateral lever -phi eta and the spin moment are taken
/// about that point. Units SI: m, N, Pa.
///
/// How the FastSim models use it. Strip j of half-length L_j = (x_lead - x_trail) / 2 holds nx
/// nodes at its element centres, as Kalker's strips of an ellipse do. The traction bound on the
/// strip is the simplified theory's parabola
///   g_j(x) = k P_j (L_j^2 - x^2),   P_j = pmax_j / L_j,
/// P_j the strip's pressure amplitude (the normal problem's p = P sqrt(L^2 - x^2) along the strip,
/// whose P is common to the strips of one lump, so that g's curvature is too, as the simplified
/// theory's pressure (d - h) / L is under a gap h = x^2 / (2 R)), and k such that the mesh's
/// quadrature of g is mu fz. On Hertz's ellipse the strips are Kalker's and g is his parabolic
/// bound mu p_s (1 - x^2/a^2 - y^2/b^2), so the forces are those of the ellipse. Flexibilities and
/// the dynamic flexibility chi come from the equivalent ellipse (StepInput::a, b), Kalker's
/// coefficients at its a/b (held at the table's end beyond [0.1, 10], with a note).
#pragma once

#include <vector>

#include "wheel_rail_contact/normal/patch_normal.hpp"

namespace wheel_rail_contact {

/// One lateral strip of a patch.
struct PatchStrip {
  double eta = 0.0;      ///< lateral centre from the creepages' reference point [m]
  double width = 0.0;    ///< [m], > 0
  double x_lead = 0.0;   ///< leading edge of the contact on the strip [m]
  double x_trail = 0.0;  ///< trailing edge [m], < x_lead, or equal for a strip out of contact
  double pmax = 0.0;     ///< the strip's peak pressure [Pa] (the pressure's weight), >= 0
};

struct PatchShape {
  /// From the smallest eta to the largest, not overlapping (gaps between them allowed: a patch of
  /// two lumps).
  std::vector<PatchStrip> strips;
  /// The reference point's lateral position in a coordinate attached to the rail's profile and
  /// growing with eta (e.g. the rail profile's arc length at the contact point) [m]: the history
  /// of a patch that moves on the profile is carried at fixed origin + eta. 0 if not known.
  double origin = 0.0;
};

/// The strips of a normal solution, with the reference point at `origin` (PatchShape::origin).
PatchShape patchShapeOf(const NormalPatch& normal, double origin = 0.0);

/// Strips whose leading and trailing edges are symmetric about x = 0 within this fraction of the
/// strip's length (the normal problem's always are: the rail is straight along x).
constexpr double kStripSymmetryTolerance = 1e-9;
/// Smallest strip width, and half-length of a strip in contact [m]; largest peak pressure [Pa]:
/// beyond them no wheel-rail contact, and the bound's arithmetic would overflow.
constexpr double kMinStripSize = 1e-9;
constexpr double kMaxStripPressure = 1e12;

/// Whether a strip is in contact: half-length (x_lead - x_trail) / 2 >= kMinStripSize and
/// pmax > 0. The models leave the others out.
inline bool inContact(const PatchStrip& s) {
  return 0.5 * (s.x_lead - s.x_trail) >= kMinStripSize && s.pmax > 0.0;
}

/// "" if `shape` is one the models take: finite values, strips in order of eta without overlap
/// (beyond 1e-9 of a width), widths in [kMinStripSize, 1] m, pmax in [0, kMaxStripPressure],
/// x_lead >= x_trail, edges symmetric about x = 0 (kStripSymmetryTolerance: an off-centre strip is
/// not supported), |eta| and x_lead at most 1 m, at most 1024 strips, at least one strip in
/// contact. Else why (static text).
const char* checkPatchShape(const PatchShape& shape);

}  // namespace wheel_rail_contact
