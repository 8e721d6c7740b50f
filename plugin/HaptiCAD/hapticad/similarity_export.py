# SPDX-License-Identifier: GPL-3.0-or-later
"""A similarity study's answers as CSV, one row per answer, for statistics elsewhere.

Every kept run is written, pooled or not (the ``pooled`` column says which the analysis
uses: a warm-up never, it only sets the scale). A run kept since the trial order is recorded gives every answer in the order it
was given, warm-ups included, each pair in the order its textures were offered
(``position`` 1, 2, ...); an older run gives its pairs and classings without an order
(``position`` empty, the pair's lower stimulus first). Each row names its stimuli and
carries their eq. 2 values, so a row reads on its own. No GUI.
"""
import csv

from .atomic_file import replacing
from .cohort import spreadsheet_safe
from .similarity_study import SYMBOLS, TEXTURE_VALUES, classings_pooled, comparable, runs

COLUMNS = ("participant", "started", "recorded", "device", "servo_rate_hz", "seed", "steps", "pooled", "position",
           "kind", "first", "second", "rating", "class", *(f"first_{SYMBOLS[k]}" for k in TEXTURE_VALUES),
           *(f"second_{SYMBOLS[k]}" for k in TEXTURE_VALUES))


def answer_rows(study):
    """The rows write_csv writes, as dicts keyed by COLUMNS."""
    rows = []
    for record in runs(study):
        items = record["stimuli"]
        if "trials" in record:
            answers = [(k + 1, kind, first, second, answer)
                       for k, (kind, first, second, answer) in enumerate(record["trials"])]
        else:
            answers = ([(None, "pair", i, j, rating) for i, j, rating in record["ratings"]]
                       + [(None, "class", i, -1, choice) for i, choice in record["choices"]])
        for position, kind, first, second, answer in answers:
            row = {"participant": spreadsheet_safe(str(record["name"])), "recorded": record.get("recorded", ""),
                   "started": record.get("started", ""), "device": spreadsheet_safe(str(record.get("device", ""))),
                   "servo_rate_hz": record.get("servo_rate_hz", ""),
                   "seed": "" if record.get("seed") is None else record["seed"], "steps": record["steps"],
                   # a classing pools only against the same references (classings_pooled); a
                   # warm-up is never analysed
                   "pooled": "yes" if kind != "warm-up" and (classings_pooled if kind == "class" else comparable)(
                       record, study) else "no",
                   "position": "" if position is None else position, "kind": kind,
                   "first": spreadsheet_safe(items[first]["name"]),
                   "second": spreadsheet_safe(items[second]["name"]) if second >= 0 else "",
                   "rating": answer if kind != "class" else "", "class": answer if kind == "class" else ""}
            for slot, index in (("first", first), ("second", second)):
                for key in TEXTURE_VALUES:
                    row[f"{slot}_{SYMBOLS[key]}"] = repr(items[index]["values"][key]) if index >= 0 else ""
            rows.append(row)
    return rows


def write_csv(path, study):
    """Writes every answer of every kept run of ``study`` to ``path``; returns the number
    of rows, all or nothing (atomic_file.replacing: a file there is left as it was if the
    write fails). Raises ValueError when the study keeps no run, OSError."""
    rows = answer_rows(study)
    if not rows:
        raise ValueError(f"{study.Label}: no participant's run is kept yet: nothing to export")
    with replacing(path, newline="") as handle:
        out = csv.DictWriter(handle, fieldnames=COLUMNS)
        out.writeheader()
        out.writerows(rows)
    return len(rows)
