/// Neighbouring contact candidates whose separating ridge lies below the wheel's approach make one
/// patch: the contact search cuts each candidate's gap function at the ridge to its neighbour, so
/// the neighbours' gap functions together span the merged patch. They are brought into one
/// candidate's contact plane (normal/patch_normal.hpp's solveWheelLoad).
#pragma once

#include <vector>

#include "wheel_rail_contact/normal/patch_normal.hpp"
#include "wheel_rail_contact/profiles/contact_search.hpp"

namespace wheel_rail_contact {

/// The vertical approach (as WheelNormal::vertical_approach) beyond which the rigid wheel
/// overlaps the rail across the ridge between candidates `a` and `b` (b the next toward the
/// flange): the lower of the two gap functions' ends at the ridge, each divided by its normal's z
/// component. Infinite if the two gap functions do not meet (their ends more than two sample
/// spacings apart in a's contact plane, or either without a gap function): then no ridge joins
/// them.
double ridgeApproach(const ContactCandidate& a, const ContactCandidate& b);

/// The candidates [first, last] of `candidates` as one candidate in the contact plane of
/// `candidates[primary]` (first <= primary <= last): the primary's own samples unchanged, the
/// others' samples moved into its plane, eta' = (o_k + eta t_k - o_p) . t_p, gap' = gap /
/// (n_k . n_p) (o the candidates' points, t their lateral and n their normal directions in the
/// track's y-z plane; the lateral shift of a sample's ends along n_k, some tens of micrometres
/// times sin(angle between the normals), is left out), and the merged function continued at the
/// primary's spacing by cubic (four-point) interpolation of the samples so moved. `ridges`, if
/// given, receives the ridges' eta in the primary's plane (the first sample of each candidate
/// after `first`, moved), in order.
ContactCandidate mergeCandidates(const std::vector<ContactCandidate>& candidates, int first,
                                 int last, int primary, std::vector<double>* ridges = nullptr);

/// The normal problem of a merged candidate (mergeCandidates, its `ridges`) at a rigid approach
/// [m] along its normal, lump by lump: each lump (the part of the gap function between the
/// ridges that bound it) by Kik-Piotrowski's strips with KPEC's penetration factor from its own
/// gap at the shared approach, the patch of a lump stopping at a ridge; one amplitude per lump,
/// such that the Boussinesq displacement at every lump's deepest point, from all lumps' strips,
/// equals the interpenetration there (a lump whose amplitude comes out negative is lifted off).
/// cut_lo, cut_hi: the gap function's first (last) sample is a ridge as well, where the patch
/// stops (a neighbouring candidate beyond). As solvePatchNormal otherwise (patch_normal.cpp).
NormalPatch solveMergedPatch(const ContactCandidate& merged, const std::vector<double>& ridges,
                             double approach, double G, double nu, const NormalOptions& options,
                             bool cut_lo = false, bool cut_hi = false);

}  // namespace wheel_rail_contact
