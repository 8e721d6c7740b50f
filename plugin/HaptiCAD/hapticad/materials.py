# SPDX-License-Identifier: GPL-3.0-or-later
"""The haptic material database (resources/materials/materials.csv).

One material per CSV row: friction against a dry fingertip (mu_s, mu_d and the
plausible range of mu_d), Young's modulus, density, the contact stiffness to render,
and the source of each value. A bad row is rejected with ``file:line: problem`` and
every other row still loads. No FreeCAD import: usable headless and from the CLI.
"""
import csv
import math
import os
from dataclasses import dataclass

from . import MATERIALS_FILE

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
            with open(path, newline="", encoding="utf-8") as handle:
                lines = list(enumerate(handle, start=1))
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
    name = row["name"]
    if not name:
        raise ValueError("empty name")
    mu_min = _number(row, "mu_min", non_negative=True)
    mu_max = _number(row, "mu_max", non_negative=True)
    if mu_min > mu_max:
        raise ValueError(f"mu_min = {mu_min} exceeds mu_max = {mu_max}")
    return Material(
        name=name,
        static_friction=_number(row, "mu_static", non_negative=True),
        dynamic_friction=_number(row, "mu_dynamic", non_negative=True),
        friction_min=mu_min,
        friction_max=mu_max,
        youngs_modulus_gpa=_number(row, "youngs_modulus_gpa", positive=True),
        density_kg_m3=_number(row, "density_kg_m3", positive=True),
        stiffness_n_per_mm=_number(row, "stiffness_n_per_mm", positive=True),
        friction_source=row["mu_source"],
        bulk_source=row["bulk_source"],
        origin=origin,
    )


def load_database(extra_files=()):
    """The shipped database, then each extra file (later files override by name)."""
    database = MaterialDatabase()
    database.load_csv(MATERIALS_FILE)
    for path in extra_files:
        if os.path.exists(path):
            database.load_csv(path)
    return database


_DEFAULT = None


def default_database():
    """The shipped database, loaded once."""
    global _DEFAULT
    if _DEFAULT is None:
        _DEFAULT = load_database()
    return _DEFAULT
