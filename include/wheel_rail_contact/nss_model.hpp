/// The non-steady FastSim models behind ContactModel: "shen-li" (time term with the static
/// flexibilities, F == 1) and "nss" (Alonso & Gimenez dynamic flexibility with the weighted chi of
/// Guiral et al. 2013, eq. 15), on a fixed mesh (sized for fz_max) or an adaptive one (follows
/// a(t), b(t), history carried along the strips: AlongStripMap). Units as in contact_model.hpp.
#pragma once

#include "wheel_rail_contact/chi_table.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/hertz.hpp"
#include "wheel_rail_contact/transient_fastsim.hpp"

namespace wheel_rail_contact {

class NssModel : public ContactModel {
 public:
  /// `chi` is used when p.model == "nss" (shen-li ignores it). Allocates everything here: step()
  /// allocates nothing.
  NssModel(const ContactParameters& p, const ChiTable& chi);
  StepOutput step(const StepInput& in) override;
  void reset() override;
  std::string name() const override { return p_.model; }

  const PatchMesh& mesh() const { return mesh_; }
  const TractionField& traction() const { return field_; }

 private:
  bool patchMoves(const HertzEllipse& h);
  void settlePatch();
  CreepForces advance(const StepInput& in, const HertzEllipse& h, bool moves);
  double historyScale(double a) const;
  void chooseFilters(const Creepages& c, double a, double b, double V, double dt);
  StepOutput hold(StepStatus status, const char* why) const;

  ContactParameters p_;
  ReferencePatch ref_;
  CreepCoefficients kalker_;
  bool adaptive_ = false;
  bool dynamic_ = false;  // nss (else shen-li)
  ChiParameters chi_[3];  // kinds 11, 22, 23 at this a/b (a/b does not change with load)
  PatchMesh mesh_, spare_;
  TransientState state_, remapped_;  // the history; the next one while the patch moves
  AlongStripMap carry_;  // the history's path from the previous patch to this one (adaptive)
  TractionField field_;
  FilterZ zx_, zy_;
  double wx_[2], wy_[2];  // eq. 15 weights, kept while both vanish
  StepOutput last_;
  double lastA_ = 0.0;  // a of the step that left the history (0: none yet) [m]
};

}  // namespace wheel_rail_contact
