# SPDX-License-Identifier: GPL-3.0-or-later
"""The haptic material database.

Shipped: resources/materials/materials.csv, one material per row: friction against a
dry fingertip (mu_s, mu_d and the plausible range of mu_d), Young's modulus, density,
the contact stiffness to render, and the source of each value.

User additions and overrides live in the user's FreeCAD folder, never in the
installation: FreeCAD 0.20 material cards (.FCMat) in <UserAppData>/Material, beside
FreeCAD's own cards, carrying the haptic values under keys prefixed ``HaptiCAD_``
(cards without them are FreeCAD's and are left alone), and an optional
<UserAppData>/HaptiCAD/materials.csv. Later sources override earlier ones by name.

A bad row or card is rejected with ``file:line: problem`` and every other material
still loads: a value that is no number, a card lacking a key, mu_d above mu_s or outside
the entry's own mu_min..mu_max, a friction or stiffness beyond what a surface's
properties take (they would clip it without a word). No FreeCAD import: usable headless and from the CLI.
"""
import csv
import glob
import math
import os
import re
from dataclasses import dataclass

from . import MATERIALS_FILE, __version__

# the ranges a HapticSurface's Friction and Stiffness properties take (surface_object's
# FRICTION_MAX and STIFFNESS_MIN/MAX_N_PER_MM, which import FreeCAD; test_materials checks
# they agree): a material beyond them would be clipped there without a word
FRICTION_MAX = 1e3
STIFFNESS_RANGE_N_PER_MM = (1e-3, 1e3)

COLUMNS = (
    "name",
    "mu_static",
    "mu_dynamic",
    "mu_min",
    "mu_max",
    "youngs_modulus_gpa",
    "density_kg_m3",
    "stiffness_n_per_mm",
    "mu_source",
    "bulk_source",
)


@dataclass(frozen=True)
class Material:
    name: str
    static_friction: float  # mu_s
    dynamic_friction: float  # mu_d
    friction_min: float  # plausible range of mu_d
    friction_max: float
    youngs_modulus_gpa: float
    density_kg_m3: float
    stiffness_n_per_mm: float  # contact stiffness to render
    friction_source: str
    bulk_source: str
    origin: str  # "file:line" it was read from

    def as_dict(self):
        return {
            "name": self.name,
            "mu_static": self.static_friction,
            "mu_dynamic": self.dynamic_friction,
            "mu_range": [self.friction_min, self.friction_max],
            "youngs_modulus_gpa": self.youngs_modulus_gpa,
            "density_kg_m3": self.density_kg_m3,
            "stiffness_n_per_mm": self.stiffness_n_per_mm,
            "mu_source": self.friction_source,
            "bulk_source": self.bulk_source,
            "origin": self.origin,
        }


class MaterialDatabase:
    """Materials by name, in file order, plus the rows that were rejected."""

    def __init__(self):
        self._materials = {}
        self.errors = []  # "file:line: problem"

    def names(self):
        return list(self._materials)

    def get(self, name):
        try:
            return self._materials[name]
        except KeyError:
            raise KeyError(
                f"unknown material {name!r}; known: {', '.join(self._materials)}"
            ) from None

    def __contains__(self, name):
        return name in self._materials

    def __iter__(self):
        return iter(self._materials.values())

    def __len__(self):
        return len(self._materials)

    def add(self, material):
        """Adds or replaces (a later file overrides an earlier one)."""
        self._materials[material.name] = material

    def load_csv(self, path):
        """Reads one CSV file; bad rows go to self.errors, good ones are added."""
        try:
            # utf-8-sig: a spreadsheet's "CSV UTF-8" starts with a byte-order mark, which
            # made the first column "\ufeffname" and refused the whole file
            with open(path, newline="", encoding="utf-8-sig") as handle:
                lines = list(enumerate(handle, start=1))
        except UnicodeDecodeError as exc:
            self.errors.append(f"{path}: not UTF-8 text ({exc.reason} at byte {exc.start}); save it as CSV UTF-8")
            return
        except OSError as exc:
            self.errors.append(f"{path}: cannot read: {exc.strerror}")
            return
        rows = [(n, line) for n, line in lines if line.strip() and not line.lstrip().startswith("#")]
        if not rows:
            self.errors.append(f"{path}: no header row")
            return
        header_line, header_text = rows[0]
        header = next(csv.reader([header_text]))
        header = [h.strip() for h in header]
        missing = [c for c in COLUMNS if c not in header]
        if missing:
            self.errors.append(f"{path}:{header_line}: header lacks column(s) {', '.join(missing)}")
            return
        seen = set()
        for number, text in rows[1:]:
            try:
                values = next(csv.reader([text]))
                if len(values) != len(header):
                    raise ValueError(f"{len(values)} fields, the header has {len(header)}")
                material = _parse_row(dict(zip(header, (v.strip() for v in values))), f"{path}:{number}")
                if material.name in seen:
                    raise ValueError(f"material {material.name!r} appears twice in this file")
                seen.add(material.name)
                self.add(material)
            except ValueError as exc:
                self.errors.append(f"{path}:{number}: {exc}")


def _number(row, key, positive=False, non_negative=False):
    text = row[key]
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{key} = {text!r} is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{key} = {text} is not finite")
    if positive and value <= 0:
        raise ValueError(f"{key} = {text} must be > 0")
    if non_negative and value < 0:
        raise ValueError(f"{key} = {text} must be >= 0")
    return value


def _parse_row(row, origin):
    """A Material of a row of strings by column; ValueError naming the column (first word)
    when a value is not a number, is out of its range or contradicts the row."""
    name = row["name"]
    if not name:
        raise ValueError("empty name")
    mu_min = _number(row, "mu_min", non_negative=True)
    mu_max = _number(row, "mu_max", non_negative=True)
    if mu_min > mu_max:
        raise ValueError(f"mu_min = {mu_min} exceeds mu_max = {mu_max}")
    mu_s = _number(row, "mu_static", non_negative=True)
    mu_d = _number(row, "mu_dynamic", non_negative=True)
    for column, mu in (("mu_static", mu_s), ("mu_dynamic", mu_d)):
        if mu > FRICTION_MAX:  # a surface's friction property would clip it there
            raise ValueError(f"{column} = {row[column]} is above {FRICTION_MAX:g}, the most a surface's friction takes")
    # mu_min..mu_max is mu_d's plausible range (the shipped file's header): mu_s, the peak a
    # finger overcomes to start sliding, lies above mu_d and may lie above the range
    if mu_d > mu_s:
        raise ValueError(f"mu_dynamic = {row['mu_dynamic']} is above mu_static = {row['mu_static']}: sliding would "
                         "feel stickier than starting to slide, which few materials do (were the two swapped?)")
    if not mu_min <= mu_d <= mu_max:
        raise ValueError(f"mu_dynamic = {row['mu_dynamic']} is outside its own plausible range mu_min..mu_max "
                         f"{mu_min:g}..{mu_max:g}")
    stiffness = _number(row, "stiffness_n_per_mm", positive=True)
    low, high = STIFFNESS_RANGE_N_PER_MM
    if not low <= stiffness <= high:  # a surface's Stiffness property would clip it silently
        raise ValueError(f"stiffness_n_per_mm = {stiffness:g} is outside {low:g}..{high:g} N/mm, the range a "
                         "surface's stiffness takes")
    return Material(
        name=name,
        static_friction=mu_s,
        dynamic_friction=mu_d,
        friction_min=mu_min,
        friction_max=mu_max,
        youngs_modulus_gpa=_number(row, "youngs_modulus_gpa", positive=True),
        density_kg_m3=_number(row, "density_kg_m3", positive=True),
        stiffness_n_per_mm=stiffness,
        friction_source=row["mu_source"],
        bulk_source=row["bulk_source"],
        origin=origin,
    )


FCMAT_PREFIX = "HaptiCAD_"
# card key -> (Material field, unit parser)
FCMAT_KEYS = {
    "HaptiCAD_StaticFriction": "static_friction",
    "HaptiCAD_DynamicFriction": "dynamic_friction",
    "HaptiCAD_FrictionMin": "friction_min",
    "HaptiCAD_FrictionMax": "friction_max",
    "HaptiCAD_ContactStiffness": "stiffness_n_per_mm",
    "HaptiCAD_FrictionSource": "friction_source",
    "HaptiCAD_BulkSource": "bulk_source",
}
# a number, then its unit with or without a space ("0.3 N/mm", "0.3N/mm": a class of
# number characters took the N of N/mm)
_QUANTITY = re.compile(r"^\s*([-+]?(?:(?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?|inf(?:inity)?|nan))\s*(.*?)\s*$",
                       re.IGNORECASE)
# unit -> how many of it make one of ours (dividing keeps 2300 MPa exactly 2.3 GPa)
_PRESSURE_IN_GPA = {"": 1e9, "pa": 1e9, "kpa": 1e6, "mpa": 1e3, "gpa": 1.0}
_DENSITY_IN_KG_M3 = {"": 1.0, "kg/m^3": 1.0, "kg/m3": 1.0, "g/cm^3": 1e-3, "g/cm3": 1e-3}
_STIFFNESS_IN_N_PER_MM = {"": 1.0, "n/mm": 1.0, "n/m": 1e3, "kn/m": 1.0}


def _quantity(text, units, key):
    """Number and unit, converted by the `units` table; ValueError names the key."""
    match = _QUANTITY.match(text)
    if not match:
        raise ValueError(f"{key} = {text!r} is not a number")
    try:
        number = float(match.group(1))
    except ValueError:
        raise ValueError(f"{key} = {text!r} is not a number") from None
    unit = match.group(2).replace(" ", "").lower()
    if unit not in units:
        raise ValueError(f"{key} = {text!r}: unknown unit {match.group(2)!r}")
    return number / units[unit]


def read_fcmat(path):
    """(Material or None, errors) of a FreeCAD material card. None, without errors, for a
    card that carries no HaptiCAD values (one of FreeCAD's own)."""
    try:
        with open(path, encoding="utf-8-sig") as handle:
            lines = list(enumerate(handle, start=1))
    except (OSError, UnicodeDecodeError) as exc:
        return None, [f"{path}: cannot read: {exc}"]
    values, where = {}, {}
    for number, raw in lines:
        line = raw.strip()
        if not line or line[0] in ";#[":
            continue
        if "=" not in line:
            return None, [f"{path}:{number}: expected 'key = value', got {line!r}"]
        key, value = (part.strip() for part in line.split("=", 1))
        values[key], where[key] = value, number
    if not any(k.startswith(FCMAT_PREFIX) for k in values):
        return None, []
    first = min(where[k] for k in values if k.startswith(FCMAT_PREFIX))
    # FreeCAD's own keys too: a card lacking YoungsModulus was "YoungsModulus = '' is not a number"
    missing = [k for k in ("Name", *FCMAT_KEYS, "YoungsModulus", "Density") if k not in values]
    if missing:
        return None, [f"{path}:{first}: the card lacks {', '.join(missing)}"]
    row = {"name": values["Name"], "mu_source": values["HaptiCAD_FrictionSource"],
           "bulk_source": values["HaptiCAD_BulkSource"]}
    try:
        for key, column in (("HaptiCAD_StaticFriction", "mu_static"), ("HaptiCAD_DynamicFriction", "mu_dynamic"),
                            ("HaptiCAD_FrictionMin", "mu_min"), ("HaptiCAD_FrictionMax", "mu_max")):
            row[column] = values[key]
        row["stiffness_n_per_mm"] = str(_quantity(values["HaptiCAD_ContactStiffness"], _STIFFNESS_IN_N_PER_MM,
                                                  "HaptiCAD_ContactStiffness"))
        row["youngs_modulus_gpa"] = str(_quantity(values["YoungsModulus"], _PRESSURE_IN_GPA, "YoungsModulus"))
        row["density_kg_m3"] = str(_quantity(values["Density"], _DENSITY_IN_KG_M3, "Density"))
    except ValueError as exc:
        key = str(exc).split(" ", 1)[0]
        return None, [f"{path}:{where.get(key, first)}: {exc}"]
    try:
        return _parse_row(row, f"{path}:{first}"), []
    except ValueError as exc:
        column = str(exc).split(" ", 1)[0]
        card_key = {"mu_static": "HaptiCAD_StaticFriction", "mu_dynamic": "HaptiCAD_DynamicFriction",
                    "mu_min": "HaptiCAD_FrictionMin", "mu_max": "HaptiCAD_FrictionMax",
                    "youngs_modulus_gpa": "YoungsModulus", "density_kg_m3": "Density",
                    "stiffness_n_per_mm": "HaptiCAD_ContactStiffness"}.get(column, "Name")
        return None, [f"{path}:{where.get(card_key, first)}: {exc}"]


def write_fcmat(material, path, overwrite=True):
    """Writes a FreeCAD 0.20 material card FreeCAD's own reader and editor accept. With
    overwrite=False a file already at ``path`` (a card the user may have edited) is kept as it
    is. Returns whether ``path`` holds this card: False when a different file was kept. Raises OSError."""
    card = os.path.splitext(os.path.basename(path))[0]
    lines = [
        f"; {card}",
        "; HaptiCAD haptic material (GPL-3.0-or-later)",
        "; information about the content of such cards can be found on the wiki:",
        "; https://www.freecadweb.org/wiki/Material",
        f"; file written by HaptiCAD {__version__}",
        "",
        "[General]",
        f"Name = {material.name}",
        f"Description = Haptic material: friction against a dry fingertip ({material.friction_source})",
        "",
        "[Mechanical]",
        f"Density = {material.density_kg_m3:g} kg/m^3",
        f"YoungsModulus = {material.youngs_modulus_gpa * 1000:g} MPa",
        "",
        "[HaptiCAD]",
        f"HaptiCAD_StaticFriction = {material.static_friction:g}",
        f"HaptiCAD_DynamicFriction = {material.dynamic_friction:g}",
        f"HaptiCAD_FrictionMin = {material.friction_min:g}",
        f"HaptiCAD_FrictionMax = {material.friction_max:g}",
        f"HaptiCAD_ContactStiffness = {material.stiffness_n_per_mm:g} N/mm",
        f"HaptiCAD_FrictionSource = {material.friction_source}",
        f"HaptiCAD_BulkSource = {material.bulk_source}",
        "",
    ]
    text = "\n".join(lines)
    try:
        # "x" checks and creates in one step: no card made meanwhile is written over
        handle = open(path, "w" if overwrite else "x", encoding="utf-8")
    except FileExistsError:  # only without overwrite
        try:
            with open(path, encoding="utf-8") as held:
                return held.read() == text
        except (OSError, UnicodeDecodeError):  # a folder, a binary file: not this card
            return False
    with handle:
        handle.write(text)
    return True


def user_data_dir():
    """FreeCAD's user data folder (<UserAppData>), from FreeCAD when it is loaded."""
    try:
        import FreeCAD

        return FreeCAD.getUserAppDataDir()
    except ImportError:
        base = os.environ.get("XDG_DATA_HOME") or os.path.join(os.path.expanduser("~"), ".local", "share")
        return os.path.join(base, "FreeCAD")


def user_sources(data_dir=None):
    """The user's material files, in the order they apply: CSV, then cards by name."""
    data_dir = data_dir or user_data_dir()
    csv_path = os.path.join(data_dir, "HaptiCAD", "materials.csv")
    cards = sorted(glob.glob(os.path.join(data_dir, "Material", "*.FCMat")))
    return ([csv_path] if os.path.exists(csv_path) else []) + cards


def load_database(extra_files=(), include_user=True, data_dir=None):
    """The shipped database, then the user's files, then each extra file; a later
    source overrides an earlier one by name."""
    database = MaterialDatabase()
    database.load_csv(MATERIALS_FILE)
    sources = (user_sources(data_dir) if include_user else []) + list(extra_files)
    for path in sources:
        if path.lower().endswith(".fcmat"):
            material, errors = read_fcmat(path)
            database.errors.extend(errors)
            if material is not None:
                database.add(material)
        else:
            database.load_csv(path)
    return database


_DEFAULT = None


def default_database():
    """The shipped database with the user's additions, loaded once per session."""
    global _DEFAULT
    if _DEFAULT is None:
        _DEFAULT = load_database()
        try:  # said once, where FreeCAD says things (the panel says it too)
            import FreeCAD

            for error in _DEFAULT.errors:
                FreeCAD.Console.PrintWarning(f"HaptiCAD materials: {error}\n")
        except ImportError:
            pass
    return _DEFAULT


def reload_default_database():
    """Reads the files again (after the user added a card)."""
    global _DEFAULT
    _DEFAULT = None
    return default_database()
