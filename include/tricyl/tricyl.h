// Umbrella header: every core query of tricyl (no FCL, libccd or Eigen).
#pragma once

#include "tricyl/triangle_cylinder.h"
#include "tricyl/types.h"
