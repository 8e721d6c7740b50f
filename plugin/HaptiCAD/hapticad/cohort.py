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
import io
import math
import os
import re
import statistics as stats
import unicodedata
from dataclasses import MISSING, asdict, dataclass, field
from datetime import datetime, timedelta

from .atomic_file import replacing

NOT_GIVEN = "not given"  # a participant need not say
GENDERS = ("F", "M", "other", NOT_GIVEN)
AGE_BANDS = ("under 18", "18-25", "26-40", "41-60", "over 60", NOT_GIVEN)  # Table 3's bands and more
# 10 kg: a two-year-old's weight. The "under 18" band has no floor, and a child old enough
# to press a toothbrush and say which feels right may weigh 12-15 kg (20 refused them)
WEIGHT_RANGE_KG = (10.0, 300.0)
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
# the cells written as text: each guarded against a spreadsheet's formulas (spreadsheet_safe)
TEXT_COLUMNS = ("name", "gender", "age_band", "unit", "model", "design", "recorded")
# what read_csv takes between cells, found from the header (a European spreadsheet writes ';')
SEPARATORS = {",": "comma", ";": "semicolon", "\t": "tab"}
# what a participant's number outside its range may be in another unit, said where it fits:
# Table 3 prints heights in cm under "Height(mm)"; a US form gives inches and pounds
OTHER_UNITS = {"height": (("centimetres", 10.0), ("inches", 25.4)), "weight": (("pounds", 0.45359237),)}


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
    return [sentence for _, sentence in field_problems(record)]


def field_problems(record):
    """problems, each with the field it is about: (field, sentence), the field a Record's
    and so a CSV column's name (CSV_COLUMNS), for a reader to say which cell is wrong."""
    found = []
    if not record.name.strip():
        found.append(("name", "a participant needs a name (or an alias)"))
    elif any(unicodedata.category(c) == "Cc" for c in record.name):  # a line break, tab or NUL: shown raw
        found.append(("name", f"the name {record.name!r} holds a control character (a line break, tab or NUL): "
                      "give it on one line, of printable characters"))
    for column, label, text in (("model", "model", record.model), ("recorded", "time recorded", record.recorded)):
        if isinstance(text, str) and any(unicodedata.category(c) == "Cc" for c in text):  # shown raw too
            found.append((column, f"the {label} {text!r} holds a control character (a line break, tab or NUL)"))
    if record.gender not in GENDERS:
        found.append(("gender", f"gender {record.gender!r} is not one of {', '.join(GENDERS)}"))
    if record.age_band not in AGE_BANDS:
        found.append(("age_band", f"age band {record.age_band!r} is not one of {', '.join(AGE_BANDS)}"))
    for column, label, value, (low, high), unit in (
            ("weight_kg", "weight", record.weight_kg, WEIGHT_RANGE_KG, "kg"),
            ("height_mm", "height", record.height_mm, HEIGHT_RANGE_MM, "mm")):
        if value is not None and not (isinstance(value, (int, float)) and low <= value <= high):
            found.append((column, f"{label} {value} {unit} is outside {low:g}..{high:g} {unit}"
                           f"{_other_unit_hint(label, value, low, high)}"))
    if not (isinstance(record.value, (int, float)) and math.isfinite(record.value) and record.value > 0):
        found.append(("value", f"the preferred value {record.value} must be a number > 0"))
    elif record.unit not in PREFERENCE_RANGES:
        found.append(("unit", f"unit {record.unit!r} is not one of {', '.join(PREFERENCE_RANGES)}"))
    else:
        low, high = PREFERENCE_RANGES[record.unit]
        if not low <= record.value <= high:
            # a stiffness written in N/m under N/mm: said, where a thousandth of it is one
            per_m = (f": in N/m? that is {record.value / 1000:g} N/mm" if record.unit == "N/mm"
                     and low <= record.value / 1000 <= high else "")
            found.append(("value", f"the preferred value {record.value:g} {record.unit} is outside the plausible "
                          f"{low:g}..{high:g} {record.unit}{per_m}"))
    return found


def _other_unit_hint(label, value, low, high):
    """What to give if ``value`` was meant in another unit (OTHER_UNITS) that lands it in
    low..high: ": in centimetres? give 690, or in inches? give 1753" (69), or ""."""
    if not isinstance(value, (int, float)) or not math.isfinite(value):
        return ""
    fits = [f"in {name}? give {value * factor:.0f}" for name, factor in OTHER_UNITS.get(label, ())
            if low <= value * factor <= high]
    return ": " + ", or ".join(fits) if fits else ""


def _flag(record, key):
    """A yes/no kept in a record's design. Records imported before design values were
    read back as numbers hold the text "0.0" or "0": no."""
    flag = record.design.get(key)
    if isinstance(flag, str):
        try:
            return float(flag) != 0.0
        except ValueError:
            return flag.strip().lower() == "true"
    return bool(flag)


def beyond_device(record):
    """Whether a record was felt at the device's limit (its design's BeyondDevice)."""
    return _flag(record, "BeyondDevice")


def beyond_force_limit(record):
    """Whether a button's record was felt with its operating force above the session's
    force limit (its design's BeyondForceLimit, the limit kept as ForceLimit, N): the
    force stopped at the limit and the click never came, so what was chosen is not what
    was felt. Such records are kept and exported, marked †, and left out of statistics
    and place_design (counted)."""
    return _flag(record, "BeyondForceLimit")


def counted(records):
    """The records statistics and place_design count: all but those beyond the force
    limit (beyond_force_limit) and those whose value is not a finite number (unfit_value),
    whose counts beyond_device_note gives instead. Left out, not flagged in the figures: a
    button whose click never came was not felt as designed at all, and its value would
    pull the mean towards forces nobody felt; a NaN made every figure NaN (and the JSON
    of `hapticad cohort --json` invalid)."""
    return [r for r in records if not beyond_force_limit(r) and not unfit_value(r)]


def mark(record):
    """The mark after a record's value in a table: " †" beyond the force limit (it
    outweighs the star: its forces were not felt as designed), " *" beyond the device's
    stiffness, or ""."""
    return " †" if beyond_force_limit(record) else " *" if beyond_device(record) else ""


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
    """The footnotes of the marked records (mark) among ``records``, all of one unit: what
    the star means there, how many preferences lie beyond the force limit and how many
    records have no number for a value (unfit_value), both left out of the statistics;
    "" when none is."""
    unfit = [r for r in records if unfit_value(r)]
    starred = [r for r in records if beyond_device(r) and not beyond_force_limit(r) and not unfit_value(r)]
    above = [r for r in records if beyond_force_limit(r) and not unfit_value(r)]
    notes = []
    if starred:
        meaning = BEYOND_DEVICE.get(starred[0].unit, "beyond what the device renders stably")
        notes.append(f"* {plural(len(starred), 'preference')} {meaning}; counted as recorded.")
    if above:
        notes.append(f"† {plural(len(above), 'preference')} {force_limit_meaning(above)}; left out of the "
                     "statistics (kept, and exported).")
    if unfit:
        shown = ", ".join(f"{r.name}: {r.value}" for r in unfit[:3]) + (f" and {len(unfit) - 3} more"
                                                                        if len(unfit) > 3 else "")
        one = len(unfit) == 1
        notes.append(f"{plural(len(unfit), 'record')} whose value {'is' if one else 'are'} not a finite number "
                     f"({shown}; a hand-edited document?) left out of the statistics: remove or correct "
                     f"{'it' if one else 'them'}.")
    return " ".join(notes)


def force_limit_meaning(records):
    """What the dagger means for ``records``, with the force limit(s) they kept: "above
    the force limit (3 N): the force stopped there and the click was never felt"."""
    limits = set()
    for r in records:
        try:
            limits.add(float(r.design.get("ForceLimit")))
        except (TypeError, ValueError):  # kept no limit: said without one
            pass
    shown = ", ".join(f"{limit:.3g} N" for limit in sorted(limits))
    return (f"above the force limit{f' ({shown})' if shown else ''}: the force stopped there and the click was "
            "never felt")


def plural(count, noun):
    """"1 participant", "3 participants"."""
    return f"{count} {noun}{'' if count == 1 else 's'}"


def format_value(value, unit):
    """A preferred value with its unit as it reads: "0.556 N/mm", "snap ratio 0.5"."""
    return f"{unit} {value:.3g}" if unit == "snap ratio" else f"{value:.3g} {unit}"


def participant_key(name):
    """Who a record is of: the name as typed, but for case and spacing ("ida  Berg" is "Ida Berg")."""
    return " ".join(str(name).split()).casefold()


def namesakes(name, records):
    """How many records already bear ``name`` (participant_key: case and spaces aside)."""
    key = participant_key(name)
    return sum(1 for r in records if participant_key(r.name) == key)


def person_key(record):
    """Who a record is of: its name (participant_key), gender and age band. Records that
    give one name but another gender or age band are two people of one name."""
    return participant_key(record.name), record.gender, record.age_band


def count_participants(records):
    """How many people the records are of (person_key), whatever they recorded."""
    return len({person_key(r) for r in records if participant_key(r.name)})


@dataclass(frozen=True)
class Participant:
    """One person's counted records pooled: their preference is the mean of their records'
    values (a second session is a second measure of one person, not a second person)."""
    name: str
    gender: str
    age_band: str
    value: float
    records: int


def participants(records):
    """The counted records (counted) pooled per person (person_key), in the order of each
    one's first record. The paper's cohort (Table 3) is one preference per person:
    statistics and place_design count people, so one person's two sessions do not weigh
    twice."""
    groups = {}
    for r in counted(records):
        groups.setdefault(person_key(r), []).append(r)
    people = []
    for group in groups.values():
        first = group[0]
        mean, _ = _mean_sd([r.value for r in group])
        people.append(Participant(first.name, first.gender, first.age_band, mean, len(group)))
    return people


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
    band, weight, height, the value, its unit and the time), numbers as _same_number, times
    as same_time. Two people of one name and value, or one person's two sessions, are two
    records. The design is left out: it is the study's, and the value and time tell it."""
    return (a.name == b.name and a.gender == b.gender and a.age_band == b.age_band and a.unit == b.unit
            and _same_number(a.value, b.value) and _same_number(a.weight_kg, b.weight_kg)
            and _same_number(a.height_mm, b.height_mm) and same_time(a.recorded, b.recorded))


# a date as ISO writes it (2026-11-24), or day and month first as spreadsheets do
# (24/11/2026, 11/24/26, 24.11.2026), then a time to the minute or second (15:17, 3:17 PM)
_TIME = r"(?:(?:T|\s+)(\d{1,2}):(\d{2})(?::(\d{2})(?:[.,]\d+)?)?\s*([AaPp][Mm])?)?"
_YEAR_FIRST = re.compile(r"(\d{4})([-/.])(\d{1,2})\2(\d{1,2})" + _TIME)
_YEAR_LAST = re.compile(r"(\d{1,2})([-/.])(\d{1,2})\2(\d{4}|\d{2})" + _TIME)
SECOND, MINUTE, DAY = timedelta(seconds=1), timedelta(minutes=1), timedelta(days=1)


def recorded_times(text):
    """The times a recorded text can be, each (datetime, precision: SECOND, MINUTE or
    DAY), as a spreadsheet may have rewritten it: ISO ("2026-11-24T15:17:03"), "2026-11-24
    15:17", "24/11/2026 15:17" or "11/24/26 3:17 PM" (day or month first: both, when both
    can be), "24.11.2026" (day first). Empty when it is none of these."""
    text = text.strip() if isinstance(text, str) else ""
    found = []
    match = _YEAR_FIRST.fullmatch(text)
    if match:
        dates = [(int(match[1]), int(match[3]), int(match[4]))]
        clock = match.groups()[4:]
    else:
        match = _YEAR_LAST.fullmatch(text)
        if not match:
            return []
        first, middle, year = int(match[1]), int(match[3]), int(match[4])
        year += 2000 if len(match[4]) == 2 else 0  # a spreadsheet's "26": this century
        dates = [(year, middle, first)]  # day first (24/11/2026, 24.11.2026)
        if match[2] != ".":  # month first too (11/24/2026); nobody writes 11.24.2026
            dates.append((year, first, middle))
        clock = match.groups()[4:]
    hour, minute, second, half = clock
    for year, month, day in dict.fromkeys(dates):
        try:
            if hour is None:
                found.append((datetime(year, month, day), DAY))
                continue
            h = int(hour)
            if half:  # 12 AM is midnight, 12 PM noon
                if not 1 <= h <= 12:
                    continue
                h = h % 12 + (12 if half.lower() == "pm" else 0)
            found.append((datetime(year, month, day, h, int(minute), int(second or 0)),
                          SECOND if second is not None else MINUTE))
        except ValueError:  # no such day (31/02), hour or minute
            pass
    return found


def same_time(a, b):
    """Whether two recorded times are one: the same text, or the same time to the precision
    the coarser gives (a spreadsheet's re-save shows "2026-11-24T15:17:03" as "24/11/2026
    15:17", cut or rounded to the minute). Texts that are no time (recorded_times) must be
    the same text."""
    if a == b:
        return True

    def cut(time, unit):
        return datetime.min + (time - datetime.min) // unit * unit

    for ta, pa in recorded_times(a):
        for tb, pb in recorded_times(b):
            (fine, _), (coarse, unit) = sorted(((ta, pa), (tb, pb)), key=lambda t: t[1])
            # shown to the minute, a time's seconds are cut or rounded: spreadsheets differ
            if coarse in (cut(fine, unit), cut(fine + unit / 2, unit) if unit != DAY else None):
                return True
    return False


# what a stored record's fields must hold to be read (a hand-edited document may hold anything)
_TEXT_FIELDS = ("name", "gender", "age_band", "unit", "model", "recorded")
_NUMBER_FIELDS = ("value", "weight_kg", "height_mm")  # weight and height may be None: not given


def from_dict(data):
    """A Record from stored JSON data; ValueError saying what it lacks or holds wrongly if
    it is not one. A value that is a number but not a finite one (NaN, inf) is read:
    counted leaves it out of the statistics, and the panel shows it to be removed."""
    if not isinstance(data, dict):
        raise ValueError(f"not a participant record but {type(data).__name__} {str(data)[:40]!r}")
    fields = Record.__dataclass_fields__
    required = [k for k, f in fields.items() if f.default is MISSING and f.default_factory is MISSING]
    lacking = [k for k in required if k not in data]
    if lacking:
        raise ValueError(f"not a participant record: it lacks {', '.join(lacking)}")
    wrong = [f"{k} {data[k]!r} is not text" for k in _TEXT_FIELDS if k in data and not isinstance(data[k], str)]
    wrong += [f"{k} {data[k]!r} is not a number" for k in _NUMBER_FIELDS
              if not _is_number(data[k]) and not (data[k] is None and k != "value")]
    if "design" in data and not isinstance(data["design"], dict):
        wrong.append(f"design {str(data['design'])[:40]!r} is not a set of design values")
    if wrong:
        raise ValueError(f"not a participant record: {'; '.join(wrong)}")
    return Record(**{k: data[k] for k in fields if k in data})


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def unfit_value(record):
    """Whether a record's preferred value cannot be summarised (not a finite number: a
    hand-edited document's NaN or inf). counted leaves such a record out."""
    return not (_is_number(record.value) and math.isfinite(record.value))


def statistics(records, by=("gender", "age_band")):
    """Rows of {group, n, records, mean, sd, median, min, max} of the preferred values: all
    participants first, then each group of each field in ``by`` (in _group_order). ``n``
    counts people (participants: one person's records averaged), ``records`` the records
    pooled into them; the records counted (counted: not those beyond the force limit). sd
    is the sample SD, None for a group of one (undefined, not 0: one person does not agree
    with themself)."""
    def row(group, people):
        values = [p.value for p in people]
        mean, sd = _mean_sd(values)
        return {"group": group, "n": len(values), "records": sum(p.records for p in people), "mean": mean,
                "sd": sd, "median": stats.median(values), "min": min(values), "max": max(values)}

    people = participants(records)
    if not people:
        return []
    rows = [row("all", people)]
    for key in by:
        groups = {}
        for p in people:
            groups.setdefault(getattr(p, key), []).append(p)
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
    spread = len(values) > 1  # a sample SD needs two values: one gives None, undefined
    if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
        return math.nan, math.nan if spread else None
    try:
        return stats.fmean(values), stats.stdev(values) if spread else None
    except OverflowError:  # in units of the largest value, then back (inf if it does not fit)
        scale = max(abs(v) for v in values)
        scaled = [v / scale for v in values]
        return stats.fmean(scaled) * scale, stats.stdev(scaled) * scale if spread else None


def format_sd(sd):
    """An SD as text: "-" when undefined (None: a group of one)."""
    return "-" if sd is None else f"{sd:.2g}"


def place_design(value, records):
    """Where a design value falls among the preferences (participants: one per person, not
    those beyond the force limit): (fraction of participants who preferred less, a sentence)."""
    values = sorted(p.value for p in participants(records))
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
    """Writes ``records`` to ``path`` as UTF-8 (what read_csv reads, whatever the system's
    encoding: a Windows FreeCAD wrote cp1252 and stopped at the first name it had no
    character for, the file cut short). All or nothing (atomic_file.replacing)."""
    with replacing(path, newline="") as handle:
        _write_rows(handle, records)


def _write_rows(handle, records):
    out = csv.writer(handle)
    out.writerow(CSV_COLUMNS)
    for r in records:
        d = r.as_dict()
        # repr: the shortest text that reads back as the same float
        d["design"] = ";".join(f"{k}={v!r}" if isinstance(v, float) else f"{k}={v}" for k, v in r.design.items())
        for key in TEXT_COLUMNS:  # every text cell: a model or time imported as "=HYPERLINK(...)" too
            d[key] = spreadsheet_safe(str(d[key]))
        for key in ("weight_kg", "height_mm"):  # not given: an empty cell
            if d[key] is None:
                d[key] = ""
        out.writerow([d[c] for c in CSV_COLUMNS])


# a number written with a decimal comma (1,5 or -0,25e3), read from a ';' file only: with
# ',' separating cells, "1,500" may be thousands
_DECIMAL_COMMA = re.compile(r"[+-]?\d*,\d+(?:[eE][+-]?\d+)?")


class _Numbers:
    """Reads a file's numbers, with decimal commas when its cells are ';'-separated, and
    remembers whether it read one (to say so)."""

    def __init__(self, decimal_comma):
        self.decimal_comma, self.read_comma = decimal_comma, False

    def text(self, text):
        text = (text or "").strip()
        if self.decimal_comma and _DECIMAL_COMMA.fullmatch(text):
            self.read_comma = True
            return text.replace(",", ".")
        return text

    def number(self, text):
        return float(self.text(text))

    def number_or_none(self, text):
        return self.number(text) if (text or "").strip() else None

    def design_value(self, text):
        """A design value as write_csv wrote it, back as the number (or boolean) it was."""
        if text in ("True", "False"):
            return text == "True"
        for kind in (int, float):
            try:
                return kind(self.text(text))
            except ValueError:
                pass
        return text


def _unguarded(text):
    """A text cell without the apostrophe write_csv put before a formula's first character."""
    return text[1:] if text[:1] == "'" and text.lstrip("'")[:1] in FORMULA_STARTS else text


def _blank(row):
    """Whether a row's cells are all empty or spaces (",,,,," as a spreadsheet writes an
    empty row): skipped as a blank line is."""
    cells = [c for v in row.values() if v is not None for c in (v if isinstance(v, list) else [v])]
    return all(not c.strip() for c in cells)


def _separator(header_line):
    """The separator (SEPARATORS) that splits a header line into the required columns;
    else the one that splits it most (for the message), None when nothing is there."""
    split = {sep: next(csv.reader([header_line], delimiter=sep), []) for sep in SEPARATORS}
    for sep, cells in split.items():
        if all(c in cells for c in CSV_COLUMNS[:7]):
            return sep, True
    return max(split, key=lambda sep: len(split[sep])), False


def _where(line, row):
    """Where a record is, as its file's line, and the spreadsheet's row when that differs
    (a cell above held line breaks): "line 4 (row 3 in a spreadsheet)"."""
    return f"line {line}" + (f" (row {row} in a spreadsheet)" if row != line else "")


def _column_letter(index):
    """A spreadsheet's letter of the column at ``index`` (0: A, 25: Z, 26: AA)."""
    letters = ""
    index += 1
    while index:
        index, rest = divmod(index - 1, 26)
        letters = chr(ord("A") + rest) + letters
    return letters


def _check_quotes_closed(text, separator, name, last_start):
    """Raises ValueError when a quote opens a cell that never closes: the reader took the
    rest of the file into that cell, and the message was about its empty columns."""
    try:
        for _ in csv.reader(io.StringIO(text, newline=""), delimiter=separator, strict=True):
            pass
    except csv.Error as exc:
        if "unexpected end of data" in str(exc):
            raise ValueError(f"{name}, line {last_start}: a quote (\") opens a cell there that never closes, so the "
                             "rest of the file was read into it: close it or remove it") from None
        # other strict-only complaints (a quote inside a cell) the lenient reading above takes


def read_csv(path):
    """Records from a CSV written by write_csv (or by hand with its columns). Raises
    ValueError naming the line and column of a cell that cannot be kept (read_csv_as_read);
    nothing is returned then."""
    return read_csv_as_read(path)[0]


def read_csv_as_read(path):
    """(records, how the file was read): read_csv's records, and "" for a comma-separated
    file, else what it was ("semicolon-separated, with decimal commas"). The separator is
    the header's (SEPARATORS); a ';' file may give numbers with decimal commas. Rows of
    empty cells are skipped as blank lines are. Text cells are kept as given, without the
    apostrophe write_csv guards a formula with (spreadsheet_safe): they are data, shown as
    plain text and never run here; every export guards them again. Raises ValueError
    naming the line of a record that cannot be kept (and its row in a spreadsheet, when a
    cell above held line breaks) and the column, by name and letter, of each cell that is
    wrong; nothing is returned then."""
    name = os.path.basename(path)
    try:
        with open(path, newline="", encoding="utf-8-sig") as handle:  # a spreadsheet's BOM too
            text = handle.read()
        separator, found = _separator(re.split(r"\r\n|\r|\n", text, maxsplit=1)[0])
        reader = csv.DictReader(io.StringIO(text, newline=""), delimiter=separator)
        rows, after, inside, start = [], 1, 0, 1
        for row in reader:  # each with the line it starts on (a quoted field may hold line breaks)
            breaks = sum(len(re.findall(r"\r\n|\r|\n", v)) for v in row.values() if isinstance(v, str))
            start = max(after + 1, reader.line_num - breaks)
            if not _blank(row):  # and the row a spreadsheet shows it on: a cell's line breaks are no rows
                rows.append((_where(start, start - inside), row))
            after, inside = reader.line_num, inside + breaks
        header = reader.fieldnames or []
        _check_quotes_closed(text, separator, name, start)
    except UnicodeDecodeError:
        raise ValueError(f"{name}: not UTF-8 text; save it from the spreadsheet as CSV UTF-8") from None
    except csv.Error as exc:
        raise ValueError(f"{name}: not a readable CSV file ({exc})") from None
    except OSError as exc:  # a folder, a file gone, no permission: said as the rest, not a traceback
        raise ValueError(f"{path}: {exc.strerror or exc}") from None
    if not found:
        raise ValueError(f"{name}: needs the columns {', '.join(CSV_COLUMNS[:7])}, separated by commas, semicolons "
                         f"or tabs; its header is {', '.join(header) or 'empty'}")
    twice = [c for c in CSV_COLUMNS if header.count(c) > 1]
    if twice:  # DictReader keeps the last of them: the first column's cells were dropped unsaid
        raise ValueError(f"{name}: the header has the column {twice[0]} more than once ("
                         + ", ".join(_column_letter(i) for i, c in enumerate(header) if c == twice[0])
                         + "): which one holds it cannot be told; keep one")
    numbers = _Numbers(decimal_comma=separator == ";")
    records = []

    def cell(column):  # a column as a spreadsheet shows it: its name and letter
        return f"{column} ({_column_letter(header.index(column))})" if column in header else column

    def number(where, row, column):
        text = row.get(column)
        try:
            return numbers.number_or_none(text) if column in OPTIONAL_COLUMNS else numbers.number(text)
        except ValueError:
            given = (text or "").strip()
            hint = (": give it with a decimal point (a comma-separated file takes no decimal commas)"
                    if _DECIMAL_COMMA.fullmatch(given) else " (or empty: not given)" if column in OPTIONAL_COLUMNS
                    else "")
            raise ValueError(f"{name}, {where}, column {cell(column)}: {given!r} is not a number{hint}") from None

    for where, row in rows:
        missing = sorted((c for c in CSV_COLUMNS[:7] if not row.get(c) and c not in OPTIONAL_COLUMNS),
                         key=header.index)  # left to right, as the file has them
        if missing:
            raise ValueError(f"{name}, {where}, column{'s' if len(missing) > 1 else ''} "
                             f"{', '.join(cell(c) for c in missing)}: empty")
        extra = [c for c in row.get(None) or () if c.strip()]
        if extra:  # the cells after would be read into the wrong columns
            raise ValueError(f"{name}, {where}: more cells than the header has columns, from column "
                             f"{_column_letter(len(header))} on (a cell holding a {SEPARATORS[separator]} without "
                             "quotes around it?)")
        items = [item for item in _unguarded(row.get("design") or "").split(";") if item.strip()]
        odd = [item for item in items if "=" not in item or not item.split("=", 1)[0].strip()]
        if odd:  # was dropped without a word
            raise ValueError(f"{name}, {where}, column {cell('design')}: {odd[0]!r} is not name=value (the design "
                             "reads like YoungsModulus=1.5;BeamWidth=5)")
        design = {key: numbers.design_value(text) for key, text in (item.split("=", 1) for item in items)}
        record = Record(_unguarded(row["name"]), _unguarded(row["gender"]), _unguarded(row["age_band"]),
                        number(where, row, "weight_kg"), number(where, row, "height_mm"),
                        number(where, row, "value"), _unguarded(row["unit"]), _unguarded(row.get("model") or ""),
                        design, _unguarded(row.get("recorded") or ""))
        wrong = field_problems(record)  # (the time recorded is text: any text comes back as given)
        wrong.sort(key=lambda found: header.index(found[0]) if found[0] in header else len(header))  # left to right
        if wrong:
            split = (" (a decimal comma in a comma-separated file splits a number in two: give it with a point, "
                     "or in quotes)" if separator == "," and re.fullmatch(r"\d+", record.unit.strip()) else "")
            raise ValueError(f"{name}, {where}, " + "; ".join(f"column {cell(c)}: {said}" for c, said in wrong)
                             + split)
        records.append(record)
    how = "" if separator == "," else f"{SEPARATORS[separator]}-separated"
    if numbers.read_comma:
        how += ", with decimal commas"
    return records, how
