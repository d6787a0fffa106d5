#include "wheel_rail_contact/fastsim/creepage_kind.hpp"

#include <stdexcept>

namespace wheel_rail_contact {

const char* toString(CreepageKind k) {
  switch (k) {
    case CreepageKind::kXi:
      return "xi";
    case CreepageKind::kEta:
      return "eta";
    case CreepageKind::kPhi:
      return "phi";
  }
  return "unknown";
}

const char* coefficientCode(CreepageKind k) {
  switch (k) {
    case CreepageKind::kXi:
      return "11";
    case CreepageKind::kEta:
      return "22";
    case CreepageKind::kPhi:
      return "23";
  }
  return "unknown";
}

CreepageKind parseCreepageKind(const std::string& text) {
  if (text == "xi") return CreepageKind::kXi;
  if (text == "eta") return CreepageKind::kEta;
  if (text == "phi") return CreepageKind::kPhi;
  throw std::invalid_argument("kind: expected xi, eta or phi, got '" + text + "'");
}

}  // namespace wheel_rail_contact
