/// The exact half-space solver (halfspace_solver.hpp) as a ContactModel named "exact": transient
/// rolling on one fixed grid of nx x ny elements over [-1.1 a_max, 1.1 a_max] x [-1.1 b_max,
/// 1.1 b_max], a_max, b_max the patch at effectiveFzMax. Units as in contact_model.hpp.
/// Each step() advances by V dt in internal sub-steps of exactly one element length dx (the
/// scheme's condition dq = dx), with V, creepages and load interpolated linearly between the
/// previous and the current input at the sub-step's position, except the last sub-step, which takes
/// the row's own input; the remainder below dx is carried to the next step. The output is the
/// state after that last sub-step (its position lags the row's by less than dx). A step longer
/// than 10 nx elements restarts from rest 10 nx elements before its end (the memory of the start
/// has decayed by e^-20 there). The pressure is the discrete Hertz normal problem at the
/// sub-step's load (a, b scale as (fz/fz0)^(1/3)), solved again whenever the load has moved by
/// more than 0.5 % and scaled to the load in between. Status rules as SteadyModel; the first step
/// after start, reset or loss of contact starts from zero traction and returns zero force.
/// V < 0 rolls forwards in the mirror x -> -x, the history mirrored at each reversal, as the
/// FastSim models do (rolling_direction.hpp).
/// Per-step a, b and mu (StepInput) are honoured: interpolated between rows like the other
/// inputs, the normal problem solved again when a or b moves by more than 0.17 %; the traction
/// history stands on the fixed grid, so a change of patch needs no remapping. A step whose a or b
/// exceeds the patch at fz_max (what the grid covers) is rejected.
#pragma once

#include "core/exact/halfspace_solver.hpp"
#include "core/models/rolling_direction.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

class ExactModel : public ContactModel {
 public:
  /// Throws std::invalid_argument if nx * ny exceeds 3600 (dense matrices on the contact set) or
  /// mesh is not "fixed".
  explicit ExactModel(const ContactParameters& p);
  StepOutput step(const StepInput& in) override;
  void reset() override;
  std::string name() const override { return "exact"; }
  const HalfspaceSolver& solver() const { return solver_; }
  /// Sub-steps taken by the last step() call.
  int subSteps() const { return subSteps_; }

 private:
  void subStep(const StepInput& in);
  /// A march-frame output in the contact frame.
  StepOutput contactFrame(StepOutput out) const;
  ContactParameters p_;
  ReferencePatch ref_;
  HalfspaceSolver solver_;
  double fzMax_;
  HertzEllipse maxPatch_;  // the patch at fz_max: what the grid covers (a step's a, b at most)
  StepInput prev_;
  bool started_ = false;
  RollingFrame frame_;                    // the mirror while rolling backwards
  double carry_ = 0.0;                    // distance rolled since the last sub-step [m]
  double loadedFz_ = -1.0;                // load of the last normal solve [N]
  double loadedA_ = 0.0, loadedB_ = 0.0;  // its patch [m]
  Eigen::VectorXd normalPressure_;        // its pressure [Pa]
  int subSteps_ = 0;
  StepOutput last_;
};

}  // namespace wheel_rail_contact
