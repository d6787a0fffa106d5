#include "wheel_rail_contact/fastsim/patch_shape.hpp"

#include <algorithm>
#include <cmath>

namespace wheel_rail_contact {

PatchShape patchShapeOf(const NormalPatch& normal, double origin) {
  PatchShape shape;
  shape.origin = origin;
  shape.strips.reserve(normal.strips.size());
  for (const NormalStrip& s : normal.strips)
    shape.strips.push_back(PatchStrip{s.eta, s.width, s.x_lead, s.x_trail, s.pmax});
  return shape;
}

const char* checkPatchShape(const PatchShape& shape) {
  if (!std::isfinite(shape.origin)) return "shape: origin is not finite";
  if (shape.strips.empty()) return "shape: no strip";
  if (shape.strips.size() > 1024) return "shape: more than 1024 strips";
  bool loaded = false;
  for (std::size_t j = 0; j < shape.strips.size(); ++j) {
    const PatchStrip& s = shape.strips[j];
    if (!std::isfinite(s.eta) || !std::isfinite(s.width) || !std::isfinite(s.x_lead) ||
        !std::isfinite(s.x_trail) || !std::isfinite(s.pmax))
      return "shape: a strip's value is not finite";
    if (!(s.width >= kMinStripSize)) return "shape: a strip's width is below 1e-9 m";
    if (!(s.pmax >= 0.0 && s.pmax <= kMaxStripPressure))
      return "shape: a strip's pmax is negative or above 1e12 Pa";
    if (!(s.x_lead >= s.x_trail)) return "shape: a strip's leading edge lies behind its trailing";
    if (std::abs(s.x_lead + s.x_trail) >
        kStripSymmetryTolerance * std::max(s.x_lead - s.x_trail, 1e-300))
      return "shape: a strip off-centre in x (x_lead != -x_trail) is not supported";
    if (std::abs(s.eta) > 1.0 || s.width > 1.0 || s.x_lead > 1.0)
      return "shape: a strip beyond 1 m of the reference point";
    if (j > 0) {
      const PatchStrip& p = shape.strips[j - 1];
      if (s.eta - 0.5 * s.width < p.eta + 0.5 * p.width - 1e-9 * (s.width + p.width))
        return "shape: strips out of order of eta or overlapping";
    }
    loaded = loaded || inContact(s);
  }
  if (!loaded) return "shape: no strip in contact (half-length >= 1e-9 m and pmax > 0)";
  return "";
}

}  // namespace wheel_rail_contact
