/// The frequency-response sweep in the time domain: one small harmonic creepage of one kind on the
/// paper's material (a = b = 20 mm, V = 25 mm/s, constant load), run through any ContactModel and
/// scored against the linear response the exact frequency-domain solver predicts
/// (nonsteady_coefficients.hpp). Convention of doc/method.md#chi-identification: creepage = amp
/// cos(omega t), F = -norm amp Re(C^ e^{i omega t}), norm = G a b (xi, eta) or G (ab)^{3/2} (phi).
/// Units SI.
#pragma once

#include <complex>
#include <vector>

#include "validation/paper_scenes.hpp"
#include "wheel_rail_contact/fastsim/creepage_kind.hpp"

namespace wheel_rail_contact {

struct HarmonicScene {
  PaperScene scene;  ///< rows, material, period; name "freq_<11|22|23>_l<lambda/a>"
  CreepageKind kind = CreepageKind::kXi;
  double lambdaOverA = 1.0;  ///< wavelength / a [-]
  double amplitude = 0.0;    ///< creepage amplitude [-] (xi, eta) or [1/m] (phi)
};

/// Kind `kind` at lambda/a, rows every V dt = `step` [m]. The amplitude keeps the force below 1e-3
/// mu Fz (full adhesion to within 0.03 % in force, so linear theory holds). The run lasts whole
/// periods, at least 8 a of rolling before the scored last period, so that the memory of the
/// start (about 2 a of rolling) has died out.
HarmonicScene harmonicScene(CreepageKind kind, double lambda_over_a, double step);

/// The force history linear theory gives at the scene's rows for the coefficient `c` (C11 for kXi,
/// C22 for kEta, C23 for kPhi): Fx for kXi, Fy otherwise; fz the row's load.
std::vector<StepOutput> harmonicResponse(const HarmonicScene& h, std::complex<double> c);

/// "11", "22" or "23": the coefficient index a kind drives.
const char* coefficientName(CreepageKind kind);

}  // namespace wheel_rail_contact
