/// The marches' vector path: several strips at a time, one in each lane of a vector register.
/// Each strip's nodes still go in order, so a strip's traction, slip flags, filter states and
/// sums are those of the scalar reference (one strip at a time: fastsim.cpp, transient_fastsim.cpp)
/// within rounding.
///
///   Lanes: 4 doubles, one strip each (Highway, hwy/highway.h, compiled for x86's AVX2 and
///          chosen at run time where the CPU has it; elsewhere stripLanesAvailable() is false and
///          the scalar reference marches).
///   Error: within 1e-12 of the scalar reference relative to each quantity's scale (the bound for
///          tractions and forces); the lanes fuse multiply-adds, the scalar reference does not.
///          Slip flags and adhesion fractions are the same but where a node's |t| lies within
///          rounding of its bound.
///   Range: every input the scalar reference takes; the nodes where the scalar reference takes
///          another path (StripSums::node's tiny traction, a slip return out of range) stop the
///          lanes and go one strip at a time.
#pragma once

#include "core/fastsim/fastsim.hpp"
#include "core/fastsim/transient_march.hpp"

namespace wheel_rail_contact {

/// steadyFastSim in lanes: the classic march, or the coupled one where L.lateralCoupling != 0.
CreepForces steadyFastSimInLanes(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                                 TractionField* field);

/// transientFastSim's march in lanes, with step.st's saturation.
CreepForces transientFastSimInLanes(const transient::TransientStep& step);

}  // namespace wheel_rail_contact
