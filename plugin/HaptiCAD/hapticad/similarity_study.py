# SPDX-License-Identifier: GPL-3.0-or-later
"""The SimilarityStudy document object: which virtual textures feel alike, and which
physical parameters make them so (seed 001 §IV, Fig. 7, eq. 3).

A study links the HapticSurface whose faces the participants stroke and holds a list of
stimuli, each a viscous grating (eq. 2's f_DC, f_vis, beta_h, alpha_h, beta_vis,
alpha_vis; the period, scale and full range stay the surface's). By default the paper's
nine: three DC friction levels by three viscosities. Optionally two reference surfaces,
A and B (textures fitted from recordings of real samples, say), whose own textures are
presented whole.

A participant's run (:class:`Run`) follows the paper's protocol:

1. warm-up comparisons (12 by default) of random pairs, not kept, for context;
2. every pair of stimuli once (36 for nine), in a random order and with a random one
   felt first, each rated on a scale of ``RatingSteps`` (1: nothing alike, the top: the
   same);
3. with references A and B, each stimulus ``Repeats`` times (3) in a random order,
   classed as closer to A or to B.

A trial takes its answer only once its textures were felt (both of a pair, a class
trial's own), whoever asks: the Feel panel or a script. Felt means stroked: the finger
slid over the study's faces, one period of the grating at least, while the texture was
held out on them.

While a run holds a stimulus out to feel, :func:`presented_texture` gives it and
surface_compile renders it on the surface in place of the surface's own texture, so the
participant feels it at the next servo tick and never sees which it is. A finished run
is kept in the document (:func:`record_run`).

:func:`analyse` inverts the cohort's mean similarities into a dissimilarity matrix,
places the stimuli in a perceptual space (classical MDS, _core.compute_perceptual_space,
or with ``Scaling`` Ordinal Kruskal's nonmetric MDS, which keeps only the order of the
dissimilarities) and draws through it, by eq. 3, a vector for each parameter that varies among the
stimuli (scaled to -0.5..0.5) and one for likeness to the references (always B: -0.5,
always A: +0.5). App-only.
"""
import itertools
import json
import math
import random
from dataclasses import dataclass
from datetime import datetime

import FreeCAD as App
import numpy as np

from . import _core, textures
from .cohort import participant_key  # who ran a run
from .proxy_state import SchemaState, add_hidden_state, add_properties, add_type_tag, is_alive
from .surface_object import TEXTURE_VALUES

TYPE = "HaptiCAD::SimilarityStudy"
SCHEMA_VERSION = 1
# eq. 2's parameters a stimulus sets (TEXTURE_VALUES, the surface's properties) as the paper writes them
SYMBOLS = dict(zip(TEXTURE_VALUES, ("f_DC", "f_vis", "beta_h", "alpha_h", "beta_vis", "alpha_vis")))
# what a reference brings along with those: it is presented as it is on its own surface
REFERENCE_VALUES = (*TEXTURE_VALUES, "TexturePeriod", "TextureScale", "TextureFullRange")
# what the stimuli take from the study's surface: runs felt with other values are not pooled
# (property: its words and unit, to say so)
CONTEXT_WORDS = {"TexturePeriod": ("period", " mm"), "TextureScale": ("texture scale", ""),
                 "TextureFullRange": ("full range", " N"), "StaticFriction": ("static friction", ""),
                 "StickSpeed": ("stick speed", " mm/s")}
# kept in the context since 2026-11-24: a run kept before has none, and is not held apart by it
CONTEXT_ADDED = ("StickSpeed",)
LIKENESS = "closer to A"
# a texture held out counts as felt once the finger slid this many of its grating's periods
# over the face: a grating is felt by the force changing along the stroke, so one full
# cycle of it (the paper's participants stroked freely; it gives no minimum); a grating
# coarser than FELT_STROKE_MM once stroked that far (a stroke a fingertip makes at once)
FELT_PERIODS = 1.0
FELT_STROKE_MM = 10.0
EXACT_STRESS = 1e-5  # the core's OrdinalScalingOptions.exact_stress: below it the order fits exactly
PROPERTIES = [
    ("Surface", "App::PropertyLink", "Study", "The haptic surface whose faces the participants stroke", None, None),
    ("ReferenceA", "App::PropertyLink", "References",
     "A haptic surface with the texture of reference A (e.g. fitted to recordings of a real sample)", None, None),
    ("ReferenceB", "App::PropertyLink", "References", "A haptic surface with the texture of reference B", None, None),
    ("RatingSteps", "App::PropertyIntegerConstraint", "Protocol",
     "Steps of the similarity scale: 1 is nothing alike, the top the same", 7, (3, 11, 1)),
    ("WarmUps", "App::PropertyIntegerConstraint", "Protocol", "Warm-up comparisons before the kept ones (not kept)",
     12, (0, 100, 1)),
    ("Repeats", "App::PropertyIntegerConstraint", "Protocol",
     "Times each stimulus is classed as closer to A or to B", 3, (1, 20, 1)),
    ("Dimensions", "App::PropertyIntegerConstraint", "Analysis", "Dimensions of the perceptual space", 2, (1, 3, 1)),
    ("Scaling", "App::PropertyEnumeration", "Analysis",
     "How the space follows the ratings: Metric (classical MDS: the dissimilarities taken as distances) or "
     "Ordinal (Kruskal's nonmetric MDS: only their order counts, for a scale used unevenly)",
     ["Metric", "Ordinal"], None),
    ("Participants", "App::PropertyInteger", "Cohort",
     "Participants whose runs are kept (a participant who ran twice counts once)", 0, None),
]
HIDDEN_STATE = [("Stimuli", "The stimuli: name and eq. 2's values of each (JSON)"),
                ("Responses", "The participants' runs (JSON)")]
# the runs removed on purpose since the document was opened (run_journal.removing): not
# saved, taken back and brought again with the removal by Undo and Redo
REMOVED_RUNS = "RemovedRuns"
# the properties that change what the study's face renders (the others are bookkeeping)
FELT_PROPERTIES = ("Surface", "Stimuli", "ReferenceA", "ReferenceB")
MAX_STIMULI = 20  # 190 pairs: about what a participant rates in one sitting


def paper_stimuli():
    """The paper's nine textures, as [{name, values}]."""
    return [{"name": name.replace("Paper ", ""), "values": dict(zip(TEXTURE_VALUES, values))}
            for name, values in textures.PRESETS.items()]


class SimilarityStudy(SchemaState):
    """Proxy of a SimilarityStudy object."""

    SCHEMA = SCHEMA_VERSION

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj, new=True)

    def setup(self, obj, new=False):
        add_type_tag(obj, TYPE)
        add_properties(obj, PROPERTIES)
        add_hidden_state(obj, HIDDEN_STATE, "Cohort")
        if REMOVED_RUNS not in obj.PropertiesList:
            obj.addProperty("App::PropertyString", REMOVED_RUNS, "Cohort",
                            "The runs removed on purpose since the document was opened (JSON, not saved): their "
                            "files beside the document go with them", 32)  # NoPersist
            obj.setEditorMode(REMOVED_RUNS, 2)
        obj.setEditorMode("Participants", 1)
        if new:
            obj.Stimuli = json.dumps(paper_stimuli())
            obj.Responses = "[]"

    def onChanged(self, obj, prop):
        loading = obj.Document.Restoring or "Restore" in obj.State
        # an undo too: what was held out may no longer be the study's (not while loading,
        # when nothing is held out yet)
        if prop in FELT_PROPERTIES and not loading:
            stop_presenting(obj)
        if prop == REMOVED_RUNS and not loading:  # a removal, or its Undo or Redo
            from . import run_journal

            before, self._removed_seen = getattr(self, "_removed_seen", ""), obj.RemovedRuns
            run_journal.removed_changed(obj, before, obj.RemovedRuns)

    def onDocumentRestored(self, obj):
        self.setup(obj)
        try:  # documents saved before it counted people counted runs
            obj.Participants = count_participants(runs(obj))
        except (ValueError, KeyError, TypeError, AttributeError):
            pass  # unreadable runs: said by validate at the next recompute
        from .surface_object import attach_view_provider

        attach_view_provider(obj)
        obj.purgeTouched()

    def execute(self, obj):
        found = validate(obj)
        if found:
            App.Console.PrintError(f"{obj.Label}: {'; '.join(found)}\n")


def is_similarity_study(obj):
    return getattr(obj, "HaptiCADType", None) == TYPE


def similarity_studies_of(doc):
    return [o for o in doc.Objects if is_similarity_study(o)]


# --- stimuli -------------------------------------------------------------------------

def stimuli(study):
    """The study's stimuli, [{name, values}], in order."""
    try:
        data = json.loads(study.Stimuli or "[]")
    except ValueError:
        raise ValueError(f"{study.Label}: the stored stimuli are not readable JSON") from None
    return data


def stimulus_problems(items):
    """What is wrong with a list of stimuli, as sentences."""
    if not isinstance(items, list) or not all(isinstance(s, dict) and isinstance(s.get("values"), dict)
                                              for s in items):
        return ["each stimulus is {name, values} (a list of them)"]
    found = []
    if len(items) < 3:
        found.append(f"{len(items)} {'stimulus' if len(items) == 1 else 'stimuli'}: a perceptual space needs "
                     "at least 3")
    if len(items) > MAX_STIMULI:
        found.append(f"{len(items)} stimuli make {len(items) * (len(items) - 1) // 2} pairs to rate; "
                     f"keep to {MAX_STIMULI} or fewer")
    names = [str(s.get("name", "")).strip() for s in items]
    if any(not str(n).strip() for n in names):
        found.append("every stimulus needs a name")
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        found.append(f"stimulus names repeat: {', '.join(repeated)}")
    for item in items:
        values = item.get("values", {})
        missing = [SYMBOLS[k] for k in TEXTURE_VALUES if k not in values]
        if missing:
            found.append(f"{item.get('name')}: no {', '.join(missing)}")
        elif not all(isinstance(values[k], (int, float)) and not isinstance(values[k], bool)
                     and math.isfinite(values[k]) for k in TEXTURE_VALUES):
            found.append(f"{item.get('name')}: a value is not a finite number")
    seen = {}
    for item in items:
        key = tuple(item.get("values", {}).get(k) for k in TEXTURE_VALUES)
        if key in seen:
            found.append(f"{item.get('name')} is the same texture as {seen[key]}: nothing to tell apart")
        seen.setdefault(key, item.get("name"))
    return found


def set_stimuli(study, items):
    """Replaces the stimuli. Raises ValueError, changing nothing, if they are not valid."""
    found = stimulus_problems(items)
    if found:
        raise ValueError(f"{study.Label}: {'; '.join(found)}")
    study.Stimuli = json.dumps([{"name": str(s["name"]).strip(),
                                 "values": {k: float(s["values"][k]) for k in TEXTURE_VALUES}} for s in items])


def texture_of(surface):
    """A surface's eq. 2 values, {property: value}; ValueError if it renders no texture."""
    if surface.Texture == "None":
        raise ValueError(f"{surface.Label} has no texture (its Texture is None): nothing to present")
    return {k: float(getattr(surface, k)) for k in TEXTURE_VALUES}


def add_stimulus_from(study, surface, name=None):
    """Adds a surface's texture as a stimulus (a texture fitted to a recording, say).
    Returns notes (sentences): a stimulus is eq. 2's values only, felt with the study
    surface's period and scale, so a source felt otherwise is said."""
    items = [*stimuli(study), {"name": name or surface.Label, "values": texture_of(surface)}]
    set_stimuli(study, items)
    return stimulus_notes(study, surface)


def stimulus_notes(study, surface):
    """What of ``surface``'s texture a stimulus taken from it leaves behind: its period,
    scale or full range, where they differ from the study surface's."""
    felt_on = study.Surface
    if felt_on is None or surface is felt_on:
        return []
    keys = ["TexturePeriod", "TextureScale"]
    if surface.TextureScale == felt_on.TextureScale == "Device force":
        keys.append("TextureFullRange")
    differ = [k for k in keys if getattr(surface, k) != getattr(felt_on, k)]
    if not differ:
        return []

    def said(obj, key):
        value = getattr(obj, key)
        if key == "TexturePeriod":
            return f"period {value:g} mm"
        if key == "TextureFullRange":
            return f"full range {value:g} N" if value else "the device's full range"
        return f"scale {value}"

    return [f"{surface.Label}'s texture was added as eq. 2's values; a stimulus is felt with {felt_on.Label}'s "
            f"{', '.join(said(felt_on, k) for k in differ)}, not {surface.Label}'s "
            f"{', '.join(said(surface, k) for k in differ)}: it will not feel as it does there"]


# --- validity ------------------------------------------------------------------------

def felt_context(study):
    """What the stimuli were felt with besides their own values, as the renderer uses it
    (force_renderer.cc): the surface's period, scale and stick speed; its full range
    under Device force; its static friction under Friction level (for it or a reference,
    presented on the same surface); and the references' textures. Runs are pooled only
    with runs of the same context (same_context)."""
    from .surface_object import is_haptic_surface

    if study.Surface is None or not is_haptic_surface(study.Surface):
        return {}  # nothing can be felt: no run matches
    context = {k: getattr(study.Surface, k) for k in ("TexturePeriod", "TextureScale", "StickSpeed",
                                                      "TextureFullRange", "StaticFriction")}
    for key, surface in references(study).items():
        if is_haptic_surface(surface) and surface.Texture != "None":
            # presented on the study's surface: a friction level is of that surface's friction
            context[f"Reference{key}"] = {**reference_texture(surface), "StaticFriction": study.Surface.StaticFriction}
    return as_felt(context)


def _felt_part(values):
    return {k: v for k, v in values.items()
            if not (k == "TextureFullRange" and values.get("TextureScale") != "Device force"
                    or k == "StaticFriction" and values.get("TextureScale") != "Friction level")}


def as_felt(context):
    """``context`` without what its scales leave unfelt, for the surface and each
    reference alike: the full range but under Device force, the static friction but
    under Friction level (runs kept before held both whatever the scale, and a
    reference's own friction, compared as it stands)."""
    return {k: _felt_part(v) if k.startswith("Reference") and isinstance(v, dict) else v
            for k, v in _felt_part(context).items()}


def same_context(then, now):
    """Whether a run felt with ``then`` (a kept run's or journal's context) pools with
    one felt with ``now`` (felt_context)."""
    return _compared(then, now) == _compared(now, then)


def _compared(context, other):
    """``context`` as felt, as compared with ``other``: JSON's lists for tuples, and a key
    added since (CONTEXT_ADDED) left out when ``other`` predates it."""
    felt = json.loads(json.dumps(as_felt(context)))
    return {k: v for k, v in felt.items() if k not in CONTEXT_ADDED or k in other}


def pooled_runs(doc):
    """{study name: how many of its runs are pooled now} of a document's similarity
    studies (runs stored unreadably count as none)."""
    counts = {}
    for study in similarity_studies_of(doc):
        try:
            counts[study.Name] = len(comparable_runs(study))
        except ValueError:
            counts[study.Name] = 0
    return counts


def unpooling_notes(doc, before):
    """Sentences for the studies of ``doc`` that pool fewer runs than ``before``
    (pooled_runs) said: an edit changed what their participants felt."""
    notes = []
    now = pooled_runs(doc)
    for study in similarity_studies_of(doc):
        lost = before.get(study.Name, 0) - now.get(study.Name, 0)
        if lost > 0:
            notes.append(f"{study.Label}: {lost} run{'s' if lost != 1 else ''} felt on the surface as it was "
                         f"{'are' if lost != 1 else 'is'} no longer pooled with runs made now (undo to pool "
                         f"{'them' if lost != 1 else 'it'} again)")
    return notes


def references(study):
    """{"A": surface, "B": surface} of the references set (both or neither count)."""
    return {key: getattr(study, f"Reference{key}") for key in "AB" if getattr(study, f"Reference{key}") is not None}


def validate(study):
    """Problems that keep a run from starting, as sentences (empty when fine)."""
    from .surface_object import is_haptic_surface, linked_surface_problems

    found = linked_surface_problems(study, similarity_studies_of(study.Document), "stroke",
                                    "a face presents one texture at a time")
    surface = study.Surface
    if (surface is not None and is_haptic_surface(surface) and surface.TextureScale == "Friction level"
            and surface.StaticFriction == 0):
        found.append(f"{surface.Label}'s texture level 1 is its friction, and its static friction is 0: "
                     "the stimuli would render nothing; raise the friction, or make level 1 a device force")
    try:
        found.extend(stimulus_problems(stimuli(study)))
    except ValueError as exc:
        found.append(str(exc))
    refs = references(study)
    if len(refs) == 1:
        missing = "B" if "A" in refs else "A"
        found.append(f"reference {missing} is not set: classing needs both references, or neither")
    for key, surface in refs.items():
        if not is_haptic_surface(surface):
            found.append(f"reference {key}, {surface.Label}, is not a haptic surface")
        elif surface.Texture == "None":
            found.append(f"reference {key}, {surface.Label}, has no texture")
        elif (surface.TextureScale == "Friction level" and study.Surface is not None
              and is_haptic_surface(study.Surface) and surface.StaticFriction != study.Surface.StaticFriction):
            # its level 1 is its own face's friction, which the study's face does not have
            found.append(f"reference {key}, {surface.Label}, scales its texture by its friction "
                         f"(mu_s {surface.StaticFriction:g}), and {study.Surface.Label}'s is "
                         f"{study.Surface.StaticFriction:g}: it would not feel as it does; make its level 1 a "
                         "device force, or give the two faces the same friction")
    if len(refs) == 2 and refs["A"] == refs["B"]:
        found.append("references A and B are the same surface")
    return found


# --- presenting ----------------------------------------------------------------------

_presented = {}  # (document name, study name) -> (the document, {surface property: value})


def _key(study):
    return study.Document.Name, study.Name


def present(study, values):
    """Holds ``values`` ({surface property: value}, a stimulus's or a reference's) out on
    the study's surface, or nothing (None). Not saved and not an undo step: it is what a
    participant feels now, not the design. Return the values presented."""
    if values is None:
        _presented.pop(_key(study), None)
    else:
        _presented[_key(study)] = (study.Document, dict(values))
    return values


def stop_presenting(study):
    present(study, None)


def presented_texture(surface):
    """What a running similarity study holds out on ``surface`` now ({surface property:
    value}, over the surface's own), or None."""
    if not _presented:
        return None
    for (doc_name, name), (doc, values) in list(_presented.items()):
        # the very document (a closed one's name may come back on another) and study
        study = doc.getObject(name) if App.listDocuments().get(doc_name) is doc else None
        if study is None or not is_alive(study):
            del _presented[(doc_name, name)]  # the study is gone: nothing stays held out
        elif study.Surface == surface:
            return values
    return None


def rendered_texture(surface):
    """The grating a surface's faces render now, {surface property: value} over
    REFERENCE_VALUES: what a study holds out on it, over its own texture; None when it
    has no texture and nothing is held out."""
    presented = presented_texture(surface)
    if presented is None and surface.Texture == "None":
        return None
    return {**{k: getattr(surface, k) for k in REFERENCE_VALUES}, **(presented or {})}


def reference_texture(surface):
    """A reference surface's texture, whole, as presented values."""
    texture_of(surface)  # refuses a surface without one
    return {k: getattr(surface, k) for k in REFERENCE_VALUES}


# --- a participant's run -------------------------------------------------------------

@dataclass
class Trial:
    kind: str  # "warm-up", "pair" or "class"
    first: int  # stimulus index
    second: int = -1  # stimulus index (pairs), -1 for a class trial


def warm_up_pairs(rng, n, count):
    """``count`` warm-up pairs of n stimuli (seed 001 §IV: they "provide context" for the
    ratings), in random order: first pairs that together hold every stimulus (a shuffled
    order paired off), then the other pairs; a pair twice only when count exceeds them all.
    Drawn with repeats, 435 of 500 runs repeated a pair and 200 left a stimulus unfelt."""
    pairs = list(itertools.combinations(range(n), 2))
    if not pairs or count <= 0:
        return []
    order = list(range(n))
    rng.shuffle(order)
    covering = [tuple(sorted(order[k:k + 2])) for k in range(0, n - 1, 2)]
    if n % 2:
        covering.append(tuple(sorted((order[-1], rng.choice(order[:-1])))))
    rest = [p for p in pairs if p not in covering]
    rng.shuffle(rest)
    chosen = (covering + rest)[:count]
    while len(chosen) < count:  # more warm-ups than pairs
        again = pairs[:]
        rng.shuffle(again)
        chosen += again[:count - len(chosen)]
    rng.shuffle(chosen)
    return chosen


class Run:
    """One participant's run through the protocol, in the order a seeded shuffle gives.
    ``present`` holds a texture of the current trial out on the face (present only while
    a Feel session renders the face; when it stops, ``forget_felt``), and ``stroked``
    counts how far the finger slid over the face since: a texture held out is felt once
    it was stroked over one period of its grating (``felt_after_mm``), not merely held
    out while the hand was elsewhere. ``answer`` takes a rating (1..steps) for a pair or
    warm-up, "A" or "B" for a class trial, once the trial's textures were felt (both of a
    pair, the texture of a class trial: ``unfelt``); ``back`` takes the last answer back.
    Nothing is kept in the document until record_run."""

    def __init__(self, study, participant, seed=None):
        found = validate(study)
        if found:
            raise ValueError(f"{study.Label}: {'; '.join(found)}")
        if not str(participant).strip():
            raise ValueError("a participant needs a name (or an alias)")
        self.study = study
        self.participant = str(participant).strip()
        self.seed = random.SystemRandom().randrange(2**31) if seed is None else int(seed)
        self.started = datetime.now().isoformat(timespec="seconds")
        self.felt_with = {}  # what rendered it: {"device": name, "servo_rate_hz": rate}, kept with it
        self.stimuli = stimuli(study)
        self.steps = int(study.RatingSteps)
        # the settings the trials are drawn and rated with, as the run began (run_journal)
        self.protocol = {"RatingSteps": self.steps, "WarmUps": int(study.WarmUps), "Repeats": int(study.Repeats)}
        self.has_references = len(references(study)) == 2
        self.context = felt_context(study)
        rng = random.Random(self.seed)
        n = len(self.stimuli)
        pairs = list(itertools.combinations(range(n), 2))
        warm = warm_up_pairs(rng, n, int(study.WarmUps))
        kept = pairs[:]
        rng.shuffle(kept)
        self.trials = [Trial("warm-up", *(p if rng.random() < 0.5 else p[::-1])) for p in warm]
        self.trials += [Trial("pair", *(p if rng.random() < 0.5 else p[::-1])) for p in kept]
        if self.has_references:
            classed = [i for i in range(n) for _ in range(int(study.Repeats))]
            rng.shuffle(classed)
            self.trials += [Trial("class", i) for i in classed]
        self.answers = []
        self.felt = set()  # the slots of the current trial felt so far (1, 2, "A", "B")
        self.held = None  # the slot held out on the face now
        self.slid_mm = 0.0  # how far the finger slid over the face since it was held out
        self.period_mm = 0.0  # the held texture's grating period

    @property
    def done(self):
        return len(self.answers) == len(self.trials)

    @property
    def current(self):
        return None if self.done else self.trials[len(self.answers)]

    def progress(self):
        """(kind, number within its kind, count of its kind) of the current trial."""
        trial = self.current
        if trial is None:
            return "done", 0, 0
        same = [t for t in self.trials if t.kind == trial.kind]
        before = sum(1 for t in self.trials[:len(self.answers)] if t.kind == trial.kind)
        return trial.kind, before + 1, len(same)

    def values(self, slot):
        """What to present for the current trial's ``slot``: 1 or 2 (a pair's first or
        second texture, a class trial's texture: 1), "A" or "B" (the references)."""
        trial = self.current
        if trial is None:
            raise ValueError("the run is done: nothing to present")
        if slot in ("A", "B"):
            reference = getattr(self.study, f"Reference{slot}") if self.has_references else None
            if reference is None:
                raise ValueError(f"reference {slot} is not set (any more)")
            return reference_texture(reference)
        if slot == 2 and trial.kind == "class":
            raise ValueError("a class trial presents one texture, and references A and B")
        index = trial.first if slot == 1 else trial.second
        return self.stimuli[index]["values"]

    def present(self, slot):
        """Holds the current trial's ``slot`` out on the face. Raises ValueError when the
        study can no longer run (its surface or a reference gone)."""
        if not is_alive(self.study):
            raise ValueError("the study was deleted")
        found = validate(self.study)
        if found:
            raise ValueError("; ".join(found))
        values = present(self.study, self.values(slot))
        self.held, self.slid_mm = slot, 0.0
        self.period_mm = float(values.get("TexturePeriod", self.study.Surface.TexturePeriod))
        return values

    def stroked(self, slid_mm):
        """The finger slid ``slid_mm`` (mm) over the study's faces while the held texture
        was on them (trace_path.slid_mm of the loop's trace); the texture counts as felt
        once it was stroked ``felt_after_mm``."""
        if self.held is None or self.current is None:
            return
        self.slid_mm += max(0.0, float(slid_mm))
        if self.slid_mm >= self.felt_after_mm:
            self.felt.add(self.held)

    @property
    def felt_after_mm(self):
        """How far the held texture is stroked before it counts as felt (mm)."""
        return min(FELT_PERIODS * self.period_mm, FELT_STROKE_MM)

    def present_each(self):
        """Presents in turn every texture the current trial needs felt, each stroked over
        what makes it felt (a scripted participant); the last stays held out."""
        for slot in self.needed():
            self.present(slot)
            self.stroked(self.felt_after_mm)

    def needed(self):
        """The slots the current trial must have felt before an answer, in order: a
        pair's (or warm-up's) two textures, a class trial's texture (empty when done)."""
        trial = self.current
        if trial is None:
            return []
        return [1] if trial.kind == "class" else [1, 2]

    def unfelt(self):
        """The needed slots (``needed``) not felt yet in the current trial."""
        return [slot for slot in self.needed() if slot not in self.felt]

    @property
    def ready(self):
        """True when the current trial can be answered: its textures were felt."""
        return self.current is not None and not self.unfelt()

    def forget_felt(self):
        """Nothing of the current trial counts as felt any more (the Feel session
        stopped: nothing was felt since, so the trial starts over)."""
        self.felt = set()
        self.held = None

    def answer(self, value):
        """Takes the current trial's answer. Raises ValueError, changing nothing, when
        the run is done, a texture of the trial was not felt yet, or ``value`` is not an
        answer the trial takes."""
        trial = self.current
        if trial is None:
            raise ValueError("the run is done")
        unfelt = self.unfelt()
        if unfelt:
            names = " and ".join("the texture" if trial.kind == "class" else f"texture {slot}" for slot in unfelt)
            raise ValueError(f"feel {names} before answering")
        if trial.kind == "class":
            if value not in ("A", "B"):
                raise ValueError(f"class the texture as A or B, not {value!r}")
        elif not (type(value) is int and 1 <= value <= self.steps):
            raise ValueError(f"rate the pair 1..{self.steps}, not {value!r}")
        self.answers.append(value)
        self.felt, self.held = set(), None  # the next trial's textures are felt anew
        stop_presenting(self.study)  # the next trial starts with nothing held out

    def back(self):
        if self.answers:
            self.answers.pop()
        self.felt, self.held = set(), None  # the trial taken back is felt again before it is answered
        stop_presenting(self.study)

    def as_record(self):
        """The run as it is kept: the pairs' ratings (not the warm-ups) and the classes."""
        if not self.done:
            raise ValueError(f"{self.participant}'s run is not done: {len(self.trials) - len(self.answers)} "
                             "trials remain")
        ratings = [[min(t.first, t.second), max(t.first, t.second), a]
                   for t, a in zip(self.trials, self.answers) if t.kind == "pair"]
        choices = [[t.first, a] for t, a in zip(self.trials, self.answers) if t.kind == "class"]
        # every answer in the order given, warm-ups included, each pair in the order felt:
        # for order effects (the ratings above are what the analysis reads)
        sequence = [[t.kind, t.first, t.second, a] for t, a in zip(self.trials, self.answers)]
        return {"name": self.participant, "started": self.started,
                "recorded": datetime.now().isoformat(timespec="seconds"), **self.felt_with, "seed": self.seed,
                "steps": self.steps, "stimuli": self.stimuli, "ratings": ratings, "choices": choices,
                "trials": sequence, "context": self.context}


def record_problems(record):
    """What is wrong with a kept run, as sentences."""
    found = []
    try:
        steps, items = record["steps"], record["stimuli"]
        if type(steps) is not int or steps < 2:
            return [f"{record.get('name')}: a scale of {steps!r} steps"]
        if any(type(x) is not int for rating in record["ratings"] for x in rating) or any(
                type(i) is not int for i, _ in record["choices"]):
            return [f"{record.get('name')}: a stimulus index or rating is not a whole number"]
        count = len(items)
        pairs = {(i, j) for i, j, _ in record["ratings"]}
        if not str(record["name"]).strip():
            found.append("a run needs a participant's name")
        if pairs != set(itertools.combinations(range(count), 2)) or len(record["ratings"]) != len(pairs):
            found.append(f"{record['name']}: the ratings are not every pair of {count} stimuli once")
        if any(not 1 <= s <= steps for _, _, s in record["ratings"]):
            found.append(f"{record['name']}: a rating is outside 1..{steps}")
        if any(c not in ("A", "B") or not 0 <= i < count for i, c in record["choices"]):
            found.append(f"{record['name']}: a class is not A or B of a stimulus")
        for kind, first, second, _ in record.get("trials", []):  # the order (runs kept since it is)
            if kind not in ("warm-up", "pair", "class") or type(first) is not int or type(second) is not int or (
                    not 0 <= first < count or not (second == -1 if kind == "class" else 0 <= second < count)):
                found.append(f"{record['name']}: the trial order names a stimulus it does not have")
                break
        found.extend(stimulus_problems(items))
    except (KeyError, TypeError, ValueError) as exc:
        found.append(f"not a similarity run: {exc}")
    return found


def runs(study):
    """The kept runs, oldest first."""
    try:
        return json.loads(study.Responses or "[]")
    except ValueError:
        raise ValueError(f"{study.Label}: the stored runs are not readable JSON") from None


def by_participant(records):
    """The runs grouped by participant_key, each group oldest first, groups in order of
    their first run."""
    groups = {}
    for record in records:  # a damaged record (validate says so) is no one's
        if isinstance(record, dict) and participant_key(record.get("name", "")):
            groups.setdefault(participant_key(record["name"]), []).append(record)
    return list(groups.values())


def count_participants(records):
    return len(by_participant(records))


def record_run(study, run):
    """Keeps a finished run in the study. Raises ValueError, keeping nothing, if it is not done."""
    record = run.as_record() if isinstance(run, Run) else run
    found = record_problems(record)
    if found:
        raise ValueError("; ".join(found))
    kept = [*runs(study), record]
    study.Responses = json.dumps(kept)
    study.Participants = count_participants(kept)
    return record


def remove_run(study, index):
    """Removes the kept run at ``index`` (of runs) on purpose: its file beside the document,
    if the document was not saved with it, goes too, so it is never offered back as lost
    (run_journal.removing; an Undo of the removal writes it again). Raises ValueError if
    there is none."""
    from . import run_journal

    kept = runs(study)
    if not 0 <= index < len(kept):
        raise ValueError(f"{study.Label}: no run {index + 1} (it has {len(kept)})")
    run_journal.removing(study, kept.pop(index))
    study.Responses = json.dumps(kept)
    study.Participants = count_participants(kept)


def same_stimuli(a, b):
    return len(a) == len(b) and all(
        all(math.isclose(x["values"][k], y["values"][k], rel_tol=0, abs_tol=1e-12) for k in TEXTURE_VALUES)
        for x, y in zip(a, b))


def comparable(record, study):
    """True when a kept run's ratings pool with the study as it is now: made on the
    stimuli and surface it holds, and whole (why_not_pooled). Its classings pool only
    when the references are the same too (classings_pooled)."""
    return not why_not_pooled(record, study)


def classings_pooled(record, study):
    """True when a kept run's classings pool with the study as it is now: its ratings
    do (comparable) and it classed against the references the study holds."""
    return not why_not_pooled(record, study, references=True)


def _reference_keys(context):
    return {k for k in context if k.startswith("Reference")}


def why_not_pooled(record, study, references=False):
    """Why a kept run is not pooled with the study as it is now, in words ("" when it is):
    what of its stimuli or surface differs, and with ``references`` (for its classings)
    of its references too. The pairs are rated before any reference is felt (the
    protocol's order), so other references, or none now, do not keep the ratings apart."""
    if record_problems(record):
        return "incomplete or damaged"
    if not same_stimuli(record["stimuli"], stimuli(study)):
        return "on other stimuli"
    then, now = record.get("context") or {}, felt_context(study)
    if not references:
        then = {k: v for k, v in then.items() if k not in _reference_keys(then)}
        now = {k: v for k, v in now.items() if k not in _reference_keys(now)}
    if same_context(then, now):
        return ""
    if not now:
        return "on a surface the study no longer has"
    then, now = _compared(then, now), _compared(now, then)
    surface = []
    for key, (word, unit) in CONTEXT_WORDS.items():
        if then.get(key) != now.get(key) and (key in then and key in now or key == "TextureScale"):
            def text(v, unit=unit):
                return "none" if v is None else f"{v:g}{unit}" if isinstance(v, float) else f"{v}{unit}"
            surface.append(f"the surface's {word} {text(then.get(key))} (now {text(now.get(key))})")
    refs = [f"another reference {key}" if now.get(f"Reference{key}") else f"a reference {key} the study no longer has"
            for key in "AB" if then.get(f"Reference{key}") != now.get(f"Reference{key}")]
    said = ([f"felt with {', '.join(surface)}"] if surface else []) + (
        [f"classed against {' and '.join(refs)}"] if refs else [])
    return "; ".join(said) or "felt otherwise"


def held_note(study, kept):
    """"3 runs felt with the surface's period 2.5 mm (now 3 mm)" and the like: the kept runs
    of ``study`` not among ``kept`` (pooled), grouped by why."""
    reasons = {}
    for record in runs(study):
        if record not in kept:
            reason = why_not_pooled(record, study)
            reasons[reason] = reasons.get(reason, 0) + 1
    return "; ".join(f"{n} run{'s' if n != 1 else ''} {reason}" for reason, n in reasons.items())


def comparable_runs(study):
    """The runs analyse pools: those comparable with the study as it is."""
    return [r for r in runs(study) if comparable(r, study)]


# --- analysis ------------------------------------------------------------------------

def dissimilarity(kept, n):
    """The cohort's dissimilarity matrix: 1 - the mean similarity of each pair, every
    rating first scaled to 0 (nothing alike) .. 1 (the same) by its run's steps. Each
    participant weighs the same: the runs of one who ran more than once are averaged
    first (the paper ran each of its ten subjects once)."""
    total = np.zeros((n, n))
    people = by_participant(kept)
    for own in people:
        for record in own:
            steps = record["steps"]
            for i, j, s in record["ratings"]:
                total[i, j] += (s - 1) / (steps - 1) / len(own)
    mean = total / len(people)
    mean = mean + mean.T
    d = 1.0 - mean
    np.fill_diagonal(d, 0.0)
    return d


def analyse(study):
    """The perceptual space of the study's comparable runs, as a dict:
    ``stimuli`` (names), ``stimulus_values`` (eq. 2's values of each), ``dissimilarity``
    (the pooled n x n matrix scaled), ``points`` (n x dims), ``stress``, ``explained``,
    ``eigenvalues``, ``vectors`` ({label: {direction, length, correlation, low, high}}),
    ``likeness`` (per stimulus, the share classed closer to A, or None), ``participants``
    (the people pooled, by participant_key), ``runs`` (their runs),
    ``classed_by`` (the runs whose classings make ``likeness``: classings_pooled),
    ``held`` (runs not pooled), ``held_note`` (why, in words), ``notes``, ``scaling`` ("metric" or "ordinal", the
    study's Scaling) and ``iterations`` (ordinal scaling's rounds). Raises ValueError
    when there is nothing to analyse."""
    items = stimuli(study)
    kept = comparable_runs(study)
    held = len(runs(study)) - len(kept)
    if not kept:
        if held:
            raise ValueError(f"{study.Label}: no run is pooled with the study as it is now: {held_note(study, kept)} "
                             f"(kept, not pooled)")
        raise ValueError(f"{study.Label}: no participant has rated these stimuli yet")
    n = len(items)
    dims = int(study.Dimensions)
    if dims >= n:
        raise ValueError(f"{study.Label}: {dims} dimensions for {n} stimuli; give fewer than {n}")
    ordinal = study.Scaling == "Ordinal"
    d = dissimilarity(kept, n)
    apart = d[np.triu_indices(n, 1)]
    if apart.max() - apart.min() < 1e-12:
        # no differences to lay out: every layout fits them (stress 0, "fits exactly") and the
        # vectors would be fitted to an arbitrary one
        how = ("the same" if apart[0] < 1e-12 else "nothing alike" if apart[0] > 1 - 1e-12
               else f"alike to one degree ({100 * (1 - apart[0]):.0f} % of the scale)")
        raise ValueError(f"{study.Label}: every pair was rated {how}, so the ratings hold no differences to lay out: "
                         "no space can be drawn from them (check the scale was used, or collect more runs)")
    space = _core.compute_ordinal_perceptual_space(d, dims) if ordinal else _core.compute_perceptual_space(d, dims)
    notes = []
    if ordinal and not space.converged:
        notes.append(f"ordinal scaling stopped after {space.iterations} rounds before it settled")
    if ordinal and n < 4 * dims + 1:
        notes.append(f"{n} stimuli in {dims} dimensions: too few pairs for only their order to hold the space "
                     "(it can collapse into clusters); compare with the metric scaling")
    vectors = {}
    for key in TEXTURE_VALUES:
        values = [s["values"][key] for s in items]
        try:
            q = _core.scale_to_unit_range(values)
        except ValueError:
            continue  # held constant, as the paper's beta_h and alpha_h: no vector
        vectors[SYMBOLS[key]] = _vector(space.points, q, f"low {SYMBOLS[key]}", f"high {SYMBOLS[key]}")
    likeness = [None] * n
    counts = [[0.0, 0.0] for _ in range(n)]
    classed = [r for r in kept if r["choices"] and classings_pooled(r, study)]
    for own in by_participant(classed):  # as the ratings: each participant weighs the same
        for record in own:
            for i, choice in record["choices"]:
                counts[i][0 if choice == "A" else 1] += 1.0 / len(own)
    apart = [r for r in kept if r["choices"] and r not in classed]
    if apart:  # their ratings are in the space; their classings meant other references
        reasons = sorted({why_not_pooled(r, study, references=True) for r in apart})
        notes.append(f"the classings of {len(apart)} run{'s' if len(apart) != 1 else ''} are left out of the "
                     f"likeness to the references ({'; '.join(reasons)}); their ratings are pooled")
    if any(a + b for a, b in counts):
        likeness = [a / (a + b) if a + b else None for a, b in counts]
        if None in likeness:
            notes.append("some stimuli were never classed: no vector for likeness to the references")
        else:
            q = [share - 0.5 for share in likeness]  # the paper: always B -0.5, always A +0.5
            if max(q) - min(q) > 1e-12:
                vectors[LIKENESS] = _vector(space.points, q, "like B", "like A")
            else:  # one share for every stimulus: nothing to point along (a vector of length 0 was shown)
                how = ("closer to A" if q[0] > 0 else "closer to B" if q[0] < 0 else "A and B equally often")
                notes.append(f"every stimulus was classed {how}: no vector for likeness")
    if space.stress > 0.2:
        notes.append(f"stress {space.stress:.2f}: the space's distances stray from the dissimilarities by a "
                     "fifth or more; more dimensions or more participants may help")
    steps = sorted({record["steps"] for record in kept})
    if len(steps) > 1:  # pooled as the share of each scale's range: say so, it is a choice
        notes.append(f"runs rated on {' and '.join(map(str, steps))}-step scales are pooled, each rating taken as "
                     "its share of its own scale's range")
    people = by_participant(kept)
    again = [own for own in people if len(own) > 1]
    if again:
        names = ", ".join(f"{own[0]['name']} ({len(own)})" for own in again)
        notes.append(f"runs of one participant are averaged before pooling, so each participant weighs the same: "
                     f"{names}")
    if len(people) < 3:
        notes.append(f"{len(people)} participant{'s' if len(people) != 1 else ''}: the space shows one or two "
                     "people's impressions, not a cohort's")
    return {"stimuli": [s["name"] for s in items], "stimulus_values": [dict(s["values"]) for s in items],
            "dissimilarity": d.tolist(), "points": space.points.tolist(), "stress": space.stress,
            "scaling": "ordinal" if ordinal else "metric", "iterations": space.iterations,
            "explained": space.explained, "eigenvalues": list(space.eigenvalues), "vectors": vectors,
            "likeness": likeness, "participants": len(people), "runs": len(kept), "classed_by": len(classed),
            "held": held,
            "held_note": held_note(study, kept) if held else "", "notes": notes}


def describe(study, result):
    """A few lines of text of ``result`` (analyse) for the console and the panel."""
    n, count = result["participants"], result.get("runs", result["participants"])
    lines = [f"{study.Label}: {len(result['stimuli'])} stimuli, {n} participant{'s' if n != 1 else ''}"
             + (f" in {count} runs" if count != n else "")
             + (f" (not pooled: {result['held_note']})" if result["held"] else ""),
             (f"  ordinal scaling, Kruskal's stress-1 {result['stress']:.3f}"
              + (": the ratings' order fits exactly" if result["stress"] < EXACT_STRESS else "")
              + f" ({result['iterations']} rounds)"
              if result.get("scaling") == "ordinal" else
              f"  stress {result['stress']:.3f}, the axes hold {100 * result['explained']:.0f} % of the spread")]
    for label, v in sorted(result["vectors"].items(), key=lambda kv: -kv[1]["length"]):
        lines.append(f"  {label:<12} |p| {v['length']:.3f}  r {v['correlation']:.2f}")
    lines.extend(f"  note: {n}" for n in result["notes"])
    return "\n".join(lines)


def _vector(points, q, low, high):
    v = _core.fit_property_vector(points, q)
    return {"direction": [float(x) for x in v.direction], "length": v.length, "correlation": v.correlation,
            "low": low, "high": high}


def make_similarity_study(doc, surface, name="SimilarityStudy", items=None, **properties):
    """A similarity study of textures felt on ``surface``'s faces: the paper's nine, or
    ``items`` ([{name, values}]). Properties may be given by name. Raises ValueError on
    bad input, adding nothing."""
    from .surface_object import attach_view_provider, is_haptic_surface

    if isinstance(surface, str):
        surface = doc.getObject(surface) or next(iter(doc.getObjectsByLabel(surface)), None)
    if surface is None or not is_haptic_surface(surface) or surface.Document != doc:
        raise ValueError("make_similarity_study: give a haptic surface of this document")
    unknown = [k for k in properties if k not in {p[0] for p in PROPERTIES}]
    if unknown:
        raise ValueError(f"make_similarity_study: unknown properties {', '.join(unknown)}")
    if items is not None:
        found = stimulus_problems(items)
        if found:
            raise ValueError(f"make_similarity_study: {'; '.join(found)}")
    obj = doc.addObject("App::FeaturePython", name)
    SimilarityStudy(obj)
    try:
        obj.Surface = surface
        if items is not None:
            set_stimuli(obj, items)
        for key, value in properties.items():
            setattr(obj, key, value)
    except Exception as exc:  # a value the property refuses: no half-made study
        doc.removeObject(obj.Name)
        raise ValueError(f"make_similarity_study: {exc}") from None
    attach_view_provider(obj)
    obj.recompute()
    return obj
