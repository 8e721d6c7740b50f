# SPDX-License-Identifier: GPL-3.0-or-later
"""Participants recorded in a stiffness study since its document was last saved,
written to disk as they come, so that a crash (FreeCAD's, the machine's) or a close
without saving loses none: a record is in the document at once, but on disk only once
the designer saves it.

One JSON file per study of a saved document, in FreeCAD's user data folder
(``HaptiCAD/cohorts``), named from the document's path and the study's name and ID
(which a document keeps: a later study given a deleted one's name is another). While the
study holds records its saved file does not, the file holds ``cohort``, every record the
study holds (rewritten after every change of it: a record, an import, a removal, an Undo
or Redo), and ``lost``, the records an earlier session recorded and never saved that
have not been put back or dropped yet. When the document is opened again, the records
the file holds and the document does not are offered back (``lost``); a save holding
them lets them go (``SaveWatcher``), and the file goes once nothing in it is unsaved. A
document never saved has no path to tell it from another's: nothing is written for it
(``never_saved``).

A document moved or renamed (in a file manager, a synced folder with another path) is
opened under another path than its file was written for: when there is no file for the
study under its path, the file of the same study left by the document at its earlier
place is taken (``opened``), its records offered as if found here, and the file moved to
the new path's name. Such a file is known by what it records: the study's name and ID,
and the document's Uid and last save (document_identity: the Uid alone is shared by
every document saved from one template); and its document must be gone from the path it
records (a file that still exists there, or a document open in this session, keeps its
own). When more than one such file matches (copies of one document moved away, each with
records unsaved), none is taken and a warning names them: which copy the records belong
to cannot be told, and the union would offer each copy's records to the other too. Files
written before the last save was recorded are not taken. Where the document was is said
(``earlier_path``).

A record the designer removes (``removing``: stiffness_study.remove_record, the panel's
Remove) is not lost: one put back and removed again is not offered any more, nor written
as lost. The study keeps what was removed in its ``Removed`` property, which the document
does not save and Undo and Redo take back and bring again with the removal: an Undo of
the removal holds the record again, as before, and an Undo of its put back offers it
again.

How a record was lost is said (``how_lost``): the document closed without saving it
(FreeCAD's Discard, a script's App.closeDocument: the close is seen, and its time
written in the file) or FreeCAD ended without closing it (a crash, the machine stopped:
nothing is seen). Neither forgets the records: a Discard meant for an edit would lose the
participants with it, who cannot be asked again; the offer says it was a close, and the
designer drops them. A file written before closes were noted says neither.

What this session knows of a study (the cohort its saved file holds, the records lost
before it and how) lives on the study's proxy, which the document does not save: a
document closed and opened again is a new session. Records are compared as stored (their
JSON, keys sorted), as many times as they are held. App-only.
"""
import collections
import hashlib
import json
import os
from datetime import datetime

import FreeCAD as App

from . import cohort
from .atomic_file import write_json
from .document_identity import identity, same_document


# how a record was lost (how_lost): FreeCAD ended without closing the document; else the
# time (ISO) the document was closed without saving it, or "" (a file written before
# closes were noted)
ENDED = "ended"
# the study's property of the records removed on purpose since its document was opened
# (JSON, as stored; not saved with the document, taken back and brought again by Undo and Redo)
REMOVED = "Removed"
# the files this session wrote (a study deleted since is noted closed with its document)
_WRITTEN = set()


def _folder():
    return os.path.join(App.getUserAppDataDir(), "HaptiCAD", "cohorts")


def _document_key(doc_path):
    return hashlib.sha1(os.path.abspath(doc_path).encode()).hexdigest()[:16]


def _path(doc_path, study):
    study_key = hashlib.sha1(f"{study.Name}\n{study.ID}".encode()).hexdigest()[:12]
    return os.path.join(_folder(), f"{_document_key(doc_path)}-{study_key}.json")


def path_for(study):
    """Where ``study``'s unsaved records are written, or None for a document never saved."""
    doc_path = study.Document.FileName
    return _path(doc_path, study) if doc_path else None


def never_saved(study):
    """True when the study's document has no file yet: its records are nowhere on disk."""
    return not study.Document.FileName


class _Session:
    """What this session knows of one study: ``saved``, the records (as stored) its
    document's file holds, counted; ``lost``, those an earlier session recorded and did
    not save, not dropped (those removed on purpose since too: an Undo of the removal
    brings them back); ``how``, how each of those was lost (ENDED, a close's time or "");
    ``path``, the document's path the file was last written for; ``failure``, why the
    last write failed ("" when it did not)."""

    def __init__(self, saved=(), lost=(), path="", how=None, moved_from=""):
        self.saved = collections.Counter(saved)
        self.lost = list(lost)
        self.how = dict(how or {})
        self.path = path
        self.failure = ""
        # the document's earlier path the lost records were found from (it was moved since), or ""
        self.moved_from = moved_from


def _session(study):
    """The study's session, made on first use (a study made in this session, or one
    whose proxy was made again: an undone deletion). Not known to be saved, its records
    count as unsaved: written more than needed, never fewer."""
    proxy = study.Proxy
    session = getattr(proxy, "_journal_session", None)
    if session is None:
        session = _Session(path=study.Document.FileName or "")
        proxy._journal_session = session
    return session


def _stored(study):
    """The study's records as stored (canonical JSON texts), in order; [] when its cohort
    cannot be read (the panel says so; nothing is written from it)."""
    try:
        data = json.loads(study.Cohort or "[]")
    except ValueError:
        return None
    if not isinstance(data, list):
        return None
    return [_canonical(d) for d in data]


def _canonical(data):
    return json.dumps(data, sort_keys=True)


def _minus(items, taken):
    """``items`` (a list) without ``taken`` (a Counter), each taken once per count, in order."""
    left = collections.Counter(taken)
    kept = []
    for item in items:
        if left[item] > 0:
            left[item] -= 1
        else:
            kept.append(item)
    return kept


def _put_back(session, held):
    """What ``held`` (the cohort now, as stored) holds beyond what its file holds, counted:
    a lost record among them is put back (a lost record alike to a saved one is still
    lost: the file held both)."""
    return collections.Counter(_minus(held, session.saved))


def _removed(study):
    """The records removed on purpose since the document was opened (REMOVED), as stored,
    counted; none when the property cannot be read."""
    try:
        data = json.loads(getattr(study, REMOVED, "") or "[]")
    except ValueError:
        return collections.Counter()
    return collections.Counter(_canonical(d) for d in data if isinstance(d, dict)) if isinstance(
        data, list) else collections.Counter()


def _offered(session, held, removed):
    """The lost records offered: not put back, and not removed on purpose (``removed``,
    counted) after they were."""
    return _minus(_minus(session.lost, _put_back(session, held)), removed)


def removing(study, record):
    """``record`` (a cohort.Record the study holds) is being removed on purpose: noted in
    the study's REMOVED property, in the removal's undo step. Called by
    stiffness_study.remove_record before the cohort changes: the file written between the
    two still holds the record in the cohort, never as lost."""
    try:
        before = json.loads(getattr(study, REMOVED, "") or "[]")
    except ValueError:
        before = []
    setattr(study, REMOVED, json.dumps([*(before if isinstance(before, list) else []), record.as_dict()]))


def _read(path):
    """What the file at ``path`` holds: (study ID, the records as stored, the older first,
    how each was lost, the document's earlier path they were found from or ""); (None, [],
    {}, "") when there is no file or it cannot be read (cut off by a crash mid-write: it is
    written beside and moved in, so only by hand)."""
    try:
        with open(path, encoding="utf-8") as handle:
            state = json.load(handle)
        lost = [d for d in state.get("lost", []) if isinstance(d, dict)]
        cohort_ = [d for d in state.get("cohort", []) if isinstance(d, dict)]
        said = state.get("lost_how")
        said = said if isinstance(said, list) and len(said) == len(lost) else [""] * len(lost)
        how = {_canonical(d): str(h or "") for d, h in zip(lost, said)}
        # the cohort as it was last written: what was not saved of it was lost when the
        # document closed (its time), or when FreeCAD ended without closing it
        ended = str(state.get("closed") or (ENDED if state.get("closes_noted") else ""))
        how.update((_canonical(d), ended) for d in cohort_)
        # the older first: lost in an earlier session, then the cohort as it was last
        moved_from = state.get("moved_from")
        return (state.get("study_id"), [_canonical(d) for d in [*lost, *cohort_]], how,
                moved_from if isinstance(moved_from, str) else "")
    except (OSError, ValueError, AttributeError, TypeError):
        return None, [], {}, ""


def _moved_here(study, path):
    """The files of ``study`` written for its document at another path, where it is no
    more (moved or renamed since; see the module's doc): [(file, what it holds)]. Not one
    whose document still exists at its path or is open in this session: it is that one's."""
    folder, own = os.path.split(path)
    suffix = own[own.index("-"):]  # the study's name and ID
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return []
    open_here = {os.path.abspath(d.FileName) for d in App.listDocuments().values() if d.FileName}
    found = []
    for name in names:
        if name == own or not name.endswith(suffix):
            continue
        try:
            with open(os.path.join(folder, name), encoding="utf-8") as handle:
                state = json.load(handle)
        except (OSError, ValueError):
            continue
        if not same_document(state, study.Document) or (state.get("study"), state.get("study_id")) != (
                study.Name, study.ID):
            continue
        was = state.get("document")
        if isinstance(was, str) and was and not os.path.exists(was) and os.path.abspath(was) not in open_here:
            found.append((os.path.join(folder, name), state))
    return found


def _take_moved(study, path):
    """Moves to ``path`` (where the study's file is written now) the file its document left
    at its earlier path, if exactly one is found (_moved_here): moved in one step (a crash
    leaves it at one name or the other), then written again saying where it was found
    from. The earlier path, or "" (none found, more than one, or it could not be moved:
    warned of, and left where it is)."""
    found = _moved_here(study, path)
    if len(found) > 1:
        App.Console.PrintWarning(
            f"HaptiCAD: {study.Label}: participant records left unsaved by {len(found)} copies of this document, "
            f"each moved away since ({', '.join(s['document'] for _, s in found)}), match it; none is offered, as "
            f"whose they are cannot be told. Their files: {', '.join(f for f, _ in found)}\n")
        return ""
    if not found:
        return ""
    (earlier, state), = found
    try:
        os.replace(earlier, path)
    except OSError as exc:
        App.Console.PrintWarning(f"HaptiCAD: {study.Label}: the participant records left unsaved when the document "
                                 f"was at {state['document']} could not be taken ({exc}): they stay in {earlier}\n")
        return ""
    try:
        write_json(path, {**state, "document": os.path.abspath(study.Document.FileName),
                          "moved_from": state["document"]})
    except OSError:
        pass  # moved as it was: what it holds is read the same
    return state["document"]


def opened(study):
    """The study's document was opened: what its file holds is its saved cohort, and the
    records its journal holds beyond them were lost unsaved (offered by ``lost``). Called
    by the study's proxy once the document is restored."""
    held = _stored(study) or []
    lost, how, moved_from, earlier = [], {}, "", ""
    path = path_for(study)
    if path is not None:
        if not os.path.exists(path):  # none here: one the document left where it was before?
            earlier = _take_moved(study, path)
        study_id, written, how, moved_from = _read(path)
        moved_from = moved_from or earlier  # the file moved here, and not written again since
        if study_id in (None, study.ID):
            lost = _minus(written, collections.Counter(held))
    study.Proxy._journal_session = _Session(held, lost, study.Document.FileName, how, moved_from)


def cohort_changed(study):
    """Writes the study's unsaved records after its cohort changed (a record, an import,
    a removal, an Undo or Redo of one): called by the study's proxy. Nothing for a document
    never saved. A failure to write is kept (``failure``) and warned of, never raised: the
    change itself is made."""
    if never_saved(study):
        return
    try:
        _write(study, _session(study))
    except OSError as exc:
        _session(study).failure = str(exc)
        App.Console.PrintWarning(f"HaptiCAD: {study.Label}: the participants recorded since the last save could "
                                 f"not be written to disk ({exc}): save the document\n")


def _write(study, session, closed=""):
    """The file as the study and its session are now: written whole beside it and moved
    in (a crash mid-write leaves the previous one); removed when it would hold nothing.
    ``closed``: the time (ISO) the document is being closed without saving, written as
    how what it holds unsaved is lost."""
    path = _path(study.Document.FileName, study)
    held = _stored(study)
    if held is None:  # an unreadable cohort: the file as it was
        return
    lost = _offered(session, held, _removed(study))
    if not _minus(held, session.saved) and not lost:  # nothing that is not on disk
        if os.path.exists(path):
            os.remove(path)
        session.failure = ""
        return
    # the whole cohort, not only what is unsaved: the records it holds as often as it does
    # (one saved and one not of two alike are one lost, which the unsaved alone would not tell)
    state = {"document": os.path.abspath(study.Document.FileName), **identity(study.Document),
             "study": study.Name, "study_id": study.ID,
             "label": study.Label, "cohort": [json.loads(t) for t in held], "lost": [json.loads(t) for t in lost],
             "lost_how": [session.how.get(t, "") for t in lost], "closes_noted": True}
    if closed:
        state["closed"] = closed
    if session.moved_from and lost:  # the records lost found from the document's earlier place
        state["moved_from"] = session.moved_from
    write_json(path, state)
    _WRITTEN.add(path)
    session.failure = ""


def failure(study):
    """Why the unsaved records could not be written the last time, or ""."""
    return _session(study).failure


def _lost(study):
    """(record, how it was lost) of each record ``lost`` offers."""
    session = _session(study)
    found = []
    for text in _offered(session, _stored(study) or [], _removed(study)):
        try:
            found.append((cohort.from_dict(json.loads(text)), session.how.get(text, "")))
        except (ValueError, TypeError):  # not a record (edited by hand): not offered
            pass
    return found


def lost(study):
    """The records recorded in ``study`` in an earlier session and never saved (the
    document was closed without saving, or FreeCAD ended) that it does not hold now, as
    cohort.Record, in the order they were recorded; not those removed on purpose since.
    Put back by adding them to the study (stiffness_study.add_records); forgotten by ``drop``."""
    return [record for record, _ in _lost(study)]


def how_lost(study):
    """How each record of ``lost`` was lost, in its order: ENDED (FreeCAD ended without
    closing the document: a crash), the time (ISO) the document was closed without saving
    it, or "" (written before closes were noted: either)."""
    return [how for _, how in _lost(study)]


def earlier_path(study):
    """Where the study's document was (its path) when the records ``lost`` offers were
    found from there, written before it was moved or renamed; "" when they were found
    where it is now, or none are offered. Some of them may have been lost here since."""
    session = _session(study)
    return session.moved_from if session.moved_from and _lost(study) else ""


def _said(how):
    if how == ENDED:
        return "FreeCAD ended before it was saved"
    try:
        return f"it was closed without saving on {datetime.fromisoformat(how):%Y-%m-%d at %H:%M}"
    except (TypeError, ValueError):
        return "it was closed without saving, or FreeCAD ended"


def said_how_lost(names, hows, also=None):
    """How records were lost, as a clause of plain text, from whose they are (``names``)
    and how each was (``hows``, as how_lost gives): "FreeCAD ended before it was saved";
    "it was closed without saving on 2026-11-24 at 15:20"; when not all alike, whose each
    is: "Bo: FreeCAD ended ...; Cy: it was closed ...". ``also``: other hows, and their
    clauses (run_journal's)."""
    groups = {}
    for name, how in zip(names, hows):
        groups.setdefault((also or {}).get(how) or _said(how), []).append(name)
    if len(groups) == 1:
        return next(iter(groups))
    return "; ".join(f"{', '.join(who)}: {said}" for said, who in groups.items())


def drop(study, records):
    """Forgets ``records`` (of ``lost``) for good: the designer dropped them. Raises
    OSError if the file cannot be rewritten (they are still offered then)."""
    session = _session(study)
    dropped = collections.Counter(_canonical(r.as_dict()) for r in records)
    remaining = _minus(session.lost, dropped)
    if never_saved(study):
        session.lost = remaining
        return
    before, session.lost = session.lost, remaining
    try:
        _write(study, session)
    except OSError:
        session.lost = before
        raise


def saved(study, doc_path):
    """The study's document was saved as ``doc_path``: what it holds now is on disk, so
    its file keeps only the lost records not put back (or goes); the file written for
    another path before (a Save As) goes."""
    session = _session(study)
    held = _stored(study)
    if held is None:  # unreadable: nothing is taken as saved
        return
    previous = session.path
    # those put back are saved now; one removed on purpose stays known (not offered) until
    # the session ends: an Undo of its removal, then of its put back, offers it again
    session.lost = _minus(session.lost, _put_back(session, held))
    session.saved = collections.Counter(held)
    session.path = doc_path
    if previous and os.path.abspath(previous) != os.path.abspath(doc_path):
        try:
            os.remove(_path(previous, study))
        except OSError:
            pass
    try:
        _write(study, session)
    except OSError as exc:
        session.failure = str(exc)


def _is_stiffness_study(obj):
    from .stiffness_study import is_stiffness_study

    return is_stiffness_study(obj)


class SaveWatcher:
    """Lets the written records go once a save holds them; the files of studies deleted
    before the save go too (their records are in no document now). Notes a document
    closed without saving (``closed``). One is enough for all documents: ``watch_saves``."""

    def slotFinishSaveDocument(self, doc, path):
        if not doc.FileName or os.path.abspath(path) != os.path.abspath(doc.FileName):
            return  # a copy saved elsewhere: the document itself is as unsaved as before
        studies = [o for o in doc.Objects if _is_stiffness_study(o)]
        for study in studies:
            saved(study, path)
        keep = {os.path.basename(_path(path, s)) for s in studies}
        prefix = _document_key(path) + "-"
        try:
            names = os.listdir(_folder())
        except OSError:
            return
        for name in names:
            if name.startswith(prefix) and name.endswith(".json") and name not in keep:
                try:
                    os.remove(os.path.join(_folder(), name))
                except OSError:
                    pass

    def slotDeletedDocument(self, doc):
        closed(doc)


def closed(doc):
    """``doc`` is being closed (FreeCAD's Discard, App.closeDocument; it is still whole):
    each file this session wrote for its studies is written again as the study is now,
    with the time, so that what it holds unsaved is said, when the document is opened
    again, to be lost to a close without saving, not to a crash. Nothing is forgotten. A
    file this session did not write says what it said (a document only read, by the
    ``hapticad cohort`` command say, changes nothing); one of a study deleted since gets
    the time alone."""
    if not doc.FileName:
        return
    now = datetime.now().isoformat(timespec="seconds")
    prefix = _document_key(doc.FileName) + "-"
    ours = {p for p in _WRITTEN if os.path.basename(p).startswith(prefix)}
    for study in [o for o in doc.Objects if _is_stiffness_study(o)]:
        session = getattr(study.Proxy, "_journal_session", None)
        path = _path(doc.FileName, study)
        if session is None or (path not in ours and not session.failure):
            continue
        ours.discard(path)
        try:
            _write(study, session, closed=now)
        except OSError as exc:
            App.Console.PrintWarning(f"HaptiCAD: {study.Label}: the participants recorded since the last save "
                                     f"could not be written to disk as the document closed ({exc})\n")
    for path in sorted(ours):
        try:
            with open(path, encoding="utf-8") as handle:
                state = json.load(handle)
            write_json(path, {**state, "closed": now})
        except (OSError, ValueError, TypeError):
            pass  # gone (saved since), or not ours to mend: said as written
    # the document opened again is another session
    _WRITTEN.difference_update({p for p in _WRITTEN if os.path.basename(p).startswith(prefix)})


_WATCHER = []


def watch_saves():
    """Registers the SaveWatcher once."""
    if not _WATCHER:
        _WATCHER.append(SaveWatcher())
        App.addDocumentObserver(_WATCHER[0])
