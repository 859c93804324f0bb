// Must NOT compile on the sensor side (CTest sensor_side_refuses_sim, WILL_FAIL): sim/ is not on its
// include path.
#include "sim/model.h"
