# SPDX-License-Identifier: GPL-3.0-or-later
"""Participants of a stiffness study and what they preferred (seed 000, Table 3).

A record is one participant's personal data (as Table 3: name, gender, age band, weight,
height) and the value of the design they preferred (a stiffness in N/mm for a bending
beam, an operating force in N for a push button), with the design it was felt on.
``statistics`` summarises the cohort by group ("statistics from this group about the
product stiffness can be used to dictate if a change should be made", seed 000 §3) and
``place_design`` says where the current design falls among the preferences. Records
are kept in the study object as JSON and exported and imported as CSV. No GUI.
"""
import csv
import math
import os
import statistics as stats
from dataclasses import asdict, dataclass, field

NOT_GIVEN = "not given"  # a participant need not say
GENDERS = ("F", "M", "other", NOT_GIVEN)
AGE_BANDS = ("under 18", "18-25", "26-40", "41-60", "over 60", NOT_GIVEN)  # Table 3's bands and more
WEIGHT_RANGE_KG = (20.0, 300.0)
HEIGHT_RANGE_MM = (500.0, 2500.0)
OPTIONAL_COLUMNS = ("weight_kg", "height_mm")  # an empty cell: not given
CSV_COLUMNS = ("name", "gender", "age_band", "weight_kg", "height_mm", "value", "unit", "model", "design",
               "recorded")


@dataclass
class Record:
    name: str
    gender: str
    age_band: str
    weight_kg: float  # None: not given
    height_mm: float  # None: not given
    value: float  # the preferred design value, in `unit`
    unit: str  # "N/mm" (bending beam) or "N" (push button)
    model: str
    design: dict = field(default_factory=dict)  # the study's parameters when recorded
    recorded: str = ""  # ISO date and time

    def as_dict(self):
        return asdict(self)


def problems(record):
    """What is wrong with a record, as sentences (empty when it can be kept)."""
    found = []
    if not record.name.strip():
        found.append("a participant needs a name (or an alias)")
    if record.gender not in GENDERS:
        found.append(f"gender {record.gender!r} is not one of {', '.join(GENDERS)}")
    if record.age_band not in AGE_BANDS:
        found.append(f"age band {record.age_band!r} is not one of {', '.join(AGE_BANDS)}")
    for label, value, (low, high), unit in (("weight", record.weight_kg, WEIGHT_RANGE_KG, "kg"),
                                            ("height", record.height_mm, HEIGHT_RANGE_MM, "mm")):
        if value is not None and not (isinstance(value, (int, float)) and low <= value <= high):
            found.append(f"{label} {value} {unit} is outside {low:g}..{high:g} {unit}")
    if not (isinstance(record.value, (int, float)) and math.isfinite(record.value) and record.value > 0):
        found.append(f"the preferred value {record.value} must be a number > 0")
    return found


def from_dict(data):
    """A Record from stored JSON data; ValueError if it is not one."""
    try:
        return Record(**{k: data[k] for k in Record.__dataclass_fields__ if k in data})
    except TypeError as exc:
        raise ValueError(f"not a participant record: {exc}") from None


def statistics(records, by=("gender", "age_band")):
    """Rows of {group, n, mean, sd, median, min, max} of the preferred values: all
    participants first, then each group of each field in ``by`` (groups sorted)."""
    def row(group, values):
        return {"group": group, "n": len(values), "mean": stats.fmean(values),
                "sd": stats.stdev(values) if len(values) > 1 else 0.0, "median": stats.median(values),
                "min": min(values), "max": max(values)}

    if not records:
        return []
    rows = [row("all", [r.value for r in records])]
    for key in by:
        groups = {}
        for r in records:
            groups.setdefault(getattr(r, key), []).append(r.value)
        for name in sorted(groups):
            rows.append(row(f"{key.replace('_', ' ')} {name}", groups[name]))
    return rows


def place_design(value, records):
    """Where a design value falls among the preferences: (fraction of participants who
    preferred less, a sentence)."""
    values = sorted(r.value for r in records)
    if not values:
        return None, "no participant has recorded a preference yet"
    below = sum(v < value for v in values) / len(values)
    if len(values) >= 4:
        q1, _, q3 = stats.quantiles(values, n=4, method="inclusive")
        if q1 <= value <= q3:
            where = f"within the middle half of the preferences ({q1:.3g}-{q3:.3g})"
        else:
            where = f"{'above' if value > q3 else 'below'} the middle half of the preferences ({q1:.3g}-{q3:.3g})"
    elif len(values) == 1:
        where = (f"{'at' if value == values[0] else 'above' if value > values[0] else 'below'} the one preference "
                 f"so far ({values[0]:.3g})")
    else:
        span = f"{len(values)} preferences ({values[0]:.3g}-{values[-1]:.3g})"
        where = (f"above all {span}" if value > values[-1] else f"below all {span}" if value < values[0]
                 else f"within the {span}")
    people = "the one participant" if len(values) == 1 else f"the {len(values)} participants"
    return below, f"{value:.3g} is {where}; {below:.0%} of {people} preferred less"


def write_csv(path, records):
    with open(path, "w", newline="") as handle:
        out = csv.writer(handle)
        out.writerow(CSV_COLUMNS)
        for r in records:
            d = r.as_dict()
            if d["name"][:1] in ("=", "+", "-", "@"):  # a spreadsheet would run it as a formula
                d["name"] = "'" + d["name"]
            d["design"] = ";".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in r.design.items())
            for key in ("weight_kg", "height_mm"):  # not given: an empty cell
                if d[key] is None:
                    d[key] = ""
            out.writerow([d[c] for c in CSV_COLUMNS])


def _number_or_none(text):
    return float(text) if (text or "").strip() else None


def read_csv(path):
    """Records from a CSV written by write_csv (or by hand with its columns). Raises
    ValueError naming the line of a record that cannot be kept; nothing is returned then."""
    name = os.path.basename(path)
    try:
        with open(path, newline="", encoding="utf-8-sig") as handle:  # a spreadsheet's BOM too
            reader = csv.DictReader(handle)
            rows = list(reader)
            header = reader.fieldnames or []
    except UnicodeDecodeError:
        raise ValueError(f"{name}: not UTF-8 text; save it from the spreadsheet as CSV UTF-8") from None
    except csv.Error as exc:
        raise ValueError(f"{name}: not a readable CSV file ({exc})") from None
    missing = [c for c in CSV_COLUMNS[:7] if c not in header]
    if missing:
        raise ValueError(f"{name}: needs the comma-separated columns {', '.join(CSV_COLUMNS[:7])}; its header is "
                         f"{', '.join(header) or 'empty'}")
    records = []
    for line, row in enumerate(rows, start=2):
        missing = [c for c in CSV_COLUMNS[:7] if not row.get(c) and c not in OPTIONAL_COLUMNS]
        if missing:
            raise ValueError(f"{name}, line {line}: no {', '.join(missing)}")
        try:
            design = dict(item.split("=", 1) for item in (row.get("design") or "").split(";") if "=" in item)
            record = Record(row["name"], row["gender"], row["age_band"], _number_or_none(row["weight_kg"]),
                            _number_or_none(row["height_mm"]), float(row["value"]), row["unit"], row.get("model", ""),
                            design, row.get("recorded", ""))
        except ValueError:
            raise ValueError(f"{name}, line {line}: weight, height and value must be numbers") from None
        wrong = problems(record)
        if wrong:
            raise ValueError(f"{name}, line {line}: {'; '.join(wrong)}")
        records.append(record)
    return records
