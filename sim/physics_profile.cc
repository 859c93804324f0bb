#include "sim/physics_profile.h"

#include <chrono>
#include <mutex>

namespace sortcell::sim {
namespace {

mjtNum SteadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void EnablePhysicsTimers() {
  static std::once_flag once;
  std::call_once(once, [] { mjcb_time = SteadySeconds; });
}

std::map<std::string, double> PhysicsStageSeconds(const Data& data) {
  const mjTimerStat* t = data->timer;
  const double collision = t[mjTIMER_POS_COLLISION].duration;
  const double constraint =
      t[mjTIMER_POS_MAKE].duration + t[mjTIMER_POS_PROJECT].duration + t[mjTIMER_CONSTRAINT].duration;
  const double step = t[mjTIMER_STEP].duration;
  return {
      {"collision", collision}, {"constraint", constraint}, {"smooth", step - collision - constraint}, {"step", step}};
}

}  // namespace sortcell::sim
