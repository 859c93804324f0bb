# The honesty rule as a build rule: robot/, perception/ and cell/ decide from sensors only, so they
# must not see the simulator. Their targets are compiled against an include root that holds only
# robot/, perception/, cell/ and common/ (header-only helpers every library may use; symbolic links into
# the source tree), so `#include "sim/..."` or
# `#include "app/..."` does not compile there; and MuJoCo's types are poisoned
# (cmake/no_mujoco.h), so including <mujoco/mujoco.h> from the system is a compile error too.
set(SORTCELL_SENSOR_SIDE_ROOT ${PROJECT_BINARY_DIR}/sensor_side_include)
file(MAKE_DIRECTORY ${SORTCELL_SENSOR_SIDE_ROOT})
foreach(dir robot perception cell common)
  file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${dir} ${SORTCELL_SENSOR_SIDE_ROOT}/${dir} SYMBOLIC)
endforeach()

# sortcell_sensor_side(target): compile `target` on the sensor side of the rule.
function(sortcell_sensor_side target)
  target_include_directories(${target} PUBLIC ${SORTCELL_SENSOR_SIDE_ROOT})
  target_compile_options(${target} PRIVATE -include ${PROJECT_SOURCE_DIR}/cmake/no_mujoco.h)
endfunction()
