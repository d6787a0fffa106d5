/// Contact table: the contact search tabulated once for a profile pair and wheelset data, then
/// interpolated per lookup, as multibody codes do. `ContactTable::search` gives what
/// `ContactSearch::search` gives (the same candidates, zones, gaps, gap functions, points, lead,
/// normals, file coordinates), to within the table's interpolation error, so a caller swaps one
/// for the other.
///
/// Axes of the table, per wheel. A wheel's contact depends on its position and orientation
/// relative to its rail only. Of the wheel's pose, the table removes exactly what is a
/// translation and tabulates the rest:
///  - Y: the lateral displacement of the wheel's bottom point B, the point nominal_radius below
///    the axle, gauge / 2 from the wheelset's centre (its y in the track minus its y at the zero
///    pose). With R = Rz(yaw) Rx(roll) and a0 = -+gauge / 2 (right -, left +),
///    Y = y + a0 (cos(yaw) cos(roll) - 1) + nominal_radius sin(roll) cos(yaw).
///    Roll about the wheelset's centre moves B sideways by nominal_radius sin(roll) (4.6 mm at
///    10 mrad): that part of roll is a translation and lies in Y;
///  - yaw^2: the contact's y-z geometry is even in yaw (a mirror in the track's y-z plane turns
///    yaw into -yaw) and `lead` odd, so the table holds lead / yaw and everything is interpolated
///    in yaw^2, on nodes evenly spaced in yaw^2 (0, 17.3, 24.5 and 30 mrad by default),
///    quadratically on the three nodes around the nearest (the flange's geometry curves in
///    yaw^2), linearly in the other axes;
///  - roll, which also tilts the wheel relative to its rail about B: that tilt moves the contact
///    along the profiles (on the benchmark's tread 2.5 mrad as far as 0.2 to 0.5 mm of Y), so it
///    is an axis of its own;
///  - the vertical position Z of B (Z = z + a0 sin(roll) + nominal_radius (1 - cos(roll))) is not
///    an axis: it shifts the vertical gap as a whole (exactly) and changes the gap and the gap
///    function, which the table holds at two heights per node (touching, and overlapping by
///    max_overlap) and interpolates linearly, each node at the candidate's vertical gap (so
///    that the nodes' candidates overlap alike).
///
/// Rule where the candidates differ between the nodes around a pose. The candidate set is that of
/// the nearest node, and each tread candidate of another node of the pose's cell (of non-zero
/// weight) that the nearest node lacks, in the search's order: near a centred tread two tread
/// candidates lie across a ridge so low that one node's search sees it and the next node's no
/// longer does, and the normal problem needs both to merge their patches across it. Each candidate
/// is the same one at another node if that node has a candidate within match_distance of it on both
/// profiles (s_wheel and s_rail). Where all twelve nodes of the quadratic stencil have it, it is
/// interpolated on them; else among the eight nodes of the pose's cell that have it, their (linear)
/// weights renormalised, except for a tread candidate that only one node of a pair of the cell's
/// nodes differing in Y alone has: the pair's share is then extrapolated linearly in Y from that
/// node and the next node beyond it (Lagrange weights 1 + f and -f, f <= 1 the pose's fraction of
/// the step from that node), or is that node's where the next one lacks it too. Up to where the
/// ridge vanishes a tread candidate's vertical gap, place and gap function move smoothly with Y, so
/// the extrapolation keeps its height above its neighbour, which sets the load split, to a fraction
/// of a micrometre where one node's value is a lateral step off (some 4 um). The zone follows from
/// the interpolated contact angle and the closest candidate from the interpolated vertical gaps, as
/// the search does. At a jump (tread to gauge corner to flange) the table therefore takes the
/// candidate set of the node nearer the pose, which is the direct search's on that node's side.
///
/// Poses beyond the table: see ContactTableOptions::beyond.
#pragma once

#include <memory>

#include "wheel_rail_contact/profiles/contact_search.hpp"

namespace wheel_rail_contact {

struct ContactTableOptions {
  /// The wheel's lateral displacement Y (see above) is tabulated over [-max_abs_lateral,
  /// max_abs_lateral] every lateral_step [m].
  double max_abs_lateral = 0.02;
  double lateral_step = 2.0e-4;
  /// |yaw| over [0, max_abs_yaw] [rad], on round(max_abs_yaw / yaw_step) + 1 nodes evenly spaced
  /// in yaw^2.
  double max_abs_yaw = 0.03;
  double yaw_step = 0.01;
  double max_abs_roll = 0.015;  ///< roll over [-max_abs_roll, max_abs_roll] every roll_step [rad]
  double roll_step = 2.5e-3;
  /// The gap and gap function are tabulated at the node's touching height and max_overlap lower
  /// [m]; between and near the two they are interpolated linearly in the height. The gap
  /// function (its gap, and the wheel's circle radius and contact angle at each sample) reaches
  /// max_overlap beyond where the search's would reach for an overlap up to max_overlap
  /// (ContactSearchOptions::gap_reach, gap_window), and no farther than its max_gap_extent.
  double max_overlap = 1.0e-4;
  int gap_samples = 101;  ///< samples of each tabulated gap function
  /// Two candidates of neighbouring nodes are the same one when both their s_wheel and their
  /// s_rail differ by less than this [m].
  double match_distance = 3.0e-3;
  /// A pose beyond the table's ranges, or in a cell next to a node where the search found no
  /// contact (a wheel beyond its rail): kSearch answers it with the direct search (exact, at the
  /// search's cost); kRefuse returns status kOutOfRange with a message naming the table's range.
  enum class Beyond { kSearch, kRefuse };
  Beyond beyond = Beyond::kSearch;
};

class ContactTable {
 public:
  /// Tabulates `search` (copied) over the options' ranges: one to three direct searches per node
  /// and wheel (the left wheel shares the right one's table when its profiles are the right ones
  /// mirrored). Throws std::invalid_argument naming the option if one is out of range.
  explicit ContactTable(const ContactSearch& search, const ContactTableOptions& options = {});

  /// What ContactSearch::search gives for this wheel and pose, interpolated. Never throws; a pose
  /// the search refuses gives the search's status and message.
  WheelContactGeometry search(WheelSide side, const WheelsetPose& pose) const;

  /// The geometry at first touch, in one lookup: what `search` gives at `*pose` when its closest
  /// candidate's vertical gap g is within touch_tolerance [m] of zero, else what it gives at the
  /// pose lowered by g (pose->z -= g, which this sets: a height moves every candidate's vertical
  /// gap alike, so the closest one then touches). Poses the table answers with the direct search
  /// get the two direct searches.
  WheelContactGeometry searchAtTouch(WheelSide side, WheelsetPose* pose,
                                     double touch_tolerance) const;

  const ContactSearch& contactSearch() const;
  const ContactTableOptions& options() const { return options_; }
  /// Nodes per wheel table, tables held (1 when the left wheel mirrors the right), and the bytes
  /// they take.
  std::size_t nodes() const;
  int tables() const;
  std::size_t bytes() const;

  ContactTable(const ContactTable&);
  ContactTable& operator=(const ContactTable&);
  ContactTable(ContactTable&&) noexcept;
  ContactTable& operator=(ContactTable&&) noexcept;
  ~ContactTable();

 private:
  WheelContactGeometry lookup(WheelSide side, const WheelsetPose& pose, WheelsetPose* touch_pose,
                              double touch_tolerance) const;
  struct Impl;
  ContactTableOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wheel_rail_contact
