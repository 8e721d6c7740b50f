# SPDX-License-Identifier: GPL-3.0-or-later
"""Regenerates the force-trace figures in docs/traces/ through the real pipeline:
a FreeCAD document with tagged faces -> haptic scene -> C++ servo loop with the
simulated probe -> trace -> plot.

    /usr/bin/python3 docs/generate_traces.py --mod build/Mod/HaptiCAD

Each figure is one topic: the seven roughness categories, the three patterns, the
viscous textures, the friction cone's stick-slip, vibration, and a stiffness edit felt
under the hand.
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mod", required=True, help="the HaptiCAD Mod folder (build/Mod/HaptiCAD)")
    parser.add_argument("--out", default=os.path.join(HERE, "traces"))
    parser.add_argument("--only", metavar="FIGURE", help="one figure, by its method's name (e.g. texture_fit)")
    args = parser.parse_args()
    sys.path.insert(0, os.path.abspath(args.mod))
    from hapticad.freecad_env import ensure_freecad

    ensure_freecad()
    os.makedirs(args.out, exist_ok=True)
    figures = Figures(args.out)
    if args.only:
        getattr(figures, args.only)()
    else:
        figures.all()


class Figures:
    def __init__(self, out):
        import FreeCAD as App
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np

        import HaptiCAD
        from hapticad import feel
        from hapticad.document_scene import build_document_scene

        self.App, self.plt, self.np = App, plt, np
        self.HaptiCAD, self.feel, self.build = HaptiCAD, feel, build_document_scene
        self.out = out

    # --- helpers -----------------------------------------------------------------
    def scene(self, size=(100, 100, 20), **surface):
        doc = self.App.newDocument("Traces")
        box = doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = size
        doc.recompute()
        extra = surface.pop("extra", None)
        if extra:
            extra(doc, surface)
        self.HaptiCAD.make_surface(doc, [(box, "Face6")], **surface)
        scene = self.build(doc)
        self.App.closeDocument(doc.Name)
        return scene

    def stroke(self, scene, p0, p1, speed=50.0, depth=1.0, rate=1000.0):
        result = self.feel.run_stroke_in_servo_loop(scene, self.feel.Stroke(p0, p1, speed, depth, rate))
        trace = result.trace
        sliding = self.feel.sliding_mask(result, scene)
        x = self.feel.distance_along_stroke_mm(result)
        return result, trace, sliding, x

    def save(self, fig, name):
        path = os.path.join(self.out, name)
        fig.savefig(path, dpi=100)
        self.plt.close(fig)
        print(f"wrote {path}")

    def all(self):
        self.roughness()
        self.linear()
        self.circular()
        self.curve()
        self.texture()
        self.texture_scale()
        self.texture_fit()
        self.stiffness_study()
        self.similarity_study()
        self.stick_slip()
        self.vibration()
        self.live_edit()

    # --- figures -------------------------------------------------------------------
    def roughness(self):
        np, plt = self.np, self.plt
        fig, axes = plt.subplots(7, 2, figsize=(11, 13), constrained_layout=True,
                                 gridspec_kw={"width_ratios": [1.6, 1]})
        for c in range(1, 8):
            g = [0.1, 0.3, 0.6, 0.9, 1.2, 1.5, 3.0][c - 1]
            scene = self.scene(material="ABS", roughness_category=c, stiffness_n_per_mm=0.8)
            _, trace, sliding, x = self.stroke(scene, (20, 50, 20), (80, 50, 20), speed=20.0, rate=5000.0)
            fn = trace["normal_force_n"][sliding]
            xs = x[sliding]
            left, right = axes[c - 1]
            shown = xs < xs[0] + 6 * max(g, 1.0)
            left.plot(xs[shown], fn[shown], lw=0.9)
            left.set_ylabel(f"cat. {c}\n$F_n$ (N)")
            left.grid(alpha=0.3)
            # spatial spectrum: resampled in space, detrended, Hann window (as seed 001)
            grid_x = np.arange(xs[0], xs[-1], 0.005)
            signal = np.interp(grid_x, xs, fn)
            signal = (signal - signal.mean()) * np.hanning(len(signal))
            spectrum = np.abs(np.fft.rfft(signal)) * 2 / np.hanning(len(signal)).sum()
            freq = np.fft.rfftfreq(len(signal), 0.005)
            right.semilogy(freq, spectrum + 1e-9, lw=0.9)
            right.axvline(1 / g, color="tab:red", ls="--", lw=1, label=f"1 / {g} mm")
            right.set_xlim(0, 12)
            right.set_ylim(1e-6, 1)
            right.legend(loc="upper right", fontsize=8)
            right.grid(alpha=0.3)
        axes[-1][0].set_xlabel("distance along the stroke (mm)")
        axes[-1][1].set_xlabel("spatial frequency (1/mm)")
        axes[0][0].set_title("normal force while sliding, 1 mm deep at 20 mm/s, 5 kHz")
        axes[0][1].set_title("spectrum: the peak sits at 1 / grid size")
        fig.suptitle("Roughness categories of seed 000 Table 2 as grid textures (ABS, 0.8 N/mm)")
        self.save(fig, "roughness_categories.png")

    def linear(self):
        np, plt = self.np, self.plt
        from hapticad import _core

        angles = np.arange(0, 181, 15)
        measured = {}
        for interpolation in ("Linear (seed 000 eq. 3)", "Friction ellipse"):
            scene = self.scene(material="PMMA", static_friction=0.4, dynamic_friction=0.3, pattern="Linear",
                               AcrossFriction=3.0, Interpolation=interpolation, FeelRoughness=False)
            values = []
            for a in angles:
                d = np.array([math.cos(math.radians(a)), math.sin(math.radians(a))]) * 25
                _, trace, sliding, _ = self.stroke(scene, (50 - d[0], 50 - d[1], 20), (50 + d[0], 50 + d[1], 20))
                values.append(np.mean(trace["tangential_force_n"][sliding] / trace["normal_force_n"][sliding]))
            measured[interpolation] = values
        fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
        theta = np.linspace(0, math.pi, 361)
        folded = np.array([_core.fold_angle(t) for t in theta])
        ax.plot(np.degrees(theta), [_core.interpolate_friction(0.3, 0.9, t, _core.AnisotropyInterpolation.LINEAR) for t in folded],
                color="tab:blue", lw=1, label="eq. 3 (model)")
        ax.plot(np.degrees(theta), [_core.interpolate_friction(0.3, 0.9, t, _core.AnisotropyInterpolation.ELLIPSE) for t in folded],
                color="tab:orange", lw=1, label="friction ellipse (model)")
        ax.plot(angles, measured["Linear (seed 000 eq. 3)"], "o", color="tab:blue", label="strokes, eq. 3")
        ax.plot(angles, measured["Friction ellipse"], "s", color="tab:orange", mfc="none", label="strokes, ellipse")
        ax.set_xlabel("stroke direction from the stripes (degrees)")
        ax.set_ylabel("$F_t/F_n$ while sliding")
        ax.set_title("Linear pattern: $\\mu_a$ = 0.3 along the stripes, $\\mu_n$ = 0.9 across")
        ax.legend()
        ax.grid(alpha=0.3)
        self.save(fig, "pattern_linear.png")

    def circular(self):
        np, plt = self.np, self.plt
        scene = self.scene(material="PMMA", static_friction=0.4, dynamic_friction=0.3, pattern="Circular",
                           pattern_center_mm=(50, 50, 20), AcrossFriction=3.0, PatternBlendRadius=2.0,
                           FeelRoughness=False)
        fig, ax = plt.subplots(figsize=(8, 4.5), constrained_layout=True)
        for offset, label in ((0.0, "through the centre (radial: across the circles)"),
                              (10.0, "10 mm beside the centre")):
            _, trace, sliding, x = self.stroke(scene, (20, 50 + offset, 20), (80, 50 + offset, 20), speed=30.0)
            ratio = np.where(sliding, trace["tangential_force_n"] / np.maximum(trace["normal_force_n"], 1e-12), np.nan)
            ax.plot(x - 30, ratio, lw=1.2, label=label)
        ax.axhline(0.6, color="gray", ls=":", lw=1, label="isotropic mean (the centre)")
        ax.set_xlabel("position along the stroke relative to the centre's abscissa (mm)")
        ax.set_ylabel("$F_t/F_n$ while sliding")
        ax.set_title("Circular pattern about (50, 50): $\\mu_a$ 0.3 along circles, $\\mu_n$ 0.9 across; 2 mm blend")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        self.save(fig, "pattern_circular.png")

    def curve(self):
        np, plt = self.np, self.plt
        import Part

        V = self.App.Vector

        def sketch(doc, surface):
            s = doc.addObject("Sketcher::SketchObject", "Guide")
            s.Placement = self.App.Placement(V(0, 0, 20), self.App.Rotation())
            s.addGeometry(Part.BSplineCurve([V(40, 5, 0), V(70, 35, 0), V(30, 65, 0), V(60, 95, 0)]), False)
            doc.recompute()
            surface["PatternCurve"] = (s, [])

        fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), constrained_layout=True,
                                 gridspec_kw={"width_ratios": [1, 1.6]})
        for evaluation, style in (("Exact", "-"), ("Lookup table", "--")):
            scene = self.scene(material="PMMA", static_friction=0.4, dynamic_friction=0.3, pattern="Curve",
                               AcrossFriction=3.0, CurveEvaluation=evaluation, CurveTableSize=16,
                               FeelRoughness=False, extra=sketch)
            result, trace, sliding, x = self.stroke(scene, (50, 10, 20), (50, 90, 20), speed=40.0)
            ratio = np.where(sliding, trace["tangential_force_n"] / np.maximum(trace["normal_force_n"], 1e-12), np.nan)
            axes[1].plot(np.asarray(trace["device_m"])[:, 1] * 1e3, ratio, style, lw=1.2,
                         label=f"{evaluation}{' (16 entries)' if evaluation != 'Exact' else ''}")
        # the curve and the stroke, from above
        doc = self.App.newDocument("Curve")
        s = doc.addObject("Sketcher::SketchObject", "Guide")
        s.addGeometry(Part.BSplineCurve([V(40, 5, 0), V(70, 35, 0), V(30, 65, 0), V(60, 95, 0)]), False)
        doc.recompute()
        pts = s.Shape.Edges[0].discretize(200)
        self.App.closeDocument(doc.Name)
        # the family translates along the pattern's x axis: perpendicular to the chord
        chord = np.array([pts[-1].x - pts[0].x, pts[-1].y - pts[0].y])
        across = np.array([chord[1], -chord[0]]) / np.linalg.norm(chord)
        for shift in range(-60, 61, 10):
            axes[0].plot([p.x + shift * across[0] for p in pts], [p.y + shift * across[1] for p in pts],
                         color="0.6", lw=0.8)
        axes[0].plot([p.x for p in pts], [p.y for p in pts], color="black", lw=2, label="sketch curve")
        axes[0].plot([50, 50], [10, 90], color="tab:red", lw=2, label="stroke")
        axes[0].set_xlim(0, 100)
        axes[0].set_ylim(0, 100)
        axes[0].set_aspect("equal")
        axes[0].legend(fontsize=8, loc="lower right")
        axes[0].set_title("family of parallel copies")
        axes[1].set_xlabel("y along the stroke (mm)")
        axes[1].set_ylabel("$F_t/F_n$ while sliding")
        axes[1].set_title("friction follows the angle between stroke and curve")
        axes[1].legend(fontsize=8)
        axes[1].grid(alpha=0.3)
        self.save(fig, "pattern_curve.png")

    def texture(self):
        np, plt = self.np, self.plt
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True, sharey=True)
        for ax, speed in zip(axes, (50.0, 200.0)):
            for vis in ("-0.2", "+0.0", "+0.2"):
                scene = self.scene(material="Glass", Texture=f"Paper f_DC 0.500 f_vis {vis}", FeelRoughness=False)
                _, trace, sliding, x = self.stroke(scene, (50, 30, 20), (50, 70, 20), speed=speed)
                ax.plot(x[sliding], trace["texture_force_n"][sliding], lw=1.0, label=f"f_vis {vis}")
            ax.set_title(f"{speed:.0f} mm/s across the ridges (period 2.5 mm)")
            ax.set_xlabel("distance along the stroke (mm)")
            ax.grid(alpha=0.3)
        axes[0].set_ylabel("lateral force (N) on a device of 8.9 N full range")
        axes[0].legend(fontsize=8)
        fig.suptitle("Viscous gratings of seed 001 eq. 2, f_DC = 0.5, level 1 = the device's full range "
                     "(8.9 N): viscosity shifts the level with speed")
        self.save(fig, "texture_viscous.png")

    def texture_scale(self):
        np, plt = self.np, self.plt
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True, sharey=True)
        for ax, scale in zip(axes, ("Device force", "Friction level")):
            for depth in (0.5, 2.0):
                scene = self.scene(material="Glass", Texture="Paper f_DC 0.500 f_vis +0.0", FeelRoughness=False,
                                   TextureScale=scale)
                _, trace, sliding, x = self.stroke(scene, (50, 30, 20), (50, 70, 20), speed=80.0, depth=depth)
                normal = trace["normal_force_n"][sliding].mean()
                ax.plot(x[sliding], trace["texture_force_n"][sliding], lw=1.0,
                        label=f"pressed {depth:g} mm (normal force {normal:.2f} N)")
            ax.set_title(f"Level 1 is: {scale}")
            ax.set_xlabel("distance along the stroke (mm), 80 mm/s across the ridges")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
        axes[0].set_ylabel("lateral force (N)")
        fig.suptitle("The same grating (f_DC 0.5) on glass: as a device force (8.9 N full range) it drags the same\n"
                     "however lightly you touch; as a friction level (seed 001's TPad) it scales with the press")
        self.save(fig, "texture_scale.png")

    def texture_fit(self):
        """A grating rendered by the servo loop, stroked at the paper's five speeds, its
        traces fitted back (seed 001 §III): the fit's spectra and lines against speed."""
        import tempfile

        from hapticad import texture_fit
        from hapticad.texture_fit_plot import plot_fit

        truth = dict(TextureDC=0.4, TextureViscosity=0.2, TextureBeta=0.1, TextureAlpha=2.0, TextureFullRange=2.0)
        scene = self.scene(size=(40, 100, 10), material="ABS", FeelRoughness=False, Texture="Custom", **truth)
        with tempfile.TemporaryDirectory() as tmp:
            paths = []
            for speed in texture_fit.PAPER_SPEEDS_MM_S:
                result = self.feel.run_stroke_in_servo_loop(
                    scene, self.feel.Stroke((20, 10, 10), (20, 90, 10), speed, 1.0, 5000.0))
                paths.append(os.path.join(tmp, f"trace_{speed:.0f}.csv"))
                self.feel.write_trace_csv(paths[-1], result, scene)
            report = texture_fit.fit_files(paths, 2.5, lowpass_hz=0)
        fitted = texture_fit.levels(report.fit, 2.0)
        path = os.path.join(self.out, "texture_fit.png")
        plot_fit(path, report, title=(
            "Fitting the rendered grating back (f_DC 0.4, f_vis 0.2, beta_h 0.1, alpha_h 2, 2 N full range): "
            f"fitted {fitted['TextureDC']:.3f}, {fitted['TextureViscosity']:.3f}, {fitted['TextureBeta']:.3f}, "
            f"{fitted['TextureAlpha']:.2f}"))
        print(f"wrote {path}")

    def stiffness_study(self):
        """Seed 000 §3: a toothbrush head on necks of three thicknesses, and a push
        button pressed through its snap and released: force against depth."""
        np, plt = self.np, self.plt
        from hapticad import stiffness_study

        def press(model, depth, **values):
            doc = self.App.newDocument("Study")
            box = doc.addObject("Part::Box", "Head")
            box.Length, box.Width, box.Height = 40, 40, 10
            doc.recompute()
            surface = self.HaptiCAD.make_surface(doc, [(box, "Face6")], material="PP", FeelRoughness=False)
            study = self.HaptiCAD.make_study(doc, surface, model=model, **values)
            label = (f"h = {study.BeamThickness:g} mm: k = {study.BendingStiffness:.2f} N/mm" if model == "Bending beam"
                     else f"F_op {study.OperatingForce:g} N at {study.Pretravel:g} mm, snap {study.SnapRatio:.0%}")
            scene = self.build(doc)
            self.App.closeDocument(doc.Name)
            result = self.feel.run_stroke_in_servo_loop(
                scene, self.feel.Stroke((20, 20, 10), (20.01, 20, 10), 2.0, depth, 1000.0))
            z = (10.0 - np.asarray(result.trace["device_m"])[:, 2] * 1e3)
            return z, result.trace["normal_force_n"], result.trace["time_s"] < result.plan.slide_start_s, label

        fig, (beam, button) = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
        for h in (3.0, 4.0, 5.0):
            z, fn, down, label = press("Bending beam", 2.0, YoungsModulus=1.5, BeamWidth=5, BeamThickness=h,
                                       BeamLength=60)
            beam.plot(z[down], fn[down], lw=1.2, label=label)
        beam.set_title("toothbrush: PP neck 5 x h mm, 60 mm long (k = 3EI/L^3)", fontsize=9)
        z, fn, down, label = press("Push button", 1.5, OperatingForce=0.8, Pretravel=0.4, SnapRatio=0.5,
                                   SnapTravel=0.2, TotalTravel=1.0)
        button.plot(z[down], fn[down], lw=1.2, label="pressing")
        button.plot(z[~down], fn[~down], lw=1.0, ls="--", label="releasing")
        button.set_title(f"push button: {label}, bottoms out at 1 mm (PP's 0.8 N/mm)", fontsize=9)
        for ax in (beam, button):
            ax.set_xlabel("depth pressed (mm)")
            ax.set_ylabel("normal force (N)")
            ax.set_xlim(left=0)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
        fig.suptitle("Stiffness studies through the servo loop (simulated probe, 1 kHz, pressing at 2 mm/s)")
        self.save(fig, "stiffness_study.png")

    def similarity_study(self):
        """Seed 001 §IV: the paper's nine gratings, each held out on one plate by a
        similarity study and stroked through the servo loop at three speeds; and the
        perceptual space of ten simulated participants with eq. 3's vectors."""
        import random

        np, plt = self.np, self.plt
        from hapticad import similarity_study as ss
        from hapticad.similarity_plot import draw_space

        doc = self.App.newDocument("Similarity")
        box = doc.addObject("Part::Box", "Plate")
        box.Length, box.Width, box.Height = 40, 100, 10
        doc.recompute()
        plate = self.HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS", FeelRoughness=False,
                                           TextureScale="Device force", TextureFullRange=2.0)
        study = self.HaptiCAD.make_similarity_study(doc, plate)
        speeds = (50.0, 120.0, 270.0)
        fig, (forces, space) = plt.subplots(1, 2, figsize=(12, 5.2), constrained_layout=True)
        colours = {0.325: "#2f855a", 0.5: "#2b6cb0", 0.675: "#c53030"}
        styles = {-0.2: ":", 0.0: "-", 0.2: "--"}
        for item in ss.stimuli(study):
            ss.present(study, item["values"])
            scene = self.build(doc)
            means = []
            for speed in speeds:
                result, trace, sliding, _ = self.stroke(scene, (20, 10, 10), (20, 90, 10), speed, 1.0)
                means.append(float(np.mean(trace["tangential_force_n"][sliding])))
            v = item["values"]
            forces.plot(speeds, means, "o", color=colours[round(v["TextureDC"], 3)],
                        ls=styles[round(v["TextureViscosity"], 1)], label=item["name"])
        ss.stop_presenting(study)
        forces.set_xlabel("stroke speed (mm/s)")
        forces.set_ylabel("mean resisting force (N), 2 N full range")
        forces.set_title("the nine stimuli held out on one plate, through the servo loop:\n"
                         "f_DC sets the level, f_vis (per 400 mm/s) the slope", fontsize=9)
        forces.legend(fontsize=7, ncol=3, loc="upper left")
        forces.grid(alpha=0.3)
        rng = random.Random(7)
        for p in range(10):
            run = ss.Run(study, f"P{p}", seed=p)
            while not run.done:
                t = run.current
                run.present_each()
                a, b = (run.stimuli[i]["values"] for i in (t.first, t.second))
                d = np.hypot((a["TextureDC"] - b["TextureDC"]) / 0.35,
                             0.5 * (a["TextureViscosity"] - b["TextureViscosity"]) / 0.4)
                run.answer(int(min(7, max(1, round(1 + (1 - d / 1.12 + rng.gauss(0, 0.1)) * 6)))))
            ss.record_run(study, run)
        draw_space(space, ss.analyse(study), "perceptual space of ten simulated participants who weigh\n"
                   "friction twice as much as viscosity (seeded noise): Fig. 7 without references")
        self.App.closeDocument(doc.Name)
        self.save(fig, "similarity_study.png")

    def stick_slip(self):
        np, plt = self.np, self.plt
        from hapticad import _core

        fig, ax = plt.subplots(figsize=(8, 4), constrained_layout=True)
        for model in ("Velocity (seed 000)", "Friction cone (stick-slip)"):
            scene = self.scene(material="Rubber", static_friction=1.0, dynamic_friction=0.6,
                               FrictionModel=model, FeelRoughness=False)
            # slide 20 mm at 10 mm/s, rest 1 s, slide on 20 mm: the plan of a stroke, cut in two
            plan = self.feel.plan_stroke(scene, self.feel.Stroke((30, 50, 20), (70, 50, 20), 10.0, 1.0))
            t, p = list(plan.times_s), list(plan.positions_m)
            middle = 0.5 * (p[3] + p[4])
            half = 0.5 * (t[4] - t[3])
            times = t[:4] + [t[3] + half, t[3] + half + 1.0] + [x + 1.0 for x in t[4:]]
            positions = np.array(p[:4] + [middle, middle] + p[4:])
            probe = _core.simulated_probe_limits()
            device = _core.SimulatedDevice(times, positions, probe)
            limits = _core.RenderLimits()
            limits.max_force_n = probe.max_force_n
            limits.max_stiffness_n_per_m = probe.max_stiffness_n_per_m
            renderer = _core.ForceRenderer(scene.scene, scene.surfaces, limits, scene.contact_options())
            loop = _core.ServoLoop(device, renderer, 1000.0, trace_capacity=int(1000 * (times[-1] + 1)))
            trace = loop.run_for(times[-1])
            start, end = times[3], times[-3]
            slide = (trace["time_s"] > start - 0.05) & (trace["time_s"] < end)
            slide &= (trace["flags"] & _core.FLAG_DEVICE_FAULT) == 0  # a host stall's tick renders nothing
            ax.plot(trace["time_s"][slide] - start,
                    trace["tangential_force_n"][slide] / np.maximum(trace["normal_force_n"][slide], 1e-9),
                    lw=1.2, label=model)
        ax.axvspan(half, half + 1.0, color="gray", alpha=0.12, lw=0, label="at rest")
        ax.axhline(1.0, color="gray", ls=":", lw=1, label="$\\mu_s$")
        ax.axhline(0.6, color="gray", ls="--", lw=1, label="$\\mu_d$")
        ax.set_xlabel("time from the start of the slide (s)")
        ax.set_ylabel("$F_t/F_n$")
        ax.set_title("Sliding at 10 mm/s, a rest, sliding on: the paper's model is smooth;\n"
                     "the friction cone breaks away at $\\mu_s$, sticks at rest, and breaks away again")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        self.save(fig, "friction_stick_slip.png")

    def vibration(self):
        np, plt = self.np, self.plt

        def vibrate(doc, surface):
            self.HaptiCAD.make_vibration(doc, doc.Box, frequency_hz=120.0, amplitude_n=0.3, axis=(0, 0, 1))

        scene = self.scene(material="ABS", FeelRoughness=False, extra=vibrate)
        result, trace, sliding, x = self.stroke(scene, (40, 50, 20), (60, 50, 20), speed=20.0, rate=2000.0)
        fig, ax = plt.subplots(figsize=(8, 3.8), constrained_layout=True)
        window = (trace["time_s"] > result.plan.slide_start_s) & (trace["time_s"] < result.plan.slide_start_s + 0.05)
        t = (trace["time_s"][window] - result.plan.slide_start_s) * 1e3
        ax.plot(t, np.asarray(trace["force_n"])[window, 2], lw=1.2, label="vertical force")
        ax.plot(t, trace["vibration_force_n"][window], lw=1.0, label="vibration part")
        ax.set_xlabel("time (ms)")
        ax.set_ylabel("force (N)")
        ax.set_title("A powered part: 120 Hz, 0.3 N along z, felt while touching it (2 kHz loop)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        self.save(fig, "vibration.png")


    def live_edit(self):
        """A stiffness edit under a pressing hand, through the live session: the steel
        top made soft (0.05 N/mm) and steel again while the simulated hand presses
        2 mm into it. The face's push blends over ContactOptions::edit_ramp_s."""
        import time

        np, plt = self.np, self.plt
        from hapticad import _core, feel_session, preferences

        doc = self.App.newDocument("LiveEdit")
        box = doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 40, 30, 20
        doc.recompute()
        surface = self.HaptiCAD.make_surface(doc, [(box, "Face6")], material="Steel")
        session = feel_session.LiveSession(self.build(doc),
                                           prefs=preferences.Preferences(servo_rate_hz=1000, force_limit_n=3.0))
        session.start(np.array([20, 15, 30]) * 1e-3)
        traces = []
        try:
            time.sleep(0.3)
            session.set_target(np.array([20, 15, 18]) * 1e-3)
            time.sleep(0.6)
            session.drain()
            steel = surface.Stiffness
            for stiffness in (0.05, steel):
                time.sleep(0.1)
                surface.Stiffness = stiffness
                doc.recompute()
                session.update_surfaces(doc)
                time.sleep(0.4)
            traces.append(session.drain())
        finally:
            session.stop()
            self.App.closeDocument(doc.Name)
        trace = np.concatenate(traces)
        t = (trace["time_s"] - trace["time_s"][0]) * 1e3
        fz = trace["force_n"][:, 2]
        blending = (trace["flags"] & _core.FLAG_EDIT_BLENDING) != 0
        fig, (force, step) = plt.subplots(2, 1, figsize=(10, 6), sharex=True, constrained_layout=True,
                                          gridspec_kw={"height_ratios": [2, 1]})
        force.plot(t, fz, lw=1.0, label="force on the hand, z")
        force.fill_between(t, 0, fz.max() * 1.1, where=blending, color="tab:orange", alpha=0.2,
                           label="blending after the edit (0.2 s)")
        force.set_ylabel("F (N)")
        force.set_title("Steel top made soft (0.05 N/mm), then steel again, under a hand pressing 2 mm")
        force.legend(loc="upper right")
        force.grid(alpha=0.3)
        step.plot(t[1:], np.abs(np.diff(fz)) * 1e3, lw=0.8)
        step.set_ylabel("|dF| per tick (mN)")
        step.set_xlabel("t (ms)")
        step.grid(alpha=0.3)
        self.save(fig, "live_edit.png")

if __name__ == "__main__":
    main()
