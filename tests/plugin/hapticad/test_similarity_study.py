# SPDX-License-Identifier: GPL-3.0-or-later
"""Similarity studies (seed 001 §IV): the protocol of a participant's run, stimuli felt
through the real servo loop in place of the surface's texture, runs kept with the
document, the perceptual space and eq. 3's vectors of a simulated cohort, clear errors."""
import itertools
import json
import math
import os
import random
import tempfile
import unittest

import numpy as np

import FreeCAD as App

import HaptiCAD
from hapticad import similarity_study as ss
from hapticad.document_scene import build_document_scene, recompile_surfaces
from hapticad.feel import Stroke, run_stroke_in_servo_loop, sliding_mask
from hapticad.surface_compile import compile_surface
from hapticad.trace_path import slid_mm


FULL_RANGE_N = 2.0


def simulated_answer(run, trial, weights, rng, noise, likes_a=None, warp=None):
    """A participant whose sense of difference is a weighted distance in (f_DC, f_vis)
    with seeded noise, read through ``warp`` (how they use the scale: the identity when
    evenly); who classes a texture as A when ``likes_a(values)``."""
    values = [run.stimuli[i]["values"] for i in (trial.first, trial.second) if i >= 0]
    if trial.kind == "class":
        return "A" if likes_a(values[0]) else "B"
    a, b = values
    distance = math.hypot(weights[0] * (a["TextureDC"] - b["TextureDC"]) / 0.35,
                          weights[1] * (a["TextureViscosity"] - b["TextureViscosity"]) / 0.4)
    similarity = 1.0 - (warp or (lambda x: x))(distance / math.hypot(*weights)) + rng.gauss(0, noise)
    return int(min(run.steps, max(1, round(1 + similarity * (run.steps - 1)))))


def finish(run, weights=(1.0, 0.5), seed=0, noise=0.05, likes_a=None, warp=None):
    rng = random.Random(seed)
    likes_a = likes_a or (lambda v: v["TextureDC"] + v["TextureViscosity"] < 0.5)
    while not run.done:
        run.present_each()  # a trial is answered once its textures were felt
        run.answer(simulated_answer(run, run.current, weights, rng, noise, likes_a, warp))
    return run


class StudyTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("SimilarityTest")
        self.box = self.doc.addObject("Part::Box", "Plate")
        self.box.Length, self.box.Width, self.box.Height = 40, 100, 10
        self.doc.recompute()
        self.plate = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", FeelRoughness=False,
                                           TextureScale="Device force", TextureFullRange=FULL_RANGE_N)
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        for study in ss.similarity_studies_of(self.doc):
            ss.stop_presenting(study)
        App.closeDocument(self.doc.Name)
        self.tmp.cleanup()

    def references(self):
        """Two surfaces with the textures of a stiff and a soft real grating."""
        box = self.doc.addObject("Part::Box", "Samples")
        self.doc.recompute()
        a = HaptiCAD.make_surface(self.doc, [(box, "Face1")], material="ABS", FeelRoughness=False, Texture="Custom",
                                  TextureDC=0.2, TextureViscosity=-0.3, TexturePeriod=2.0)
        b = HaptiCAD.make_surface(self.doc, [(box, "Face2")], material="ABS", FeelRoughness=False, Texture="Custom",
                                  TextureDC=0.8, TextureViscosity=0.3, TexturePeriod=3.0)
        return a, b

    def test_a_new_study_holds_the_papers_nine_textures(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate)
        self.assertEqual(ss.validate(study), [])
        items = ss.stimuli(study)
        self.assertEqual(len(items), 9)
        dcs = sorted({s["values"]["TextureDC"] for s in items})
        viss = sorted({s["values"]["TextureViscosity"] for s in items})
        self.assertEqual([round(x, 3) for x in dcs], [0.325, 0.5, 0.675])
        self.assertEqual([round(x, 3) for x in viss], [-0.2, 0.0, 0.2])
        for s in items:  # the values the paper held
            self.assertEqual(s["values"]["TextureBeta"], 0.125)
            self.assertEqual(s["values"]["TextureAlpha"], 2.5)
        self.assertEqual((study.RatingSteps, study.WarmUps, study.Repeats, study.Dimensions), (7, 12, 3, 2))

    def test_a_run_follows_the_papers_protocol(self):
        a, b = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=a, ReferenceB=b)
        run = ss.Run(study, "P1", seed=5)
        kinds = [t.kind for t in run.trials]
        # 12 warm-ups, then the 36 pairs, then each of nine classed three times: 75 trials
        self.assertEqual(kinds, ["warm-up"] * 12 + ["pair"] * 36 + ["class"] * 27)
        pairs = [tuple(sorted((t.first, t.second))) for t in run.trials if t.kind == "pair"]
        self.assertEqual(sorted(pairs), list(itertools.combinations(range(9), 2)))
        firsts = [t.first < t.second for t in run.trials if t.kind == "pair"]
        self.assertTrue(any(firsts) and not all(firsts))  # either may be felt first
        classed = [t.first for t in run.trials if t.kind == "class"]
        self.assertEqual(sorted(classed), sorted(list(range(9)) * 3))
        self.assertNotEqual(classed, sorted(classed))
        # seeded: the same seed, the same order; another, another
        self.assertEqual([(t.first, t.second) for t in ss.Run(study, "P1", seed=5).trials],
                         [(t.first, t.second) for t in run.trials])
        self.assertNotEqual([(t.first, t.second) for t in ss.Run(study, "P2", seed=6).trials],
                            [(t.first, t.second) for t in run.trials])
        self.assertEqual(run.progress(), ("warm-up", 1, 12))
        for _ in range(12):
            run.present_each()
            run.answer(4)
        self.assertEqual(run.progress(), ("pair", 1, 36))
        run.back()
        self.assertEqual(run.progress(), ("warm-up", 12, 12))
        # without references there is nothing to class
        study.ReferenceA = study.ReferenceB = None
        self.assertEqual([t.kind for t in ss.Run(study, "P3", seed=1).trials].count("class"), 0)

    def test_a_presented_stimulus_replaces_the_surfaces_texture_and_is_felt(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate)
        items = ss.stimuli(study)
        low = next(i for i, s in enumerate(items) if s["values"]["TextureDC"] == 0.325
                   and s["values"]["TextureViscosity"] == 0.0)
        high = next(i for i, s in enumerate(items) if s["values"]["TextureDC"] == 0.675
                    and s["values"]["TextureViscosity"] == 0.0)
        face = self.box.Shape.Face6
        self.assertIsNone(compile_surface(self.plate, face).texture)  # the plate's own: no texture
        scene = build_document_scene(self.doc)

        def resisting_force_n():
            stroke = Stroke((20, 10, 10), (20, 90, 10), speed_mm_s=100.0, depth_mm=1.0, rate_hz=1000)
            result = run_stroke_in_servo_loop(scene, stroke)
            sliding = sliding_mask(result, scene)
            self.assertGreater(sliding.sum(), 300)
            return float(np.mean(result.trace["tangential_force_n"][sliding]))

        forces = {}
        for index in (low, high):
            ss.present(study, items[index]["values"])
            texture = compile_surface(self.plate, face).texture
            self.assertAlmostEqual(texture.params.f_dc, items[index]["values"]["TextureDC"])
            self.assertAlmostEqual(texture.params.period_m, self.plate.TexturePeriod * 1e-3)
            scene = recompile_surfaces(self.doc, scene)  # what a running session does on a change
            forces[index] = resisting_force_n()
        # eq. 2 at f_vis 0: the mean resisting force is f_DC of the full range (the
        # harmonics average out over whole periods)
        self.assertAlmostEqual(forces[low], 0.325 * FULL_RANGE_N, delta=0.03)
        self.assertAlmostEqual(forces[high], 0.675 * FULL_RANGE_N, delta=0.03)
        ss.stop_presenting(study)
        self.assertIsNone(compile_surface(self.plate, face).texture)

    def test_a_reference_is_presented_whole_and_an_answer_clears_what_was_held(self):
        a, b = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=a, ReferenceB=b, WarmUps=0)
        run = ss.Run(study, "P1", seed=2)
        while run.current.kind != "class":
            run.present_each()
            run.answer(3)
        with self.assertRaises(ValueError):
            run.values(2)  # a class trial has one texture
        run.present("B")
        texture = ss.rendered_texture(self.plate)
        self.assertEqual((texture["TextureDC"], texture["TexturePeriod"]), (0.8, 3.0))  # B's own period
        run.present(1)
        self.assertEqual(ss.rendered_texture(self.plate)["TexturePeriod"], self.plate.TexturePeriod)
        run.stroked(run.felt_after_mm)
        run.answer("A")
        self.assertIsNone(ss.presented_texture(self.plate))
        run.present(1)
        run.stroked(run.felt_after_mm)
        with self.assertRaisesRegex(ValueError, "class the texture as A or B, not 4"):
            run.answer(4)  # a class trial takes A or B
        # the study's own deletion leaves nothing held out
        run.present(1)
        self.doc.removeObject(study.Name)
        self.assertIsNone(ss.presented_texture(self.plate))

    def test_a_finished_run_is_kept_with_the_document_and_nothing_before(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate)
        run = ss.Run(study, "Ada", seed=1)
        run.present_each()
        run.answer(5)
        with self.assertRaisesRegex(ValueError, "not done: 47 trials remain"):
            ss.record_run(study, run)
        self.assertEqual((ss.runs(study), study.Participants), ([], 0))
        run.present_each()
        with self.assertRaisesRegex(ValueError, r"rate the pair 1\.\.7"):
            run.answer(8)
        finish(run)
        record = ss.record_run(study, run)
        self.assertEqual(len(record["ratings"]), 36)  # the warm-ups are not kept
        self.assertEqual(study.Participants, 1)
        ss.present(study, ss.stimuli(study)[0]["values"])
        path = os.path.join(self.tmp.name, "study.FCStd")
        self.doc.saveAs(path)
        name = self.doc.Name
        App.closeDocument(name)
        self.doc = App.openDocument(path)
        study = ss.similarity_studies_of(self.doc)[0]
        self.assertEqual(study.Participants, 1)
        self.assertEqual(ss.runs(study)[0]["ratings"], record["ratings"])
        # the document does not save the ranges: restored, they hold again (a scale of
        # one step would have let a whole run start, to be refused at its end)
        for name, bad, kept in (("RatingSteps", 1, 3), ("Dimensions", 9, 3), ("Repeats", 0, 1)):
            setattr(study, name, bad)
            self.assertEqual(getattr(study, name), kept, name)
        study.RatingSteps, study.Dimensions, study.Repeats = 7, 2, 3
        self.assertIsNone(ss.presented_texture(study.Surface))  # what was held out is not saved
        # undo takes a kept run back
        run = finish(ss.Run(study, "Bea", seed=2))
        self.doc.UndoMode = 1
        self.doc.openTransaction("Similarity run")
        ss.record_run(study, run)
        self.doc.commitTransaction()
        self.assertEqual(study.Participants, 2)
        self.doc.undo()
        self.assertEqual((study.Participants, len(ss.runs(study))), (1, 1))

    def test_the_cohorts_space_shows_what_it_was_made_of(self):
        a, b = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=a, ReferenceB=b)
        # ten participants who weigh friction twice as much as viscosity (seeded noise),
        # and class low friction and viscosity as A
        for p in range(10):
            ss.record_run(study, finish(ss.Run(study, f"P{p}", seed=p), weights=(1.0, 0.5), seed=100 + p))
        result = ss.analyse(study)
        self.assertEqual(result["participants"], 10)
        self.assertLess(result["stress"], 0.15)
        self.assertGreater(result["explained"], 0.8)
        vectors = result["vectors"]
        self.assertEqual(set(vectors), {"f_DC", "f_vis", ss.LIKENESS})  # beta_h, alpha_h held: no vector
        dc, vis, like = vectors["f_DC"], vectors["f_vis"], vectors[ss.LIKENESS]
        self.assertGreater(dc["correlation"], 0.9)
        self.assertGreater(vis["correlation"], 0.8)
        self.assertAlmostEqual(dc["length"] / vis["length"], 2.0, delta=0.5)
        # friction and viscosity are separate directions of the space ...
        cos = np.dot(dc["direction"], vis["direction"]) / (dc["length"] * vis["length"])
        self.assertLess(abs(cos), 0.3)
        # ... and higher friction and viscosity both lead away from A
        unit = np.asarray(like["direction"]) / like["length"]
        self.assertLess(np.dot(dc["direction"], unit), 0)
        self.assertLess(np.dot(vis["direction"], unit), 0)
        names = result["stimuli"]
        self.assertEqual(result["likeness"][names.index("f_DC 0.325 f_vis -0.2")], 1.0)
        self.assertEqual(result["likeness"][names.index("f_DC 0.675 f_vis +0.2")], 0.0)

    def test_one_share_for_every_stimulus_gives_no_likeness_vector_and_says_so(self):
        # everything classed closer to A was shown as a vector "closer to A |p| 0.000 r 0.00"
        a, b = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=a, ReferenceB=b)
        for p in range(3):
            ss.record_run(study, finish(ss.Run(study, f"P{p}", seed=p), seed=p, likes_a=lambda v: True))
        result = ss.analyse(study)
        self.assertEqual(result["likeness"], [1.0] * 9)
        self.assertNotIn(ss.LIKENESS, result["vectors"])
        self.assertIn("every stimulus was classed closer to A: no vector for likeness", result["notes"])

    def test_warm_ups_hold_every_stimulus_and_no_pair_twice(self):
        # drawn with repeats, 435 of 500 runs repeated a warm-up pair and 200 left a
        # stimulus unfelt before the rated pairs: the paper's warm-ups give context
        study = HaptiCAD.make_similarity_study(self.doc, self.plate)  # nine stimuli, twelve warm-ups
        for seed in range(500):
            warm = [tuple(sorted((t.first, t.second))) for t in ss.Run(study, "P", seed=seed).trials
                    if t.kind == "warm-up"]
            self.assertEqual(len(warm), 12)
            self.assertEqual(len(set(warm)), 12, seed)
            self.assertEqual({i for pair in warm for i in pair}, set(range(9)), seed)
        firsts = [ss.Run(study, "P", seed=seed).trials[0] for seed in range(200)]
        self.assertGreater(len({(t.first, t.second) for t in firsts}), 30)  # still random, both orders
        # more warm-ups than pairs: every pair, then every pair again, and so on
        seven = ss.warm_up_pairs(random.Random(1), 3, 7)
        self.assertEqual(sorted({p: seven.count(p) for p in seven}.values()), [2, 2, 3])

    def test_ordinal_scaling_keeps_what_a_scale_used_unevenly_hides_from_the_metric_one(self):
        # ten participants who call anything past half the largest difference "nothing
        # alike": the metric space reads those ties as distance and loses viscosity. Over
        # six cohorts (one cohort alone is luck: its ordinal f_vis correlation ranged
        # 0.22-0.79 between cohorts, 0.24-0.76 before the warm-ups covered every stimulus)
        saturating = lambda x: min(1.0, 2.0 * x)  # noqa: E731
        metric_vis, ordinal_dc, ordinal_vis, weighs = [], [], [], []
        for cohort in range(6):
            study = HaptiCAD.make_similarity_study(self.doc, self.plate)
            self.assertEqual(study.Scaling, "Metric")  # the default, as before this choice
            for p in range(10):
                k = 10 * cohort + p
                ss.record_run(study, finish(ss.Run(study, f"P{p}", seed=k), weights=(1.0, 0.5), seed=100 + k,
                                            warp=saturating))
            metric = ss.analyse(study)
            self.assertEqual(metric["scaling"], "metric")
            self.assertGreater(metric["stress"], 0.3)
            metric_vis.append(metric["vectors"]["f_vis"]["correlation"])
            study.Scaling = "Ordinal"
            ordinal = ss.analyse(study)
            self.assertEqual((ordinal["scaling"], ordinal["participants"]), ("ordinal", 10))
            self.assertGreater(ordinal["iterations"], 1)
            self.assertLess(ordinal["stress"], 0.2)
            dc, vis = ordinal["vectors"]["f_DC"], ordinal["vectors"]["f_vis"]
            ordinal_dc.append(dc["correlation"])
            ordinal_vis.append(vis["correlation"])
            weighs.append(dc["length"] > vis["length"])  # friction weighs more (2x, blurred by the ties)
            self.doc.removeObject(study.Name)
        self.assertLess(max(metric_vis), 0.3)
        self.assertGreater(np.mean(ordinal_dc), 0.9)
        self.assertGreater(np.mean(ordinal_vis), np.mean(metric_vis) + 0.3)  # what the metric space lost
        self.assertTrue(all(weighs), weighs)
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, Scaling="Ordinal")
        for p in range(10):
            ss.record_run(study, finish(ss.Run(study, f"P{p}", seed=p), weights=(1.0, 0.5), seed=100 + p,
                                        warp=saturating))
        text = ss.describe(study, ss.analyse(study))
        self.assertIn("ordinal scaling, Kruskal's stress-1", text)
        # too few stimuli for their order alone to hold three dimensions: said
        study.Dimensions = 3
        self.assertTrue(any("too few pairs" in n for n in ss.analyse(study)["notes"]))

    def test_a_participant_who_ran_twice_counts_once_and_weighs_as_much_as_the_others(self):
        a, b = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=a, ReferenceB=b, WarmUps=0)
        # Ida weighs friction only and classes everything A; Bo weighs viscosity only and
        # classes everything B. Ida runs twice, the second time typed "ida " in lower case.
        ida, bo = dict(weights=(1.0, 0.0), likes_a=lambda v: True), dict(weights=(0.0, 1.0), likes_a=lambda v: False)
        for name, seed, how in (("Ida", 1, ida), ("Bo", 2, bo), (" ida ", 3, ida)):
            ss.record_run(study, finish(ss.Run(study, name, seed=seed), seed=seed, noise=0.0, **how))
        self.assertEqual(study.Participants, 2)
        result = ss.analyse(study)
        self.assertEqual((result["participants"], result["runs"]), (2, 3))
        # each person half: Ida's two runs are one share, so the likeness is 0.5 (not 2/3)
        self.assertEqual(result["likeness"], [0.5] * 9)
        kept = ss.runs(study)
        once = ss.dissimilarity([kept[0], kept[1]], 9)  # Ida once and Bo
        np.testing.assert_allclose(result["dissimilarity"], once, atol=1e-12)  # Ida twice: the same
        as_runs = ss.dissimilarity([kept[0], kept[1], {**kept[2], "name": "Ida's twin"}], 9)
        self.assertGreater(np.abs(as_runs - once).max(), 0.05)  # counted as runs she would weigh double
        self.assertIn("runs of one participant are averaged before pooling, so each participant weighs the same: "
                      "Ida (2)", result["notes"])
        self.assertIn("9 stimuli, 2 participants in 3 runs", ss.describe(study, result))
        # a damaged stored record (no name) is no one's: keeping and counting go on
        self.assertEqual(ss.count_participants([*ss.runs(study), {"steps": 7}, "not a run"]), 2)
        # removing a run recounts the people, and so does opening a document that counted runs
        ss.remove_run(study, 1)
        self.assertEqual(study.Participants, 1)
        study.Participants = 7  # as a document saved before counting people
        path = os.path.join(self.tmp.name, "counted.FCStd")
        self.doc.saveAs(path)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        study = ss.similarity_studies_of(self.doc)[0]
        self.assertEqual(study.Participants, 1)
        self.assertNotIn("Touched", study.State)

    def test_ratings_all_alike_are_refused_not_laid_out(self):
        # every pair rated 1 (or 7): "stress 0.000: the ratings' order fits exactly", and
        # vectors with r 0.38 drawn over an arbitrary layout
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=0)
        for rating, how in ((1, "nothing alike"), (7, "the same"), (4, "alike to one degree \\(50 % of the scale\\)")):
            for scaling in ("Metric", "Ordinal"):
                with self.subTest(rating=rating, scaling=scaling):
                    while ss.runs(study):
                        ss.remove_run(study, 0)
                    run = ss.Run(study, "P1", seed=1)
                    while not run.done:
                        run.present_each()
                        run.answer("A" if run.current.kind == "class" else rating)
                    ss.record_run(study, run)
                    study.Scaling = scaling
                    with self.assertRaisesRegex(ValueError, f"every pair was rated {how}, so the ratings hold no "
                                                            "differences to lay out"):
                        ss.analyse(study)

    def test_runs_on_other_stimuli_are_kept_but_not_pooled(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=0)
        ss.record_run(study, finish(ss.Run(study, "P1", seed=1)))
        items = ss.stimuli(study)[:4]
        ss.set_stimuli(study, items)
        with self.assertRaisesRegex(ValueError, "no run is pooled with the study as it is now: 1 run on other "
                                                "stimuli \\(kept, not pooled\\)"):
            ss.analyse(study)
        ss.record_run(study, finish(ss.Run(study, "P2", seed=2)))
        result = ss.analyse(study)
        self.assertEqual((result["participants"], result["held"]), (1, 1))
        self.assertEqual(len(result["points"]), 4)
        self.assertTrue(any("one or two people" in n for n in result["notes"]))
        self.assertIn("4 stimuli, 1 participant (not pooled: 1 run on other stimuli)", ss.describe(study, result))

    def test_only_what_the_texture_is_felt_with_keeps_runs_apart(self):
        # a friction edit on a Device force texture unpooled every run, "felt with the
        # static friction 0.6 (now 0.7)", though the texture replaces the friction there
        a, b = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=a, ReferenceB=b, WarmUps=0)
        for p in range(2):
            ss.record_run(study, finish(ss.Run(study, f"P{p}", seed=p)))
        self.assertEqual(self.plate.TextureScale, "Device force")
        self.plate.StaticFriction, a.StaticFriction = 0.7, 0.3
        self.assertEqual(len(ss.comparable_runs(study)), 2)
        self.plate.StickSpeed = 4.0  # the texture's viscous term uses it
        self.assertEqual(ss.comparable_runs(study), [])
        self.assertEqual(ss.why_not_pooled(ss.runs(study)[0], study),
                         "felt with the surface's stick speed 2 mm/s (now 4 mm/s)")
        self.plate.StickSpeed = 2.0
        # runs kept before the stick speed was kept, with the friction and full range they held
        old = ss.runs(study)
        for record in old:
            record["context"] = {**record["context"], "StaticFriction": 0.6}
            del record["context"]["StickSpeed"]
        study.Responses = json.dumps(old)
        self.assertEqual(len(ss.comparable_runs(study)), 2)
        # Friction level: the friction is felt (the references', presented here, too) and
        # the full range is not
        self.plate.TextureScale = "Friction level"
        ss.record_run(study, finish(ss.Run(study, "P2", seed=2)))
        self.plate.TextureFullRange = 5.0
        self.assertEqual([r["name"] for r in ss.comparable_runs(study)], ["P2"])
        self.plate.StaticFriction = 0.8
        self.assertEqual(ss.why_not_pooled(ss.runs(study)[2], study),
                         "felt with the surface's static friction 0.7 (now 0.8)")
        self.plate.StaticFriction, self.plate.TextureScale = 0.7, "Device force"
        self.plate.TextureFullRange = FULL_RANGE_N
        b.TextureScale = "Friction level"  # presented on the plate: the plate's friction counts for B
        self.assertEqual(ss.why_not_pooled(ss.runs(study)[0], study, references=True),
                         "classed against another reference B")
        self.assertEqual(ss.why_not_pooled(ss.runs(study)[0], study), "")  # rated before B was felt
        self.assertEqual(ss.felt_context(study)["ReferenceB"]["StaticFriction"], self.plate.StaticFriction)
        self.assertNotIn("StaticFriction", ss.felt_context(study))

    def test_why_runs_are_not_pooled_is_said_and_two_rating_scales_pooled_are_noted(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=0)
        for p in range(2):
            ss.record_run(study, finish(ss.Run(study, f"P{p}", seed=p)))
        # the same stimuli, felt now with another period: the message names it, not "no one rated these"
        self.plate.TexturePeriod = 3.0
        with self.assertRaises(ValueError) as caught:
            ss.analyse(study)
        self.assertIn("no run is pooled with the study as it is now: 2 runs felt with the surface's period 2.5 mm "
                      "(now 3 mm)", str(caught.exception))
        self.plate.TexturePeriod = 2.5
        # a run on a 5-step scale pooled with 7-step ones: each rating as its share of its scale, and said
        study.RatingSteps = 5
        ss.record_run(study, finish(ss.Run(study, "P5", seed=5)))
        result = ss.analyse(study)
        self.assertEqual(result["participants"], 3)
        self.assertIn("runs rated on 5 and 7-step scales are pooled, each rating taken as its share of its own "
                      "scale's range", result["notes"])

    def test_bad_input_is_refused_and_changes_nothing(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate)
        before = study.Stimuli
        items = ss.stimuli(study)
        for bad, message in (
                (items[:2], "at least 3"),
                ([*items, dict(items[0], name="again")], "same texture as"),
                ([*items[:8], dict(items[8], name=items[0]["name"])], "names repeat"),
                ([*items[:8], {"name": "x", "values": dict(items[8]["values"], TextureDC=float("nan"))}],
                 "not a finite number"),
                ([*items[:8], {"name": "x", "values": {"TextureDC": 0.3}}], "no f_vis"),
                ([*items[:8], "a string"], "each stimulus"),
                ("not a list", "each stimulus")):
            with self.assertRaisesRegex(ValueError, message):
                ss.set_stimuli(study, bad)
            self.assertEqual(study.Stimuli, before)
        a, _ = self.references()
        study.ReferenceA = a
        self.assertIn("reference B is not set: classing needs both references, or neither", ss.validate(study))
        with self.assertRaisesRegex(ValueError, "reference B is not set"):
            ss.Run(study, "P1")
        study.ReferenceA = None
        with self.assertRaisesRegex(ValueError, "needs a name"):
            ss.Run(study, "  ")
        other = HaptiCAD.make_similarity_study(self.doc, self.plate, name="Other")
        self.assertTrue(any("also studied by" in p for p in ss.validate(other)))
        self.doc.removeObject(other.Name)
        with self.assertRaisesRegex(ValueError, "a haptic surface"):
            HaptiCAD.make_similarity_study(self.doc, self.box)
        with self.assertRaisesRegex(ValueError, "unknown properties Colour"):
            HaptiCAD.make_similarity_study(self.doc, self.plate, Colour=1)
        with self.assertRaisesRegex(ValueError, "each stimulus is"):
            HaptiCAD.make_similarity_study(self.doc, self.plate, items=["one", "two", "three"])
        self.assertEqual(len(ss.similarity_studies_of(self.doc)), 1)
        # a stored run that is not a run
        self.assertIn("not a similarity run", ss.record_problems({"name": "x"})[0])
        study.Responses = "{not json"
        with self.assertRaisesRegex(ValueError, "not readable JSON"):
            ss.runs(study)
        study.Responses = "[]"
        study.Dimensions = 3
        ss.set_stimuli(study, items[:3])
        ss.record_run(study, finish(ss.Run(study, "P", seed=1)))
        with self.assertRaisesRegex(ValueError, "3 dimensions for 3 stimuli"):
            ss.analyse(study)

    def test_what_was_held_out_goes_with_an_undo_and_a_closed_document(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate)
        self.doc.UndoMode = 1
        self.doc.openTransaction("Fewer stimuli")
        ss.set_stimuli(study, ss.stimuli(study)[:5])
        self.doc.commitTransaction()
        ss.present(study, ss.stimuli(study)[0]["values"])
        self.assertIsNotNone(ss.presented_texture(self.plate))
        self.doc.undo()  # the stimulus held out may no longer be the study's
        self.assertEqual(len(ss.stimuli(study)), 9)
        self.assertIsNone(ss.presented_texture(self.plate))
        # a document closed while a texture is held out: one opened under its name does not inherit it
        path = os.path.join(self.tmp.name, "SimilarityTest.FCStd")
        self.doc.saveAs(path)
        name = self.doc.Name
        ss.present(study, ss.stimuli(study)[0]["values"])
        App.closeDocument(name)
        self.doc = App.openDocument(path)
        self.assertEqual(self.doc.Name, name)
        plate = ss.similarity_studies_of(self.doc)[0].Surface
        self.assertIsNone(ss.presented_texture(plate))
        self.assertIsNone(compile_surface(plate, self.doc.getObject("Plate").Shape.Face6).texture)

    def test_runs_on_another_surface_are_not_pooled_and_against_other_references_only_their_ratings_are(self):
        a, b = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=a, ReferenceB=b, WarmUps=0)
        ss.record_run(study, finish(ss.Run(study, "P1", seed=1)))
        (record,) = ss.runs(study)
        self.assertEqual(len(ss.comparable_runs(study)), 1)
        self.assertTrue(ss.classings_pooled(record, study))
        self.assertEqual(ss.analyse(study)["classed_by"], 1)
        # swapped: "closer to A" meant the other sample. The pairs were rated before any
        # reference was felt: the ratings still pool, the classings do not
        study.ReferenceA, study.ReferenceB = b, a
        self.assertEqual(len(ss.comparable_runs(study)), 1)
        self.assertFalse(ss.classings_pooled(record, study))
        self.assertEqual(ss.why_not_pooled(record, study, references=True),
                         "classed against another reference A and another reference B")
        result = ss.analyse(study)
        self.assertEqual((result["participants"], result["classed_by"], result["likeness"]), (1, 0, [None] * 9))
        self.assertNotIn(ss.LIKENESS, result["vectors"])
        self.assertIn("the classings of 1 run are left out of the likeness to the references (classed against "
                      "another reference A and another reference B); their ratings are pooled", result["notes"])
        # the references unlinked: likewise
        study.ReferenceA = study.ReferenceB = None
        self.assertEqual(len(ss.comparable_runs(study)), 1)
        self.assertEqual(ss.why_not_pooled(record, study, references=True),
                         "classed against a reference A the study no longer has and a reference B the study "
                         "no longer has")
        study.ReferenceA, study.ReferenceB = a, b
        self.assertTrue(ss.classings_pooled(record, study))
        self.plate.TexturePeriod = 4.0  # the stimuli felt on another grating period
        self.assertEqual(len(ss.comparable_runs(study)), 0)
        self.plate.TexturePeriod = 2.5
        self.assertEqual(len(ss.comparable_runs(study)), 1)
        # a stored run that is not whole is shown but never pooled
        broken = dict(ss.runs(study)[0], ratings=ss.runs(study)[0]["ratings"][1:])
        study.Responses = json.dumps([*ss.runs(study), broken])
        self.assertEqual(len(ss.comparable_runs(study)), 1)
        self.assertIn("not every pair", ss.record_problems(broken)[0])
        for bad in (dict(broken, steps=1), dict(broken, steps=True), dict(broken, choices=[[0.5, "A"]])):
            self.assertTrue(ss.record_problems(bad))
        self.assertEqual(ss.analyse(study)["participants"], 1)

    def test_answers_are_whole_numbers_on_the_scale(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=0)
        run = ss.Run(study, "P1", seed=1)
        run.present_each()  # felt: what is refused is the answer itself
        for bad in (True, 4.0, 0, 8, "4"):
            with self.assertRaisesRegex(ValueError, "rate the pair"):
                run.answer(bad)
        self.assertEqual(run.answers, [])

    def test_an_answer_waits_until_the_trials_textures_were_felt(self):
        a, b = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=a, ReferenceB=b, WarmUps=1)
        run = ss.Run(study, "P1", seed=3)
        first = run.current

        def state():
            return (list(run.answers), set(run.felt), run.current, run.progress(),
                    ss.presented_texture(self.plate))

        # nothing felt: refused, and nothing changes (no answer, nothing felt or held out)
        self.assertFalse(run.ready)
        self.assertEqual(run.unfelt(), [1, 2])
        before = state()
        with self.assertRaisesRegex(ValueError, "feel texture 1 and texture 2 before answering"):
            run.answer(4)
        self.assertEqual(state(), before)
        self.assertEqual(before[:2], ([], set()))
        # held out is not felt: the finger must stroke it over one period of its grating
        run.stroked(5.0)  # nothing held out: a stroke feels nothing
        self.assertEqual(run.felt, set())
        run.present(2)
        self.assertEqual((run.held, run.felt_after_mm), (2, 2.5))  # the plate's period
        with self.assertRaisesRegex(ValueError, "feel texture 1 and texture 2 before answering"):
            run.answer(4)
        run.stroked(1.5)
        run.stroked(-3.0)  # nothing is taken back by a negative length
        self.assertEqual(run.unfelt(), [1, 2])
        run.stroked(1.0)
        # one of the pair felt: still refused; what is felt and held out stays
        self.assertEqual(run.unfelt(), [1])
        before = state()
        self.assertEqual(before[1], {2})
        self.assertIsNotNone(before[4])
        with self.assertRaisesRegex(ValueError, "feel texture 1 before answering"):
            run.answer(4)
        self.assertEqual(state(), before)
        # both felt: taken; the next trial starts with nothing felt or held
        run.present(1)
        self.assertFalse(run.ready)
        run.stroked(2.5)
        self.assertTrue(run.ready)
        run.answer(4)
        self.assertEqual(run.answers, [4])
        self.assertEqual((run.felt, run.held), (set(), None))
        run.stroked(10.0)  # the last trial's texture is no longer held out
        with self.assertRaisesRegex(ValueError, "feel texture 1 and texture 2"):
            run.answer(4)
        # a trial taken back is felt again before it is answered again
        run.present_each()
        run.back()
        self.assertIs(run.current, first)
        with self.assertRaisesRegex(ValueError, "feel texture 1 and texture 2"):
            run.answer(4)
        # the session stopped (forget_felt): what was felt before no longer counts
        run.present_each()
        run.forget_felt()
        with self.assertRaisesRegex(ValueError, "before answering"):
            run.answer(4)
        self.assertEqual(run.answers, [])
        # a class trial: the references alone are not the texture classed
        while run.current.kind != "class":
            run.present_each()
            run.answer(4)
        self.assertEqual(run.needed(), [1])
        run.present("A")
        self.assertEqual(run.felt_after_mm, 2.0)  # reference A's own period
        run.stroked(2.0)
        run.present("B")
        run.stroked(2.5)
        self.assertEqual(run.felt, {"A"})  # B's grating is 3 mm
        run.stroked(0.5)
        answered = len(run.answers)
        with self.assertRaisesRegex(ValueError, "feel the texture before answering"):
            run.answer("A")
        self.assertEqual((len(run.answers), run.felt), (answered, {"A", "B"}))
        run.present(1)
        run.stroked(2.5)
        run.answer("A")
        self.assertEqual(run.answers[-1], "A")

    def test_a_texture_is_felt_by_stroking_the_studys_face_through_the_servo_loop(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=0)
        scene = build_document_scene(self.doc)
        plate_faces = [i for i, name in enumerate(scene.face_names) if scene.face_surface.get(name) == self.plate.Name]
        self.assertEqual(plate_faces, [scene.face_id("Plate.Face6")])

        def stroke_over(p0, p1):
            stroke = Stroke(p0, p1, speed_mm_s=80.0, depth_mm=1.0, rate_hz=1000)
            result = run_stroke_in_servo_loop(scene, stroke)
            anywhere = slid_mm(result.trace, range(len(scene.face_names)))
            return slid_mm(result.trace, plate_faces), anywhere

        run = ss.Run(study, "P1", seed=4)
        run.present(1)
        # the hand on the part's side (x = 0, not the study's face) while texture 1 is held
        # out on the plate: it slid, but not over the study's face, so nothing is felt
        slid, anywhere = stroke_over((0, 30, 2), (0, 38, 8))
        self.assertEqual(slid, 0.0)
        self.assertGreater(anywhere, 8.0)
        self.assertEqual(run.unfelt(), [1, 2])
        # 12 mm along the plate: slid (the approach and the retreat less), and felt
        slid, anywhere = stroke_over((20, 10, 10), (20, 22, 10))
        self.assertEqual(slid, anywhere)
        self.assertGreater(slid, 10.0)
        self.assertLess(slid, 12.5)
        run.stroked(slid)
        self.assertEqual(run.unfelt(), [2])

    def test_a_stimulus_can_come_from_a_surfaces_texture(self):
        a, _ = self.references()
        study = HaptiCAD.make_similarity_study(self.doc, self.plate)
        notes = ss.add_stimulus_from(study, a, "Fitted A")
        # only eq. 2's values travel: the period and the force level 1 stands for are the plate's
        (note,) = notes
        self.assertIn(f"is felt with {self.plate.Label}'s period 2.5 mm, full range {FULL_RANGE_N:g} N, "
                      f"not {a.Label}'s period 2 mm, the device's full range", note)
        a.TexturePeriod, a.TextureFullRange = self.plate.TexturePeriod, self.plate.TextureFullRange
        self.assertEqual(ss.stimulus_notes(study, a), [])  # felt alike on both: nothing to say
        added = ss.stimuli(study)[-1]
        self.assertEqual(added["name"], "Fitted A")
        self.assertEqual(added["values"]["TextureDC"], 0.2)
        with self.assertRaisesRegex(ValueError, "has no texture"):
            ss.add_stimulus_from(study, self.plate)
        self.assertEqual(len(ss.stimuli(study)), 10)


if __name__ == "__main__":
    unittest.main()
