#pragma once
/// @file
/// Where a physics step's time goes, from MuJoCo's own stage timers (mjData::timer), which 2.2 fills only
/// while a time callback (mjcb_time) is installed.

#include <map>
#include <string>

#include "sim/model.h"

namespace sortcell::sim {

/// Installs a steady-clock mjcb_time once per process (idempotent, thread-safe), so that every
/// mjData's stage timers accumulate seconds. Costs two clock reads per timed stage (< 1 % of a step).
void EnablePhysicsTimers();

/// Seconds per stage accumulated in `data` since its last reset: "collision" (broad and narrow phase),
/// "constraint" (building the constraint rows, the solver and the noslip iterations after it),
/// "smooth" (kinematics, inertia, passive and actuator forces, the rest of the step) and "step" (all).
/// Zero until EnablePhysicsTimers() has been called. The few mj_forward calls outside mj_step (resets,
/// set-up) add to collision and constraint but not to step: negligible next to thousands of steps.
std::map<std::string, double> PhysicsStageSeconds(const Data& data);

}  // namespace sortcell::sim
