// SPDX-License-Identifier: BSD-3-Clause
// Bit-exact cases kept in every default run of tricyl-compare and in the
// tests: inputs on which a method is known to fail in a way the seeded
// families may not show. Header-only, no FCL.
#pragma once

#include "scenes.h"

namespace tricyl::compare {

/// A disc (r ~ 778, lz ~ 1.06e-6) whose rim the triangle crosses, in a
/// proper rotation (det R = +1): they intersect. FCL 0.7's
/// GJKSolver_libccd<double> never returns on it at its default tolerance
/// (~2e-14): libccd's MPR has no iteration cap. At 1e-6 it answers.
inline scenes::TriCase discHangCase() {
  scenes::TriCase k;
  k.cyl = {0x1.8523b2c7f16bfp+9, 0x1.1d3482e4f382bp-20};
  const double R[3][3] = {
      {0x1.48b62eb9de056p-2, -0x1.5f07bdb4e0192p-1, -0x1.4e872644fc344p-1},
      {0x1.5c2a442996f94p-2, 0x1.746386dd0c053p-1, -0x1.313b183115a55p-1},
      {0x1.c493d98a71998p-1, -0x1.f850245fded6p-6, 0x1.ddc88111b7d02p-2}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) k.pose.R[i][j] = R[i][j];
  k.pose.t = {-0x1.51bb1180c6b4p-1, 0x1.a407417745a74p+0, 0x1.286f93e83346p-1};
  k.tri = {
      {-0x1.3534e5984faf4p+6, -0x1.a6f71157db70ep+8, -0x1.44a19c5402542p+9},
      {-0x1.6fc68327e9913p+7, -0x1.4d2ce616c4b6cp+8, -0x1.55e5b744efdp+9},
      {-0x1.5d58739ed8ec2p+6, -0x1.6c8a172168b19p+8, -0x1.3777f50c50d2cp+9}};
  k.feature = "disc_hang";
  return k;
}

}  // namespace tricyl::compare
