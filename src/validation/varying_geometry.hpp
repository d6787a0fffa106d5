/// Scenes with a changing contact geometry (StepInput::a, b per row) for the accuracy of the
/// FastSim models against the exact half-space solver (doc/varying_geometry.md). The paper's
/// material and reference patch (paper_scenes.hpp: a0 = b0 = 20 mm, Fz = 470.5 N, V = 0.25 m/s),
/// constant load and constant creepages xi = 0.003, phi = 0.5 1/m; the patch keeps its area
/// pi a0^2 while a/b changes. Units SI.
#pragma once

#include "validation/paper_scenes.hpp"

namespace wheel_rail_contact {

/// a/b oscillating between 0.7 and 1.4, log-harmonically in the rolled distance q with wavelength
/// lambda = lambda_over_a0 * a0: a/b = sqrt(0.98) 2^(sin(2 pi q / lambda) / 2). At least 8 a0 of
/// rolling before the scored last period; rows every V dt = `step` [m]. fz_max covers the largest
/// patch (1.8 Fz), so the fixed meshes and the exact grid cover every patch.
PaperScene harmonicAOverBScene(double lambda_over_a0, double step);

/// a/b = 1.4 for 8 a0 of rolling, then 0.7 for 8 a0 (the scored "period" is the latter).
PaperScene stepAOverBScene(double step);

}  // namespace wheel_rail_contact
