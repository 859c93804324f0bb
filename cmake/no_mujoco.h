// Force-included into the sensor-side libraries (robot/, perception/, cell/): any use of MuJoCo's
// types there, including through <mujoco/mujoco.h>, is a compile error. See cmake/sensor_side.cmake.
#pragma GCC poison mjModel mjData mjModel_ mjData_ mj_step mj_forward
