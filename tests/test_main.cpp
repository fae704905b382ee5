// SPDX-License-Identifier: BSD-3-Clause
#include <gtest/gtest.h>

#include "test_support.h"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(new tricyl::test::FpTrapEnvironment);
  return RUN_ALL_TESTS();
}
