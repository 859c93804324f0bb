// Must NOT compile on the sensor side (CTest sensor_side_refuses_mujoco, WILL_FAIL): MuJoCo's types
// are poisoned there.
#include <mujoco/mujoco.h>
