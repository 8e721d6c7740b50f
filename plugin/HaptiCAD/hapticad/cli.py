# SPDX-License-Identifier: GPL-3.0-or-later
"""The ``hapticad`` command line. Prints JSON on stdout; errors go to stderr with
exit status 2 (bad input) or 1 (failure, or a material card refused)."""
import argparse
import errno
import json
import os
import re
import signal
import sys
import zipfile

from .accuracy import ANGULAR_RANGE_DEG_SHOWN, CUSTOM, LINEAR_RANGE_MM, PRESETS, REFINE_RANGE_MM
from .freecad_env import ensure_freecad
from . import texture_fit_options as fit_options


def _point(text):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3:
        raise argparse.ArgumentTypeError(f"{text!r} is not X,Y,Z")
    return tuple(values)


def _stroke(text):
    parts = text.split(":")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"{text!r} is not X0,Y0,Z0:X1,Y1,Z1")
    return _point(parts[0]), _point(parts[1])


def _count(lo, hi):
    """An argparse type: a whole number from lo to hi (the option names itself in argparse's message)."""
    def parse(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number: give one from {lo} to {hi}") from None
        if not lo <= value <= hi:
            raise argparse.ArgumentTypeError(f"{text} is out of range: give a whole number from {lo} to {hi}")
        return value
    return parse


def _output_file(kind, example):
    """An argparse type: a file to write, not empty, not a folder, in a folder that exists, and
    not a FreeCAD document (a plot or a table written over a .FCStd loses its parts and studies).
    The name must end in the kind's extension (.png, .csv; any case): a name without one gets it
    (what is reported is the file written), any other is refused."""
    wanted = "." + kind.lower()
    what = {"PNG": "the plot is a PNG image", "CSV": "the table is a CSV file"}[kind]

    def parse(text):
        if not text.strip():
            raise argparse.ArgumentTypeError(f"an empty name: give the {kind} file to write, like {example}")
        if os.path.isdir(text):
            raise argparse.ArgumentTypeError(f"{text} is a folder: give the {kind} file to write in it, like "
                                             f"{os.path.join(text, example)}")
        extension = os.path.splitext(text)[1]
        if not extension:
            text += wanted
        elif extension.lower() != wanted:
            raise argparse.ArgumentTypeError(f"{text}: {what}, so the name must end in {wanted} (like "
                                             f"{os.path.splitext(text)[0]}{wanted}), not {extension}")
        if os.path.isdir(text):
            raise argparse.ArgumentTypeError(f"{text} is a folder: give the {kind} file to write")
        folder = os.path.dirname(text)
        if folder and not os.path.isdir(folder):
            # said now, before the work, and by the user's name (not the temporary file's)
            raise argparse.ArgumentTypeError(f"{text}: {_no_folder(folder)}")
        if _is_freecad_document(text):
            raise argparse.ArgumentTypeError(f"{text} is a FreeCAD document: writing the {kind} over it would "
                                             f"lose it; give another name, like {example}")
        return text
    return parse


def _no_folder(folder):
    """Why ``folder`` (not an existing folder) cannot take a file."""
    return f"{folder} is a file, not a folder" if os.path.exists(folder) else f"there is no folder {folder}"


def _is_freecad_document(path):
    """Whether ``path`` is a file holding a FreeCAD document (a zip archive with a Document.xml), whatever its name."""
    try:
        if not os.path.isfile(path) or not zipfile.is_zipfile(path):
            return False
        with zipfile.ZipFile(path) as archive:
            return "Document.xml" in archive.namelist()
    except (OSError, zipfile.BadZipFile):
        return False


def _output_folder(written=()):
    """An argparse type: a folder to write the files ``written`` in (made if missing): not empty,
    not a file, and none of ``written`` in it a FreeCAD document (the one read, by any name, or
    another). Said before the work (a stroke), which found a file only when it came to write."""
    def parse(text):
        if not text.strip():
            raise argparse.ArgumentTypeError("an empty name: give the folder to write in, like out")
        if os.path.exists(text) and not os.path.isdir(text):
            raise argparse.ArgumentTypeError(f"{text} is a file, not a folder: give a folder to write in (it is "
                                             f"made if missing), like {os.path.splitext(text)[0] or 'out'}-out")
        above = os.path.dirname(text)  # the folders made with it: not one where a file is
        while above and not os.path.exists(above):
            above = os.path.dirname(above)
        if above and not os.path.isdir(above):
            raise argparse.ArgumentTypeError(f"{text}: {above} is a file, not a folder")
        for name in written:
            if _is_freecad_document(os.path.join(text, name)):
                raise argparse.ArgumentTypeError(f"{os.path.join(text, name)} is a FreeCAD document: writing the "
                                                 f"{name} over it would lose it; give another folder")
        return text
    return parse


_png_file = _output_file("PNG", "plot.png")
_csv_file = _output_file("CSV", "cohort.csv")
_answers_csv_file = _output_file("CSV", "answers.csv")


def _feel_accuracy(args, prefs):
    """The accuracy `hapticad feel` builds with: --accuracy, else the preferences'. A
    custom value given (--linear-deflection ...) makes it Custom, starting from the
    preferences' custom values."""
    from . import accuracy, preferences

    given = {"custom_linear_deflection_mm": args.linear_deflection,
             "custom_angular_deflection_deg": args.angular_deflection,
             "custom_refine_edge_mm": args.refine_edge,
             "custom_force_shading": args.force_shading}
    given = {key: value for key, value in given.items() if value is not None}
    name = args.accuracy or (accuracy.CUSTOM if given else prefs.accuracy)
    if given and name != accuracy.CUSTOM:
        raise ValueError(f"--linear-deflection, --angular-deflection, --refine-edge and --[no-]force-shading set a "
                         f"custom accuracy; they cannot go with --accuracy {name} (leave --accuracy out)")
    chosen = prefs.replace(accuracy=name, **given)
    found = [p for p in preferences.problems(chosen) if p.startswith("custom")]
    if found and name == accuracy.CUSTOM:
        # said by the option that sets it (a bad value from the preferences by its own name)
        flags = {"custom_linear_deflection_mm": ("custom linear deflection", "--linear-deflection"),
                 "custom_angular_deflection_deg": ("custom angular deflection", "--angular-deflection"),
                 "custom_refine_edge_mm": ("custom refinement edge", "--refine-edge")}
        for key, (said, flag) in flags.items():
            if key in given:
                found = [p.replace(said, flag, 1) if p.startswith(said) else p for p in found]
        raise ValueError("; ".join(found))
    return preferences.scene_accuracy(chosen)


TRACE_FILES = ("trace.csv", "trace.png")  # what `hapticad feel` writes in --out (feel.feel_document)
RATE_OPTION = "with --rate"  # where `hapticad feel` sets the servo rate (the GUI: in Preferences)


def cmd_feel(args):
    App = ensure_freecad()
    from . import feel_notes, preferences
    from .document_scene import build_document_scene
    from .feel import Stroke, feel_document, probe_limits, study_labels

    doc = _open_document(App, args.file)
    try:
        prefs = preferences.load()
        doc_scene = build_document_scene(doc, _feel_accuracy(args, prefs))
        limits = probe_limits(prefs)  # the force limit the Feel panel renders with
        if not doc_scene.watertight:
            print(f"hapticad feel: the scene is not closed: {doc_scene.repair}", file=sys.stderr)
        # what the Feel panel would say (feel_notes), said before the stroke, which takes seconds
        notes = feel_notes.stroke_notes(doc, args.rate, limits.max_force_n, where=RATE_OPTION)
        for note in notes:
            print(f"hapticad feel: {note}", file=sys.stderr)
        p0, p1 = args.stroke
        stroke = Stroke(p0, p1, args.speed, args.depth, args.rate)
        summary = feel_document(doc_scene, stroke, args.out, limits=limits, studies=study_labels(doc, doc_scene))
        felt = summary["notes"]  # a study's law in place of the surface's stiffness, a face stiffer than the device
        if summary["expected_normal_force_n"] > limits.max_force_n:
            felt.append(f"{args.depth:g} mm deep the face pushes back with {summary['expected_normal_force_n']:.2f} "
                        f"N, more than the {limits.max_force_n:g} N force limit (HaptiCAD's Preferences): the stroke "
                        "is felt at the limit")
        for note in felt:
            print(f"hapticad feel: {note}", file=sys.stderr)
        summary["notes"] = notes + felt  # all it said, in the JSON too
        return summary
    finally:
        App.closeDocument(doc.Name)


def cmd_demo(args):
    from . import demo

    headless = args.headless or not os.environ.get("DISPLAY")
    if not headless:
        result = demo.launch_gui(args.out)
        if args.json:
            return result
        print(f"HaptiCAD demo: FreeCAD opens {result['document']}, "
              + ("a copy of the example: save your changes there" if result["copied"] else
                 "your copy from before (delete it for the example as shipped)"))
        return None
    ensure_freecad()
    result = demo.run_headless(args.out)
    for note in result["notes"]:  # what the Feel panel would say of the copy (feel_notes)
        print(f"hapticad demo: {note}", file=sys.stderr)
    if args.json:
        for stroke in result["strokes"]:
            _say_demo_notes(stroke)
        print(f"HaptiCAD demo: traces and plots of {len(result['strokes'])} strokes are in "
              f"{result['out_dir']}", file=sys.stderr)
        return result
    # what a designer reads: each face stroked, what it is and what it felt like
    print(f"HaptiCAD demo: each tagged face of {result['document']} stroked by the simulated "
          f"probe; traces and plots in {result['out_dir']}")
    for stroke in result["strokes"]:
        if "skipped" in stroke:
            print(f"  {stroke['face']}: skipped, {stroke['skipped']}")
            continue
        felt = stroke["faces"].get(stroke["face"])
        what = (f"{felt['material']}, pressed {felt['mean_normal_force_n']:.2f} N, friction "
                f"Ft/Fn {felt['mean_ft_over_fn']:.2f} (mu_d {felt['mu_dynamic']:.2f})"
                if felt and felt["mean_normal_force_n"] is not None else "not slid on")
        print(f"  {stroke['face']}: {what}; {os.path.relpath(stroke['trace_png'])}")
        _say_demo_notes(stroke)
    return None


def _say_demo_notes(stroke):
    """A demo stroke's notes (what it felt otherwise than set: a stiffness study's law, a face
    stiffer than the device) on stderr, as `hapticad feel` says them."""
    for note in stroke.get("notes", ()):  # a skipped stroke has none
        print(f"hapticad demo: {note}", file=sys.stderr)


def cmd_materials(args):
    from . import materials

    folder = args.export_fcmat
    if folder is not None and not os.path.isdir(folder):
        raise ValueError(f"{_no_folder(folder) if folder.strip() else 'an empty name'}: give --export-fcmat the "
                         "folder to write the cards in")
    if args.overwrite and folder is None:
        raise ValueError("--overwrite replaces cards --export-fcmat DIR writes: give the folder too")
    database = materials.load_database(include_user=not args.shipped_only)
    for error in database.errors:
        print(f"hapticad materials: rejected {error}", file=sys.stderr)
    if folder is not None:
        _export_cards(database, folder, args.overwrite)
    rows = [m.as_dict() for m in database]
    if not args.json:
        for row in rows:
            print(f"{row['name']:<16} mu_s {row['mu_static']:<5} mu_d {row['mu_dynamic']:<5} "
                  f"range {row['mu_range'][0]}-{row['mu_range'][1]:<5} E {row['youngs_modulus_gpa']:g} GPa  "
                  f"k {row['stiffness_n_per_mm']} N/mm")
    if database.errors:
        # the others are still listed, but a script checking its cards must see the refusal
        count = len(database.errors)
        print(f"hapticad materials: {count} entr{'ies' if count != 1 else 'y'} rejected; the other materials "
              "are listed", file=sys.stderr)
        return Finished(rows if args.json else None, 1)
    return rows if args.json else None


def _export_cards(database, folder, overwrite):
    """Writes each material of ``database`` as folder/HaptiCAD-<name>.FCMat. A different card
    already there (the user's edits?) is kept unless ``overwrite``, and named on stderr with how
    to replace it; that is no failure (exit status 0): nothing the designer made is lost."""
    from . import materials

    kept, cards = [], {}
    for material in database:
        card = "HaptiCAD-{}.FCMat".format("".join(c if c.isalnum() or c in "-_" else "-" for c in material.name))
        if card in cards:  # names alike but for their punctuation: the second would replace the first's card
            print(f"hapticad materials: {material.name} is not written: its card {card} is {cards[card]}'s "
                  "(rename one of them)", file=sys.stderr)
            continue
        cards[card] = material.name
        if not materials.write_fcmat(material, os.path.join(folder, card), overwrite=overwrite):
            kept.append(card)
    if kept:
        many = len(kept) != 1
        print(f"hapticad materials: kept {len(kept)} card{'s' if many else ''} already in {folder} that "
              f"differ{'' if many else 's'} from HaptiCAD's (edited?), not replaced: {', '.join(kept)}; give "
              f"--overwrite to replace {'them' if many else 'it'}", file=sys.stderr)


def cmd_roughness_table(args):
    from . import _core
    from .roughness_text import ra_band

    table = _core.roughness_table()
    if args.json:
        return [{
            "category": r.category,
            "ra_min_um": r.ra_min_um,
            "ra_max_um": r.ra_max_um,
            "n_grades": list(r.n_grades),
            "grid_size_mm": r.grid_size_mm,
        } for r in table]
    for r in table:
        print(f"{r.category}  {ra_band(r, grades=False):<20}  {', '.join(r.n_grades) or 'Unclassified':<12}  "
              f"grid {r.grid_size_mm:g} mm")
    return None


def cmd_accuracy_table(args):
    ensure_freecad()
    from . import accuracy_table

    rows = accuracy_table.run_table()
    if args.plot:
        accuracy_table.plot(rows, args.plot)
        print(f"hapticad accuracy-table: plot in {os.path.abspath(args.plot)}", file=sys.stderr)
    if args.json:
        return rows
    print(accuracy_table.markdown(rows))
    return None


BENCH_MESH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "hapticad-bench-mesh")


def _mesh_files(options):
    """The mesh files among bench-mesh's ``options``: what is not an option nor an option's
    value. Every option of the program but --json takes the word after it (bench_mesh.cc's Parse)."""
    files, value_next = [], False
    for word in options:
        if value_next:
            value_next = False
        elif word.startswith("-"):
            value_next = word != "--json"
        else:
            files.append(word)
    return files


def cmd_bench_mesh(args):
    """Runs the contact engine's benchmark program, which prints the JSON itself."""
    meshes = _mesh_files(args.options)
    if len(meshes) > 1:  # the program took the last one without a word
        raise ValueError(f"one mesh file at a time: give one of {', '.join(meshes)}")
    if not os.access(BENCH_MESH, os.X_OK):
        raise RuntimeError(f"{BENCH_MESH} is missing: build HaptiCAD (packaging/setup.sh)")
    sys.stdout.flush()
    os.execv(BENCH_MESH, [BENCH_MESH, *args.options])


def cmd_devices(args):
    from . import _core

    rows = _core.list_devices()
    if args.json:
        return rows
    for row in rows:
        limits = row["limits"]
        if limits:
            size = [round((hi - lo) * 1000) for lo, hi in zip(limits["workspace_min_d"], limits["workspace_max_d"])]
            what = (f"{limits['max_force_n']:g} N, {limits['max_stiffness_n_per_m'] / 1000:g} N/mm, "
                    f"workspace {size[0]} x {size[1]} x {size[2]} mm")
        else:
            what = f"unusable: {row['error']}"
        print(f"{row['kind']:<4} {row['path']:<20} {row['name']:<32} {what}")
    return None


def _speeds(text):
    from .texture_fit import parse_speeds

    try:
        return parse_speeds(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _open_document(App, path):
    """document_file.open_document: the file checked before FreeCAD opens it (the demo checks its copy so)."""
    from .document_file import open_document

    return open_document(App, path)


def cmd_fit_texture(args):
    from . import texture_fit

    if bool(args.apply) != bool(args.surface):
        raise ValueError("--apply DOCUMENT and --surface NAME go together")
    if args.apply and os.path.exists(args.apply):
        from .document_saving import check_savable

        check_savable(args.apply)  # before the fit, not after it
    speeds = args.speeds or texture_fit.PAPER_SPEEDS_MM_S
    report = texture_fit.fit_files(args.recordings, args.period, speeds, args.tolerance, args.lowpass,
                                   args.harmonics, args.min_periods)
    result = texture_fit.summary(report)
    if args.plot:
        from .texture_fit_plot import plot_fit

        plot_fit(args.plot, report)
        result["plot"] = os.path.abspath(args.plot)
    if args.apply:
        App = ensure_freecad()
        from .document_saving import fingerprint, save_in_place
        from .surface_object import surfaces_of, validate

        read = fingerprint(args.apply) if os.path.isfile(args.apply) else None
        doc = _open_document(App, args.apply)
        try:
            found = [o for o in surfaces_of(doc) if args.surface in (o.Name, o.Label)]
            if not found:
                names = ", ".join(o.Label for o in surfaces_of(doc)) or "none"
                raise ValueError(f"{args.apply}: no haptic surface named {args.surface!r} (it has: {names})")
            surface = found[0]
            try:
                notes = texture_fit.apply_to_surface(surface, report)
            except ValueError as exc:
                raise ValueError(f"{exc}; nothing was changed") from None
            doc.recompute()
            problems = validate(surface)
            if problems:
                raise ValueError(f"{surface.Label}: the fitted texture is not valid: {'; '.join(problems)}; "
                                 "the document was not saved")
            save_in_place(doc, read)
            result["applied"] = {"document": os.path.abspath(args.apply), "surface": surface.Label,
                                 **{name: getattr(surface, name) for name in
                                    (*texture_fit.FIELDS, "TexturePeriod", "TextureFullRange", "TextureScale")},
                                 "notes": notes}
        finally:
            App.closeDocument(doc.Name)
    if args.json:
        return result
    print(texture_fit.describe(result))
    return None


def _chosen_studies(args, found, kind):
    """The studies --study names (name or label), or all; ValueError naming those there are."""
    if args.study is not None and not args.study.strip():
        raise ValueError(f"--study needs a study's name or label (it has: "
                         f"{', '.join(s.Label for s in found) or 'none'})")
    studies = [s for s in found if args.study is None or args.study in (s.Name, s.Label)]
    if not studies:
        names = ", ".join(s.Label for s in found) or "none"
        raise ValueError(f"{args.file}: no {kind}{' named ' + repr(args.study) if args.study else ''} "
                         f"(it has: {names})")
    return studies


def cmd_cohort(args):
    App = ensure_freecad()
    from . import cohort, stiffness_study

    doc = _open_document(App, args.file)
    try:
        studies = _chosen_studies(args, stiffness_study.studies_of(doc), "stiffness study")
        if args.csv and len(studies) > 1:
            raise ValueError("--csv writes one study's cohort: name it with --study")
        result = []
        for study in studies:
            try:
                records = stiffness_study.comparable_records(study)
                held, unread = stiffness_study.readable_records(study)  # unread: named, left out
            except ValueError as exc:  # a stored cohort not readable at all: the other studies are still told
                if args.study is not None:
                    raise
                result.append({"study": study.Label, "error": str(exc)})
                continue
            value, unit = stiffness_study.design_value(study)
            # starred: felt beyond the device (cohort.BEYOND_DEVICE says how), as the panel's table marks them
            result.append({"study": study.Label, "model": study.Model, "design_value": value, "unit": unit,
                           "participants": cohort.count_participants(records), "records": len(records),
                           "other_unit": len(held) - len(records),
                           "other_note": stiffness_study.others_note(study),
                           # starred as the panel's table marks them; † above the force limit, not counted
                           "beyond_device": sum(1 for r in records if cohort.mark(r) == " *"),
                           "beyond_force_limit": sum(1 for r in records if cohort.beyond_force_limit(r)),
                           "beyond_device_note": cohort.beyond_device_note(records),
                           "statistics": cohort.statistics(records),
                           "design_among_preferences": cohort.place_design(value, records)[1],
                           "unread": unread})
            if args.csv:  # every record, as the panel exports: each row says its unit; refused, named, if
                cohort.write_csv(args.csv, stiffness_study.records(study))  # one cannot be read
    finally:
        App.closeDocument(doc.Name)
    failed = [study["error"] for study in result if "error" in study]
    if failed and len(failed) == len(result):
        raise ValueError("; ".join(failed))
    status = 1 if failed else 0
    if args.json:
        return Finished(result, status)
    for study in result:
        if "error" in study:
            print(f"hapticad cohort: {study['error']}", file=sys.stderr)
            continue
        print(f"{study['study']} ({study['model']}): design {cohort.format_value(study['design_value'], study['unit'])}"
              f", {cohort.plural(study['participants'], 'participant')}"
              + (f" in {study['records']} records" if study["records"] != study["participants"] else "")
              + (f" ({study['other_note']})" if study["other_note"] else ""))
        for row in study["statistics"]:  # n: people (one person's records averaged)
            print(f"  {row['group']:<20} n {row['n']:<3} mean {row['mean']:.3g} sd {cohort.format_sd(row['sd'])} "
                  f"median {row['median']:.3g} range {row['min']:.3g}-{row['max']:.3g}")
        print(f"  this design: {study['design_among_preferences']}")
        if study["beyond_device_note"]:
            print(f"  {study['beyond_device_note']}")
        for sentence in study["unread"]:
            print(f"  {sentence}; left out of the statistics")
    return Finished(None, status)


def cmd_similarity(args):
    App = ensure_freecad()
    from . import similarity_study

    doc = _open_document(App, args.file)
    try:
        studies = _chosen_studies(args, similarity_study.similarity_studies_of(doc), "similarity study")
        if args.plot and len(studies) > 1:
            raise ValueError("--plot draws one study's space: name it with --study")
        if args.csv and len(studies) > 1:
            raise ValueError("--csv writes one study's answers: name it with --study")
        written, said = None, ""
        if args.csv:  # every kept answer, whether the space can be drawn or not
            from .similarity_export import write_csv

            written = {"csv": os.path.abspath(args.csv), "answers": write_csv(args.csv, studies[0])}
            said = f" (its {written['answers']} answers were written to {written['csv']})"
        result, lines = [], []
        for study in studies:
            if args.scaling:  # for this analysis only: the document is not saved
                study.Scaling = args.scaling.capitalize()
            try:
                analysis = similarity_study.analyse(study)
            except ValueError as exc:
                if args.study is not None:  # the one asked for
                    raise ValueError(f"{exc}{said}") from None
                result.append({"study": study.Label, "error": str(exc)})  # the others are still told
                lines.append(str(exc))  # it names the study
                continue
            result.append({"study": study.Label, **analysis})
            if args.plot:
                from .similarity_plot import plot_space, space_title

                plot_space(args.plot, analysis, space_title(analysis, study.Label))
                result[-1]["plot"] = os.path.abspath(args.plot)  # where it went: the file written
            lines.append(similarity_study.describe(study, analysis)
                         + (f"\nplot: {os.path.abspath(args.plot)}" if args.plot else ""))
        if all("error" in r for r in result):  # said once, as the command's error
            raise ValueError("; ".join(r["error"] for r in result) + said)
        if written:
            result[0].update(written)
            lines.append(f"answers: {written['csv']} ({written['answers']} rows)")
        if not args.json:
            print("\n".join(lines))
    finally:
        App.closeDocument(doc.Name)
    return result if args.json else None


def build_parser():
    parser = argparse.ArgumentParser(prog="hapticad", description="Feel CAD parts: HaptiCAD's command line")
    sub = parser.add_subparsers(dest="command", required=True)

    feel = sub.add_parser("feel", help="feel a stroke over a document's tagged faces")
    feel.add_argument("file", help="FreeCAD document (.FCStd) with HapticSurface objects")
    feel.add_argument("--stroke", type=_stroke, required=True, metavar="X0,Y0,Z0:X1,Y1,Z1",
                      help="stroke from P0 to P1 on the surface, mm")
    feel.add_argument("--speed", type=float, default=50.0, metavar="MM_PER_S", help="sliding speed (50)")
    feel.add_argument("--depth", type=float, default=1.0, metavar="MM", help="depth below the surface (1)")
    feel.add_argument("--rate", type=float, default=1000.0, metavar="HZ", help="servo rate (1000)")
    feel.add_argument("--out", type=_output_folder(TRACE_FILES), required=True, metavar="DIR",
                      help="folder for trace.csv and trace.png (made if missing)")
    feel.add_argument("--accuracy", default=None, choices=list(PRESETS) + [CUSTOM],
                      help="tessellation and shading preset (default: the preferences', else Fine); Custom "
                           "uses the preferences' custom values and the four options below")
    feel.add_argument("--linear-deflection", type=float, default=None, metavar="MM",
                      help="custom accuracy: largest distance between a facet and its face, "
                           "{:g}-{:g} mm".format(*LINEAR_RANGE_MM))
    feel.add_argument("--angular-deflection", type=float, default=None, metavar="DEGREES",
                      help="custom accuracy: largest angle between neighbouring facets, "
                           "{:g}-{:g} degrees".format(*ANGULAR_RANGE_DEG_SHOWN))
    feel.add_argument("--refine-edge", type=float, default=None, metavar="MM",
                      help="custom accuracy: split edges longer than this, {:g}-{:g} mm (0: off)".format(
                          *REFINE_RANGE_MM))
    feel.add_argument("--force-shading", action=argparse.BooleanOptionalAction, default=None,
                      help="custom accuracy: push along the exact B-rep normals (--no-force-shading: along the "
                           "facets' own)")
    feel.set_defaults(run=cmd_feel)

    mats = sub.add_parser("materials", help="list the haptic materials (shipped and the user's)")
    mats.add_argument("--json", action="store_true", help="print JSON")
    mats.add_argument("--shipped-only", action="store_true", help="ignore the user's own materials")
    mats.add_argument("--export-fcmat", metavar="DIR",
                      help="also write each as a FreeCAD .FCMat card (HaptiCAD-NAME.FCMat) into the folder DIR; "
                           "a different card already there (your edits?) is kept and named on stderr, with exit "
                           "status 0")
    mats.add_argument("--overwrite", action="store_true",
                      help="with --export-fcmat: replace the cards already in DIR with HaptiCAD's")
    mats.set_defaults(run=cmd_materials)

    rough = sub.add_parser("roughness-table", help="the seven roughness categories (seed 000, Table 2)")
    rough.add_argument("--json", action="store_true", help="print JSON")
    rough.set_defaults(run=cmd_roughness_table)

    bench = sub.add_parser(
        "bench-mesh", help="time the contact engine on a mesh file or an icosphere (JSON)",
        description="hapticad bench-mesh (MESH_FILE | --icosphere TRIANGLES) [--radius MM] "
                    "[--proxy point|sphere:R_MM] [--ticks N] [--units mm|m] [--seed S] "
                    "[--convex-pieces on|off] [--warm-ahead N] [--rate-hz R [--pace sleep|spin]] --json. "
                    "Strokes the surface along a seeded path at 50-100 mm/s, 1-3 mm deep, "
                    "k = 0.4 N/mm, mu 0.3/0.2, and prints build time, tick percentiles, bytes "
                    "per triangle, contact ticks, pop-through and the largest force.")
    bench.set_defaults(run=cmd_bench_mesh)

    table = sub.add_parser("accuracy-table", help="speed against accuracy of each accuracy preset "
                                                  "on an analytic sphere and cylinder")
    table.add_argument("--json", action="store_true", help="print JSON (default: a Markdown table)")
    table.add_argument("--plot", type=_png_file, metavar="PNG", help="also draw the errors and tick cost against triangles")
    table.set_defaults(run=cmd_accuracy_table)
    devices = sub.add_parser("devices", help="list the haptic devices (the simulated hand and HID devices)")
    devices.add_argument("--json", action="store_true", help="print JSON")
    devices.set_defaults(run=cmd_devices)

    fit = sub.add_parser(
        "fit-texture", help="fit a viscous grating texture to force recordings (seed 001 §III)",
        description="Cuts the recordings into sections of constant speed, takes each one's spatial FFT "
                    "and fits seed 001's eq. 2 (f_DC, f_vis, beta_h, alpha_h and their change with speed). "
                    "A recording is a CSV with time_s, position_mm, lateral_force_n [, normal_force_n] "
                    "(the lateral force on the finger), or a HaptiCAD trace.csv.")
    fit.add_argument("recordings", nargs="+", metavar="CSV", help="recordings (CSV)")
    fit.add_argument("--period", type=float, required=True, metavar="MM", help="the grating's period lambda, mm")
    fit.add_argument("--speeds", type=_speeds, default=None, metavar="MM_S,...",
                     help="target scanning speeds, mm/s (the paper's 50,80,120,180,270)")
    fit.add_argument("--tolerance", type=float, default=fit_options.DEFAULT_TOLERANCE_PERCENT, metavar="PERCENT",
                     help="how far a section's speed may stray from its target (2.5 %%)")
    fit.add_argument("--lowpass", type=float, default=fit_options.DEFAULT_LOWPASS_HZ, metavar="HZ",
                     help="first-order low-pass on the force, 0 for none (1000, as the paper's rig)")
    fit.add_argument("--harmonics", type=_count(*fit_options.HARMONICS_RANGE), default=fit_options.DEFAULT_HARMONICS,
                     help="harmonic peaks fitted, 2 to 8 (3, as the paper)")
    fit.add_argument("--min-periods", type=_count(*fit_options.MIN_PERIODS_RANGE),
                     default=fit_options.DEFAULT_MIN_PERIODS, metavar="N",
                     help=f"shortest section, periods, 6 to {fit_options.MAX_MIN_PERIODS} (6)")
    fit.add_argument("--plot", type=_png_file, metavar="PNG", help="draw the spectra and the fits against speed")
    fit.add_argument("--apply", metavar="FCSTD", help="set the fitted texture on a surface of this document and save it")
    fit.add_argument("--surface", metavar="NAME", help="the haptic surface (name or label) --apply sets")
    fit.add_argument("--json", action="store_true", help="print JSON")
    fit.set_defaults(run=cmd_fit_texture)

    coh = sub.add_parser("cohort", help="a document's stiffness studies: participants' preferences by group")
    coh.add_argument("file", help="FreeCAD document (.FCStd) with StiffnessStudy objects")
    coh.add_argument("--study", metavar="NAME", help="only this study (name or label)")
    coh.add_argument("--csv", type=_csv_file, metavar="FILE",
                     help="also write the study's participants as CSV (the name ends in .csv, added if it has "
                          "no extension; never written over a FreeCAD document)")
    coh.add_argument("--json", action="store_true", help="print JSON")
    coh.set_defaults(run=cmd_cohort)

    sim = sub.add_parser("similarity", help="a document's similarity studies: the perceptual space of the "
                         "textures (MDS) and each parameter's vector through it")
    sim.add_argument("file", help="FreeCAD document (.FCStd) with SimilarityStudy objects")
    sim.add_argument("--study", metavar="NAME", help="only this study (name or label)")
    sim.add_argument("--plot", type=_png_file, metavar="PNG", help="draw the space and its vectors (seed 001 Fig. 7)")
    sim.add_argument("--scaling", choices=("metric", "ordinal"),
                     help="classical MDS, or Kruskal's ordinal MDS (only the order of the dissimilarities counts); "
                          "default: each study's Scaling")
    sim.add_argument("--csv", type=_answers_csv_file, metavar="FILE",
                     help="also write every participant's answers (one row each, with the stimuli's values) as CSV "
                          "(the name ends in .csv, added if it has no extension; never written over a FreeCAD "
                          "document)")
    sim.add_argument("--json", action="store_true", help="print JSON (with the dissimilarity matrix and the "
                     "stimuli's values)")
    sim.set_defaults(run=cmd_similarity)

    demo = sub.add_parser("demo", help="open the example toothbrush and feel it")
    demo.add_argument("--headless", action="store_true", help="stroke every tagged face, even with a display")
    demo.add_argument("--out", type=_output_folder(), default="hapticad-demo", metavar="DIR",
                      help="output folder (hapticad-demo): the traces and plots, or the example's copy the GUI opens")
    demo.add_argument("--json", action="store_true", help="print every stroke's summary as JSON")
    demo.set_defaults(run=cmd_demo)
    return parser


class Finished:
    """A command's result with a non-zero exit status: it did its work, but refused part of
    its input (said on stderr)."""

    def __init__(self, result, status):
        self.result, self.status = result, status


_NEGATIVE_VALUE = re.compile(r"^-\.?\d[\d.,:eE+-]*$")


def _valued_options(parser):
    """The option strings of ``parser`` and its commands that take a value."""
    found = set()
    for action in parser._actions:  # argparse keeps no public list of them
        if isinstance(action, argparse._SubParsersAction):
            for command in action.choices.values():
                found |= _valued_options(command)
        elif action.option_strings and action.nargs != 0:
            found.update(action.option_strings)
    return found


def _joined_negative_values(argv, valued):
    """`--stroke -10,0,30:10,0,30` as `--stroke=-10,0,30:10,0,30`: argparse reads a value
    starting with a minus as an option unless it is one plain number, and said the
    stroke had no value. Only after an option in ``valued`` and before `--`; not for
    bench-mesh, whose options its own program reads."""
    if argv[:1] == ["bench-mesh"]:
        return list(argv)
    joined = []
    for index, token in enumerate(argv):
        if token == "--":
            return joined + list(argv[index:])
        if joined and joined[-1] in valued and _NEGATIVE_VALUE.match(token):
            joined[-1] += "=" + token
        else:
            joined.append(token)
    return joined


def _said(exc):
    """An OSError as "<path>: <reason>", without Python's "[Errno N]": the path as the user gave
    it (a file written through "<path>.part" named without the .part), a missing folder said so."""
    if not exc.strerror:
        return str(exc)
    reason = exc.strerror
    if exc.filename is None:
        return reason
    path = os.fsdecode(exc.filename)
    if path.endswith(".part"):
        path = path[:-len(".part")]
    folder = os.path.dirname(path)
    if exc.errno in (errno.ENOENT, errno.ENOTDIR) and folder and not os.path.isdir(folder):
        reason = _no_folder(folder)
    elif exc.errno == errno.EISDIR:
        reason = "is a folder, not a file"
    return f"{path}: {reason}"


def main(argv=None):
    # a closed pipe (`hapticad materials | head`) ends the program quietly
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    parser = build_parser()
    # bench-mesh passes its options on to the program untouched
    args, extra = parser.parse_known_args(
        _joined_negative_values(sys.argv[1:] if argv is None else argv, _valued_options(parser)))
    if args.command == "bench-mesh":
        args.options = extra
    elif extra:
        parser.error(f"unrecognized arguments: {' '.join(extra)}")
    try:
        result = args.run(args)
    except (ValueError, KeyError, OSError) as exc:
        message = exc.args[0] if isinstance(exc, KeyError) and exc.args else exc
        if isinstance(exc, OSError):
            message = _said(exc)
        print(f"hapticad {args.command}: {message}", file=sys.stderr)
        return 2
    except RuntimeError as exc:
        print(f"hapticad {args.command}: {exc}", file=sys.stderr)
        return 1
    except MemoryError:  # a scene too fine for this computer: said, not a traceback
        print(f"hapticad {args.command}: not enough memory for this scene: choose a coarser --accuracy or a longer "
              f"--refine-edge", file=sys.stderr)
        return 1
    status = 0
    if isinstance(result, Finished):
        result, status = result.result, result.status
    if result is not None:
        json.dump(result, sys.stdout, indent=2)
        sys.stdout.write("\n")
    return status


if __name__ == "__main__":
    sys.exit(main())
