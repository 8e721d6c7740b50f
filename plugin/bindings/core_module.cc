// SPDX-License-Identifier: GPL-3.0-or-later
// hapticad._core: the one bridge from the C++ core and device layer to Python.
// It holds no logic: it converts arrays and names, and releases the GIL around calls
// that run long (scene builds, servo sessions). Argument names equal the C++ ones.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hapticad/core/analysis/perceptual_space.h"
#include "hapticad/core/analysis/stroke_run.h"
#include "hapticad/core/analysis/texture_fit.h"
#include "hapticad/core/rendering/force_renderer.h"
#include "hapticad/core/rendering/haptic_scene.h"
#include "hapticad/core/surfaces/anisotropy.h"
#include "hapticad/core/surfaces/curve_pattern.h"
#include "hapticad/core/surfaces/force_travel.h"
#include "hapticad/core/surfaces/friction.h"
#include "hapticad/core/surfaces/nurbs_curve.h"
#include "hapticad/core/surfaces/roughness.h"
#include "hapticad/core/surfaces/roughness_texture.h"
#include "hapticad/core/surfaces/stripe_pattern.h"
#include "hapticad/core/surfaces/surface_properties.h"
#include "hapticad/core/surfaces/vibration.h"
#include "hapticad/core/surfaces/viscous_texture.h"
#include "hapticad/devices/device_catalog.h"
#include "hapticad/devices/hid/hid_device.h"
#include "hapticad/devices/servo_loop.h"
#include "hapticad/devices/simulated_device.h"
#include "hapticad/devices/simulated_hand.h"
#include "hapticad/devices/workspace_mapping.h"

namespace py = pybind11;
using namespace hapticad;

namespace {

using RowsD = py::array_t<double, py::array::c_style | py::array::forcecast>;
using RowsI = py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>;

void RequireShape(const py::array& a, py::ssize_t cols, const char* name) {
  if (a.ndim() != 2 || a.shape(1) != cols) {
    throw py::value_error(std::string(name) + " must have shape (n, " + std::to_string(cols) + ")");
  }
}

TriangleSoup MakeSoup(const RowsD& vertices, const RowsI& triangles, const RowsI& cad_faces,
                      const std::optional<RowsD>& corner_normals) {
  RequireShape(vertices, 3, "vertices");
  RequireShape(triangles, 3, "triangles");
  if (cad_faces.ndim() != 1) throw py::value_error("cad_faces must be one-dimensional");
  TriangleSoup soup;
  auto v = vertices.unchecked<2>();
  soup.vertices.resize(v.shape(0));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) soup.vertices[i] = Vec3(v(i, 0), v(i, 1), v(i, 2));
  auto t = triangles.unchecked<2>();
  soup.triangles.resize(t.shape(0));
  for (py::ssize_t i = 0; i < t.shape(0); ++i) soup.triangles[i] = {t(i, 0), t(i, 1), t(i, 2)};
  auto f = cad_faces.unchecked<1>();
  soup.cad_faces.assign(f.data(0), f.data(0) + f.shape(0));
  if (corner_normals) {
    RequireShape(*corner_normals, 9, "corner_normals");
    auto n = corner_normals->unchecked<2>();
    soup.corner_normals.resize(n.shape(0));
    for (py::ssize_t i = 0; i < n.shape(0); ++i) {
      for (int c = 0; c < 3; ++c) {
        soup.corner_normals[i][c] = Vec3(n(i, 3 * c), n(i, 3 * c + 1), n(i, 3 * c + 2));
      }
    }
  }
  return soup;
}

py::object NanToNone(double x) { return std::isnan(x) ? py::none() : py::object(py::float_(x)); }

void DefineFriction(py::module_& m) {
  py::class_<FrictionParams>(m, "FrictionParams")
      .def(py::init<>())
      .def_readwrite("static_coefficient", &FrictionParams::static_coefficient)
      .def_readwrite("dynamic_coefficient", &FrictionParams::dynamic_coefficient)
      .def_readwrite("stick_speed_mps", &FrictionParams::stick_speed_mps)
      .def_readwrite("transition_speed_mps", &FrictionParams::transition_speed_mps)
      .def_readwrite("stribeck_speed_mps", &FrictionParams::stribeck_speed_mps);
  m.def("equivalent_friction", &EquivalentFriction, py::arg("params"), py::arg("speed_mps"));
  m.def("calc_friction_force", &CalcFrictionForce, py::arg("params"), py::arg("normal_force_n"),
        py::arg("v_t_mps"));

  py::enum_<AnisotropyInterpolation>(m, "AnisotropyInterpolation")
      .value("LINEAR", AnisotropyInterpolation::kLinear)
      .value("ELLIPSE", AnisotropyInterpolation::kEllipse);
  m.def("fold_angle", &FoldAngle, py::arg("theta"));
  m.def("interpolate_friction", &InterpolateFriction, py::arg("mu_along"), py::arg("mu_across"),
        py::arg("theta"), py::arg("interpolation"));
  py::class_<AnisotropicFriction>(m, "AnisotropicFriction")
      .def(py::init<>())
      .def_readwrite("across_factor", &AnisotropicFriction::across_factor)
      .def_readwrite("backward_factor", &AnisotropicFriction::backward_factor)
      .def_readwrite("interpolation", &AnisotropicFriction::interpolation);
  py::enum_<FrictionMode>(m, "FrictionMode")
      .value("VELOCITY", FrictionMode::kVelocity)
      .value("CONE", FrictionMode::kCone);
}

void DefinePatterns(py::module_& m) {
  py::class_<SurfaceFrame>(m, "SurfaceFrame")
      .def(py::init<>())
      .def(py::init([](const Vec3& o, const Vec3& e1, const Vec3& e2) {
             return SurfaceFrame{o, e1, e2};
           }),
           py::arg("origin_w"), py::arg("e1_w"), py::arg("e2_w"))
      .def_readwrite("origin_w", &SurfaceFrame::origin_w)
      .def_readwrite("e1_w", &SurfaceFrame::e1_w)
      .def_readwrite("e2_w", &SurfaceFrame::e2_w)
      .def_readwrite("radius_m", &SurfaceFrame::radius_m)
      .def_readwrite("axis_point_w", &SurfaceFrame::axis_point_w)
      .def_readwrite("axis_w", &SurfaceFrame::axis_w);
  py::class_<StripeFrame>(m, "StripeFrame")
      .def_readonly("stripe", &StripeFrame::stripe)
      .def_readonly("weight", &StripeFrame::weight);
  py::class_<LinearPattern>(m, "LinearPattern")
      .def(py::init([](const Vec3& d, double radius, const Vec3& origin, const Vec3& axis_point,
                       const Vec3& axis) {
             return LinearPattern{d, radius, origin, axis_point, axis};
           }),
           py::arg("direction_w"), py::arg("radius_m") = 0.0, py::arg("origin_w") = Vec3::Zero(),
           py::arg("axis_point_w") = Vec3::Zero(), py::arg("axis_w") = Vec3::UnitZ())
      .def_readwrite("direction_w", &LinearPattern::direction_w)
      .def_readwrite("radius_m", &LinearPattern::radius_m)
      .def_readwrite("origin_w", &LinearPattern::origin_w)
      .def_readwrite("axis_point_w", &LinearPattern::axis_point_w)
      .def_readwrite("axis_w", &LinearPattern::axis_w);
  m.def(
      "frame_coordinates",
      [](const SurfaceFrame& frame, const RowsD& points_w) {
        RequireShape(points_w, 3, "points_w");
        const auto p = points_w.unchecked<2>();
        py::array_t<double> out({p.shape(0), static_cast<py::ssize_t>(2)});
        auto o = out.mutable_unchecked<2>();
        for (py::ssize_t i = 0; i < p.shape(0); ++i) {
          const FrameCoordinates c = CalcFrameCoordinates(frame, Vec3(p(i, 0), p(i, 1), p(i, 2)));
          o(i, 0) = c.x;
          o(i, 1) = c.y;
        }
        return out;
      },
      py::arg("frame"), py::arg("points_w"));
  m.def("evaluate_linear", &EvaluateLinear, py::arg("pattern"), py::arg("point_w"),
        py::arg("normal"));
  py::class_<CircularPattern>(m, "CircularPattern")
      .def(py::init([](const Vec3& c, const Vec3& a, double r) {
             return CircularPattern{c, a, r};
           }),
           py::arg("centre_w"), py::arg("axis_w"), py::arg("blend_radius_m"))
      .def_readwrite("centre_w", &CircularPattern::centre_w)
      .def_readwrite("axis_w", &CircularPattern::axis_w)
      .def_readwrite("blend_radius_m", &CircularPattern::blend_radius_m);
  m.def("evaluate_circular", &EvaluateCircular, py::arg("pattern"), py::arg("point_w"),
        py::arg("normal"));

  py::class_<PatternPlane>(m, "PatternPlane")
      .def(py::init([](const Vec3& o, const Vec3& x, const Vec3& y) {
             return PatternPlane{o, x, y};
           }),
           py::arg("origin_w"), py::arg("x_w"), py::arg("y_w"));
  py::enum_<CurvePattern::Evaluation>(m, "CurveEvaluation")
      .value("LOOKUP_TABLE", CurvePattern::Evaluation::kLookupTable)
      .value("EXACT", CurvePattern::Evaluation::kExact);
  py::class_<CurvePattern, std::shared_ptr<CurvePattern>>(m, "CurvePattern")
      .def_static(
          "build",
          [](const PatternPlane& plane, int degree, std::vector<double> knots, const RowsD& poles,
             std::vector<double> weights, int lut_size, CurvePattern::Evaluation evaluation) {
            RequireShape(poles, 2, "poles");
            std::vector<Vec2> p;
            auto a = poles.unchecked<2>();
            for (py::ssize_t i = 0; i < a.shape(0); ++i) p.emplace_back(a(i, 0), a(i, 1));
            return std::make_shared<CurvePattern>(CurvePattern::Build(
                plane, NurbsCurve2(degree, std::move(knots), std::move(p), std::move(weights)),
                lut_size, evaluation));
          },
          py::arg("plane"), py::arg("degree"), py::arg("knots"), py::arg("poles"),
          py::arg("weights"), py::arg("lut_size"), py::arg("evaluation"))
      .def("evaluate", &CurvePattern::Evaluate, py::arg("point_w"), py::arg("normal"))
      .def("lookup_angle", &CurvePattern::LookupAngle, py::arg("y"))
      .def("exact_angle", &CurvePattern::ExactAngle, py::arg("y"))
      .def("member_offset", &CurvePattern::MemberOffset, py::arg("point_w"))
      .def_property_readonly("y_min", &CurvePattern::y_min)
      .def_property_readonly("y_max", &CurvePattern::y_max)
      .def_property_readonly("lut_size", &CurvePattern::lut_size);
}

void DefineTextures(py::module_& m) {
  py::class_<RoughnessCategory>(m, "RoughnessCategory")
      .def_readonly("category", &RoughnessCategory::category)
      .def_property_readonly("ra_min_um",
                             [](const RoughnessCategory& r) { return NanToNone(r.ra_min_um); })
      .def_property_readonly("ra_max_um",
                             [](const RoughnessCategory& r) { return NanToNone(r.ra_max_um); })
      .def_property_readonly("n_grades",
                             [](const RoughnessCategory& r) {
                               std::vector<std::string> grades;
                               for (const char* g : r.n_grades) {
                                 if (g) grades.emplace_back(g);
                               }
                               return grades;
                             })
      .def_readonly("grid_size_mm", &RoughnessCategory::grid_size_mm);
  m.def("roughness_table", [] {
    const auto& t = RoughnessTable();
    return std::vector<RoughnessCategory>(t.begin(), t.end());
  });
  m.def("roughness_category", &GetRoughnessCategory, py::arg("category"),
        py::return_value_policy::copy);
  py::class_<RoughnessGrid>(m, "RoughnessGrid")
      .def(py::init<>())
      .def_readwrite("frame", &RoughnessGrid::frame)
      .def_readwrite("spacing_m", &RoughnessGrid::spacing_m)
      .def_readwrite("amplitude_m", &RoughnessGrid::amplitude_m)
      .def_readwrite("friction_modulation", &RoughnessGrid::friction_modulation);
  m.attr("DEFAULT_ROUGHNESS_AMPLITUDE_RATIO") = kDefaultRoughnessAmplitudeRatio;
  m.def("make_roughness_grid", &MakeRoughnessGrid, py::arg("category"), py::arg("frame"),
        py::arg("amplitude_ratio") = kDefaultRoughnessAmplitudeRatio,
        py::arg("friction_modulation") = 0.15);

  py::class_<ViscousTextureParams>(m, "ViscousTextureParams")
      .def(py::init<>())
      .def_readwrite("f_dc", &ViscousTextureParams::f_dc)
      .def_readwrite("f_vis", &ViscousTextureParams::f_vis)
      .def_readwrite("beta_h", &ViscousTextureParams::beta_h)
      .def_readwrite("beta_vis", &ViscousTextureParams::beta_vis)
      .def_readwrite("alpha_h", &ViscousTextureParams::alpha_h)
      .def_readwrite("alpha_vis", &ViscousTextureParams::alpha_vis)
      .def_readwrite("period_m", &ViscousTextureParams::period_m);
  m.attr("VISCOUS_SPEED_UNIT_MPS") = kViscousSpeedUnitMps;
  m.attr("VISCOUS_HARMONICS") = kViscousHarmonics;
  m.attr("PAPER_DC_LEVELS") = kPaperDcLevels;
  m.attr("PAPER_VISCOSITIES") = kPaperViscosities;
  m.def("paper_preset", &PaperPreset, py::arg("dc"), py::arg("vis"));
  m.def("viscous_texture_level", &ViscousTextureLevel, py::arg("params"), py::arg("x_m"),
        py::arg("speed_mps"));
  py::enum_<TextureScale>(m, "TextureScale")
      .value("DEVICE_FORCE", TextureScale::kDeviceForce)
      .value("FRICTION_LEVEL", TextureScale::kFrictionLevel);
  py::class_<ViscousGrating>(m, "ViscousGrating")
      .def(py::init([](const ViscousTextureParams& p, const SurfaceFrame& f) {
             return ViscousGrating{p, f};
           }),
           py::arg("params"), py::arg("frame"))
      .def_readwrite("params", &ViscousGrating::params)
      .def_readwrite("frame", &ViscousGrating::frame)
      .def_readwrite("full_range_n", &ViscousGrating::full_range_n)
      .def_readwrite("scale", &ViscousGrating::scale);

  py::class_<Vibration>(m, "Vibration")
      .def(py::init([](double f, double a, const Vec3& axis, bool powered) {
             return Vibration{f, a, axis, powered};
           }),
           py::arg("frequency_hz"), py::arg("amplitude_n"), py::arg("axis_w"), py::arg("powered"))
      .def_readwrite("frequency_hz", &Vibration::frequency_hz)
      .def_readwrite("amplitude_n", &Vibration::amplitude_n)
      .def_readwrite("axis_w", &Vibration::axis_w)
      .def_readwrite("powered", &Vibration::powered);
}

void DefineForceTravel(py::module_& m) {
  py::class_<ForceTravel>(m, "ForceTravel")
      .def(py::init<>())
      .def_readonly("points", &ForceTravel::points)
      .def_property_readonly("travel_m",
                             [](const ForceTravel& l) {
                               return std::vector<double>(l.travel_m.begin(),
                                                          l.travel_m.begin() + l.points);
                             })
      .def_property_readonly("force_n",
                             [](const ForceTravel& l) {
                               return std::vector<double>(l.force_n.begin(),
                                                          l.force_n.begin() + l.points);
                             })
      .def("force", &ForceTravel::Force, py::arg("x_m"))
      .def(
          "force_clamped",
          [](const ForceTravel& l, double x_m, double max_slope) {
            return l.ForceClamped(x_m, max_slope, nullptr);
          },
          py::arg("x_m"), py::arg("max_slope"))
      .def_readwrite("ends_on_stop", &ForceTravel::ends_on_stop)
      .def("max_slope", &ForceTravel::MaxSlope)
      .def("stretch_slope", &ForceTravel::StretchSlope);
  m.def("validate_force_travel", &ValidateForceTravel, py::arg("law"));
  m.def("make_linear_force_travel", &MakeLinearForceTravel, py::arg("stiffness_n_per_m"));
  m.def("cantilever_stiffness", &CantileverStiffness, py::arg("youngs_modulus_pa"),
        py::arg("width_m"), py::arg("thickness_m"), py::arg("length_m"));
  m.def("series_stiffness", &SeriesStiffness, py::arg("a_n_per_m"), py::arg("b_n_per_m"));
  py::class_<PushButtonParams>(m, "PushButtonParams")
      .def(py::init<>())
      .def_readwrite("operating_force_n", &PushButtonParams::operating_force_n)
      .def_readwrite("pretravel_m", &PushButtonParams::pretravel_m)
      .def_readwrite("snap_ratio", &PushButtonParams::snap_ratio)
      .def_readwrite("snap_travel_m", &PushButtonParams::snap_travel_m)
      .def_readwrite("total_travel_m", &PushButtonParams::total_travel_m)
      .def_readwrite("bottom_stiffness_n_per_m", &PushButtonParams::bottom_stiffness_n_per_m);
  m.def("make_push_button", &MakePushButton, py::arg("params"));
}

void DefineSurfaces(py::module_& m) {
  py::class_<SurfaceProperties>(m, "SurfaceProperties")
      .def(py::init<>())
      .def_readwrite("friction", &SurfaceProperties::friction)
      .def_readwrite("stiffness_n_per_m", &SurfaceProperties::stiffness_n_per_m)
      .def_readwrite("damping_n_s_per_m", &SurfaceProperties::damping_n_s_per_m)
      .def_readwrite("friction_mode", &SurfaceProperties::friction_mode)
      .def_readwrite("anisotropy", &SurfaceProperties::anisotropy)
      .def_readwrite("roughness", &SurfaceProperties::roughness)
      .def_readwrite("texture", &SurfaceProperties::texture)
      .def_readwrite("vibration", &SurfaceProperties::vibration)
      .def_readwrite("force_travel", &SurfaceProperties::force_travel)
      // the pattern is one of None, LinearPattern, CircularPattern, CurvePattern
      .def_property(
          "pattern",
          [](const SurfaceProperties& s) -> py::object {
            switch (s.pattern.index()) {
              case 1:
                return py::cast(std::get<LinearPattern>(s.pattern));
              case 2:
                return py::cast(std::get<CircularPattern>(s.pattern));
              case 3:
                return py::cast(std::const_pointer_cast<CurvePattern>(
                    std::get<std::shared_ptr<const CurvePattern>>(s.pattern)));
              default:
                return py::none();
            }
          },
          [](SurfaceProperties& s, const py::object& p) {
            if (p.is_none()) {
              s.pattern = std::monostate{};
            } else if (py::isinstance<LinearPattern>(p)) {
              s.pattern = p.cast<LinearPattern>();
            } else if (py::isinstance<CircularPattern>(p)) {
              s.pattern = p.cast<CircularPattern>();
            } else if (py::isinstance<CurvePattern>(p)) {
              s.pattern =
                  std::shared_ptr<const CurvePattern>(p.cast<std::shared_ptr<CurvePattern>>());
            } else {
              throw py::type_error(
                  "pattern must be None, LinearPattern, CircularPattern or CurvePattern");
            }
          });
  m.attr("UNTAGGED_SURFACE") = kUntaggedSurface;
  m.def("validate_surface_properties", &ValidateSurfaceProperties, py::arg("surface"));
  py::class_<SurfaceTable, std::shared_ptr<SurfaceTable>>(m, "SurfaceTable")
      .def(py::init<std::vector<SurfaceProperties>, std::vector<Vibration>>(), py::arg("by_face"),
           py::arg("vibrations") = std::vector<Vibration>{})
      .def("surface", &SurfaceTable::surface, py::arg("face"), py::return_value_policy::copy)
      .def("effects", &SurfaceTable::effects, py::arg("face"))
      .def("__len__", &SurfaceTable::size);
  m.attr("EFFECT_PATTERN") = static_cast<std::uint32_t>(kEffectPattern);
  m.attr("EFFECT_ROUGHNESS") = static_cast<std::uint32_t>(kEffectRoughness);
  m.attr("EFFECT_TEXTURE") = static_cast<std::uint32_t>(kEffectTexture);
  m.attr("EFFECT_VIBRATION") = static_cast<std::uint32_t>(kEffectVibration);
  m.attr("EFFECT_CONE") = static_cast<std::uint32_t>(kEffectCone);
  m.attr("EFFECT_FORCE_TRAVEL") = static_cast<std::uint32_t>(kEffectForceTravel);
}

void DefineScene(py::module_& m) {
  py::class_<SurfaceSample>(m, "SurfaceSample")
      .def_readonly("point_w", &SurfaceSample::point_w)
      .def_readonly("normal_w", &SurfaceSample::normal_w)
      .def_readonly("triangle", &SurfaceSample::triangle)
      .def_readonly("cad_face", &SurfaceSample::cad_face)
      .def_readonly("distance_m", &SurfaceSample::distance_m);

  py::class_<RepairReport>(m, "RepairReport")
      .def_readonly("input_triangles", &RepairReport::input_triangles)
      .def_readonly("output_triangles", &RepairReport::output_triangles)
      .def_readonly("removed_nonfinite", &RepairReport::removed_nonfinite)
      .def_readonly("merged_vertices", &RepairReport::merged_vertices)
      .def_readonly("welded_vertices", &RepairReport::welded_vertices)
      .def_readonly("removed_degenerate", &RepairReport::removed_degenerate)
      .def_readonly("collapsed_needles", &RepairReport::collapsed_needles)
      .def_readonly("split_caps", &RepairReport::split_caps)
      .def_readonly("removed_duplicates", &RepairReport::removed_duplicates)
      .def_readonly("reoriented", &RepairReport::reoriented)
      .def_readonly("non_manifold_edges", &RepairReport::non_manifold_edges)
      .def_readonly("non_manifold_vertices", &RepairReport::non_manifold_vertices)
      .def_readonly("boundary_edges", &RepairReport::boundary_edges)
      .def_property_readonly("watertight", &RepairReport::watertight)
      .def("describe", &RepairReport::Describe);

  py::class_<HapticScene, std::shared_ptr<HapticScene>>(m, "HapticScene")
      .def_static(
          "build",
          [](const RowsD& vertices, const RowsI& triangles, const RowsI& cad_faces,
             double metres_per_unit, const std::optional<RowsD>& corner_normals, bool repair,
             double refine_edge) {
            TriangleSoup soup = MakeSoup(vertices, triangles, cad_faces, corner_normals);
            SceneOptions options;
            options.repair = repair;
            options.refine_edge = refine_edge;
            py::gil_scoped_release release;
            return std::const_pointer_cast<HapticScene>(
                HapticScene::Build(soup, metres_per_unit, options));
          },
          py::arg("vertices"), py::arg("triangles"), py::arg("cad_faces"),
          py::arg("metres_per_unit"), py::arg("corner_normals") = py::none(),
          py::arg("repair") = true, py::arg("refine_edge") = 0.0)
      .def_property_readonly("repair_report", &HapticScene::repair_report)
      .def_property_readonly("origin_w", &HapticScene::origin_w)
      .def_property_readonly("size_m", &HapticScene::size_m)
      .def_property_readonly("metres_per_unit", &HapticScene::metres_per_unit)
      .def_property_readonly("num_triangles",
                             [](const HapticScene& s) { return s.mesh().num_triangles(); })
      .def_property_readonly("num_cad_faces",
                             [](const HapticScene& s) { return s.mesh().num_cad_faces(); })
      .def("calc_memory_bytes", &HapticScene::CalcMemoryBytes)
      .def("calc_closest_point", &HapticScene::CalcClosestPoint, py::arg("p_w"));
}

// Vec3 from a 3-sequence or array, refusing other shapes with a clear message.
Vec3 ToVec3(const py::object& p, const char* name) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(p);
  if (!a || a.ndim() != 1 || a.shape(0) != 3) {
    throw py::value_error(std::string(name) + " must be three numbers (x, y, z)");
  }
  return Vec3(a.at(0), a.at(1), a.at(2));
}

ScriptedPath ToPath(std::vector<double> times_s, const RowsD& positions) {
  RequireShape(positions, 3, "positions");
  ScriptedPath path;
  path.times_s = std::move(times_s);
  auto p = positions.unchecked<2>();
  for (py::ssize_t i = 0; i < p.shape(0); ++i)
    path.positions.emplace_back(p(i, 0), p(i, 1), p(i, 2));
  return path;
}

py::array_t<TraceSample> ToArray(const std::vector<TraceSample>& samples) {
  py::array_t<TraceSample> out(static_cast<py::ssize_t>(samples.size()));
  std::copy(samples.begin(), samples.end(), out.mutable_data());
  return out;
}

py::dict LimitsDict(const DeviceLimits& l) {
  py::dict d;
  d["max_force_n"] = l.max_force_n;
  d["continuous_force_n"] = l.continuous_force_n;
  d["max_stiffness_n_per_m"] = l.max_stiffness_n_per_m;
  d["max_damping_n_s_per_m"] = l.max_damping_n_s_per_m;
  d["workspace_min_d"] =
      std::vector<double>{l.workspace_min_d.x(), l.workspace_min_d.y(), l.workspace_min_d.z()};
  d["workspace_max_d"] =
      std::vector<double>{l.workspace_max_d.x(), l.workspace_max_d.y(), l.workspace_max_d.z()};
  d["position_resolution_m"] = l.position_resolution_m;
  return d;
}

py::object NoneIfEmpty(const std::string& s) {
  return s.empty() ? py::none() : py::object(py::str(s));
}

void DefineDeviceTypes(py::module_& m) {
  PYBIND11_NUMPY_DTYPE(TraceSample, time_s, device_m, velocity_mps, proxy_m, force_n,
                       normal_force_n, tangential_force_n, friction_force_n, texture_force_n,
                       vibration_force_n, cad_face, flags, tick_us, handle_d_m, period_us, buttons,
                       reserved);
  // a DeviceError is a RuntimeError to Python (the CLI reports those with status 1)
  py::register_exception<DeviceError>(m, "DeviceError", PyExc_RuntimeError);

  py::class_<DeviceLimits>(m, "DeviceLimits")
      .def(py::init<>())
      .def_readwrite("max_force_n", &DeviceLimits::max_force_n)
      .def_readwrite("continuous_force_n", &DeviceLimits::continuous_force_n)
      .def_readwrite("max_stiffness_n_per_m", &DeviceLimits::max_stiffness_n_per_m)
      .def_readwrite("max_damping_n_s_per_m", &DeviceLimits::max_damping_n_s_per_m)
      .def_readwrite("workspace_min_d", &DeviceLimits::workspace_min_d)
      .def_readwrite("workspace_max_d", &DeviceLimits::workspace_max_d)
      .def_readwrite("position_resolution_m", &DeviceLimits::position_resolution_m);
  m.def("validate_device_limits", &ValidateDeviceLimits, py::arg("limits"));
  m.def("simulated_probe_limits", &SimulatedProbeLimits);
  m.def("simulated_hand_limits", &SimulatedHandLimits);
  py::class_<DeviceInfo>(m, "DeviceInfo")
      .def_readonly("kind", &DeviceInfo::kind)
      .def_readonly("name", &DeviceInfo::name)
      .def_readonly("path", &DeviceInfo::path)
      .def_readonly("limits", &DeviceInfo::limits);

  py::class_<WorkspaceMapping>(m, "WorkspaceMapping")
      .def(py::init<>())
      .def_readwrite("scale", &WorkspaceMapping::scale)
      .def_readwrite("rotation_wd", &WorkspaceMapping::rotation_wd)
      .def_readwrite("offset_w", &WorkspaceMapping::offset_w)
      .def("device_to_world", &WorkspaceMapping::DeviceToWorld, py::arg("p_d"))
      .def("world_to_device", &WorkspaceMapping::WorldToDevice, py::arg("p_w"))
      .def("force_to_device", &WorkspaceMapping::ForceToDevice, py::arg("f_w"));
  m.def("validate_workspace_mapping", &ValidateWorkspaceMapping, py::arg("mapping"));
  m.def("render_limits_for", &RenderLimitsFor, py::arg("limits"), py::arg("mapping"));
  m.def("fit_workspace", &FitWorkspace, py::arg("limits"), py::arg("world_min_w"),
        py::arg("world_max_w"), py::arg("min_scale") = 1.0);

  py::class_<SafetyConfig>(m, "SafetyConfig")
      .def(py::init<>())
      .def_readwrite("ramp_s", &SafetyConfig::ramp_s)
      .def_readwrite("watchdog_s", &SafetyConfig::watchdog_s)
      .def_readwrite("stale_after_s", &SafetyConfig::stale_after_s)
      .def_readwrite("fault_timeout_s", &SafetyConfig::fault_timeout_s)
      .def_readwrite("workspace_margin", &SafetyConfig::workspace_margin)
      .def_readwrite("max_speed_mps", &SafetyConfig::max_speed_mps)
      .def_readwrite("thermal_time_constant_s", &SafetyConfig::thermal_time_constant_s);
  m.def("min_servo_rate_hz", &MinServoRateHz, py::arg("safety") = SafetyConfig{},
        "The slowest servo rate the loop accepts with these safety settings (400 Hz with "
        "the defaults: its period at most half the watchdog and the stale-data limit).");

  py::class_<HandModel>(m, "HandModel")
      .def(py::init<>())
      .def_readwrite("mass_kg", &HandModel::mass_kg)
      .def_readwrite("damping_n_s_per_m", &HandModel::damping_n_s_per_m)
      .def_readwrite("grip_stiffness_n_per_m", &HandModel::grip_stiffness_n_per_m)
      .def_readwrite("grip_damping_n_s_per_m", &HandModel::grip_damping_n_s_per_m)
      .def_readwrite("max_grip_force_n", &HandModel::max_grip_force_n)
      .def_readwrite("latency_s", &HandModel::latency_s)
      .def_readwrite("velocity_cutoff_hz", &HandModel::velocity_cutoff_hz)
      .def_readwrite("watchdog_s", &HandModel::watchdog_s)
      .def_readwrite("step_s", &HandModel::step_s);
  py::class_<HandState>(m, "HandState")
      .def_readonly("time_s", &HandState::time_s)
      .def_readonly("position_d", &HandState::position_d)
      .def_readonly("velocity_d", &HandState::velocity_d)
      .def_readonly("target_d", &HandState::target_d)
      .def_readonly("force_d", &HandState::force_d);

  py::enum_<SessionEnd>(m, "SessionEnd")
      .value("NOT_STARTED", SessionEnd::kNotStarted)
      .value("RUNNING", SessionEnd::kRunning)
      .value("STOPPED", SessionEnd::kStopped)
      .value("FINISHED", SessionEnd::kFinished)
      .value("UNPLUGGED", SessionEnd::kUnplugged)
      .value("DEVICE_LOST", SessionEnd::kDeviceLost);
  py::class_<FaultCounts>(m, "FaultCounts")
      .def_readonly("no_data", &FaultCounts::no_data)
      .def_readonly("stale", &FaultCounts::stale)
      .def_readonly("out_of_range", &FaultCounts::out_of_range)
      .def_readonly("non_finite", &FaultCounts::non_finite)
      .def_readonly("reported", &FaultCounts::reported)
      .def_readonly("watchdog", &FaultCounts::watchdog)
      .def_readonly("unplugged", &FaultCounts::unplugged)
      .def_readonly("renderer", &FaultCounts::renderer)
      .def_readonly("zero_force_ticks", &FaultCounts::zero_force_ticks)
      .def_readonly("clamped", &FaultCounts::clamped)
      .def_readonly("thermal_limited", &FaultCounts::thermal_limited);
  py::class_<ServoStats>(m, "ServoStats")
      .def_readonly("ticks", &ServoStats::ticks)
      .def_readonly("overruns", &ServoStats::overruns)
      .def_readonly("skipped_ticks", &ServoStats::skipped_ticks)
      .def_readonly("trace_dropped", &ServoStats::trace_dropped)
      .def_readonly("elapsed_s", &ServoStats::elapsed_s)
      .def_readonly("wall_s", &ServoStats::wall_s)
      .def_readonly("achieved_rate_hz", &ServoStats::achieved_rate_hz)
      .def_readonly("period_jitter_p50_us", &ServoStats::period_jitter_p50_us)
      .def_readonly("period_jitter_p99_us", &ServoStats::period_jitter_p99_us)
      .def_readonly("period_jitter_max_us", &ServoStats::period_jitter_max_us)
      .def_readonly("wake_latency_p50_us", &ServoStats::wake_latency_p50_us)
      .def_readonly("wake_latency_p99_us", &ServoStats::wake_latency_p99_us)
      .def_readonly("wake_latency_max_us", &ServoStats::wake_latency_max_us)
      .def_readonly("tick_p50_us", &ServoStats::tick_p50_us)
      .def_readonly("tick_p99_us", &ServoStats::tick_p99_us)
      .def_readonly("tick_max_us", &ServoStats::tick_max_us)
      .def_readonly("faults", &ServoStats::faults)
      .def_readonly("realtime", &ServoStats::realtime);

  py::class_<RenderLimits>(m, "RenderLimits")
      .def(py::init<>())
      .def_readwrite("max_force_n", &RenderLimits::max_force_n)
      .def_readwrite("max_stiffness_n_per_m", &RenderLimits::max_stiffness_n_per_m)
      .def_readwrite("max_damping_n_s_per_m", &RenderLimits::max_damping_n_s_per_m)
      .def_readwrite("workspace_scale", &RenderLimits::workspace_scale);
  m.attr("FLAG_CONTACT") = static_cast<std::uint32_t>(kContact);
  m.attr("FLAG_FORCE_CLAMPED") = static_cast<std::uint32_t>(kForceClamped);
  m.attr("FLAG_STIFFNESS_CLAMPED") = static_cast<std::uint32_t>(kStiffnessClamped);
  m.attr("FLAG_INPUT_FAULT") = static_cast<std::uint32_t>(kInputFault);
  m.attr("FLAG_STICKING") = static_cast<std::uint32_t>(kSticking);
  m.attr("FLAG_DAMPING_CLAMPED") = static_cast<std::uint32_t>(kDampingClamped);
  m.attr("FLAG_EDIT_BLENDING") = static_cast<std::uint32_t>(kEditBlending);
  m.attr("FLAG_DEVICE_FAULT") = kDeviceFault;
  m.attr("FLAG_FAULT_NO_DATA") = kFaultNoData;
  m.attr("FLAG_FAULT_STALE") = kFaultStale;
  m.attr("FLAG_FAULT_OUT_OF_RANGE") = kFaultOutOfRange;
  m.attr("FLAG_FAULT_NON_FINITE") = kFaultNonFinite;
  m.attr("FLAG_FAULT_REPORTED") = kFaultReported;
  m.attr("FLAG_FAULT_WATCHDOG") = kFaultWatchdog;
  m.attr("FLAG_FAULT_UNPLUGGED") = kFaultUnplugged;
  m.attr("FLAG_FAULT_RENDERER") = kFaultRenderer;
  m.attr("FLAG_RAMPING") = kRamping;
  m.attr("FLAG_SAFETY_CLAMPED") = kSafetyClamped;
  m.attr("FLAG_THERMAL_LIMITED") = kThermalLimited;
  m.attr("FLAG_CLUTCHED") = kClutched;
}

void DefineDevices(py::module_& m) {
  py::class_<Device>(m, "Device")
      .def_property_readonly("info", &Device::info)
      .def("describe_fault", &Device::DescribeFault);
  py::class_<SimulatedDevice, Device>(m, "SimulatedDevice")
      .def(py::init([](std::vector<double> times_s, const RowsD& positions_w, DeviceLimits limits) {
             return std::make_unique<SimulatedDevice>(ToPath(std::move(times_s), positions_w),
                                                      limits);
           }),
           py::arg("times_s"), py::arg("positions_w"), py::arg("limits"))
      .def_property_readonly("duration_s",
                             [](const SimulatedDevice& d) { return d.path().duration_s(); })
      .def_property_readonly("last_force_d", &SimulatedDevice::last_force_d);
  py::class_<SimulatedHand, Device>(m, "SimulatedHand")
      .def(py::init<DeviceLimits, HandModel>(), py::arg("limits") = SimulatedHandLimits(),
           py::arg("model") = HandModel{})
      .def(
          "set_target",
          [](SimulatedHand& h, const py::object& p_w) { h.SetTarget(ToVec3(p_w, "target")); },
          py::arg("p_w"))
      .def(
          "follow_path",
          [](SimulatedHand& h, std::vector<double> times_s, const RowsD& positions_w) {
            h.FollowPath(ToPath(std::move(times_s), positions_w));
          },
          py::arg("times_s"), py::arg("positions_w"))
      .def("follow_target", &SimulatedHand::FollowTarget)
      .def_property_readonly("following_path", &SimulatedHand::following_path)
      .def_property_readonly("in_session", &SimulatedHand::in_session)
      .def_property_readonly("true_state", &SimulatedHand::true_state)
      .def_property_readonly("model", &SimulatedHand::model);

  py::class_<HidLinkStats>(m, "HidLinkStats")
      .def_readonly("reports_read", &HidLinkStats::reports_read)
      .def_readonly("reports_used", &HidLinkStats::reports_used)
      .def_readonly("malformed", &HidLinkStats::malformed)
      .def_readonly("not_newer", &HidLinkStats::not_newer)
      .def_readonly("dropped", &HidLinkStats::dropped)
      .def_readonly("out_of_range", &HidLinkStats::out_of_range)
      .def_readonly("device_faults", &HidLinkStats::device_faults)
      .def_readonly("watchdog_reports", &HidLinkStats::watchdog_reports)
      .def_readonly("writes", &HidLinkStats::writes)
      .def_readonly("writes_failed", &HidLinkStats::writes_failed)
      .def_readonly("round_trip_last_us", &HidLinkStats::round_trip_last_us)
      .def_readonly("round_trip_p50_us", &HidLinkStats::round_trip_p50_us)
      .def_readonly("round_trip_p99_us", &HidLinkStats::round_trip_p99_us)
      .def_readonly("round_trip_count", &HidLinkStats::round_trip_count);
  py::class_<HidDevice, Device>(m, "HidDevice")
      .def_static("open", &HidDevice::Open, py::arg("path"), py::arg("watchdog_ms") = 5,
                  py::call_guard<py::gil_scoped_release>())
      .def("calc_link_stats", &HidDevice::CalcLinkStats,
           "The link statistics so far (scans the round-trip histogram).")
      .def_property_readonly("unplugged", &HidDevice::unplugged);
  // what `hapticad devices --json` prints: kind, name, path, limits (None when the
  // device could not be read), protocol (HID: the versions it speaks), error
  m.def("list_devices", [] {
    std::vector<DeviceListing> listings;
    {
      py::gil_scoped_release release;
      listings = ListDevices();
    }
    py::list out;
    for (const DeviceListing& l : listings) {
      py::dict d;
      d["kind"] = l.info.kind;
      d["name"] = l.info.name;
      d["path"] = l.info.path;
      d["limits"] = l.has_limits ? py::object(LimitsDict(l.info.limits)) : py::none();
      d["protocol"] = NoneIfEmpty(l.protocol);
      d["error"] = NoneIfEmpty(l.error);
      out.append(d);
    }
    return out;
  });
  m.def("open_device", &OpenDevice, py::arg("path"), py::call_guard<py::gil_scoped_release>());

  py::class_<ContactOptions>(m, "ContactOptions")
      .def(py::init<>())
      .def_readwrite("proxy_radius_m", &ContactOptions::proxy_radius_m)
      .def_readwrite("force_shading", &ContactOptions::force_shading)
      .def_readwrite("edit_ramp_s", &ContactOptions::edit_ramp_s);
  py::class_<ForceRenderer, std::shared_ptr<ForceRenderer>>(m, "ForceRenderer")
      .def(py::init([](std::shared_ptr<HapticScene> scene, std::shared_ptr<SurfaceTable> surfaces,
                       RenderLimits limits, ContactOptions options) {
             return std::make_shared<ForceRenderer>(scene, surfaces, limits, options);
           }),
           py::arg("scene"), py::arg("surfaces"), py::arg("limits"),
           py::arg("options") = ContactOptions{})
      .def("set_surfaces", &ForceRenderer::SetSurfaces, py::arg("surfaces"),
           "The surface properties from the next tick on; the scene is not rebuilt.");

  py::class_<ServoLoop>(m, "ServoLoop")
      .def(py::init([](Device& device, std::shared_ptr<ForceRenderer> renderer, double rate_hz,
                       std::size_t trace_capacity, int realtime_priority, int clutch_button,
                       SafetyConfig safety) {
             return std::make_unique<ServoLoop>(
                 device, std::move(renderer),
                 ServoConfig{rate_hz, trace_capacity, realtime_priority, clutch_button, safety});
           }),
           py::arg("device"), py::arg("renderer"), py::arg("rate_hz") = 1000.0,
           py::arg("trace_capacity") = std::size_t{1} << 16, py::arg("realtime_priority") = 70,
           py::arg("clutch_button") = -1, py::arg("safety") = SafetyConfig{},
           py::keep_alive<1, 2>())
      .def("start", &ServoLoop::Start, py::call_guard<py::gil_scoped_release>())
      .def("stop", &ServoLoop::Stop, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("running", &ServoLoop::running)
      .def_property_readonly("session_end", &ServoLoop::session_end)
      .def_property_readonly("fault_message", &ServoLoop::fault_message)
      .def_property_readonly("realtime_report", &ServoLoop::realtime_report)
      .def("calc_stats", &ServoLoop::CalcStats,
           "The statistics so far (scans the latency histograms); ticks alone: .ticks.")
      .def_property_readonly("ticks", &ServoLoop::ticks)
      .def("drain_trace",
           [](ServoLoop& loop) {
             std::vector<TraceSample> samples;
             {
               py::gil_scoped_release release;
               loop.DrainTrace(&samples);
             }
             return ToArray(samples);
           })
      .def("latest",
           [](ServoLoop& loop) {
             const py::array_t<TraceSample> one = ToArray({loop.latest()});
             return py::object(one[py::int_(0)]);
           })
      .def("set_renderer", &ServoLoop::SetRenderer, py::arg("renderer"),
           py::call_guard<py::gil_scoped_release>())
      .def("release_replaced_renderers", &ServoLoop::ReleaseReplacedRenderers,
           "Frees the renderers the servo thread has moved past; how many are kept.")
      .def("set_mapping", &ServoLoop::SetMapping, py::arg("mapping"))
      .def_property_readonly("mapping", &ServoLoop::mapping)
      .def("set_clutch", &ServoLoop::SetClutch, py::arg("held"))
      .def(
          "run_for",
          [](ServoLoop& loop, double duration_s) {
            std::vector<TraceSample> samples;
            {
              py::gil_scoped_release release;
              samples = loop.RunFor(duration_s);
            }
            return ToArray(samples);
          },
          py::arg("duration_s"));
}

void DefineAnalysis(py::module_& m) {
  m.def(
      "run_stroke",
      [](ForceRenderer& renderer, const RowsD& positions_w, const RowsD& velocities_w,
         const std::vector<double>& times_s) {
        RequireShape(positions_w, 3, "positions_w");
        RequireShape(velocities_w, 3, "velocities_w");
        const auto p = positions_w.unchecked<2>();
        const auto v = velocities_w.unchecked<2>();
        if (v.shape(0) != p.shape(0) || static_cast<py::ssize_t>(times_s.size()) != p.shape(0)) {
          throw py::value_error("run_stroke: positions, velocities and times differ in length");
        }
        std::vector<RenderInput> inputs(static_cast<std::size_t>(p.shape(0)));
        for (py::ssize_t i = 0; i < p.shape(0); ++i) {
          inputs[i].position_w = Vec3(p(i, 0), p(i, 1), p(i, 2));
          inputs[i].velocity_w = Vec3(v(i, 0), v(i, 1), v(i, 2));
          inputs[i].time_s = times_s[i];
        }
        StrokeRun run;
        {
          py::gil_scoped_release release;
          run = RunStroke(renderer, inputs);
        }
        const auto n = static_cast<py::ssize_t>(inputs.size());
        py::array_t<double> force({n, py::ssize_t{3}}), proxy({n, py::ssize_t{3}});
        py::array_t<std::uint32_t> flags(n);
        py::array_t<std::int32_t> face(n), constraints(n);
        py::array_t<double> tick_us(n);
        for (py::ssize_t i = 0; i < n; ++i) {
          const RenderOutput& o = run.outputs[i];
          for (int c = 0; c < 3; ++c) {
            force.mutable_at(i, c) = o.force_w[c];
            proxy.mutable_at(i, c) = o.proxy_w[c];
          }
          flags.mutable_at(i) = o.flags;
          face.mutable_at(i) = o.cad_face;
          constraints.mutable_at(i) = o.constraints;
          tick_us.mutable_at(i) = run.tick_us[i];
        }
        py::dict out;
        out["force_w"] = force;
        out["proxy_w"] = proxy;
        out["flags"] = flags;
        out["cad_face"] = face;
        out["constraints"] = constraints;
        out["tick_us"] = tick_us;
        return out;
      },
      py::arg("renderer"), py::arg("positions_w"), py::arg("velocities_w"), py::arg("times_s"));
}

std::vector<double> ToVector(const RowsD& a, const char* name) {
  if (a.ndim() != 1) throw py::value_error(std::string(name) + " must be one-dimensional");
  return std::vector<double>(a.data(), a.data() + a.shape(0));
}

void DefineTextureFit(py::module_& m) {
  py::class_<TextureRecording>(m, "TextureRecording")
      .def(py::init([](const RowsD& t, const RowsD& x, const RowsD& f) {
             return TextureRecording{ToVector(t, "time_s"), ToVector(x, "position_m"),
                                     ToVector(f, "lateral_force_n")};
           }),
           py::arg("time_s"), py::arg("position_m"), py::arg("lateral_force_n"))
      .def_property_readonly("samples", [](const TextureRecording& r) { return r.time_s.size(); });
  py::class_<TextureFitOptions>(m, "TextureFitOptions")
      .def(py::init<>())
      .def_readwrite("period_m", &TextureFitOptions::period_m)
      .def_readwrite("speeds_mps", &TextureFitOptions::speeds_mps)
      .def_readwrite("speed_tolerance", &TextureFitOptions::speed_tolerance)
      .def_readwrite("lowpass_hz", &TextureFitOptions::lowpass_hz)
      .def_readwrite("velocity_window_s", &TextureFitOptions::velocity_window_s)
      .def_readwrite("min_periods", &TextureFitOptions::min_periods)
      .def_readwrite("harmonics", &TextureFitOptions::harmonics)
      .def_readwrite("samples_per_period", &TextureFitOptions::samples_per_period);
  m.attr("LOWPASS_SETTLE_TIME_CONSTANTS") = kLowPassSettleTimeConstants;
  py::class_<TextureSection>(m, "TextureSection")
      .def_readonly("recording", &TextureSection::recording)
      .def_readonly("first_sample", &TextureSection::first_sample)
      .def_readonly("last_sample", &TextureSection::last_sample)
      .def_readonly("samples_per_period", &TextureSection::samples_per_period)
      .def_readonly("period_found_m", &TextureSection::period_found_m)
      .def_readonly("harmonic_n", &TextureSection::harmonic_n)
      .def_readonly("target_speed_mps", &TextureSection::target_speed_mps)
      .def_readonly("speed_mps", &TextureSection::speed_mps)
      .def_readonly("start_m", &TextureSection::start_m)
      .def_readonly("end_m", &TextureSection::end_m)
      .def_readonly("periods", &TextureSection::periods)
      .def_readonly("dc_n", &TextureSection::dc_n)
      .def_property_readonly("amplitude_n", [](const TextureSection& s) {
        return py::array_t<double>(static_cast<py::ssize_t>(s.amplitude_n.size()),
                                   s.amplitude_n.data());
      });
  py::class_<PowerFit>(m, "PowerFit")
      .def_readonly("beta", &PowerFit::beta)
      .def_readonly("alpha", &PowerFit::alpha)
      .def_readonly("points", &PowerFit::points)
      .def_readonly("r_squared", &PowerFit::r_squared);
  py::class_<SpeedFit>(m, "SpeedFit")
      .def_readonly("target_speed_mps", &SpeedFit::target_speed_mps)
      .def_readonly("speed_mps", &SpeedFit::speed_mps)
      .def_readonly("sections", &SpeedFit::sections)
      .def_readonly("samples_per_period", &SpeedFit::samples_per_period)
      .def_readonly("dc_n", &SpeedFit::dc_n)
      .def_readonly("dc_sd_n", &SpeedFit::dc_sd_n)
      .def_readonly("harmonic", &SpeedFit::harmonic)
      .def_readonly("background", &SpeedFit::background);
  py::class_<SpeedLine>(m, "SpeedLine")
      .def_readonly("intercept", &SpeedLine::intercept)
      .def_readonly("slope", &SpeedLine::slope)
      .def_property_readonly("intercept_se",
                             [](const SpeedLine& l) { return NanToNone(l.intercept_se); })
      .def_property_readonly("slope_se", [](const SpeedLine& l) { return NanToNone(l.slope_se); });
  py::class_<TextureFit>(m, "TextureFit")
      .def_readonly("period_m", &TextureFit::period_m)
      .def_readonly("sections", &TextureFit::sections)
      .def_readonly("speeds", &TextureFit::speeds)
      .def_readonly("speeds_without_sections_mps", &TextureFit::speeds_without_sections_mps)
      .def_readonly("dc_n", &TextureFit::dc_n)
      .def_readonly("beta_h_n", &TextureFit::beta_h_n)
      .def_readonly("alpha_h", &TextureFit::alpha_h);
  m.def("fit_texture", &FitTexture, py::arg("recordings"), py::arg("options"),
        py::call_guard<py::gil_scoped_release>());
}

void DefinePerceptualSpace(py::module_& m) {
  py::class_<PerceptualSpace>(m, "PerceptualSpace")
      .def_readonly("points", &PerceptualSpace::points)
      .def_readonly("eigenvalues", &PerceptualSpace::eigenvalues)
      .def_readonly("explained", &PerceptualSpace::explained)
      .def_readonly("stress", &PerceptualSpace::stress)
      .def_readonly("iterations", &PerceptualSpace::iterations)
      .def_readonly("converged", &PerceptualSpace::converged);
  py::class_<OrdinalScalingOptions>(m, "OrdinalScalingOptions")
      .def(py::init<>())
      .def_readwrite("max_iterations", &OrdinalScalingOptions::max_iterations)
      .def_readwrite("tolerance", &OrdinalScalingOptions::tolerance);
  py::class_<PropertyVector>(m, "PropertyVector")
      .def_readonly("direction", &PropertyVector::direction)
      .def_readonly("length", &PropertyVector::length)
      .def_readonly("correlation", &PropertyVector::correlation);
  m.def("compute_perceptual_space", &ComputePerceptualSpace, py::arg("dissimilarity"),
        py::arg("dimensions"));
  m.def("compute_ordinal_perceptual_space", &ComputeOrdinalPerceptualSpace,
        py::arg("dissimilarity"), py::arg("dimensions"),
        py::arg("options") = OrdinalScalingOptions{});
  m.def("fit_property_vector", &FitPropertyVector, py::arg("points"), py::arg("q"));
  m.def("scale_to_unit_range", &ScaleToUnitRange, py::arg("values"));
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "HaptiCAD core and device layer (C++), bound without logic.";
  // classes before the functions that take them, so signatures show Python names
  DefineFriction(m);
  DefinePatterns(m);
  DefineTextures(m);
  DefineForceTravel(m);
  DefineSurfaces(m);
  DefineScene(m);
  DefineDeviceTypes(m);
  DefineDevices(m);
  DefineAnalysis(m);
  DefineTextureFit(m);
  DefinePerceptualSpace(m);
}
