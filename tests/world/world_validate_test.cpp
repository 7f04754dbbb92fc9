// The validation pass's checks (world/world_validate.h and
// CheckColouring) on structures built and then broken by hand: each check
// passes the well-formed structure and fires, naming the invariant and the
// ids, on each kind of breakage. (Built with TALUS_VALIDATE, every step of
// every test also runs them on real worlds.)
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dynamics/constraint_colouring.h"
#include "world/world_validate.h"

namespace talus {
namespace world_validate_test {

// Contacts are set in place (their Eigen members are left uninitialised
// by default, so copies of them trip GCC's maybe-uninitialized).
void SetTouching(Contact& c, int a, int b) {
  c.bodyA = a;
  c.bodyB = b;
  c.manifold.pointCount = 1;
}

void AddTouching(WorldData& d, int a, int b) {
  d.contacts.resize(d.contacts.size() + 1);
  SetTouching(d.contacts.back(), a, b);
  d.contactAnchors.resize(d.contacts.size());
}

// Body 0 static (the floor), bodies 1-3 dynamic and awake; 1 rests on the
// floor and 2 on 1 (one island {1, 2}); 3 touches nothing (an island of
// its own). Sleeping on.
WorldData RestingStack() {
  WorldData d;
  d.settings.sleeping = true;
  d.sims.resize(4);
  d.records.resize(4);
  for (std::size_t i = 0; i < 4; ++i) {
    d.records[i].alive = true;
    d.sims[i].type = i == 0 ? BodyType::Static : BodyType::Dynamic;
  }
  AddTouching(d, 0, 1);
  AddTouching(d, 1, 2);
  return d;
}

void ExpectFires(const std::string& failure, const std::string& part) {
  EXPECT_NE(failure.find(part), std::string::npos) << "expected \"" << part << "\" in \"" << failure << "\"";
}

TEST(ValidateContactGraph, AWellFormedGraphPasses) { EXPECT_EQ(CheckContactGraph(RestingStack()), ""); }

TEST(ValidateContactGraph, APairListedTwiceFiresNamingTheBodies) {
  WorldData d = RestingStack();
  AddTouching(d, 2, 1);  // (1, 2) again, the other way round
  ExpectFires(CheckContactGraph(d), "bodies 1 and 2 have two contacts");
}

TEST(ValidateContactGraph, ContactsOutOfPairOrderFire) {
  WorldData d = RestingStack();
  SetTouching(d.contacts[0], 1, 2);
  SetTouching(d.contacts[1], 0, 1);
  ExpectFires(CheckContactGraph(d), "contact 1 (0, 1) is not after contact 0 (1, 2)");
}

TEST(ValidateContactGraph, AContactOfADestroyedBodyFires) {
  WorldData d = RestingStack();
  d.records[2].alive = false;
  ExpectFires(CheckContactGraph(d), "contact 1 (1, 2) names a body that is not live");
}

TEST(ValidateContactGraph, AContactOfTwoImmovableBodiesFires) {
  WorldData d = RestingStack();
  d.sims[1].type = BodyType::Kinematic;
  ExpectFires(CheckContactGraph(d), "contact 0 (0, 1) joins two bodies neither of which is dynamic");
}

TEST(ValidateContactGraph, AMissingAnchorRecordFires) {
  WorldData d = RestingStack();
  d.contactAnchors.pop_back();
  ExpectFires(CheckContactGraph(d), "2 contacts but 1 anchor records");
}

TEST(ValidateContactGraph, SatCachesOutOfOrderFire) {
  WorldData d = RestingStack();
  d.satCaches.resize(2);
  d.satCaches[0].pairKey = PairKey(1, 2);
  d.satCaches[1].pairKey = PairKey(0, 1);
  ExpectFires(CheckContactGraph(d), "SAT cache 1");
}

// {1, 2} and {3}: two awake islands (the static floor joins none).
TEST(ValidateIslands, TheSleepPassCountMustMatchTheContacts) {
  const WorldData d = RestingStack();
  EXPECT_EQ(CheckIslands(d, 2), "");
  ExpectFires(CheckIslands(d, 3), "into 2 islands, the sleep pass counted 3");
}

TEST(ValidateIslands, AnIslandHalfAsleepFiresNamingBothBodies) {
  WorldData d = RestingStack();
  d.sims[2].awake = false;
  ExpectFires(CheckIslands(d, 2), "contact (1, 2) joins awake body 1 to sleeping body 2");
}

TEST(ValidateIslands, AWholeIslandAsleepPasses) {
  WorldData d = RestingStack();
  d.sims[1].awake = false;
  d.sims[2].awake = false;
  EXPECT_EQ(CheckIslands(d, 1), "");  // only {3} is awake
}

TEST(ValidateIslands, ASleepingBodyWithAVelocityFires) {
  WorldData d = RestingStack();
  d.sims[3].awake = false;
  d.sims[3].linearVelocity = Vec3(0, -1e-9, 0);
  ExpectFires(CheckIslands(d, 1), "body 3 sleeps with a velocity");
}

TEST(ValidateIslands, ASleepingBodyWithoutSleepingFires) {
  WorldData d = RestingStack();
  d.settings.sleeping = false;
  d.sims[3].awake = false;
  ExpectFires(CheckIslands(d, 0), "body 3 sleeps in a world without sleeping");
}

// Every body of RestingStack has a box; a body without a shape collides
// with nothing and has no active proxy.
TEST(ValidateBroadPhase, ALiveBodyWithoutAnActiveProxyFires) {
  WorldData d = RestingStack();
  d.shapes.assign(4, Shape::CreateBox({0.5, 0.5, 0.5}).Value());
  std::vector<BroadPhaseProxy> proxies(4);
  for (std::size_t i = 0; i < proxies.size(); ++i)
    proxies[i].sphere = {.center = Vec3(0, i, 0), .radius = 0.5};
  ASSERT_TRUE(d.broadPhase.Update(proxies));
  EXPECT_EQ(CheckBroadPhase(d, BroadPhaseKind::BruteForce), "");
  proxies[3].active = false;
  ASSERT_TRUE(d.broadPhase.Update(proxies));
  ExpectFires(CheckBroadPhase(d, BroadPhaseKind::BruteForce),
              "body 3's proxy is inactive, but the body is live");
  d.shapes[3].reset();
  EXPECT_EQ(CheckBroadPhase(d, BroadPhaseKind::BruteForce), "");
  d.records[2].alive = false;
  ExpectFires(CheckBroadPhase(d, BroadPhaseKind::BruteForce),
              "body 2's proxy is active, but the body is not live");
}

// The tree as FindPairs builds it passes its own structural check.
TEST(ValidateBroadPhase, ABuiltTreePasses) {
  WorldData d = RestingStack();
  d.shapes.assign(4, Shape::CreateBox({0.5, 0.5, 0.5}).Value());
  d.broadPhase.SetKind(BroadPhaseKind::AabbTree);
  d.broadPhase.SetTinyWorldProxies(0);
  std::vector<BroadPhaseProxy> proxies(4);
  for (std::size_t i = 0; i < proxies.size(); ++i)
    proxies[i].sphere = {.center = Vec3(0, i, 0), .radius = 0.6};
  ASSERT_TRUE(d.broadPhase.Update(proxies));
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  d.broadPhase.FindPairs(pairs, stats);
  ASSERT_EQ(stats.kindUsed, BroadPhaseKind::AabbTree);
  EXPECT_EQ(d.broadPhase.Tree().LeafCount(), 4);
  EXPECT_EQ(CheckBroadPhase(d, stats.kindUsed), "");
}

// A chain of boxes 1-2-3-4 on a floor 0: ColourPairs's colours pass; two
// pairs of one colour sharing a box fail, naming both pairs and the box;
// sharing only the floor (immovable) does not.
TEST(ValidateColours, ColouringsThatShareAMovedBodyFire) {
  const std::vector<ColourInput> pairs = {
      {.bodyA = 0, .bodyB = 1, .movesA = false, .movesB = true},
      {.bodyA = 0, .bodyB = 2, .movesA = false, .movesB = true},
      {.bodyA = 1, .bodyB = 2, .movesA = true, .movesB = true},
      {.bodyA = 2, .bodyB = 3, .movesA = true, .movesB = true},
  };
  std::vector<int> colours;
  std::vector<std::uint32_t> used;
  ColourPairs(pairs, 4, colours, used);
  EXPECT_EQ(CheckColouring(pairs, 4, colours), "");
  EXPECT_EQ(colours[0], colours[1]);  // they share only the floor

  std::vector<int> broken = colours;
  broken[3] = broken[2];  // (1, 2) and (2, 3) both move body 2
  ExpectFires(CheckColouring(pairs, 4, broken),
              "pairs 2 and 3 of colour " + std::to_string(broken[2]) + " both move body 2");
  broken = colours;
  broken[0] = kOverflowColour + 1;
  ExpectFires(CheckColouring(pairs, 4, broken), "pair 0 has colour 25");
  // The overflow colour holds pairs that share bodies by design.
  EXPECT_EQ(CheckColouring(pairs, 4, std::vector<int>(4, kOverflowColour)), "");
}

TEST(ValidateDeathTest, AFailedCheckAbortsWithItsMessage) {
  EXPECT_DEATH(AbortIfInvalid("islands: body 3 sleeps with a velocity"),
               "talus validation failed: islands: body 3 sleeps with a velocity");
  AbortIfInvalid("");  // an empty message is a pass
}

}  // namespace world_validate_test
}  // namespace talus
