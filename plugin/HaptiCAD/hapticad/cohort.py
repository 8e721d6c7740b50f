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
import re
import statistics as stats
import unicodedata
from dataclasses import asdict, dataclass, field

NOT_GIVEN = "not given"  # a participant need not say
GENDERS = ("F", "M", "other", NOT_GIVEN)
AGE_BANDS = ("under 18", "18-25", "26-40", "41-60", "over 60", NOT_GIVEN)  # Table 3's bands and more
WEIGHT_RANGE_KG = (20.0, 300.0)
HEIGHT_RANGE_MM = (500.0, 2500.0)
# What a preference can plausibly be, per unit; beyond it a value is a typo or another
# unit (N/m as N/mm), and near the float limit it breaks the statistics (1e308).
# N/mm, a bending neck: 1e-4 N/mm pressed 20 mm is 2 mN, below what a fingertip feels,
# and 1000 N/mm is some 300x the stiffest device in the field notes (Falcon, 3 N/mm) and
# 200x the stiffest neck of seed 000 Table 3 (4.5 N/mm): a wide margin either way.
# N, a push button: the model's OperatingForce range, 0.05..50 N (a study feels and
# records no other). A snap ratio: the model's SnapRatio range, 0.01..0.99 (a button
# whose force drops by none or all of it does not snap). test_stiffness_study checks the
# two against the model's properties.
PREFERENCE_RANGES = {"N/mm": (1e-4, 1000.0), "N": (0.05, 50.0), "snap ratio": (0.01, 0.99)}
FORMULA_STARTS = ("=", "+", "-", "@")  # a spreadsheet runs a cell starting so as a formula
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
    elif any(unicodedata.category(c) == "Cc" for c in record.name):  # a line break, tab or NUL: shown raw
        found.append(f"the name {record.name!r} holds a control character (a line break, tab or NUL): "
                     "give it on one line, of printable characters")
    if record.gender not in GENDERS:
        found.append(f"gender {record.gender!r} is not one of {', '.join(GENDERS)}")
    if record.age_band not in AGE_BANDS:
        found.append(f"age band {record.age_band!r} is not one of {', '.join(AGE_BANDS)}")
    for label, value, (low, high), unit in (("weight", record.weight_kg, WEIGHT_RANGE_KG, "kg"),
                                            ("height", record.height_mm, HEIGHT_RANGE_MM, "mm")):
        if value is not None and not (isinstance(value, (int, float)) and low <= value <= high):
            # Table 3 prints heights in cm under "Height(mm)": say what to give instead
            hint = (f": in centimetres? give {value * 10:g}" if label == "height" and isinstance(value, (int, float))
                    and low <= value * 10 <= high else "")
            found.append(f"{label} {value} {unit} is outside {low:g}..{high:g} {unit}{hint}")
    if not (isinstance(record.value, (int, float)) and math.isfinite(record.value) and record.value > 0):
        found.append(f"the preferred value {record.value} must be a number > 0")
    elif record.unit not in PREFERENCE_RANGES:
        found.append(f"unit {record.unit!r} is not one of {', '.join(PREFERENCE_RANGES)}")
    else:
        low, high = PREFERENCE_RANGES[record.unit]
        if not low <= record.value <= high:
            found.append(f"the preferred value {record.value:g} {record.unit} is outside the plausible "
                         f"{low:g}..{high:g} {record.unit}")
    return found


def beyond_device(record):
    """Whether a record was felt at the device's limit. Records imported before design
    values were read back as numbers hold the text "0.0" or "0": not beyond."""
    flag = record.design.get("BeyondDevice")
    if isinstance(flag, str):
        try:
            return float(flag) != 0.0
        except ValueError:
            return flag.strip().lower() == "true"
    return bool(flag)


# what the star beside a preference means, by the unit it is in: the renderer stretches a
# law's travel until its steepest slope fits the device (force_travel.h, ForceClamped), so a
# neck stiffer than the device is felt at the device's stiffness, while a button keeps its
# forces (its operating force and snap ratio are felt as designed) over a longer travel
BEYOND_DEVICE = {
    "N/mm": "beyond what the device renders stably, felt at its limit (softer)",
    "N": "steeper than the device renders stably, its forces felt as designed over a longer travel",
}
BEYOND_DEVICE["snap ratio"] = BEYOND_DEVICE["N"]


def beyond_device_note(records):
    """The footnote of the starred records (beyond_device) among ``records``, all of one
    unit, saying what the star means there, or "" when none is starred."""
    starred = [r for r in records if beyond_device(r)]
    if not starred:
        return ""
    meaning = BEYOND_DEVICE.get(starred[0].unit, "beyond what the device renders stably")
    return f"* {plural(len(starred), 'preference')} {meaning}; counted as recorded."


def plural(count, noun):
    """"1 participant", "3 participants"."""
    return f"{count} {noun}{'' if count == 1 else 's'}"


def format_value(value, unit):
    """A preferred value with its unit as it reads: "0.556 N/mm", "snap ratio 0.5"."""
    return f"{unit} {value:.3g}" if unit == "snap ratio" else f"{value:.3g} {unit}"


def namesakes(name, records):
    """How many records already bear ``name`` (case and spaces aside)."""
    key = " ".join(name.split()).casefold()
    return sum(1 for r in records if " ".join(r.name.split()).casefold() == key)


def _same_number(a, b):
    """Two recorded numbers alike, not given (None) alike: within a relative 1e-12, so a
    value saved back by a spreadsheet (rounded to 15 significant digits) still matches."""
    if a is None or b is None:
        return a is None and b is None
    try:
        return math.isclose(float(a), float(b), rel_tol=1e-12, abs_tol=1e-300)
    except (TypeError, ValueError):
        return a == b


def same_record(a, b):
    """Whether two records are one participant's one preference (a re-import, a row listed
    twice): every field the participant gave or was recorded with alike (name, gender, age
    band, weight, height, the value, its unit and the time), numbers as _same_number. Two
    people of one name and value, or one person's two sessions, are two records. The
    design is left out: it is the study's, and the value and time already tell it."""
    return (a.name == b.name and a.gender == b.gender and a.age_band == b.age_band and a.unit == b.unit
            and a.recorded == b.recorded and _same_number(a.value, b.value)
            and _same_number(a.weight_kg, b.weight_kg) and _same_number(a.height_mm, b.height_mm))


def from_dict(data):
    """A Record from stored JSON data; ValueError if it is not one."""
    try:
        return Record(**{k: data[k] for k in Record.__dataclass_fields__ if k in data})
    except TypeError as exc:
        raise ValueError(f"not a participant record: {exc}") from None


def statistics(records, by=("gender", "age_band")):
    """Rows of {group, n, mean, sd, median, min, max} of the preferred values: all
    participants first, then each group of each field in ``by`` (in _group_order)."""
    def row(group, values):
        mean, sd = _mean_sd(values)
        return {"group": group, "n": len(values), "mean": mean, "sd": sd, "median": stats.median(values),
                "min": min(values), "max": max(values)}

    if not records:
        return []
    rows = [row("all", [r.value for r in records])]
    for key in by:
        groups = {}
        for r in records:
            groups.setdefault(getattr(r, key), []).append(r.value)
        for name in sorted(groups, key=lambda g, k=key: _group_order(k, g)):
            rows.append(row(f"{key.replace('_', ' ')} {name}", groups[name]))
    return rows


def _group_order(key, group):
    """Groups in their own order (age bands young to old, genders as listed), a value not
    listed after them, "not given" last."""
    listed = {"gender": GENDERS, "age_band": AGE_BANDS}.get(key, ())
    if group == NOT_GIVEN:
        return (2, 0, "")
    if group in listed:
        return (0, listed.index(group), "")
    return (1, 0, str(group))


def _mean_sd(values):
    """fmean and stdev that never raise on stored values (a document saved before their
    range was checked may hold 1e308, whose sum overflows, or inf): such a cohort must still
    be shown so the record can be removed."""
    if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
        return math.nan, math.nan
    try:
        return stats.fmean(values), stats.stdev(values) if len(values) > 1 else 0.0
    except OverflowError:  # in units of the largest value, then back (inf if it does not fit)
        scale = max(abs(v) for v in values)
        scaled = [v / scale for v in values]
        return stats.fmean(scaled) * scale, stats.stdev(scaled) * scale if len(values) > 1 else 0.0


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


def spreadsheet_safe(text):
    """``text`` as a CSV cell a spreadsheet shows as text: one starting like a formula
    (FORMULA_STARTS) is guarded with a leading apostrophe, which read_csv takes off."""
    return "'" + text if text.lstrip("'")[:1] in FORMULA_STARTS else text


def write_csv(path, records):
    with open(path, "w", newline="") as handle:
        out = csv.writer(handle)
        out.writerow(CSV_COLUMNS)
        for r in records:
            d = r.as_dict()
            d["name"] = spreadsheet_safe(d["name"])
            # repr: the shortest text that reads back as the same float
            d["design"] = ";".join(f"{k}={v!r}" if isinstance(v, float) else f"{k}={v}" for k, v in r.design.items())
            for key in ("weight_kg", "height_mm"):  # not given: an empty cell
                if d[key] is None:
                    d[key] = ""
            out.writerow([d[c] for c in CSV_COLUMNS])


def _number_or_none(text):
    return float(text) if (text or "").strip() else None


def _design_value(text):
    """A design value as write_csv wrote it, back as the number (or boolean) it was."""
    if text in ("True", "False"):
        return text == "True"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def _unguarded(name):
    """A name without the apostrophe write_csv put before a formula's first character."""
    return name[1:] if name[:1] == "'" and name.lstrip("'")[:1] in FORMULA_STARTS else name


def read_csv(path):
    """Records from a CSV written by write_csv (or by hand with its columns). Raises
    ValueError naming the line of a record that cannot be kept; nothing is returned then."""
    name = os.path.basename(path)
    try:
        with open(path, newline="", encoding="utf-8-sig") as handle:  # a spreadsheet's BOM too
            reader = csv.DictReader(handle)
            rows, after = [], 1
            for row in reader:  # each with the line it starts on (a quoted field may hold line breaks)
                breaks = sum(len(re.findall(r"\r\n|\r|\n", v)) for v in row.values() if isinstance(v, str))
                rows.append((max(after + 1, reader.line_num - breaks), row))
                after = reader.line_num
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
    for line, row in rows:
        missing = [c for c in CSV_COLUMNS[:7] if not row.get(c) and c not in OPTIONAL_COLUMNS]
        if missing:
            raise ValueError(f"{name}, line {line}: no {', '.join(missing)}")
        try:
            design = {key: _design_value(text) for key, text in
                      (item.split("=", 1) for item in (row.get("design") or "").split(";") if "=" in item)}
            record = Record(_unguarded(row["name"]), row["gender"], row["age_band"], _number_or_none(row["weight_kg"]),
                            _number_or_none(row["height_mm"]), float(row["value"]), row["unit"], row.get("model", ""),
                            design, row.get("recorded", ""))
        except ValueError:
            raise ValueError(f"{name}, line {line}: weight, height and value must be numbers") from None
        wrong = problems(record)
        if wrong:
            raise ValueError(f"{name}, line {line}: {'; '.join(wrong)}")
        records.append(record)
    return records
