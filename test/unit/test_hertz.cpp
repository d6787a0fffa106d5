#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "wheel_rail_contact/geometry/hertz.hpp"

using namespace wheel_rail_contact;

TEST(Hertz, EllipticIntegralsKnownValues) {
  double K, E;
  completeEllipticIntegrals(0.0, &K, &E);
  EXPECT_NEAR(K, M_PI / 2, 1e-15);
  EXPECT_NEAR(E, M_PI / 2, 1e-15);
  completeEllipticIntegrals(0.5, &K, &E);  // Abramowitz & Stegun table 17.1
  EXPECT_NEAR(K, 1.8540746773013719, 1e-13);
  EXPECT_NEAR(E, 1.3506438810476755, 1e-13);
  completeEllipticIntegrals(0.99, &K, &E);
  EXPECT_NEAR(K, 3.6956373629898747, 1e-12);
  EXPECT_NEAR(E, 1.0159935450252239, 1e-12);
}

TEST(Hertz, CircularContactClosedForm) {
  // Two spheres of radius R: A = B = 1/R (gap h = (x^2 + y^2)/R, relative curvature 2/R over 2).
  const double R = 0.5, G = 8.0e10, nu = 0.3, P = 1.0e5;
  const double Estar = contactModulus(G, nu);
  const double Reff = R / 2.0;  // 1/Reff = 1/R + 1/R
  const HertzEllipse h = hertzFromCurvatures(P, 1.0 / (2 * Reff), 1.0 / (2 * Reff), G, nu);
  const double a = std::cbrt(3.0 * P * Reff / (4.0 * Estar));
  EXPECT_NEAR(h.a, a, 1e-12 * a);
  EXPECT_NEAR(h.b, a, 1e-12 * a);
  EXPECT_NEAR(h.p0, 3.0 * P / (2.0 * M_PI * a * a), 1e-6 * h.p0);
}

// Timoshenko & Goodier, Theory of Elasticity, Hertz table: with cos(theta) = (B - A)/(B + A),
// a = m cbrt(3 P / (4 E* (A + B))), b = n cbrt(...), for two identical bodies (k1 + k2 = 1/(pi
// E*)).
struct HertzTableCase {
  double thetaDeg, m, n;
};

TEST(Hertz, EllipticContactAgainstPublishedTable) {
  const HertzTableCase cases[] = {{30, 2.731, 0.493}, {60, 1.486, 0.717}, {80, 1.128, 0.893}};
  const double G = 8.0e10, nu = 0.3, P = 1.0e5, sum = 10.0;  // A + B [1/m]
  for (const auto& c : cases) {
    const double ct = std::cos(c.thetaDeg * M_PI / 180.0);
    const double A = 0.5 * sum * (1 - ct), B = 0.5 * sum * (1 + ct);
    const HertzEllipse h = hertzFromCurvatures(P, A, B, G, nu);
    const double scale = std::cbrt(3.0 * P / (4.0 * contactModulus(G, nu) * sum));
    EXPECT_NEAR(h.a / scale, c.m, 0.002 * c.m) << "theta " << c.thetaDeg;
    EXPECT_NEAR(h.b / scale, c.n, 0.002 * c.n) << "theta " << c.thetaDeg;
    EXPECT_GT(h.a, h.b);  // the long axis lies along the smaller curvature
  }
}

TEST(Hertz, SwappingCurvaturesSwapsAxes) {
  const HertzEllipse h1 = hertzFromCurvatures(5e4, 2.0, 7.0, 8e10, 0.28);
  const HertzEllipse h2 = hertzFromCurvatures(5e4, 7.0, 2.0, 8e10, 0.28);
  EXPECT_NEAR(h1.a, h2.b, 1e-14);
  EXPECT_NEAR(h1.b, h2.a, 1e-14);
}

TEST(Hertz, ReferencePatchScalesWithCubeRootOfLoad) {
  const ReferencePatch ref{6e-3, 4e-3, 8e4};
  const HertzEllipse h = ref.at(8e4 * 8.0);
  EXPECT_NEAR(h.a, 12e-3, 1e-15);
  EXPECT_NEAR(h.b, 8e-3, 1e-15);
  EXPECT_NEAR(h.p0, 3.0 * 6.4e5 / (2.0 * M_PI * 12e-3 * 8e-3), 1e-3);
  // Consistent with the curvature form: the same curvatures give the same scaling.
  const HertzEllipse h1 = hertzFromCurvatures(1e4, 3.0, 5.0, 8e10, 0.28);
  const HertzEllipse h8 = hertzFromCurvatures(8e4, 3.0, 5.0, 8e10, 0.28);
  EXPECT_NEAR(h8.a / h1.a, 2.0, 1e-9);
  EXPECT_NEAR(h8.b / h1.b, 2.0, 1e-9);
}

TEST(Hertz, RejectsBadInput) {
  EXPECT_THROW(hertzFromCurvatures(0.0, 1, 1, 8e10, 0.3), std::invalid_argument);
  EXPECT_THROW(hertzFromCurvatures(1e4, -1, 1, 8e10, 0.3), std::invalid_argument);
  EXPECT_THROW(hertzFromCurvatures(1e4, 1, 1, 8e10, 0.5), std::invalid_argument);
  EXPECT_THROW(hertzFromCurvatures(NAN, 1, 1, 8e10, 0.3), std::invalid_argument);
}
