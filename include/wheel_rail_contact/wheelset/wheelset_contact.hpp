/// A wheelset on its track: give it the wheelset's state, get every contact patch of each wheel
/// with its geometry, normal solution, creepages and tangential forces. The one entry point that
/// ties the contact search (or a contact table), the normal problem per patch, the creepages and a
/// creep-force model together (doc/wheelset.md).
///
/// Axes: REP 103 track axes (x forward, y left, z up), as wheelset_track.hpp. Each patch's forces
/// are in its own contact frame (doc/conventions.md: z the contact normal from the rail into the
/// wheel, x forward in the contact plane, y = z x x), acting on the wheel; PatchResult::wrench and
/// WheelResult::wrench give them in track axes about the wheel's centre (TrackWrench). Units SI.
///
/// Per step, for each wheel:
///   1. the contact candidates for the pose at first touch (ContactSearch::search, or
///      ContactTable::search; pose.z is not used: the wheel is searched at the height where its
///      closest candidate touches, one more search when z = 0 is more than 10 um from it);
///   2. the wheel's vertical load shared among them (solveWheelLoad: the approach at which the
///      patches' normal forces' vertical components add up to the load, or with
///      WheelsetContactOptions::whole_force_balance their whole forces'); a patch is a candidate
///      with fn > 0. With a table, a wheel whose normal problem fails on the table's geometry is
///      searched again directly (at the search's cost) and takes that geometry when its normal
///      problem succeeds (counted: directSearchFallbacks). The table keeps a tread candidate
///      across a low ridge that its nearest node lacks (contact_table.hpp), so near a centred
///      tread, where that happened, it no longer does;
///   3. each patch's creepages xi, eta, phi from the wheelset's motion (patchCreepages);
///   4. its tangential forces from the creep-force model of ContactParameters::model (unless
///      WheelsetContactOptions::tangential is false) with its fn and creepages: on the true patch
///      (StepInput::shape, the normal problem's strips, fastsim/patch_shape.hpp) where the patch
///      is non-Hertzian (NormalPatch::method kNonHertzian) or blended (strip_weight > 0), or
///      its a/b lies beyond Kalker's table [0.1, 10] (a flange's, 17 to 23: its strips are then
///      Kalker's strips of the ellipse, the coefficients held at the table's end); on the
///      ellipse (a, b) otherwise, as the normal problem chose (no more model than the patch
///      needs). The strips' eta runs toward the track centre, the contact frame's y is the same on
///      both wheels: the left wheel's strips are mirrored. The exact model solves every patch on
///      its ellipse and refuses an a/b beyond the table (doc/true_patch.md). Model auto, given the
///      strips, runs them only where the equivalent ellipse (placed at the strips' centre) is
///      predicted to miss its tolerance, the ellipse otherwise (doc/performance.md#model-auto).
///
/// History: one model instance per patch slot, a slot being (wheel, zone, rank among that wheel's
/// patches of the same zone counted from the field side). A slot whose patch is present is stepped
/// with the step's dt; a slot whose patch is absent is reset (its model dropped), so a patch that
/// appears starts from rest (zero traction history) on a new model, stepped with the step's dt as
/// a model's first step is (the FastSim models roll dt from rest; exact's first step rolls
/// nothing). nss thereby carries its transient across steps while a patch stays in its zone. On
/// the true patch its history is carried from step to step at fixed physical coordinates, x along
/// the rolling direction and laterally in a frame that follows half the contact point's move on
/// the rail profile (its arc length, PatchShape::origin; the half measured against exact theory,
/// doc/true_patch.md): a patch that changes shape or moves keeps the traction of the material
/// still in contact, zero where it newly reaches; one that moves clear of where it was starts
/// from rest, with a message (status kOk). A patch that jumps to another zone (tread to gauge
/// corner to flange) is another slot's: it starts from rest, the old slot's history dropped.
///
/// The model's reference patch (ContactParameters a0, b0, fz0, fz_max) is not used: a and b come
/// from the normal problem every step, and a slot's model is made when its patch appears with the
/// reference patch set to that patch's a, b, fn and fz_max 0, so that a fixed mesh covers the patch
/// up to 1.5 times its first load. A FastSim model grows its mesh beyond that with a note
/// (doc/varying_geometry.md); the exact model, whose grid is fixed, is restarted from rest on a
/// grid for the patch when the patch's a or b outgrows it, with a note (PatchResult::message).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/contact_parameters.hpp"
#include "wheel_rail_contact/normal/patch_normal.hpp"
#include "wheel_rail_contact/profiles/contact_search.hpp"
#include "wheel_rail_contact/profiles/contact_table.hpp"
#include "wheel_rail_contact/profiles/wheelset_track.hpp"
#include "wheel_rail_contact/wheelset/creepages.hpp"

namespace wheel_rail_contact {

/// The wheelset's state at one step, in the track frame under the wheelset (REP 103 axes of the
/// rails' plane, turned by the step's cant, motion.cant).
///
/// The loads are along the track's z, normal to the rails' plane (the patches' normal forces'
/// components along it add up to the load, step 2 above), so the cant does not change what a
/// load does; a simulator whose loads are along gravity gives their components along the track's
/// z. The cant enters only the creepages in a curve (WheelsetMotion::cant).
struct WheelsetState {
  WheelsetPose pose;      ///< y, yaw, roll; z is not used (each wheel's load sets its approach)
  WheelsetMotion motion;  ///< V, omega, vy, yaw_rate, curvature, cant, vz, roll_rate
  double fz_left = 0.0;   ///< load on the left wheel along the track's z [N], > 0 for contact
  double fz_right = 0.0;  ///< load on the right wheel along the track's z [N]
};

struct WheelsetContactOptions {
  /// Search through a ContactTable built once at construction (faster, interpolated; see
  /// contact_table.hpp for its error) instead of the direct ContactSearch.
  bool use_contact_table = false;
  ContactSearchOptions search;
  ContactTableOptions table;  ///< with use_contact_table
  /// A contact table built once and shared by every wheelset on the same profiles and track data
  /// (a vehicle's), instead of one built per object: used when set, whatever use_contact_table
  /// says; its own search options apply. It must tabulate this object's track data (the same
  /// values and profiles), else the constructor throws std::invalid_argument("contact_table: ...").
  std::shared_ptr<const ContactTable> contact_table;
  /// normal.start_beyond_touch and start_exponent are set per wheel when warm_start is on.
  NormalOptions normal;
  /// Start each wheel's load iteration (solveWheelLoad) from its previous step's solution (the
  /// approach beyond first touch and the load's exponent there) when the wheel's candidates are
  /// of the same zones in the same order as then; else, and after a step that cleared the wheel's
  /// history (no load, no contact, no normal solution, reset()), cold. Only the cost depends on
  /// it: the patches are the same within the iteration's load tolerance.
  bool warm_start = true;
  /// false: each patch's geometry, normal solution and creepages only; no tangential model is
  /// run (fx = fs = mz = 0, the slots keep no history) and every patch says so in its message.
  bool tangential = true;
  /// The wheel's vertical load carried by the vertical components of the patches' whole contact
  /// forces, normal and tangential (sum_i fn_i n_z,i - fs_i n_y,i = load, as multibody codes and
  /// CONTACT balance it), instead of the normal forces' alone (sum_i fn_i n_z,i = load). The
  /// tangential forces depend on fn, and a model's step cannot be repeated within a step, so the
  /// balance takes each patch slot's fs / fn from the slot's previous step (lagged one step; a
  /// patch new this step, or one whose model gave no force, 0), bounded by mu (Coulomb: a traction
  /// ratio beyond mu is impossible), as solveWheelLoad's tangential_vertical term
  /// t = -(fs / fn) n_y. A simulator stepping at a small dt sees the lag as a step's delay on a
  /// slowly changing ratio; a steady evaluation at one state repeats the step (settle()). Where the
  /// term leaves the load no balance (a patch whose whole force has no upward component, n_z + t
  /// <= 0: on a flange of tan(delta) >= 1 / mu in full slip), or the normal problem fails with it,
  /// the normal forces alone carry the load that step and the wheel's message says so (status
  /// kOk). Needs `tangential`.
  /// Off by default: it moves fn by about |fs| tan(delta) (on the benchmark's 1.4 to 3.4 %
  /// on the tread, 9 to 11 % on the gauge corner), it makes a step's patches depend on the
  /// previous step's forces, and where it matters most, the flange, the elliptic-patch models
  /// refuse the patch (a/b beyond Kalker's table: no tangential force, so no term) until they run
  /// on the true patch (doc/wheelset.md).
  bool whole_force_balance = false;
};

enum class WheelStatus {
  kOk,            ///< one or more patches
  kNoLoad,        ///< vertical load <= 0: zero forces, the wheel's history cleared
  kNoContact,     ///< no contact candidate (the wheel is not above its rail): zero forces
  kInvalidInput,  ///< a state value not finite, dt < 0, or the pose beyond the search's range
  kNormalFailed,  ///< the normal problem gave no solution for the load (its status's message)
};
/// "ok", "no_load", "no_contact", "invalid_input", "normal_failed": the CLI's status column.
const char* toString(WheelStatus s);

/// A force on the wheel in track axes (REP 103: x forward, y left, z up) [N] and its moment about
/// the wheel's centre (WheelResult::centre) [N m].
///
/// For one patch, with n = (0, n_y, n_z) its contact normal (ContactCandidate::normal, rail into
/// wheel), e_x the track's x and e_y = n x e_x = (0, n_z, -n_y) its contact frame's axes (the same
/// on both wheels), p its contact point (ContactCandidate::point, on the rail) and c the wheel's
/// centre:
///   F = fx e_x + fs e_y + fn n,   M = (p - c) x F + mz n.
/// So fz = fn n_z - fs n_y: with n_y = sin(delta) on the right wheel and -sin(delta) on the left
/// (delta the contact angle), fz = fn cos(delta) - fs sin(delta) on the right wheel and
/// fn cos(delta) + fs sin(delta) on the left; on a flange the second term is large. The normal
/// force alone has no moment about the axle (a wheel's normals cross its axle), so M's component
/// along the axle comes from the tangential forces alone (the traction or braking torque).
struct TrackWrench {
  double fx = 0, fy = 0, fz = 0, mx = 0, my = 0, mz = 0;
};

/// One contact patch of a wheel.
struct PatchResult {
  ContactZone zone = ContactZone::kTread;
  /// The patch's slot name: its zone ("tread", "gauge_corner", "flange"), with "_2", "_3" for a
  /// second and third patch of the same zone on the wheel, counted from the field side.
  std::string slot;
  /// The candidate from the search: contact point (on both profiles in their files' coordinates:
  /// rail_file, wheel_file), contact angle, rolling radius, gap function.
  ContactCandidate geometry;
  PatchCreepages creepages;  ///< xi [-], eta [-], phi [1/m] in the patch's contact frame
  NormalPatch normal;        ///< fn [N], a, b [m], pmax [Pa], method, strips
  /// Tangential forces on the wheel in the patch's contact frame, from the model on the true patch
  /// or its ellipse (step 4 above): fx along the rolling direction, fs lateral in the contact
  /// plane [N], mz the spin moment about the normal through the candidate's contact point [N m].
  double fx = 0.0, fs = 0.0, mz = 0.0;
  StepStatus tangential_status = StepStatus::kOk;  ///< the model's step status
  std::string message;                             ///< the model's message or note, "" if none
  /// fn, fx, fs and mz in track axes about the wheel's centre (TrackWrench): the whole force the
  /// rail exerts on the wheel at this patch.
  TrackWrench wrench;
};

struct WheelResult {
  WheelSide side = WheelSide::kRight;
  WheelStatus status = WheelStatus::kOk;
  std::string message;
  std::vector<PatchResult> patches;  ///< in contact (fn > 0), from the field side to the flange
  /// The sum of the patches' wrenches: the rail's whole force on the wheel, track axes, and its
  /// moment about `centre`. Zero for a wheel with no patch (any status but kOk).
  TrackWrench wrench;
  /// The wheel's centre [m], track axes: the point of the axle in the plane of the wheel
  /// profile's nominal rolling circle (the profile file's lateral origin, where its radius is
  /// nominal_radius; the benchmark's S1002: its taping line, flange_back_distance / 2 + 70 mm
  /// from the wheelset's centre), at the wheel's loaded height (the searched height lowered by the
  /// normal problem's vertical approach). Zero for a wheel with no patch.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

struct WheelsetResult {
  WheelResult left, right;
};

class WheelsetContact {
 public:
  /// Validates everything (std::invalid_argument naming the parameter): the track data
  /// (WheelsetTrackData::validate), the parameters (validate(ContactParameters)), the options.
  WheelsetContact(const WheelsetTrackData& track, const ContactParameters& parameters,
                  const WheelsetContactOptions& options = {});
  ~WheelsetContact();
  WheelsetContact(WheelsetContact&&) noexcept;
  WheelsetContact& operator=(WheelsetContact&&) noexcept;

  /// Advances both wheels by one step of dt [s] (0 for the first step: no travel yet). Never
  /// throws on a state and never gives a non-finite number: bad input (a value not finite,
  /// |motion.cant| > kMaxCant, dt < 0, a pose beyond the search's range) gives the wheels
  /// kInvalidInput with zero forces and leaves their history as it was.
  WheelsetResult step(const WheelsetState& state, double dt);
  /// A steady evaluation at one state for whole_force_balance: step(state, dt) repeated until no
  /// patch's fn changes by more than tolerance times its wheel's load from one step to the next
  /// and the patches stay the same, at most max_steps steps; the last step's result. A wheel that
  /// has not settled says so in its message (status kOk). Each repeat's balance takes the previous
  /// repeat's tangential forces, so it settles on the state's steady balance where the model's
  /// forces are steady: the steady model at any dt, nss and shen-li at a dt that rolls many patch
  /// lengths (V dt >> a; at dt = 0 they roll nothing and give no force). The slots' history
  /// advances by every repeat. Without whole_force_balance the second step settles it.
  /// tolerance in (0, 0.1), max_steps >= 2, else both wheels kInvalidInput.
  WheelsetResult settle(const WheelsetState& state, double dt, double tolerance = 1e-4,
                        int max_steps = 30);
  /// Clears every slot's history: the next step equals that of a fresh object.
  void reset();

  const ContactSearch& search() const;
  const ContactParameters& parameters() const;
  /// With a contact table: the wheel-steps since construction whose normal problem had no
  /// solution on the table's geometry, which were searched again directly (step 2 above; about a
  /// millisecond each). reset() leaves it. 0 without a table.
  std::size_t directSearchFallbacks() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wheel_rail_contact
