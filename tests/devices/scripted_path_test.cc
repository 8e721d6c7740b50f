// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/scripted_path.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "scripted_paths.h"

namespace hapticad {
namespace {

// The message Validate() throws, or "" when the path is valid.
std::string Problem(const ScriptedPath& p) {
  try {
    p.Validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ScriptedPath, RejectsBadPathsSayingWhichWaypoint) {
  EXPECT_EQ(Problem(testing::ThreeWaypointPath()), "");
  ScriptedPath one;
  one.times_s = {0.5};
  one.positions = {Vec3(1, 2, 3)};
  EXPECT_EQ(Problem(one), "");
  EXPECT_EQ(Problem(ScriptedPath{}), "scripted path: no waypoints");
  ScriptedPath uneven = testing::ThreeWaypointPath();
  uneven.times_s.pop_back();
  EXPECT_EQ(Problem(uneven), "scripted path: 2 times for 3 positions");
  ScriptedPath back = testing::ThreeWaypointPath();
  back.times_s[2] = 0.5;
  EXPECT_EQ(Problem(back), "scripted path: time of waypoint 2 does not increase");
  ScriptedPath still =
      testing::ThreeWaypointPath();  // strictly: two waypoints at one time are refused too
  still.times_s[1] = 0.0;
  EXPECT_EQ(Problem(still), "scripted path: time of waypoint 1 does not increase");
  ScriptedPath nan = testing::ThreeWaypointPath();
  nan.positions[1].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(Problem(nan), "scripted path: waypoint 1 is not finite");
  ScriptedPath inf = testing::ThreeWaypointPath();
  inf.times_s[2] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Problem(inf), "scripted path: waypoint 2 is not finite");
}

TEST(ScriptedPath, LastsUntilItsLastWaypoint) {
  EXPECT_EQ(testing::ThreeWaypointPath().duration_s(), 3.0);
  EXPECT_EQ(ScriptedPath{}.duration_s(), 0.0);
}

TEST(PathCursor, MovesLinearlyWithTheSegmentsSlopeAndRestsAtTheEnds) {
  const ScriptedPath p = testing::ThreeWaypointPath();
  PathCursor cursor(&p);
  PathSample s = cursor.Sample(0.25);
  EXPECT_NEAR((s.position - Vec3(0.025, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.velocity - Vec3(0.1, 0, 0)).norm(), 0.0, 1e-15);
  // at a waypoint: there, moving along the segment that starts there
  s = cursor.Sample(1.0);
  EXPECT_EQ(s.position, Vec3(0.1, 0, 0));
  EXPECT_NEAR((s.velocity - Vec3(0, 0.1, 0)).norm(), 0.0, 1e-15);
  s = cursor.Sample(2.5);
  EXPECT_NEAR((s.position - Vec3(0.1, 0.15, 0)).norm(), 0.0, 1e-15);
  // at and after the last waypoint, and before the first: at rest
  for (const double t : {3.0, 7.0, 0.0, -1.0}) {
    s = cursor.Sample(t);
    EXPECT_EQ(s.velocity, Vec3::Zero()) << t;
    EXPECT_EQ(s.position, t > 1.0 ? Vec3(0.1, 0.2, 0) : Vec3::Zero()) << t;
  }
  // a single waypoint: there at any time
  ScriptedPath one;
  one.times_s = {2.0};
  one.positions = {Vec3(1, 2, 3)};
  PathCursor still(&one);
  for (const double t : {0.0, 2.0, 5.0}) {
    EXPECT_EQ(still.Sample(t).position, Vec3(1, 2, 3)) << t;
    EXPECT_EQ(still.Sample(t).velocity, Vec3::Zero()) << t;
  }
}

TEST(PathCursor, AnyOrderOfTimesGivesWhatAFreshCursorGives) {
  // a recorded trajectory: 2000 waypoints at uneven times (seeded)
  std::mt19937 random(7);
  std::uniform_real_distribution<double> step(1e-4, 2e-3), coordinate(-0.05, 0.05);
  ScriptedPath p;
  double t = 0.5;
  for (int i = 0; i < 2000; ++i) {
    p.times_s.push_back(t);
    p.positions.emplace_back(coordinate(random), coordinate(random), coordinate(random));
    t += step(random);
  }
  p.Validate();
  // mostly forward, as a servo clock runs, with rewinds (a restarted session) and jumps
  PathCursor cursor(&p);
  std::uniform_real_distribution<double> anywhere(0.0, p.duration_s() + 0.5);
  double clock = 0.0;
  int rewinds = 0;
  for (int k = 0; k < 20000; ++k) {
    if (k % 500 == 499) {
      clock = anywhere(random);
      ++rewinds;
    } else {
      clock += 1e-4;
    }
    const PathSample s = cursor.Sample(clock);
    PathCursor fresh(&p);
    const PathSample expected = fresh.Sample(clock);
    ASSERT_EQ(s.position, expected.position) << "t " << clock << " sample " << k;
    ASSERT_EQ(s.velocity, expected.velocity) << "t " << clock << " sample " << k;
  }
  EXPECT_EQ(rewinds, 40);
  // and a fresh cursor is right: on the segment round the time, by its own endpoints
  PathCursor fresh(&p);
  const double mid = 0.5 * (p.times_s[1234] + p.times_s[1235]);
  const PathSample s = fresh.Sample(mid);
  EXPECT_NEAR((s.position - 0.5 * (p.positions[1234] + p.positions[1235])).norm(), 0.0, 1e-12);
  EXPECT_NEAR(
      (s.velocity - (p.positions[1235] - p.positions[1234]) / (p.times_s[1235] - p.times_s[1234]))
          .norm(),
      0.0, 1e-9);
}

TEST(PathCursor, SamplingDoesNotAllocate) {
  const ScriptedPath p = testing::ThreeWaypointPath();
  PathCursor cursor(&p);
  testing::AllocationCounter counter;
  double sum = 0.0;
  for (int k = 0; k < 1000; ++k) sum += cursor.Sample((k % 400) * 1e-2).position.x();
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace hapticad
