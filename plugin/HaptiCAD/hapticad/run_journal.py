# SPDX-License-Identifier: GPL-3.0-or-later
"""A similarity run in progress, written to disk after every answer, so that a crash
(FreeCAD's, the machine's) loses no participant's answers: the document holds a run only
once it is kept, and is saved only when the designer saves it.

One JSON file per study of a saved document, in FreeCAD's user data folder
(``HaptiCAD/runs``), named from the document's path and the study's name; it holds the
participant, the seed, the trials and answers so far, and what the run was felt on. A
run is resumed only on the study as it was (the same trials from the same seed, the same
stimuli and context): ``resumable`` says why not otherwise. The file goes when the run
is kept or stopped. App-only.

A kept run is in the document, but on disk only once the document is saved: until then
it is written here too (``write_kept``, one file per kept run), offered back by
``unsaved_kept`` if the document was closed or lost without it, and forgotten when the
document is saved holding it (``SaveWatcher``). A kept run removed on purpose
(similarity_study.remove_run, the study panel's Remove) is forgotten with it
(``removed_changed``), and written again when an Undo puts it back in the document.

How a kept run was lost is said (``how_lost``) as for a stiffness study's records
(study_journal): the document closed without saving it (the close is seen, and its time
written in the run's file), FreeCAD ended without closing it (a crash), or an Undo took
it out before a save; none forgets it: the designer drops it.

A document moved or renamed since its runs were written is opened under another path:
the run in progress its document left at its earlier place, when there is none under its
path (``read``), and the kept runs it left there (``unsaved_kept``) are taken as if
written here, their files moved to the new path's names, as study_journal takes a
stiffness study's records: known by the study's name and ID and the document's Uid and
last save they record (document_identity), only when the document is gone from the path
they record (and not open in this session), and none when they were left by more than
one such path (copies of one document moved away: whose they are cannot be told; a
warning names them). Where the document was is said (``earlier_path``; a run in
progress's state holds it as ``moved_from``).
"""
import hashlib
import json
import os
from datetime import datetime

import FreeCAD as App

from . import similarity_study as ss
from .atomic_file import write_json
from .document_identity import identity, same_document
from .study_journal import ENDED, said_how_lost as _said_how_lost

# how a kept run was lost besides study_journal's (ENDED, a close's time, ""): an Undo
# took it out of the document, which was saved without it (this session: the document is open)
UNDONE = "undone"


def _folder():
    return os.path.join(App.getUserAppDataDir(), "HaptiCAD", "runs")


def _key(doc_path, study_name):
    return hashlib.sha1(f"{os.path.abspath(doc_path)}\n{study_name}".encode()).hexdigest()[:16]


def path_for(study):
    """Where ``study``'s run in progress is written, or None for a document never saved
    (no path to tell it from another's)."""
    doc_path = study.Document.FileName
    if not doc_path:
        return None
    return os.path.join(_folder(), f"{_key(doc_path, study.Name)}.json")


def write(study, run):
    """Writes ``run`` (answers so far) beside nothing the designer sees; atomically, so
    a crash mid-write leaves the previous answers."""
    path = path_for(study)
    if path is None:
        return
    state = {"document": os.path.abspath(study.Document.FileName), **identity(study.Document),
             "study": study.Name, "study_id": study.ID, "name": run.participant, "seed": run.seed,
             "started": run.started,
             "trials": [[t.kind, t.first, t.second] for t in run.trials], "answers": list(run.answers),
             "stimuli": run.stimuli, "context": run.context, "protocol": run.protocol}
    write_json(path, state)


def read(study):
    """The run in progress written for ``study``, as written, or None; the one its document
    left at its earlier path when there is none here (moved here: see the module's doc)."""
    path = path_for(study)
    if path is None:
        return None
    if not os.path.exists(path):
        found = _moved_here(study, kept=False)
        if len(found) == 1:
            earlier, state = next(iter(found.values()))[0]  # one file a path
            _move(study, earlier, path, state)
        else:
            _say_not_taken(study, found, "a similarity run in progress")
    if not os.path.exists(path):
        return None
    try:
        with open(path, encoding="utf-8") as handle:
            state = json.load(handle)
    except (OSError, ValueError):
        return None
    return state if isinstance(state, dict) and state.get("answers") else None


def _moved_here(study, kept):
    """The files of ``study``'s kept runs (``kept``) or runs in progress written for its
    document at another path, where it is no more (moved or renamed since): {that path:
    [(file, what it holds)]}. Not those whose document still exists at its path or is open
    in this session: they are that one's."""
    try:
        names = sorted(os.listdir(_folder()))
    except OSError:
        return {}
    open_here = {os.path.abspath(d.FileName) for d in App.listDocuments().values() if d.FileName}
    found = {}
    for name in names:
        if not name.endswith(".json") or ("-kept-" in name) != kept:
            continue
        path = os.path.join(_folder(), name)
        try:
            with open(path, encoding="utf-8") as handle:
                state = json.load(handle)
        except (OSError, ValueError):
            continue
        if not isinstance(state, dict):
            continue
        was = state.get("document")
        if not same_document(state, study.Document) or (state.get("study"), state.get("study_id")) != (
                study.Name, study.ID):
            continue
        if isinstance(was, str) and was and not os.path.exists(was) and os.path.abspath(was) not in open_here:
            found.setdefault(os.path.abspath(was), []).append((path, state))
    return found


def _move(study, earlier, path, state):
    """Moves the file ``earlier`` (holding ``state``) to ``path``, of the study's document
    where it is now: in one step (a crash leaves it at one name or the other), then written
    again saying where it was found from. False, warned of, when it cannot be moved (it
    stays where it was, found again next time)."""
    try:
        os.replace(earlier, path)
    except OSError as exc:
        App.Console.PrintWarning(f"HaptiCAD: {study.Label}: a run written when the document was at "
                                 f"{state.get('document')} could not be taken ({exc}): it stays in {earlier}\n")
        return False
    try:
        write_json(path, {**state, "document": os.path.abspath(study.Document.FileName),
                          "moved_from": state.get("document")})
    except OSError:
        pass  # moved as it was: read the same
    return True


# the files said not taken (left by more than one document moved away), said once a session
_SAID_NOT_TAKEN = set()


def _say_not_taken(study, found, what):
    """Warns, once, that the files in ``found`` (of _moved_here, more than one earlier path)
    are not taken: whose they are cannot be told."""
    files = tuple(sorted(f for files in found.values() for f, _ in files))
    if len(found) < 2 or files in _SAID_NOT_TAKEN:
        return
    _SAID_NOT_TAKEN.add(files)
    App.Console.PrintWarning(
        f"HaptiCAD: {study.Label}: {what} left unsaved by {len(found)} copies of this document, each moved away "
        f"since ({', '.join(sorted(found))}), match it; none is taken, as whose they are cannot be told. "
        f"Their files: {', '.join(files)}\n")


def forget(study):
    """The run is kept or stopped: its file goes."""
    path = path_for(study)
    if path is not None and os.path.exists(path):
        os.remove(path)


def _as_written(value):
    return json.loads(json.dumps(value))  # tuples become lists, as the file has them


# the study's settings a run's trials and ratings are made with: (property, words)
PROTOCOL = (("RatingSteps", "Rating steps"), ("WarmUps", "Warm ups"), ("Repeats", "Repeats"))


def protocol_of(study):
    return {name: int(getattr(study, name)) for name, _ in PROTOCOL}


def resumable(study, state):
    """"" when ``state`` can go on on ``study`` as it is now, else why not: what changed
    and, for a setting of the protocol, the value to set back (a rating given on a
    7-step scale is not one on a 5-step scale; the warm-ups and repeats draw the trials)."""
    if state.get("stimuli") != _as_written(ss.stimuli(study)):
        return "the study's stimuli changed since"
    if not ss.same_context(state.get("context") or {}, ss.felt_context(study)):
        return "the surface or a reference changed since"
    then, now = state.get("protocol") or {}, protocol_of(study)  # journals before it: none
    changed = [f"{words} {now[name]} (it was {then[name]}: set it back to go on)"
               for name, words in PROTOCOL if name in then and then[name] != now[name]]
    if changed:
        return f"the study's {', '.join(changed)}"
    return ""


def resume(study, state):
    """The run of ``state`` on ``study``, its answers back. Raises ValueError saying why
    it cannot go on (resumable), or when the seed no longer gives the same trials."""
    why = resumable(study, state)
    if why:
        raise ValueError(f"{state.get('name')}'s run cannot go on: {why}")
    run = ss.Run(study, state["name"], seed=state["seed"])
    if [[t.kind, t.first, t.second] for t in run.trials] != state["trials"]:
        raise ValueError(f"{state.get('name')}'s run cannot go on: its trials were drawn by another version")
    run.started = state.get("started", run.started)
    run.answers = list(state["answers"])
    return run


# --- kept runs the document has not saved yet ------------------------------------------

def _kept_prefix(doc_path, study_name):
    return os.path.join(_folder(), f"{_key(doc_path, study_name)}-kept-")


def _same(a, b):
    return json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)


def write_kept(study, record):
    """Writes a run just kept in ``study`` (its record as stored) until the document is
    saved. Nothing for a document never saved."""
    doc_path = study.Document.FileName
    if not doc_path:
        return
    _WRITTEN_UNDER.setdefault(study.Document.Name, set()).add(doc_path)
    digest = hashlib.sha1(json.dumps(record, sort_keys=True).encode()).hexdigest()[:12]
    path = _kept_prefix(doc_path, study.Name) + f"{digest}.json"
    # the study's ID tells it from a later study given the name of a deleted one
    write_json(path, {"document": os.path.abspath(doc_path), **identity(study.Document),
                      "study": study.Name, "study_id": study.ID, "kept": record, "closes_noted": True})
    _KEPT_HERE.add(path)


def _kept_files(doc_path, study_name):
    folder, prefix = os.path.split(_kept_prefix(doc_path, study_name))
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return []
    return [os.path.join(folder, n) for n in names if n.startswith(prefix) and n.endswith(".json")]


def _read_kept(path, how=False):
    """(the study's ID, the record) of a kept file, and with ``how`` how it was lost
    (how_lost); None for one that cannot be read or holds no run that could be kept."""
    try:
        with open(path, encoding="utf-8") as handle:
            state = json.load(handle)
        record = state["kept"]
        if not isinstance(record, dict) or ss.record_problems(record):
            return None
        if not how:
            return state.get("study_id"), record
        said = str(state.get("closed") or (UNDONE if path in _KEPT_HERE else ENDED if state.get("closes_noted")
                                           else ""))
        return state.get("study_id"), record, said
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def unsaved_kept(study):
    """The runs kept in ``study`` and not saved with its document that the study does
    not hold now (the document was closed without saving, or FreeCAD ended), oldest
    first. Raises ValueError if the study's own runs cannot be read."""
    doc_path = study.Document.FileName
    if not doc_path:
        return []
    held = ss.runs(study)
    _take_moved_kept(study)
    found = []
    for path in _kept_files(doc_path, study.Name):
        read = _read_kept(path)
        if read is None or read[0] not in (None, study.ID):
            continue
        if not any(_same(read[1], r) for r in held):
            found.append(read[1])
    return sorted(found, key=lambda r: str(r.get("started", "")))


def _take_moved_kept(study):
    """Takes the files of the kept runs the study's document left at its earlier path (moved
    here: see the module's doc), moved to the names of its path now; none when more than
    one earlier path left some."""
    found = _moved_here(study, kept=True)
    if len(found) != 1:
        _say_not_taken(study, found, "kept similarity runs")
        return
    prefix = _kept_prefix(study.Document.FileName, study.Name)
    for earlier, state in next(iter(found.values())):
        _move(study, earlier, prefix + earlier.rsplit("-kept-", 1)[1], state)


def earlier_path(study, records):
    """Where the study's document was (its path) when those of ``records`` (of unsaved_kept)
    found from there were written, before it was moved or renamed; "" when all were written
    where it is now."""
    doc_path = study.Document.FileName
    for path in _kept_files(doc_path, study.Name) if doc_path else []:
        try:
            with open(path, encoding="utf-8") as handle:
                state = json.load(handle)
            if state.get("moved_from") and state.get("study_id") in (None, study.ID) and any(
                    _same(state.get("kept"), r) for r in records):
                return str(state["moved_from"])
        except (OSError, ValueError, AttributeError):
            continue
    return ""


def how_lost(study, records):
    """How each of ``records`` (of unsaved_kept) was lost, in their order: ENDED (FreeCAD
    ended without closing the document: a crash), the time (ISO) the document was closed
    without saving it, UNDONE (an Undo took it out, in this session), or "" (written
    before closes were noted: either)."""
    doc_path = study.Document.FileName
    found = []
    for path in _kept_files(doc_path, study.Name) if doc_path else []:
        read = _read_kept(path, how=True)
        if read is not None and read[0] in (None, study.ID):
            found.append(read[1:])
    return [next((how for record, how in found if _same(record, r)), "") for r in records]


def said_how_lost(names, hows):
    """How kept runs were lost, as plain text (study_journal.said_how_lost, UNDONE too)."""
    return _said_how_lost(names, hows, {UNDONE: "an Undo took it out of the document before it was saved"})


def forget_saved(doc_path, study):
    """The document was saved as ``doc_path``: the files of the runs ``study`` holds
    go (they are on disk now); those of runs it does not hold (an Undo took them back)
    stay."""
    held = ss.runs(study)
    for path in _kept_files(doc_path, study.Name):
        read = _read_kept(path)
        if read is not None and read[0] not in (None, study.ID):
            continue  # another study of that name, since deleted
        if read is None or any(_same(read[1], r) for r in held):
            try:
                os.remove(path)
            except OSError:
                pass


def drop_kept(study, records):
    """The files of ``records`` (kept in ``study``, held by no saved document) go: the
    designer dropped them. Raises OSError if one cannot be removed."""
    doc_path = study.Document.FileName
    if not doc_path or not records:
        return
    for path in _kept_files(doc_path, study.Name):
        read = _read_kept(path)
        if read is not None and read[0] in (None, study.ID) and any(_same(read[1], r) for r in records):
            os.remove(path)
            _KEPT_HERE.discard(path)


def _has_file(study, record):
    doc_path = study.Document.FileName
    return bool(doc_path) and any(
        read is not None and read[0] in (None, study.ID) and _same(read[1], record)
        for read in map(_read_kept, _kept_files(doc_path, study.Name)))


def removing(study, record):
    """``record`` (a kept run the study holds, as stored) is being removed on purpose:
    noted in the study's REMOVED_RUNS property, in the removal's undo step, with whether
    a file holds it (written and not saved yet), whose file goes then (removed_changed).
    Called by similarity_study.remove_run."""
    noted = _removed_runs(getattr(study, ss.REMOVED_RUNS, ""))
    noted.append({"run": record, "written": _has_file(study, record)})
    setattr(study, ss.REMOVED_RUNS, json.dumps(noted))


def _removed_runs(text):
    try:
        data = json.loads(text or "[]")
    except ValueError:
        return []
    return [e for e in data if isinstance(e, dict) and isinstance(e.get("run"), dict)] if isinstance(
        data, list) else []


def removed_changed(study, before, after):
    """The study's REMOVED_RUNS went from ``before`` to ``after`` (JSON texts): a run
    removed on purpose (a removal, or its Redo) has its file forgotten, so that it is
    never offered back as lost; one whose removal was undone, in the document again, is
    written again if it was before, or if the document was saved since the removal (its
    file on disk no longer holds the run). Called by the study's proxy; a failure is
    warned of, never raised."""
    was = [json.dumps(e, sort_keys=True) for e in _removed_runs(before)]
    now = [json.dumps(e, sort_keys=True) for e in _removed_runs(after)]
    gone = [json.loads(t) for t in now if t not in was]
    back = [json.loads(t) for t in was if t not in now]
    saved_without = _SAVED_WITHOUT.get(study.Document.Name, set())
    try:
        # a file of a run removed is dropped whatever wrote it (an Undo after a save writes one)
        drop_kept(study, [e["run"] for e in gone])
        for entry in back:
            # a save since its removal left it out of the file on disk: only this one holds it now
            if entry.get("written") or _run_key(study, entry["run"]) in saved_without:
                write_kept(study, entry["run"])
    except OSError as exc:
        App.Console.PrintWarning(f"HaptiCAD: {study.Label}: a removed run's file beside the document could not be "
                                 f"{'removed' if gone else 'written again'} ({exc})\n")


# document name -> the kept runs (_run_key) a save left out, removed on purpose before it:
# an Undo of such a removal puts back a run that only the document in memory holds
_SAVED_WITHOUT = {}


def _run_key(study, record):
    return (study.Name, json.dumps(record, sort_keys=True))


# document name -> the paths its kept runs were written under this session (Save As
# names it anew, and FreeCAD has taken the new name by the time it says it saves)
_WRITTEN_UNDER = {}
# the kept runs' files written in this session (one of them offered was taken out by an Undo)
_KEPT_HERE = set()


class SaveWatcher:
    """Forgets the files of kept runs once a save holds them; notes a document closed
    without saving them (``closed``). One is enough for all documents: ``watch_saves``."""

    def slotFinishSaveDocument(self, doc, path):
        if not doc.FileName or os.path.abspath(path) != os.path.abspath(doc.FileName):
            return  # a copy saved elsewhere: the document itself is as unsaved as before
        paths = {path, *_WRITTEN_UNDER.get(doc.Name, ())}
        saved_without = _SAVED_WITHOUT.setdefault(doc.Name, set())
        for obj in doc.Objects:
            if ss.is_similarity_study(obj):
                removed = {_run_key(obj, e["run"]) for e in _removed_runs(getattr(obj, ss.REMOVED_RUNS, ""))}
                try:
                    held = {_run_key(obj, r) for r in ss.runs(obj)}
                except ValueError:
                    held = set()
                saved_without.difference_update(held)  # in the file on disk again
                saved_without.update(removed - held)
                for doc_path in paths:
                    try:
                        forget_saved(doc_path, obj)
                    except ValueError:  # its runs unreadable: nothing is taken as saved
                        pass
                _restamp(doc, obj)

    def slotDeletedDocument(self, doc):
        closed(doc)
        # a document of the same name opened later is another document
        _WRITTEN_UNDER.pop(doc.Name, None)
        _SAVED_WITHOUT.pop(doc.Name, None)


def _restamp(doc, study):
    """The files of ``study`` that outlive a save of ``doc`` (a run in progress, kept runs
    an Undo took out) get the document's identity as saved now (document_identity): they
    are known by it if the document is moved."""
    for path in [path_for(study), *_kept_files(doc.FileName, study.Name)]:
        try:
            with open(path, encoding="utf-8") as handle:
                state = json.load(handle)
            if isinstance(state, dict) and state.get("study") == study.Name:
                write_json(path, {**state, **identity(doc)})
        except (OSError, ValueError, TypeError):
            pass  # none, or not readable: as it was


def closed(doc):
    """``doc`` is being closed (FreeCAD's Discard, App.closeDocument; it is still whole):
    the files of the kept runs it loses unsaved (those it holds, and those written in this
    session that an Undo took out) get the time, so that they are said, when it is opened
    again, to be lost to a close without saving, not to a crash. Nothing is forgotten."""
    if not doc.FileName:
        return
    now = datetime.now().isoformat(timespec="seconds")
    for study in [o for o in doc.Objects if ss.is_similarity_study(o)]:
        try:
            held = ss.runs(study)
        except ValueError:
            held = []
        for doc_path in {doc.FileName, *_WRITTEN_UNDER.get(doc.Name, ())}:
            for path in _kept_files(doc_path, study.Name):
                read = _read_kept(path)
                if read is None or read[0] not in (None, study.ID):
                    continue
                if path in _KEPT_HERE or any(_same(read[1], r) for r in held):
                    try:
                        with open(path, encoding="utf-8") as handle:
                            state = json.load(handle)
                        write_json(path, {**state, "closed": now})
                    except (OSError, ValueError, TypeError):
                        pass  # said as written
                    _KEPT_HERE.discard(path)  # the document opened again is another session


_WATCHER = []


def watch_saves():
    """Registers the SaveWatcher once."""
    if not _WATCHER:
        _WATCHER.append(SaveWatcher())
        App.addDocumentObserver(_WATCHER[0])
