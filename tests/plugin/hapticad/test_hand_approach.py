# SPDX-License-Identifier: GPL-3.0-or-later
"""Where the simulated hand aims (hapticad/hand_approach.py), headless: a hand that
follows its target at a bounded speed is steered over a part, and the targets it is
given are checked: it comes down onto a face slowing as it nears, slides straight
while it rests, and comes over (lift, hover, down) after a jump, onto a step, and when
its proxy is caught; a proxy caught behind the part is let go of (a clutch) and the hand
re-lands. No loop and no GUI: the Feel GUI tests feel the same with the real
loop. Run by freecadcmd."""
import unittest

import numpy as np

from hapticad import hand_approach as ha

MM = 1e-3
DT_S = 0.02  # the Feel panel's timer
TOP_MM = 20.0  # the part's top face, z = 20 mm, looking up
UP = np.array([0.0, 0.0, 1.0])


class Hand:
    """A hand that moves toward its target at up to ``speed_mm_s`` (it lags a fast one)."""

    def __init__(self, at_mm, speed_mm_s=300.0):
        self.tool_w = np.asarray(at_mm, float) * MM
        self.target_w = self.tool_w.copy()
        self.proxy_w = None  # None: the proxy is where the hand is (above the part)
        self.ceiling_mm = None  # held under this z (by a proxy caught under the part), until let go
        self.speed_mm_s = speed_mm_s
        self.targets = []  # every target handed over, mm
        self.path = []  # where the hand was after each move, mm

    def set_target(self, target_w):
        self.target_w = np.asarray(target_w, float)
        self.targets.append(self.target_w / MM)

    def move(self, dt_s):
        way = self.target_w - self.tool_w
        reach = self.speed_mm_s * MM * dt_s
        length = float(np.linalg.norm(way))
        self.tool_w = self.target_w.copy() if length <= reach else self.tool_w + way * reach / length
        if self.ceiling_mm is not None:
            self.tool_w[2] = min(self.tool_w[2], self.ceiling_mm * MM)
        self.path.append(self.tool_w / MM)

    def proxy(self):
        """On the top face above the hand when the hand is in the part, else the hand."""
        if self.proxy_w is not None:
            return self.proxy_w
        p = self.tool_w.copy()
        p[2] = max(p[2], TOP_MM * MM)
        return p


class Clutch:
    """A session's clutch for ``hand``: taking hold restarts the proxy at the hand."""

    def __init__(self, hand):
        self.hand = hand
        self.calls = []

    def let_go(self):
        self.calls.append("let_go")
        self.hand.ceiling_mm = None  # no force holds it now

    def take_hold(self):
        self.calls.append("take_hold")
        self.hand.proxy_w = None

    def hand_w(self):
        return self.hand.tool_w


def steer(hand, approach, seconds):
    """Ticks the approach and the hand together; returns the targets set meanwhile."""
    first = len(hand.targets)
    for _ in range(int(round(seconds / DT_S))):
        approach.step(DT_S)
        hand.move(DT_S)
    return np.array(hand.targets[first:]).reshape(-1, 3)


def steer_until(hand, approach, condition, seconds):
    """Ticks the approach and the hand together until ``condition()``; the seconds it took."""
    for tick in range(int(round(seconds / DT_S))):
        if condition():
            return tick * DT_S
        approach.step(DT_S)
        hand.move(DT_S)
    raise AssertionError(f"not within {seconds} s")


def on_top(x, y=15.0):
    return (np.array([x, y, TOP_MM]), UP)


class HandApproachTest(unittest.TestCase):
    def setUp(self):
        self.hand = Hand([20.0, 15.0, 40.0])
        self.approach = ha.HandApproach(self.hand.set_target, lambda: self.hand.tool_w, self.hand.proxy,
                                        top_mm=TOP_MM)

    def land(self, x=20.0):
        self.approach.aim(on_top(x))
        steer(self.hand, self.approach, 2.0)
        self.assertTrue(self.approach.landed)

    def test_the_first_touch_comes_down_slowing_as_it_nears(self):
        self.approach.aim(on_top(20.0))
        self.assertTrue(self.approach.coming)
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM + ha.CLEAR_MM])  # hover first
        targets = steer(self.hand, self.approach, 2.0)
        self.assertTrue(self.approach.landed)
        self.assertFalse(self.approach.coming)
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM - 1.0])  # 1 mm in
        z = targets[:, 2]
        self.assertTrue((np.diff(z) <= 1e-9).all())  # only down
        speed = -np.diff(z) / DT_S  # mm/s, from one tick to the next
        above = z[1:] - TOP_MM
        self.assertLessEqual(speed.max(), ha.DESCENT_FAST_MM_S + 1e-6)
        near = (above < ha.DESCENT_SLOW_ZONE_MM - 0.5) & (above > 0)
        self.assertTrue(near.any())
        self.assertLessEqual(speed[near].max(), ha.DESCENT_MM_S[1] + 1e-6)  # slow near the face
        self.assertGreaterEqual(speed[near].min(), ha.DESCENT_MM_S[0] - 1e-6)

    def test_resting_on_the_part_it_slides_straight(self):
        self.land()
        for x in np.linspace(20.0, 30.0, 11):  # 1 mm per mouse event
            self.approach.aim(on_top(x))
            np.testing.assert_allclose(self.hand.targets[-1], [x, 15, TOP_MM - 1.0])
            steer(self.hand, self.approach, DT_S)
        self.assertTrue(self.approach.landed)
        self.assertFalse(self.approach.coming)

    def test_after_a_jump_it_comes_over_not_through(self):
        # straight there, the hand was dragged through the part and a step on the way
        # caught its proxy: it lifts off, crosses above the parts' top, comes down
        self.land(8.0)
        self.approach.aim(on_top(130.0))
        self.assertFalse(self.approach.landed)
        np.testing.assert_allclose(self.hand.targets[-1], [8, 15, TOP_MM + ha.CLEAR_MM])  # up first, where it was
        first = len(self.hand.path)
        steer(self.hand, self.approach, 3.0)
        self.assertTrue(self.approach.landed)
        np.testing.assert_allclose(self.hand.targets[-1], [130, 15, TOP_MM - 1.0])
        # between the two points the hand crossed at the crossing height, clear of the part
        path = np.array(self.hand.path[first:])
        across = path[(path[:, 0] > 8.5) & (path[:, 0] < 129.5)]
        self.assertGreater(len(across), 10)
        self.assertGreaterEqual(float(across[:, 2].min()), TOP_MM + ha.CLEAR_MM - 1e-9)

    def test_a_step_up_under_the_cursor_is_come_over(self):
        self.land(20.0)
        step = (np.array([30.0, 15.0, TOP_MM + 5.0]), UP)  # a face 5 mm above the hand
        self.approach.aim(step)
        self.assertFalse(self.approach.landed)
        self.assertGreater(self.hand.targets[-1][2], TOP_MM + 5.0)
        steer(self.hand, self.approach, 3.0)
        np.testing.assert_allclose(self.hand.targets[-1], [30, 15, TOP_MM + 4.0])

    def test_a_caught_proxy_lifts_the_hand_and_brings_it_back(self):
        self.land(20.0)
        self.hand.proxy_w = np.array([60.0, 15.0, TOP_MM]) * MM  # held on a wall the hand left
        steer(self.hand, self.approach, DT_S)  # no mouse move needed
        self.assertFalse(self.approach.landed)
        self.assertTrue(self.approach.coming)
        self.hand.proxy_w = None  # lifted clear, the proxy follows the hand again
        steer(self.hand, self.approach, 3.0)
        self.assertTrue(self.approach.landed)
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM - 1.0])

    def test_pressing_deep_with_friction_is_not_taken_for_caught(self):
        self.land(20.0)
        self.approach.depth_mm = 15.0  # the slider's deepest
        self.approach.aim_again()
        steer(self.hand, self.approach, 1.0)
        # the proxy on the face above the hand, and as far again sideways (friction 1)
        self.hand.proxy_w = self.hand.tool_w + np.array([15.0, 0.0, 15.0]) * MM
        steer(self.hand, self.approach, 0.2)
        self.assertTrue(self.approach.landed)

    def test_the_wheel_while_coming_down_sets_where_it_lands(self):
        self.approach.aim(on_top(20.0))
        steer(self.hand, self.approach, 0.3)
        self.assertTrue(self.approach.coming)
        self.approach.depth_mm = 2.5
        self.approach.aim_again()
        steer(self.hand, self.approach, 2.0)
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM - 2.5])

    def test_off_the_part_it_lifts_off_the_face_it_was_on(self):
        self.land(20.0)
        self.approach.aim(None)
        self.assertFalse(self.approach.landed)
        self.assertFalse(self.approach.coming)
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM + ha.LIFT_MM])

    def with_clutch(self):
        """The approach again, with a clutch: letting go frees the hand; taking hold
        restarts the proxy at the hand (the loop's, feel_session.LiveSession)."""
        clutch = Clutch(self.hand)
        self.approach = ha.HandApproach(self.hand.set_target, lambda: self.hand.tool_w, self.hand.proxy,
                                        top_mm=TOP_MM, clutch=clutch)
        return clutch

    def test_a_proxy_caught_under_the_part_is_let_go_of_and_the_hand_lands_on_top(self):
        # a part moved up over the resting probe: its proxy restarted on the bottom face,
        # under the hand; every way up went through the part, the proxy held below for good
        clutch = self.with_clutch()
        self.land(20.0)
        self.hand.proxy_w = np.array([20.0, 15.0, 12.0]) * MM  # under the bottom, 7 mm below
        self.hand.ceiling_mm = TOP_MM + 2.0  # the force holds it back
        steer(self.hand, self.approach, DT_S)  # caught: it comes over, lifting first
        self.assertEqual(clutch.calls, [])
        # it tried to lift, and the proxy did not come
        took_s = steer_until(self.hand, self.approach, lambda: clutch.calls, 2.0)
        self.assertGreaterEqual(took_s, ha.WAYPOINT_TIMEOUT_S)
        self.assertEqual(clutch.calls, ["let_go"])
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM + ha.CLEAR_MM])  # its hover point
        steer(self.hand, self.approach, 3.0)
        self.assertEqual(clutch.calls, ["let_go", "take_hold"])  # the proxy restarted in the open
        self.assertTrue(self.approach.landed)
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM - 1.0])

    def test_off_the_part_a_caught_proxy_is_let_go_of_clear_of_the_parts(self):
        clutch = self.with_clutch()
        self.land(20.0)
        self.hand.proxy_w = np.array([20.0, 15.0, 12.0]) * MM
        self.hand.ceiling_mm = TOP_MM + 2.0
        self.approach.aim(None)
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM + ha.LIFT_MM])  # lifts off, as ever
        steer_until(self.hand, self.approach, lambda: clutch.calls, 2.0)
        self.assertEqual(clutch.calls, ["let_go"])
        # the face it lifted off may be inside the part now (it moved): clear of the parts instead
        np.testing.assert_allclose(self.hand.targets[-1], [20, 15, TOP_MM + ha.CLEAR_MM])
        steer(self.hand, self.approach, 1.0)
        self.assertEqual(clutch.calls, ["let_go", "take_hold"])
        steer(self.hand, self.approach, 2.0)
        self.assertEqual(clutch.calls, ["let_go", "take_hold"])  # free now: nothing more
        self.assertFalse(self.approach.landed)

    def test_off_the_part_a_free_proxy_is_not_let_go_of(self):
        clutch = self.with_clutch()
        self.land(20.0)
        self.approach.aim(None)
        steer(self.hand, self.approach, 2.0)
        self.assertEqual(clutch.calls, [])

    def test_a_swap_that_leaves_the_proxy_under_the_part_relands_on_the_face_under_the_cursor(self):
        clutch = self.with_clutch()
        self.land(20.0)
        # a 10 mm part moved 7 mm up (17..27): the proxy restarted on its bottom (3 mm away, the top 7),
        # the hand 2 mm in; the cursor now over the top, at x 27, y 8 in an isometric view
        self.hand.proxy_w = np.array([20.0, 15.0, 17.0]) * MM
        self.approach.scene_changed((np.array([27.0, 8.0, TOP_MM + 7.0]), UP), top_mm=TOP_MM + 7.0)
        self.assertEqual(clutch.calls, [])  # not before the loop has taken the new scene
        took_s = steer_until(self.hand, self.approach, lambda: clutch.calls, 1.0)
        self.assertLessEqual(took_s, ha.SWAP_SETTLE_S + DT_S)
        self.assertEqual(clutch.calls, ["let_go"])
        np.testing.assert_allclose(self.hand.targets[-1], [27, 8, TOP_MM + 7.0 + ha.CLEAR_MM])
        steer(self.hand, self.approach, 3.0)
        self.assertEqual(clutch.calls, ["let_go", "take_hold"])
        self.assertTrue(self.approach.landed)
        np.testing.assert_allclose(self.hand.targets[-1], [27, 8, TOP_MM + 7.0 - 1.0])

    def test_a_swap_that_pushes_the_proxy_out_on_the_face_under_the_cursor_changes_nothing(self):
        # the part grew 3 mm under the resting hand: the new top pushes it out, as the
        # hand still aims where it did
        clutch = self.with_clutch()
        self.land(20.0)
        before = len(self.hand.targets)
        self.hand.proxy_w = np.array([20.0, 15.0, TOP_MM + 3.0]) * MM
        self.approach.scene_changed((np.array([23.0, 12.0, TOP_MM + 3.0]), UP), top_mm=TOP_MM + 3.0)
        steer(self.hand, self.approach, 0.5)
        self.assertEqual(clutch.calls, [])
        self.assertTrue(self.approach.landed)
        self.assertEqual(len(self.hand.targets), before)  # no new target

    def test_without_the_tools_position_it_goes_straight(self):
        hand = Hand([20.0, 15.0, 40.0])
        approach = ha.HandApproach(hand.set_target)
        approach.aim(on_top(130.0))
        np.testing.assert_allclose(hand.targets[-1], [130, 15, TOP_MM - 1.0])
        self.assertFalse(approach.coming)



class CastRayTest(unittest.TestCase):
    """The line of sight cast against the felt surface, for a hidden part the view's pick
    does not see: here a 10 mm ball at the origin, and a step of two slabs."""

    @staticmethod
    def ball(p):
        return abs(float(np.linalg.norm(p)) - 10.0)

    def test_it_meets_the_nearest_surface_first(self):
        hit = ha.cast_ray(self.ball, (3.0, 4.0, 100.0), (0.0, 0.0, -1.0), 200.0)
        np.testing.assert_allclose(hit, [3.0, 4.0, np.sqrt(100.0 - 25.0)], atol=2 * ha.RAY_HIT_MM)
        # from inside, the inside of the ball's far side; along a slant
        hit = ha.cast_ray(self.ball, (0.0, 0.0, 0.0), (1.0, 1.0, 0.0), 50.0)
        np.testing.assert_allclose(hit, [10.0 / np.sqrt(2.0)] * 2 + [0.0], atol=2 * ha.RAY_HIT_MM)

        def step(p):  # the top faces z = 10 (x < 0) and z = 15 (x > 0): distances to those planes
            return min(abs(p[2] - 10.0) if p[0] < 0 else np.hypot(p[0], p[2] - 10.0) if p[2] > 10 else 0.0,
                       abs(p[2] - 15.0) if p[0] > 0 else np.hypot(p[0], p[2] - 15.0))

        hit = ha.cast_ray(step, (5.0, 0.0, 40.0), (-1.0, 0.0, -1.0), 100.0)  # passes over the step's edge
        np.testing.assert_allclose(hit, [-25.0, 0.0, 10.0], atol=2 * ha.RAY_HIT_MM)

    def test_it_misses_beside_the_part_and_beyond_its_length(self):
        self.assertIsNone(ha.cast_ray(self.ball, (11.0, 0.0, 100.0), (0.0, 0.0, -1.0), 200.0))
        self.assertIsNone(ha.cast_ray(self.ball, (0.0, 0.0, 100.0), (0.0, 0.0, -1.0), 50.0))
        # grazing the outline, it creeps and counts as a miss rather than looping
        self.assertIsNone(ha.cast_ray(self.ball, (10.01, -100.0, 0.0), (0.0, 1.0, 0.0), 200.0))


if __name__ == "__main__":
    unittest.main()
