# SPDX-License-Identifier: GPL-3.0-or-later
"""Where the simulated hand aims: how it comes to the part and presses on it. The Feel
panel's mouse steering (gui/feel_view.py) hands it the face under the cursor and ticks
it from a timer; no GUI here.

Points are world millimetres, normals unit vectors; ``set_target`` takes metres, and
``tool_w()`` / ``proxy_w()`` give the loop's last device and proxy positions in metres.

The hand presses ``depth_mm`` into the face under the cursor. It goes straight there
only while it rests on the part and the new point is near. Otherwise it comes over,
as a hand lowers a finger, not dragged through whatever stands between:

1. lift: when it rests on the part, off the face it rests on, along its normal (for a
   face that looks up, to CLEAR_MM above the parts' top);
2. hover: HOVER_MM off the new face along its normal (for a face that looks up, at
   least CLEAR_MM above the parts' top);
3. down onto the face: at DESCENT_FAST_MM_S to DESCENT_SLOW_ZONE_MM above it, then
   slowing as it nears, so it lands without a knock.

It comes over on the session's first touch, when the cursor comes back onto the part,
when a face stands above the hand (a step up), when the cursor jumped (the new point
farther than JUMP_MM from the hand), and when the proxy is held far from the hand
(caught: the hand went where the proxy could not follow). Off the part, the hand lifts
LIFT_MM off the face it was on.

A proxy caught on the far side of a part is not freed by any of those ways: a part moved
up over the resting probe restarts the proxy on its bottom face (the nearer one), and
every way to its top, or off the part, goes up through it, the proxy held under the
bottom and the hand with it at the force limit, for good. So with a ``clutch`` (the
session's: the simulated hand only; a real user moves the handle out) the hand lets go
and re-lands as at the first touch: the force stops (the clutch held), the hand moves
freely to its hover point (off the part: the hover point of the face it left, clear of
the parts), the proxy restarts there, in the open, and the hand comes down (off the
part: stays there). It does so when the hand reached a lift or hover point, or off the
part where it lifts to (or tried for WAYPOINT_TIMEOUT_S), and the proxy did not come
with it (held more than HELD_MM away: in the open it is where the hand is); and at once
after a scene swap (``scene_changed``) that left the proxy off the face under the cursor
with the hand deep under that face (a step up the hand did not come over).

Where the cursor points: the view's own pick gives the point under the cursor on the
parts drawn. A hidden part is not drawn, yet it is felt (a Cut or Fillet made after
tagging hides the tagged part, and Feel says so): there the line of sight through the
cursor is cast against the felt surface itself (cast_ray).
"""
import numpy as np

MM = 1e-3
LIFT_MM = 5.0  # where the hand goes when the cursor leaves the part: lifted off along the normal
HOVER_MM = 5.0  # coming to a face it is not on: this far off it, along its normal, first
CLEAR_MM = 10.0  # above the parts' top, where a hand crosses to a face that looks up
ARRIVED_MM = 1.0  # near enough a lift or hover point to go on
WAYPOINT_TIMEOUT_S = 1.0  # goes on then anyway (a hand held back by something)
# How the hand comes down: a target stepped onto the face landed at 1.45 N on ABS
# pressed to 0.40 N, a knock on every first touch. At 150 mm/s to 4 mm above the face,
# then slowing as it nears (the distance left / 0.1 s, 30 to 10 mm/s), it lands at
# 1.16x / 1.10x / 1.03x what it then presses at 1 / 1.5 / 3 mm, in 0.4-0.6 s from 10 mm
# above (the hand lags a fast target by some 3 mm: slow down before the face)
DESCENT_FAST_MM_S = 150.0
DESCENT_SLOW_ZONE_MM = 4.0
DESCENT_TIME_S = 0.1
DESCENT_MM_S = (10.0, 30.0)
STEP_MM = 2.0  # a face under the cursor this much (beyond the press) above the hand: a step up
# A cursor that jumped: straight there, a reviewer's jump along a toothbrush dragged
# the hand through a 1.5 mm step, its proxy caught on the step's wall 101 mm away.
# A drag moves the target 1-5 mm per mouse event, the hand lagging some 3 mm.
JUMP_MM = 10.0
HELD_MM = 2.0  # at a lift or hover point the proxy is where the hand is: held this far away, caught behind a part
SWAP_SETTLE_S = 0.05  # after a scene swap, looked at this much later: the loop takes the new scene at its next tick
RAY_HIT_MM = 1e-3  # a cast ray this near the surface has met it
RAY_STEPS = 200  # steps a cast ray takes at most (it creeps along a face it grazes: a miss)


class HandApproach:
    def __init__(self, set_target, tool_w=None, proxy_w=None, top_mm=None, clutch=None):
        """``tool_w``: None aims straight at every face (no approach); ``proxy_w``: None
        does not watch for a caught proxy; ``top_mm``: the parts' highest z; ``clutch``:
        None never lets go (a proxy caught behind a part stays caught), or what lets the
        hand go and re-land: ``let_go()`` (the force stops, the hand moves freely, the
        loop's tool position stays where it was), ``take_hold()`` (the proxy restarts at
        the hand, as at a session's start, the force ramps in from zero) and ``hand_w()``
        (where the hand is, m, let go or not): feel_session.LiveSession's."""
        self.set_target = set_target
        self.tool_w = tool_w
        self.proxy_w = proxy_w
        self.top_mm = top_mm
        self.clutch = clutch
        self.freeing_w = None  # let go: where the hand goes, at no force, and the proxy restarts
        self.off_w = None  # off the part: where the hand lifts to (until it is there, or tried)
        self._swapped = None  # [surface, seconds to wait] after a scene swap, until a step looks at it
        self.depth_mm = 1.0
        self.last_surface = None  # (point_mm, normal) under the cursor last
        self.resting = None  # (point_mm, normal) of the face the hand rests on, while landed
        self.landed = False  # the hand is on the part (not lifted, not coming)
        self.lift_w = None  # while lifting off the face it rested on
        self.approach = None  # (hover_w, press_w) while coming to the part
        self.descent_left_mm = None  # while coming down from the hover point: how far is left
        self._waited_s = 0.0  # at the current lift or hover point

    @property
    def coming(self):
        """True while the hand lifts, hovers or comes down (``step`` has work)."""
        return self.approach is not None

    def aim(self, surface):
        """The cursor is on ``surface`` = (point_mm, normal) of a part, or off the parts
        (None)."""
        if surface is not None:
            self.last_surface = (np.asarray(surface[0], float), np.asarray(surface[1], float))
        if self.last_surface is None:
            return
        point_mm, normal = self.last_surface
        if surface is None:
            self.landed = False
            self.resting = self.lift_w = self.approach = self.descent_left_mm = None
            if self.off_w is None and self.freeing_w is None:
                self._waited_s = 0.0
            self.off_w = (point_mm + LIFT_MM * normal) * MM
            if self.freeing_w is not None:  # let go: clear of the parts, as it would be had it not been
                self.freeing_w = self._hover_w(point_mm, normal)
            self.set_target(self.freeing_w if self.freeing_w is not None else self.off_w)
            return
        self.off_w = None
        press_w = (point_mm - self.depth_mm * normal) * MM
        if self.landed and self.tool_w is not None and self._must_come_over(point_mm, normal, press_w):
            self.landed = False
            self.lift_w = self._lift_point()
            self._waited_s = 0.0
        if self.landed or self.tool_w is None:
            self.resting = self.last_surface
            self.set_target(press_w)
            return
        if self.approach is None and self.freeing_w is None:
            self._waited_s = 0.0
        self.approach = (self._hover_w(point_mm, normal), press_w)
        if self.freeing_w is not None:  # let go: it goes to the new hover point free
            self.freeing_w = self.approach[0]
        self.set_target(self._target())

    def scene_changed(self, surface, top_mm=None):
        """The parts changed shape or moved (a new scene swapped into the loop), the cursor
        now on ``surface`` (as ``aim`` takes it; None: off the parts) and the parts' top at
        ``top_mm``. SWAP_SETTLE_S later (``step``), the loop having taken the new scene: a hand
        resting on the part whose proxy the swap restarted off the face under the cursor,
        the hand deep under that face (a part moved up over the probe: the proxy restarts
        on its bottom face), lets go and re-lands on that face as at the first touch.
        Otherwise nothing changes: a part grown under the hand pushes it out, and the hand
        aims where it did until the mouse moves."""
        if top_mm is not None:
            self.top_mm = top_mm
        self._swapped = [surface, SWAP_SETTLE_S]

    def aim_again(self):
        """Aims at the face it was on with the current depth (the wheel or the slider
        changed it): felt at once, not at the next mouse move; coming down, it lands at
        the new depth."""
        if self.last_surface is None:
            return
        point_mm, normal = self.last_surface
        press_w = (point_mm - self.depth_mm * normal) * MM
        if self.landed:
            self.set_target(press_w)
        elif self.approach is not None:
            self.approach = (self.approach[0], press_w)

    def step(self, dt_s):
        """``dt_s`` later: on along the way (lift, hover, down), or, resting on the part,
        over again if the proxy is caught where the hand left it; let go (a proxy caught
        behind a part), on to where the proxy restarts."""
        if self._swapped is not None:
            self._swapped[1] -= dt_s
            if self._swapped[1] <= 0:
                surface, self._swapped = self._swapped[0], None
                if self._trapped_by_swap(surface):
                    self.last_surface = (np.asarray(surface[0], float), np.asarray(surface[1], float))
                    self._reland()
                    return
        if self.freeing_w is not None:
            if self._reached(self.freeing_w, dt_s, self.clutch.hand_w):
                self.freeing_w = self.off_w = None
                self.clutch.take_hold()  # the proxy restarts at the hand, in the open
                if self.approach is not None:  # down from the hover point, where the hand is
                    self.set_target(self._target())
            return
        if self.approach is None:
            if self.off_w is not None:
                if self._reached(self.off_w, dt_s):
                    if self._held():  # lifting off did not bring the proxy: caught behind the part
                        # (the face it lifts off may be inside the part now: clear of the parts instead)
                        self._let_go(self._hover_w(*self.last_surface))
                    else:
                        self.off_w = None
            elif self.landed and self._caught():
                self.aim(self.last_surface)
            return
        if self.lift_w is not None:
            if self._reached(self.lift_w, dt_s):
                self.lift_w = None
                self._waited_s = 0.0
                if self._held():  # lifted, and the proxy did not come: caught behind the part
                    self._let_go(self.approach[0])
                else:
                    self.set_target(self._target())
            return
        hover_w, press_w = self.approach
        if self.descent_left_mm is None:
            if self._reached(hover_w, dt_s):
                if self._held():
                    self._let_go(hover_w)
                else:
                    self.descent_left_mm = float(np.linalg.norm(hover_w - press_w)) / MM
            return
        above_mm = self.descent_left_mm - self.depth_mm  # the face is depth_mm up the way
        if above_mm > DESCENT_SLOW_ZONE_MM:
            self.descent_left_mm = max(self.depth_mm + DESCENT_SLOW_ZONE_MM,
                                       self.descent_left_mm - DESCENT_FAST_MM_S * dt_s)
        else:
            self.descent_left_mm -= float(np.clip(above_mm / DESCENT_TIME_S, *DESCENT_MM_S)) * dt_s
        if self.descent_left_mm > 0:
            self.set_target(self._target())
            return
        self.approach = self.descent_left_mm = None
        self.landed = True
        self.resting = self.last_surface
        self.set_target(press_w)

    def halt(self):
        """No more aiming: a hand on its way stops where it is (the session ends: a hand
        let go stays so)."""
        self.lift_w = self.approach = self.descent_left_mm = self.freeing_w = self.off_w = self._swapped = None

    # --- the way -----------------------------------------------------------------------

    def _must_come_over(self, point_mm, normal, press_w):
        tool_w = self.tool_w()
        step_up = float(np.dot(tool_w / MM - point_mm, normal)) < -(self.depth_mm + STEP_MM)
        jump = float(np.linalg.norm(tool_w - press_w)) / MM > JUMP_MM
        return step_up or jump or self._caught()

    def _apart_mm(self):
        return float(np.linalg.norm(self.proxy_w() - self.tool_w())) / MM

    def _caught(self):
        """The proxy is held much farther from the hand than pressing puts it (at most
        the depth, and as far again sideways under friction up to 1)."""
        if self.proxy_w is None or self.tool_w is None:
            return False
        return self._apart_mm() > 2.0 * self.depth_mm + STEP_MM

    def _held(self):
        """At a lift or hover point, or off the part (in the open, where the proxy is
        where the hand is), the proxy is held away from the hand: caught behind a part,
        and there is a clutch to let go with."""
        return self.clutch is not None and self.proxy_w is not None and self._apart_mm() > HELD_MM

    def _trapped_by_swap(self, surface):
        """After a scene swap: resting on the part with a clutch, the proxy is off the
        face under the cursor (more than STEP_MM off its plane) and the hand deep under
        that face (more than STEP_MM beyond the press)."""
        if surface is None or not self.landed or self.clutch is None or self.proxy_w is None:
            return False
        point_mm, normal = np.asarray(surface[0], float), np.asarray(surface[1], float)
        off_face_mm = abs(float(np.dot(self.proxy_w() / MM - point_mm, normal)))
        under_mm = -float(np.dot(self.tool_w() / MM - point_mm, normal))
        return off_face_mm > STEP_MM and under_mm > self.depth_mm + STEP_MM

    def _reland(self):
        """Lets go and comes to the face last under the cursor as at the first touch:
        to its hover point free, then down."""
        point_mm, normal = self.last_surface
        self.landed = False
        self.resting = self.lift_w = self.descent_left_mm = self.off_w = None
        self.approach = (self._hover_w(point_mm, normal), (point_mm - self.depth_mm * normal) * MM)
        self._let_go(self.approach[0])

    def _let_go(self, to_w):
        """The force stops and the hand goes to ``to_w`` freely; the proxy restarts there
        (``step``)."""
        self.clutch.let_go()
        self.freeing_w = to_w
        self._waited_s = 0.0
        self.set_target(to_w)

    def _hover_w(self, point_mm, normal):
        hover_mm = point_mm + HOVER_MM * normal
        if self.top_mm is not None and normal[2] > 0.5:
            hover_mm[2] = max(hover_mm[2], self.top_mm + CLEAR_MM)
        return hover_mm * MM

    def _lift_point(self):
        return self._hover_w(*(self.resting if self.resting is not None else self.last_surface))

    def _reached(self, point_w, dt_s, where_w=None):
        """True once the hand (``where_w()``, by default the loop's tool) is at ``point_w``,
        or has tried for WAYPOINT_TIMEOUT_S."""
        self._waited_s += dt_s
        there = np.linalg.norm((where_w or self.tool_w)() - point_w) < ARRIVED_MM * MM
        if there or self._waited_s >= WAYPOINT_TIMEOUT_S:
            self._waited_s = 0.0
            return True
        return False

    def _target(self):
        """Where the hand aims on its way: where it goes let go, the lift point, the hover
        point, or on the way down from it to the press point (the cursor moved while coming
        down: as far down over the new point)."""
        if self.freeing_w is not None:
            return self.freeing_w
        if self.lift_w is not None:
            return self.lift_w
        hover_w, press_w = self.approach
        if self.descent_left_mm is None:
            return hover_w
        way = hover_w - press_w
        length_mm = float(np.linalg.norm(way)) / MM
        return press_w + way * min(1.0, self.descent_left_mm / length_mm) if length_mm > 0 else press_w


def cast_ray(distance_mm, origin_mm, direction, length_mm):
    """The first point (mm) where the ray from ``origin_mm`` along ``direction`` meets a
    surface, within ``length_mm`` of the origin, or None when it misses. ``distance_mm(p)``
    is how far point p (mm) is from the nearest point of the surface (unsigned, mm).
    Sphere tracing: the ray steps on by that distance, within which no surface lies, so
    it never steps through one; a ray that grazes a face takes many short steps, and
    after RAY_STEPS counts as missing it (the cursor is at the part's outline)."""
    origin = np.asarray(origin_mm, float)
    direction = np.asarray(direction, float)
    direction = direction / np.linalg.norm(direction)
    travelled = 0.0
    for _ in range(RAY_STEPS):
        point = origin + travelled * direction
        distance = float(distance_mm(point))
        if distance <= RAY_HIT_MM:
            return point
        travelled += distance
        if travelled > length_mm:
            return None
    return None
