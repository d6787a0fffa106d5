/// Which single creepage drives a linear (creep-coefficient) computation.
#pragma once

#include <string>

namespace wheel_rail_contact {

/// kXi: longitudinal xi -> C11 (Fx); kEta: lateral eta -> C22 (Fy); kPhi: spin phi -> C23 (Fy).
enum class CreepageKind { kXi, kEta, kPhi };

/// Every kind, in the order of the enum (and of the chi table's rows).
inline constexpr CreepageKind kCreepageKinds[] = {CreepageKind::kXi, CreepageKind::kEta,
                                                  CreepageKind::kPhi};

/// "xi", "eta", "phi".
const char* toString(CreepageKind k);
/// The coefficient's indices, "11", "22", "23": the kind column of a chi table and of the
/// accuracy CSVs.
const char* coefficientCode(CreepageKind k);

/// Parses "xi", "eta" or "phi"; throws std::invalid_argument naming the text otherwise.
CreepageKind parseCreepageKind(const std::string& text);

}  // namespace wheel_rail_contact
