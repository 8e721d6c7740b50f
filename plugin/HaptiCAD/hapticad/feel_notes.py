# SPDX-License-Identifier: GPL-3.0-or-later
"""What a document's parts and surfaces are felt as, otherwise than set, said before
feeling them: the notes the Feel panel shows as its session starts (session_notes), and
what ``hapticad feel`` and ``hapticad demo --headless`` say before their strokes
(stroke_notes: those, and what the surface panel would have said of a texture and the
study controls of a study not felt, which they do not show). Gathered here, in one
place, so the panels and the command line say the same. Sentences without a closing full
stop. App-only (no GUI).
"""


def session_notes(doc, rate_hz, force_limit_n, where="in Preferences"):
    """The Feel panel's notes on ``doc`` for a session at ``rate_hz`` (Hz) held to
    ``force_limit_n`` (N), as sentences, in this order: vibrations felt nowhere (their part
    deleted); what the servo rate and the force limit keep a vibration from being felt as
    set; the roughness grids and gratings the rate cannot follow at a brisk stroke; the
    textures that leave the press too little of the force limit (texture_force_notes); tagged
    parts hidden behind what is shown (a Cut or a Fillet made after tagging: the hidden
    shape is felt), each part once. ``where`` says where the rate is set."""
    from . import surface_object, vibration_object

    # one part under two surfaces is said once
    hidden = list(dict.fromkeys(note for surface in surface_object.surfaces_of(doc)
                                for note in surface_object.hidden_part_notes(surface)))
    partless = [f"{v.Label}: {vibration_object.no_part_note(v)}" for v in vibration_object.vibrations_of(doc)
                if v.Part is None]
    return (partless + vibration_object.rate_notes(doc, rate_hz, where)
            + vibration_object.force_notes(doc, force_limit_n)
            + surface_object.rate_notes(doc, rate_hz, where) + texture_force_notes(doc, force_limit_n) + hidden)


def _each_surface(doc, notes_of):
    """``notes_of(surface)`` of each surface of ``doc``, each led by the surface's Label; a
    surface whose texture cannot be compiled says nothing here: building the scene names it."""
    from .surface_object import surfaces_of

    notes = []
    for surface in surfaces_of(doc):
        try:
            notes += [f"{surface.Label}: {note}" for note in notes_of(surface) if note]
        except ValueError:
            continue
    return notes


def texture_force_notes(doc, force_limit_n):
    """surface_compile.texture_force_note of each surface of ``doc`` held to
    ``force_limit_n`` (N): a texture whose drag, with the press, passes the force limit, so
    the renderer scales the whole force down (the press felt lighter, the ridges cut), with
    the press that fits; as the surface panel says it at the limit in use."""
    from .surface_compile import texture_force_note

    return _each_surface(doc, lambda surface: [texture_force_note(surface, force_limit_n)])


def texture_notes(doc):
    """surface_compile.texture_shape_notes of each surface of ``doc`` (a grating clipped at
    its full range, one whose harmonics grow, one finer across a Curve pattern's ridges than
    its period), each led by the surface's Label, as the surface panel shows them (its note on
    the force limit is session_notes')."""
    from .surface_compile import texture_shape_notes

    return _each_surface(doc, texture_shape_notes)


def study_notes(doc):
    """A sentence for each stiffness study of ``doc`` whose law is not felt, led by its
    Label, with stiffness_study.law_problems, the words the Feel panel's study controls
    show after "Not felt:" (two studies of one surface, none linked, values that make no
    law); when its surface is still felt, it says so, at its own stiffness. A duplicated
    study left its surface felt at 0.8 N/mm in place of its 0.556 N/mm neck, unsaid."""
    from .stiffness_study import law_problems, studies_of
    from .surface_object import active_reference_pairs, is_haptic_surface

    notes = []
    for study in studies_of(doc):
        problems = law_problems(study)
        if not problems:
            continue
        surface = study.Surface
        instead = (f" ({surface.Label} is felt at its own stiffness)" if surface is not None
                   and is_haptic_surface(surface) and active_reference_pairs(surface) else "")
        notes.append(f"{study.Label} is not felt{instead}: {'; '.join(problems)}")
    return notes


def stroke_notes(doc, rate_hz, force_limit_n, where, broken=True):
    """What ``hapticad feel`` and the headless demo say of ``doc`` before their strokes, as
    sentences: session_notes (as the Feel panel), texture_notes (as the surface panel, which
    they do not show), study_notes (as the Feel panel's study controls, which they do not
    show either) and the surfaces not felt at all (feel.skipped_surface_notes; without the
    broken face references unless ``broken``: the demo says each as its skipped stroke)."""
    from .feel import skipped_surface_notes

    return (session_notes(doc, rate_hz, force_limit_n, where) + texture_notes(doc) + study_notes(doc)
            + skipped_surface_notes(doc, broken))
