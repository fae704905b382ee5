// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Umbrella header: every core query of tricyl (no FCL, libccd or Eigen).
#pragma once

#include "tricyl/endpoint_form.h"
#include "tricyl/fcl_contact.h"
#include "tricyl/line_cylinder.h"
#include "tricyl/mesh_cylinder.h"
#include "tricyl/point_cone.h"
#include "tricyl/point_cylinder.h"
#include "tricyl/segment_cylinder.h"
#include "tricyl/sphere_cylinder.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_margin.h"
#include "tricyl/types.h"
