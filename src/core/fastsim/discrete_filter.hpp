/// The dynamic flexibility F (wheel_rail_contact/fastsim/nss_filter.hpp) discretised for one time
/// step: what the time-term march runs. Private to the core (the march's internals).
#pragma once

#include "wheel_rail_contact/fastsim/nss_filter.hpp"
#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"

namespace wheel_rail_contact {

/// F discretised for one step (Tustin, doc/method.md#dynamic-flexibility) in transposed direct form
/// II:
///   h_n = b0 g_n + s_{n-1},  s_n = b1 g_n - a1 h_n + s2_{n-1},  s2_n = b2 g_n - a2 h_n,
/// where g is the traction rate dtau/dt [Pa/s] and h the filtered rate [Pa/s]. A first-order F has
/// b2 = a2 = 0 (its state s2 stays zero and the march skips it); the pole -a1 lies inside the unit
/// circle for every dt > 0 whenever chi3 > 0. A second-order F (second_order_flexibility.hpp) uses
/// all five; its two poles lie inside the unit circle whenever its continuous poles are stable.
struct FilterZ {
  double b0 = 1.0;
  double b1 = 0.0;
  double a1 = 0.0;
  double b2 = 0.0;
  double a2 = 0.0;
  /// The second state is in use: the march must carry s2.
  bool secondOrder() const { return b2 != 0.0 || a2 != 0.0; }
};

/// Z coefficients for semi-axis a [m], speed V > 0 [m/s] and step dt > 0 [s].
FilterZ discretise(const ChiParameters& chi, double a, double V, double dt);

/// The same for a second-order F. With chi4 = chi5 = 0 it is the first-order discretise, bit for
/// bit (b2 = a2 = 0): the Tustin image of a first-order F written as second order would carry a
/// pole and a zero cancelled at z = -1.
FilterZ discretise(const SecondOrderChi& chi, double a, double V, double dt);

/// Paper eq. 15: per direction, the Z coefficients of the two creepage kinds acting along it,
/// weighted by w1 and w2 (|xi| and |phi| sqrt(ab) along x; |eta| and |phi| sqrt(ab) along y).
/// Both weights zero would be 0/0: the caller keeps its previous weights instead. All five
/// coefficients are mixed (second order: the denominators' convex combination stays stable,
/// doc/validation.md "Spin: a second-order F").
FilterZ weightedFilter(const FilterZ& z1, double w1, const FilterZ& z2, double w2);

}  // namespace wheel_rail_contact
