// SPDX-License-Identifier: Apache-2.0
// kind_partners (lookup/src/jump_side.hpp): how the lookup pairs the contact jumps of a load
// cell's two nodes when their kind lists differ. A jump pairs with the other node's jump of the
// same pairing key (its geometric bits, or its whole kind without them) and rank.
#include "jump_side.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace railtab::lookup::detail {
namespace {

// The tread-flange hand-over of the loaded patch (kind 192, no geometric bits) passes the flange
// root's rigid-point jump (kind 3) between the nodes: each pairs with its own kind across the swap.
TEST(JumpPairing, CrossingJumpsPairByKind) {
  const std::vector<std::uint32_t> a = {4, 192, 3, 8}, b = {4, 3, 192, 8};
  EXPECT_EQ(kind_partners(a, b), (std::vector<int>{0, 2, 1, 3, 0, 2, 1, 3}));
}

// A rigid-point jump at which a loaded patch appears at one load only (worn_miniprof.toml's right
// wheel at -5.07 mm: kind 68 = 64 + 4 at 60 kN, kind 4 at 100 kN) keeps its geometric bits: it
// pairs with itself, and the kind-4 jumps after it keep their ranks. Paired by the whole kind, 68
// had no partner and every later kind-4 jump paired with the one before it at the other node.
TEST(JumpPairing, ARigidPointJumpPairsByItsGeometricBitsWhenItsPatchBitsChangeWithLoad) {
  const std::vector<std::uint32_t> a = {1, 68, 4, 4}, b = {65, 4, 4, 4};
  EXPECT_EQ(kind_partners(a, b), (std::vector<int>{0, 1, 2, 3, 0, 1, 2, 3}));
  EXPECT_EQ(pairing_key(68), 4u);
  EXPECT_EQ(pairing_key(192), 192u);
}

// A jump one node lacks has no partner (-1) and does not shift the others' pairing.
TEST(JumpPairing, AJumpTheOtherNodeLacksHasNoPartner) {
  const std::vector<std::uint32_t> a = {4, 20, 4}, b = {4, 4};
  EXPECT_EQ(kind_partners(a, b), (std::vector<int>{0, -1, 1, 0, 2}));
}

}  // namespace
}  // namespace railtab::lookup::detail
