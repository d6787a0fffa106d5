/// The Manchester contact benchmark's case A-2.2 (S1002 on UIC60 1:40, 10 kN per wheel, y from 0 to
/// 10 mm with 2.4 mrad of yaw per mm) run through our chain: contact search, the normal problem
/// under the wheel load, creepages, and the exact half-space solver on each patch's gap as the
/// reference (doc/manchester.md). CONTACT's published results are read beside ours as reference
/// points only. Used by src/tools/manchester_a22.cpp and test/unit/test_manchester_a22.cpp.
///
/// Signs. The benchmark's (CONTACT's) axes are ours turned half a turn about x (doc/profiles.md):
/// y_ours = -y, yaw_ours = -yaw, roll_ours = roll, omega = -vpitch, V = vs. Both wheels of a case
/// belong to the same wheelset state (CONTACT's left-wheel output is that state's left wheel).
/// CONTACT gives a left profile point in the track's lateral direction, ours in the right file's
/// (mirrored): y_rail_ours = -YCP(R) on the left, +YCP(R) on the right; its contact angle is
/// ours with the sign of the right wheel's reversed: delta_ours = -DELTCP on the right, +DELTCP on
/// the left.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/exact/halfspace_influence.hpp"
#include "validation/patch_exact.hpp"
#include "wheel_rail_contact/normal/patch_normal.hpp"
#include "wheel_rail_contact/profiles/contact_search.hpp"
#include "wheel_rail_contact/profiles/contact_table.hpp"
#include "wheel_rail_contact/wheelset/creepages.hpp"
#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

namespace wheel_rail_contact {

/// One wheel of one wheelset state as test/data/profiles/a22_cases.csv gives it (the benchmark's
/// axes and units: mm, rad, N, mm/s, rad/s).
struct A22State {
  WheelSide side = WheelSide::kRight;
  int number = 0;  ///< the benchmark's case number, 1..21
  double y_mm = 0.0, yaw = 0.0, roll = 0.0, fz = 0.0, vs_mm_s = 0.0, vpitch = 0.0;
};

/// Reads a22_cases.csv; throws std::runtime_error naming the file and line on a bad one.
std::vector<A22State> readA22States(const std::string& path);

WheelsetPose a22Pose(const A22State& s);      ///< ours (REP 103, SI), z = 0
WheelsetMotion a22Motion(const A22State& s);  ///< V = vs, omega = -vpitch, no yaw rate, tangent

/// One of CONTACT's patches (test/data/profiles/contact_a22_reference.csv), turned into our signs
/// and SI units (see the header's "Signs"): the contact point on the rail in the right rail file's
/// coordinates, the contact angle, normal force, peak pressure, approach, creepages as printed.
struct A22Reference {
  WheelSide side = WheelSide::kRight;
  int number = 0, patch = 0;
  double y_rail = 0.0, z_rail = 0.0;          ///< [m], file coordinates (z down, as the file)
  double contact_angle = 0.0;                 ///< [rad], ours
  double fn = 0.0, pmax = 0.0;                ///< [N], [Pa]
  double approach = 0.0;                      ///< [m]
  double cksi = 0.0, ceta = 0.0, cphi = 0.0;  ///< CONTACT's creepages, its signs, cphi [1/m]
  /// CONTACT's creep forces [N] and spin moment [N m] in our signs (PatchResult's): CKSI is -xi,
  /// CETA eta, CPHI phi, and CONTACT's FX, FS, MN oppose its own creepages as ours do, so
  /// fx = -FX, fs = FS, mz = MN.
  double fx = 0.0, fs = 0.0, mz = 0.0;
};

std::vector<A22Reference> readA22Reference(const std::string& path);

/// The exact half-space solution of one patch on its own grid.
struct A22Exact {
  bool solved = false;
  std::string message;          ///< why not solved, or empty
  double fn = 0.0, pmax = 0.0;  ///< [N], [Pa]
  double approach = 0.0;        ///< along the candidate's normal beyond first touch [m]
  /// Extent of the loaded elements (their outer edges) on the contact plane [m]: x along rolling,
  /// eta as ContactCandidate::gap_function.
  double x_min = 0.0, x_max = 0.0, eta_min = 0.0, eta_max = 0.0;
  HalfspaceGrid grid;
  double eta_offset = 0.0;  ///< eta of the grid's centre
  Eigen::VectorXd p;        ///< pressure per element [Pa]
};

struct A22Options {
  double G = 82e9, nu = 0.28;
  NormalOptions normal;
  /// Exact grid (validation/patch_exact.hpp): mx elements along x and my across, over the box
  /// where the undeformed bodies interpenetrate at the approach (the contact lies inside it).
  int exact_mx = 32, exact_my = 24;
  /// The exact wheel load is met within this relative error (iterations on the vertical
  /// approach, at most exact_iterations).
  double exact_load_tolerance = 1e-3;
  int exact_iterations = 8;
};

/// One patch (candidate) of one wheel: ours, the exact solution, and the creepages.
struct A22Patch {
  int index = 0;  ///< the candidate's index in the geometry
  ContactCandidate candidate;
  NormalPatch ours;
  PatchCreepages creepages;
  /// The candidates [merged_first, merged_last] whose patches solveWheelLoad merged into this
  /// one (ours.merged_into < 0 here, the others' naming this index); both equal to index when
  /// nothing merged into it. A candidate merged into another has no exact solution of its own
  /// (fn 0): the exact solver sees the merged gap (mergeCandidates) on the patch that took it.
  int merged_first = 0, merged_last = 0;
  /// The geometry the exact solver solves: the candidate, or the merged candidate.
  ContactCandidate exact_candidate;
  /// Exact at the wheel's vertical load, and at our own approach (its force only).
  A22Exact exact;
  double exact_fn_at_our_approach = 0.0;
};

struct A22Wheel {
  A22State state;
  /// Empty when solved; else why our normal problem failed on this wheel (no patches then).
  std::string message;
  WheelContactGeometry geometry;
  WheelNormal normal;
  double exact_vertical_approach = 0.0;
  bool exact_converged = false;
  std::vector<A22Patch> patches;  ///< every candidate, in the geometry's order
};

/// Runs one wheel of one state: search, our normal problem under state.fz, creepages, and the exact
/// solver on every candidate's gap (a merged patch's on the merged gap), its vertical approach
/// iterated until the patches' vertical forces add up to state.fz. Throws std::runtime_error if
/// the search or the exact solver fails (the benchmark's states are all valid); our normal
/// problem's failure is A22Wheel::message.
A22Wheel runA22Wheel(const ContactSearch& search, const A22State& state, const A22Options& o);
/// The same with the contact table's geometry in place of the direct search's.
A22Wheel runA22Wheel(const ContactTable& table, const A22State& state, const A22Options& o);

/// The exact normal problem of one candidate at a rigid approach along its normal beyond first
/// touch, on the gap h(x, eta) = g(eta) - g(0) + x^2 cos(delta(eta)) / (2 r(eta)) of its gap
/// function (normal/patch_normal.hpp's geometry; exactPatchNormal, validation/patch_exact.hpp),
/// with the loaded elements' extent along x too.
A22Exact solveExactPatch(const ContactCandidate& c, double approach, const A22Options& o);

/// One model's creep forces on one patch through WheelsetContact (PatchResult's frame and signs).
struct A22ModelForces {
  std::string model;                    ///< ContactParameters::model
  bool found = false;                   ///< WheelsetContact gave this patch
  double fx = 0.0, fs = 0.0, mz = 0.0;  ///< [N], [N m]
  StepStatus status = StepStatus::kOk;
  std::string message;
  /// Steps at the constant state until no force moved by more than
  /// A22CreepOptions::settle_tolerance mu fn in a step (the model's steady limit); settled false if
  /// max_steps passed first.
  int steps = 0;
  bool settled = false;
};

/// One loaded patch of one wheel: the models' creep forces through WheelsetContact against the
/// exact tangential solution on the same patch (the exact normal pressure on the patch's gap at
/// the wheel load, scaled to WheelsetContact's fn; WheelsetContact's creepages).
struct A22Creep {
  int index = 0;  ///< the candidate's index (A22Patch::index)
  ContactZone zone = ContactZone::kTread;
  double fn = 0.0, a = 0.0, b = 0.0;  ///< WheelsetContact's normal force and equivalent ellipse
  Creepages creepages;                ///< WheelsetContact's, at the candidate's contact point
  ExactTangential exact;
  std::vector<A22ModelForces> models;
  const A22Reference* contact = nullptr;  ///< CONTACT's patch beside this one, if any
};

struct A22CreepOptions {
  std::vector<std::string> models = {"steady", "nss", "shen-li"};
  double mu = 0.3;
  double dt = 1e-3;  ///< [s] per step at the benchmark's 2 m/s: 2 mm of rolling
  int max_steps = 2000;
  double settle_tolerance = 1e-7;
};

/// The creep forces of every loaded patch of a wheel run by runA22Wheel (its exact pressures),
/// each model's by a fresh WheelsetContact (default track data, the state's load on both wheels)
/// stepped at the constant state until settled. refs: CONTACT's patches, matched by the contact
/// point on the rail as manchester_a22 does (none if empty).
std::vector<A22Creep> runA22Creep(const A22Wheel& wheel, const A22Options& o,
                                  const A22CreepOptions& c,
                                  const std::vector<A22Reference>& refs = {});

/// The candidate's point moved eta along its contact plane, in the right rail file's coordinates
/// (y, z down) [m]: the tangent line, good to curvature * eta^2 / 2.
Eigen::Vector2d railFilePointAt(const ContactCandidate& c, double eta);

}  // namespace wheel_rail_contact
