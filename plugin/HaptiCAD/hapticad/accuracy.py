# SPDX-License-Identifier: GPL-3.0-or-later
"""Accuracy presets: how finely a part is tessellated for touch, and whether its
curved faces are force-shaded. Designers trade speed for accuracy here.

A preset fixes FreeCAD's tessellation (``MeshPart.meshFromShape``: the largest chord
deviation in mm and the largest angle between neighbouring facet normals), an optional
refinement (the core splits edges longer than a length; off in the presets: with
shading it buys nothing the table shows) and force shading (the spring acts along the exact B-rep normal blended over each facet, so a
coarse tessellation of a curved face feels smooth). ``custom`` takes any values. The
default is the one the speed/accuracy table in BENCHMARKS.md justifies
(``hapticad accuracy-table``). No GUI, no FreeCAD needed.
"""
import math
from dataclasses import dataclass

# what a custom accuracy may take (FreeCAD's tessellator and the core's refinement)
LINEAR_RANGE_MM = (1e-4, 10.0)
ANGULAR_RANGE_RAD = (0.01, 1.5)
# the same in degrees as shown and typed: 4 decimals, rounded inwards (0.573..85.9436)
ANGULAR_RANGE_DEG_SHOWN = (math.ceil(math.degrees(ANGULAR_RANGE_RAD[0]) * 1e4) / 1e4,
                           math.floor(math.degrees(ANGULAR_RANGE_RAD[1]) * 1e4) / 1e4)
REFINE_RANGE_MM = (0.01, 100.0)  # or 0: no refinement
CUSTOM = "Custom"


@dataclass(frozen=True)
class Accuracy:
    name: str
    linear_deflection_mm: float  # largest distance between a facet and its face
    angular_deflection_rad: float  # largest angle between neighbouring facets' normals
    force_shading: bool = True
    refine_edge_mm: float = 0.0  # split longer edges after tessellating (0: no)

    def problems(self):
        """What is wrong with the values, as sentences (empty when fine)."""
        found = []
        def within(value, bounds):
            return (isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
                    and bounds[0] <= value <= bounds[1])

        if not within(self.linear_deflection_mm, LINEAR_RANGE_MM):
            found.append(f"linear deflection {self.linear_deflection_mm!r} mm is outside 0.0001..10 mm")
        if not within(self.angular_deflection_rad, ANGULAR_RANGE_RAD):
            found.append(f"angular deflection {self.angular_deflection_rad!r} rad is outside 0.01..1.5 rad")
        if not (self.refine_edge_mm == 0.0 or within(self.refine_edge_mm, REFINE_RANGE_MM)):
            found.append(f"refinement edge {self.refine_edge_mm!r} mm is neither 0 (off) nor in 0.01..100 mm")
        if not isinstance(self.force_shading, bool):
            found.append(f"force shading {self.force_shading!r} is neither True nor False")
        return found

    def deflections(self):
        """Its deflections as the Preferences page and `hapticad feel` take them: "a linear
        deflection of 0.02 mm and an angular deflection of 5.73 degrees (Fine)"."""
        return (f"a linear deflection of {self.linear_deflection_mm:g} mm and an angular deflection of "
                f"{round(math.degrees(self.angular_deflection_rad), 4):g} degrees ({self.name})")


PRESETS = {
    "Draft": Accuracy("Draft", 0.5, 0.5),
    "Normal": Accuracy("Normal", 0.1, 0.26),
    "Fine": Accuracy("Fine", 0.02, 0.1),
}
# Fine: its force error stays below the 7 % force JND (2.7 % at most on a 25 mm sphere
# 1 mm deep) for 0.1 us more per tick than Normal, whose facets make a 20 % ripple
# (BENCHMARKS.md, speed/accuracy table). Normal and Draft build faster on big models.
DEFAULT = "Fine"


def preset(name=DEFAULT):
    """The preset called ``name``; KeyError listing the presets otherwise."""
    try:
        return PRESETS[name]
    except KeyError:
        raise KeyError(f"accuracy preset {name!r} is not one of {', '.join(PRESETS)}") from None


def custom(linear_deflection_mm, angular_deflection_rad, force_shading=True, refine_edge_mm=0.0):
    """A preset of one's own. ValueError naming what is out of range."""
    accuracy = Accuracy(CUSTOM, linear_deflection_mm, angular_deflection_rad, force_shading, refine_edge_mm)
    found = accuracy.problems()
    if found:
        raise ValueError("; ".join(found))
    return accuracy
