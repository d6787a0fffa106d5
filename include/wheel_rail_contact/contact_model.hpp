/// One interface for every creep-force model, advanced one time step per call.
/// Units: time s, speed m/s, creepages xi, eta [-], spin phi [1/m], forces N, moment N m, lengths
/// m.
#pragma once

#include <memory>
#include <string>

#include "wheel_rail_contact/contact_parameters.hpp"

namespace wheel_rail_contact {

struct PatchShape;  // fastsim/patch_shape.hpp

struct StepInput {
  double dt = 0.0;   ///< time since the previous step [s] (ignored by the steady model)
  double V = 0.0;    ///< signed rolling speed [m/s]; V < 0 rolls backwards (material enters at -a)
  double xi = 0.0;   ///< longitudinal creepage [-]
  double eta = 0.0;  ///< lateral creepage [-]
  double phi = 0.0;  ///< spin [1/m]
  double fz = 0.0;   ///< normal load [N]
  /// Optional per-step contact geometry and friction (a simulator whose contact point moves across
  /// the profiles); 0 = not given, the parameters apply: a = a0 (fz/fz0)^(1/3), b likewise, mu.
  /// Given, they must lie in the ranges the parameters a0, b0, a0/b0, mu accept (a, b in
  /// [1e-6, 1] m, a/b in [0.1, 10], mu in [1e-6, 1000]; a and b together), else kRejected. The
  /// FastSim models carry their history across a change of a, b, a/b (doc/varying_geometry.md),
  /// and a change of mu only moves the traction bound; a patch beyond the fixed mesh (sized for
  /// fz_max at a0, b0) grows the mesh, the history carried over, with a message (status kOk);
  /// exact rejects such a patch.
  double a = 0.0;   ///< patch semi-axis along x (rolling) [m]; given together with b
  double b = 0.0;   ///< patch semi-axis along y (lateral) [m]; given together with a
  double mu = 0.0;  ///< Coulomb friction coefficient [-]
  /// Optional non-Hertzian patch (fastsim/patch_shape.hpp), given with its equivalent ellipse a, b
  /// (the flexibilities' and chi's); nullptr: the ellipse a, b is the patch. The FastSim models
  /// (steady, shen-li, nss, auto) march the shape's strips, the traction bound from its pressure;
  /// the pointer is read during step() only. With a shape, a/b may lie outside [0.1, 10]: Kalker's
  /// coefficients and chi are then taken at the table's nearer end (the output's message says so).
  /// The exact model runs on the ellipse a, b and says so. A shape that checkPatchShape refuses
  /// gives kRejected.
  const PatchShape* shape = nullptr;
};

enum class StepStatus {
  kOk = 0,
  kNoLoad,        ///< fz < kMinLoad (1e-6 N): zero force, history cleared
  kStandstill,    ///< V == 0: no travel, state and forces held
  kRejected,      ///< non-finite or out-of-range input: zero force, state untouched
  kNotConverged,  ///< an iterative solver hit its cap: forces are its last iterate, not trusted
};
const char* toString(StepStatus s);

struct StepOutput {
  double fx = 0.0;                ///< [N]
  double fy = 0.0;                ///< [N]
  double mz = 0.0;                ///< [N m]
  double fz = 0.0;                ///< load used [N]
  double a = 0.0;                 ///< patch semi-axis along x [m]
  double b = 0.0;                 ///< patch semi-axis along y [m]
  double adhesionFraction = 0.0;  ///< [-]
  StepStatus status = StepStatus::kOk;
  /// Why, when status != kOk, or an OK step's note (the fixed mesh grew, or the patch covers few of
  /// its nodes); "" if none.
  /// Static text, never null: a step allocates nothing, not even for its message.
  const char* message = "";
};

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  /// Advance one step. Never throws for bad input and never returns non-finite forces: such input
  /// gives status kRejected with zero forces and leaves the state as it was.
  virtual StepOutput step(const StepInput& in) = 0;
  /// Clear every piece of state: the next outputs equal those of a fresh model.
  virtual void reset() = 0;
  virtual std::string name() const = 0;
  /// What the model chose at construction that the parameters do not say (auto's mesh), for the
  /// start-up log; empty if nothing.
  virtual std::string choices() const { return {}; }
};

/// The model named by p.model. Validates p (std::invalid_argument naming the parameter).
/// Throws std::invalid_argument for a model this build does not provide, saying so.
std::unique_ptr<ContactModel> makeContactModel(const ContactParameters& p);

/// Largest magnitude of any StepInput field in SI units; beyond it input is out of range.
constexpr double kMaxInputMagnitude = 1e12;
/// Smallest load that makes contact [N]: below it the patch is so small that squared tractions
/// underflow (the exact solver then returned NaN, found by fuzzing).
constexpr double kMinLoad = 1e-6;

/// Checks shared by every model: finite fields, dt >= 0, magnitudes at most kMaxInputMagnitude,
/// per-step a, b, mu absent (0) or in range, a and b together; a shape only with a and b, and one
/// that checkPatchShape takes (its a/b then unbounded).
/// Returns "" if fine, else why (static text).
const char* checkStepInput(const StepInput& in);

/// The step rules every model shares (doc/conventions.md), applied before any physics: non-finite
/// or out-of-range input or dt < 0 give kRejected; fz < kMinLoad (including fz <= 0) gives kNoLoad
/// (the caller clears its history). V < 0 passes: each model rolls backwards by mirror symmetry
/// (rolling_direction.hpp) or refuses it.
/// Fills `out` with zero forces and the status and returns true when the step ends there.
bool screenStep(const StepInput& in, StepOutput* out);

}  // namespace wheel_rail_contact
