# SPDX-License-Identifier: GPL-3.0-or-later
"""Preferences: stored in FreeCAD's parameter group, checked in one place. freecadcmd."""
import unittest

import FreeCAD as App

from hapticad import preferences


class PreferencesTest(unittest.TestCase):
    def setUp(self):
        App.ParamGet("User parameter:BaseApp/Preferences/Mod").RemGroup("HaptiCAD")

    tearDown = setUp

    def test_defaults_when_nothing_is_stored(self):
        self.assertEqual(preferences.load(), preferences.Preferences())
        self.assertEqual(preferences.load().device, "simulated")

    def test_round_trip_through_the_parameter_group(self):
        prefs = preferences.Preferences(device="/dev/hidraw3", servo_rate_hz=2000, accuracy="Fine",
                                        force_limit_n=2.5, workspace_mapping="Fixed scale",
                                        workspace_scale=0.5, overlay_visible=False,
                                        overlay_colour_by="Roughness")
        preferences.save(prefs)
        self.assertEqual(preferences.load(), prefs)
        group = App.ParamGet(preferences.GROUP)
        self.assertEqual(group.GetInt("ServoRateHz"), 2000)
        self.assertEqual(group.GetString("AccuracyPreset"), "Fine")
        self.assertEqual(group.GetFloat("ForceLimitN"), 2.5)

    def test_bad_values_are_refused_and_nothing_is_written(self):
        preferences.save(preferences.Preferences(servo_rate_hz=500))
        for change, message in (({"servo_rate_hz": 50}, "servo rate"), ({"accuracy": "Ultra"}, "accuracy"),
                                ({"force_limit_n": float("nan")}, "force limit"),
                                ({"workspace_scale": 0.0}, "workspace scale"),
                                ({"device": " "}, "device"), ({"workspace_mapping": "Warp"}, "mapping")):
            with self.subTest(change=change):
                with self.assertRaisesRegex(ValueError, message):
                    preferences.update(**change)
        self.assertEqual(preferences.load(), preferences.Preferences(servo_rate_hz=500))

    def test_the_slowest_servo_rate_offered_is_the_slowest_the_loop_runs(self):
        from hapticad import _core
        low, high = preferences.SERVO_RATE_RANGE_HZ
        self.assertEqual((low, high), (_core.min_servo_rate_hz(), 10000))
        preferences.save(preferences.Preferences(servo_rate_hz=low))
        for rate in (low - 1, 100, 199):
            with self.subTest(rate=rate):
                with self.assertRaisesRegex(ValueError, f"servo rate {rate} Hz is outside {low}..{high} Hz"):
                    preferences.update(servo_rate_hz=rate)
        self.assertEqual(preferences.load().servo_rate_hz, low)
        # a rate stored by an older version that allowed it falls back to the default
        App.ParamGet(preferences.GROUP).SetInt("ServoRateHz", 150)
        self.assertEqual(preferences.load().servo_rate_hz, 1000)

    def test_a_hand_edited_bad_value_falls_back_to_its_default_only(self):
        group = App.ParamGet(preferences.GROUP)
        group.SetInt("ServoRateHz", 7)
        group.SetString("AccuracyPreset", "Fine")
        prefs = preferences.load()
        self.assertEqual((prefs.servo_rate_hz, prefs.accuracy), (1000, "Fine"))

    def test_a_custom_accuracy_round_trips_and_builds_the_scene(self):
        import math

        prefs = preferences.Preferences(accuracy="Custom", custom_linear_deflection_mm=0.3,
                                        custom_angular_deflection_deg=20.0, custom_force_shading=False,
                                        custom_refine_edge_mm=2.5)
        preferences.save(prefs)
        self.assertEqual(preferences.load(), prefs)
        group = App.ParamGet(preferences.GROUP)
        self.assertEqual((group.GetString("AccuracyPreset"), group.GetFloat("CustomAngularDeflectionDeg"),
                          group.GetBool("CustomForceShading")), ("Custom", 20.0, False))
        chosen = preferences.scene_accuracy(preferences.load())
        self.assertEqual((chosen.name, chosen.linear_deflection_mm, chosen.force_shading, chosen.refine_edge_mm),
                         ("Custom", 0.3, False, 2.5))
        self.assertAlmostEqual(chosen.angular_deflection_rad, math.radians(20.0), places=12)
        # a preset chosen keeps the custom values for later, and is what the scene uses
        preferences.update(accuracy="Draft")
        self.assertEqual(preferences.scene_accuracy(preferences.load()).name, "Draft")
        self.assertEqual(preferences.load().custom_linear_deflection_mm, 0.3)

    def test_bad_custom_values_are_each_said_and_nothing_is_written(self):
        preferences.save(preferences.Preferences(accuracy="Custom", custom_linear_deflection_mm=0.3))
        with self.assertRaises(ValueError) as raised:
            preferences.update(custom_linear_deflection_mm=0.0, custom_angular_deflection_deg=90.0,
                               custom_refine_edge_mm=0.001)
        message = str(raised.exception)
        for part in ("custom linear deflection 0.0 mm is outside 0.0001..10 mm",
                     "custom angular deflection 90.0 degrees is outside 0.573..85.9436 degrees",
                     "custom refinement edge 0.001 mm is neither 0 (off) nor in 0.01..100 mm"):
            self.assertIn(part, message)
        for change in ({"custom_angular_deflection_deg": float("nan")}, {"custom_force_shading": 1},
                       {"custom_linear_deflection_mm": "0.1"}):
            with self.subTest(change=change):
                with self.assertRaisesRegex(ValueError, "custom"):
                    preferences.update(**change)
        self.assertEqual(preferences.load(),
                         preferences.Preferences(accuracy="Custom", custom_linear_deflection_mm=0.3))
        # a hand-edited bad custom value falls back to its default alone
        App.ParamGet(preferences.GROUP).SetFloat("CustomAngularDeflectionDeg", -3.0)
        prefs = preferences.load()
        self.assertEqual((prefs.accuracy, prefs.custom_linear_deflection_mm, prefs.custom_angular_deflection_deg),
                         ("Custom", 0.3, preferences.DEFAULTS.custom_angular_deflection_deg))


if __name__ == "__main__":
    unittest.main()
