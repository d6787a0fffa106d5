/// Strip mesh of a contact patch, Kalker's FastSim layout, reused by every FastSim model: an
/// ellipse's, or a non-Hertzian patch's own strips (setStrips).
/// Units: lengths m, areas m^2. Coordinates: x rolling (material enters at x = +a), y lateral.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "wheel_rail_contact/fastsim/patch_shape.hpp"

namespace wheel_rail_contact {

/// How a mesh on a patch's strips (PatchMesh::setStrips) weights the parabola of each strip, the
/// traction bound's shape c_j (L_j^2 - x^2): kCommonCurvature, c_j = P_j the strip's pressure
/// amplitude pmax_j / L_j (the simplified theory's: one curvature per lump, Kalker's parabola on
/// an ellipse); kStripForce, c_j = P_j / L_j, each strip's bound carrying mu times the strip's own
/// normal force (pi/2 P_j L_j^2 w_j) in proportion (a comparison, doc/true_patch.md).
enum class StripBound { kCommonCurvature, kStripForce };

/// ny strips of equal width 2b/ny across y in [-b, b] (an ellipse), or the strips of a patch's
/// PatchShape (setStrips). Strip j (centre y_j) spans
/// |x| <= a_j = a sqrt(1 - y_j^2/b^2) and holds nx elements of length dx_j = 2 a_j / nx, with one
/// node at each element centre: x_ij = a_j - (i + 1/2) dx_j, i = 0 at the leading edge. Centre
/// nodes make the midpoint rule exact for the linear adhesion traction, so small creepage
/// reproduces linear theory. The mesh is stored in normalised coordinates (x/a, y/b), so one mesh
/// serves every patch size: scale() changes a and b only.
class PatchMesh {
 public:
  PatchMesh() = default;
  /// Throws std::invalid_argument if nx < 2, ny < 1, a <= 0 or b <= 0.
  PatchMesh(int nx, int ny, double a, double b);
  /// The strips of `shape` (checkPatchShape fine) with nx nodes each, normalised by (a, b) > 0 (the
  /// equivalent ellipse's semi-axes): strip j at y_j = eta, of width w and half-length
  /// a_j = (x_lead - x_trail) / 2, its nodes at x_ij = a_j - (i + 1/2) dx_j as on an ellipse.
  /// Strips not in contact (inContact: shorter than 1e-9 m or without pressure) are left out. The
  /// pressure shape is c_j (a_j^2 - x^2) / a^2 per `bound`, c_j scaled to at most 1; on Hertz's
  /// ellipse (Kalker's strips) it is the ellipse's 1 - x^2/a^2 - y^2/b^2. Reuses the storage of a
  /// mesh with as many nodes. Throws std::invalid_argument if nx < 2, a or b <= 0 or no strip is
  /// left.
  void setStrips(int nx, const PatchShape& shape, double a, double b,
                 StripBound bound = StripBound::kCommonCurvature);
  /// Whether the mesh holds a patch's strips (setStrips) rather than an ellipse's.
  bool onStrips() const { return onStrips_; }

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int size() const { return nx_ * ny_; }
  int index(int i, int j) const { return j * nx_ + i; }
  double a() const { return a_; }
  double b() const { return b_; }
  /// Re-size the patch to semi-axes (a, b) keeping the normalised layout.
  void scale(double a, double b);

  /// The k-th strip from the centre out, k in [0, ny): the centre strip (or the two beside y = 0)
  /// first, then the strips on either side of them, alternately. Strips j and ny - 1 - j are as
  /// long, and strips next to each other about as long: the marches that take four at a time take
  /// them in this order.
  int centreOutStrip(int k) const {
    const int half = ny_ / 2;
    if (ny_ % 2 == 0) return k % 2 == 0 ? half - 1 - k / 2 : half + k / 2;
    return k == 0 ? half : (k % 2 == 1 ? half - (k + 1) / 2 : half + k / 2);
  }
  double stripWidth(int j) const { return b_ * widthNorm_(j); }            ///< dy_j [m]
  double stripY(int j) const { return b_ * yNorm_(j); }                    ///< y_j [m]
  double stripHalfLength(int j) const { return a_ * halfNorm_(j); }        ///< a_j [m]
  double stripStep(int j) const { return 2.0 * a_ * halfNorm_(j) / nx_; }  ///< dx_j [m]
  double nodeX(int i, int j) const { return a_ * xNorm(i, j); }            ///< x_ij [m]
  /// Normalised node coordinate x_ij / a.
  double xNorm(int i, int j) const { return xNorm_(index(i, j)); }
  double yNorm(int j) const { return yNorm_(j); }        ///< y_j / b
  double halfNorm(int j) const { return halfNorm_(j); }  ///< a_j / a
  /// All x_ij / a, indexed by index(i, j).
  const Eigen::ArrayXd& xNorms() const { return xNorm_; }
  /// 1 - x^2/a^2 - y^2/b^2 at every node (>= 0; on strips c_j (a_j^2 - x^2) / a^2), and its
  /// quadrature on the unit mesh sum(shape * dx_j dy_j) / (a b): the parabolic pressure of a patch
  /// that fills the mesh.
  const Eigen::ArrayXd& pressureShape() const { return shape_; }
  double shapeIntegral() const { return shapeIntegral_; }
  /// Sum over nodes of a_j / a times the shape, and times its square (flattenedBound's node sums;
  /// on strips each strip also times its width over the ellipse's, dy_j ny / (2 b)).
  double shapeSum() const { return shapeSums_[0]; }
  double shapeSquareSum() const { return shapeSums_[1]; }
  /// 1 / shapeIntegral() and shapeSquareSum() / shapeSum(), kept so that flattenedBound's step
  /// where the patch fills the mesh needs one division, not four.
  double inverseShapeIntegral() const { return inverseShapeIntegral_; }
  /// On strips: the largest c_j a_j^2 / a^2, the shape's peak (its value at a strip's centre).
  double shapePeak() const { return shapePeak_; }
  double shapeSquareRatio() const { return shapeSquareRatio_; }
  /// Over the interior nodes of a strip whose first loaded node is `first` (StripEntry, < nx):
  /// u = L - 2, L - 4, ..., 2 - L, L = nx - 1 - 2 first, u = nx - 1 - 2i the node's distance from
  /// the strip's centre in half elements: their count, Sum u^2 and Sum u^4 (flattenedBound's node
  /// sums in closed form).
  struct InteriorMoments {
    double count = 0.0, u2 = 0.0, u4 = 0.0;
  };
  const InteriorMoments& interiorMoments(int first) const { return interior_[first]; }
  /// Area a node stands for, dx_j * dy [m^2] (midpoint rule).
  double nodeArea(int j) const { return stripStep(j) * stripWidth(j); }

 private:
  int nx_ = 0;
  int ny_ = 0;
  double a_ = 0.0;
  double b_ = 0.0;
  Eigen::ArrayXd yNorm_;      ///< y_j / b, size ny
  Eigen::ArrayXd halfNorm_;   ///< a_j / a, size ny
  Eigen::ArrayXd widthNorm_;  ///< dy_j / b, size ny
  bool onStrips_ = false;
  /// The node positions, shape and its sums from yNorm_, halfNorm_, widthNorm_ and the strips'
  /// shape factors c_j (empty: 1 - yNorm_^2 - xNorm^2, the ellipse's).
  void layOut(const std::vector<double>& shapeFactor);
  Eigen::ArrayXd xNorm_;  ///< x_ij / a, size nx*ny
  Eigen::ArrayXd shape_;  ///< 1 - (x/a)^2 - (y/b)^2, size nx*ny
  double shapeIntegral_ = 0.0;
  double shapeSums_[2] = {0.0, 0.0};
  double inverseShapeIntegral_ = 0.0, shapeSquareRatio_ = 0.0, shapePeak_ = 1.0;
  std::vector<InteriorMoments> interior_;  ///< by first loaded node, size nx
};

/// The march's step onto node i of a strip with element length dx and half-length aj [m]: from
/// the leading edge (half an element) for i = 0, else from the upstream node; or of a given
/// length h (from a patch edge inside the mesh). xMid is the step's midpoint, where a term linear
/// in x (spin) integrates exactly over the step.
struct UpstreamStep {
  double h, xMid;
  UpstreamStep(int i, double dx, double aj, double length)
      : h(length), xMid(aj - (i + 0.5) * dx + 0.5 * length) {}
  UpstreamStep(int i, double dx, double aj) : UpstreamStep(i, dx, aj, i == 0 ? 0.5 * dx : dx) {}
};

}  // namespace wheel_rail_contact
