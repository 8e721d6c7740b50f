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

#include "hapticad/core/rendering/force_renderer.h"
#include "hapticad/core/rendering/haptic_scene.h"
#include "hapticad/core/surfaces/friction.h"
#include "hapticad/core/surfaces/roughness.h"
#include "hapticad/core/surfaces/surface_properties.h"
#include "hapticad/devices/servo_loop.h"
#include "hapticad/devices/simulated_device.h"

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

void DefineSurfaces(py::module_& m) {
  py::class_<FrictionParams>(m, "FrictionParams")
      .def(py::init<>())
      .def_readwrite("static_coefficient", &FrictionParams::static_coefficient)
      .def_readwrite("dynamic_coefficient", &FrictionParams::dynamic_coefficient)
      .def_readwrite("stick_speed_mps", &FrictionParams::stick_speed_mps)
      .def_readwrite("transition_speed_mps", &FrictionParams::transition_speed_mps);
  m.def("equivalent_friction", &EquivalentFriction, py::arg("params"), py::arg("speed_mps"));
  m.def("calc_friction_force", &CalcFrictionForce, py::arg("params"), py::arg("normal_force_n"),
        py::arg("v_t_mps"));

  py::class_<SurfaceProperties>(m, "SurfaceProperties")
      .def(py::init<>())
      .def_readwrite("friction", &SurfaceProperties::friction)
      .def_readwrite("stiffness_n_per_m", &SurfaceProperties::stiffness_n_per_m);
  m.attr("UNTAGGED_SURFACE") = kUntaggedSurface;
  m.def("validate_surface_properties", &ValidateSurfaceProperties, py::arg("surface"));
  py::class_<SurfaceTable, std::shared_ptr<SurfaceTable>>(m, "SurfaceTable")
      .def(py::init<std::vector<SurfaceProperties>>(), py::arg("by_face"))
      .def("surface", &SurfaceTable::surface, py::arg("face"), py::return_value_policy::copy)
      .def("__len__", &SurfaceTable::size);

  py::class_<RoughnessCategory>(m, "RoughnessCategory")
      .def_readonly("category", &RoughnessCategory::category)
      .def_property_readonly("ra_min_um",
                             [](const RoughnessCategory& r) { return NanToNone(r.ra_min_um); })
      .def_property_readonly("ra_max_um",
                             [](const RoughnessCategory& r) { return NanToNone(r.ra_max_um); })
      .def_property_readonly("n_grades",
                             [](const RoughnessCategory& r) {
                               std::vector<std::string> grades;
                               for (const char* g : r.n_grades)
                                 if (g) grades.emplace_back(g);
                               return grades;
                             })
      .def_readonly("grid_size_mm", &RoughnessCategory::grid_size_mm);
  m.def("roughness_table", [] {
    const auto& t = RoughnessTable();
    return std::vector<RoughnessCategory>(t.begin(), t.end());
  });
  m.def("roughness_category", &GetRoughnessCategory, py::arg("category"),
        py::return_value_policy::copy);
}

void DefineScene(py::module_& m) {
  py::class_<SurfaceSample>(m, "SurfaceSample")
      .def_readonly("point_w", &SurfaceSample::point_w)
      .def_readonly("normal_w", &SurfaceSample::normal_w)
      .def_readonly("triangle", &SurfaceSample::triangle)
      .def_readonly("cad_face", &SurfaceSample::cad_face)
      .def_readonly("distance_m", &SurfaceSample::distance_m);

  py::class_<HapticScene, std::shared_ptr<HapticScene>>(m, "HapticScene")
      .def_static(
          "build",
          [](const RowsD& vertices, const RowsI& triangles, const RowsI& cad_faces,
             double metres_per_unit, const std::optional<RowsD>& corner_normals) {
            TriangleSoup soup = MakeSoup(vertices, triangles, cad_faces, corner_normals);
            py::gil_scoped_release release;
            return std::const_pointer_cast<HapticScene>(HapticScene::Build(soup, metres_per_unit));
          },
          py::arg("vertices"), py::arg("triangles"), py::arg("cad_faces"),
          py::arg("metres_per_unit"), py::arg("corner_normals") = py::none())
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

void DefineDevices(py::module_& m) {
  PYBIND11_NUMPY_DTYPE(TraceSample, time_s, device_m, velocity_mps, proxy_m, force_n,
                       normal_force_n, tangential_force_n, cad_face, flags, tick_us);
  py::class_<DeviceLimits>(m, "DeviceLimits")
      .def(py::init<>())
      .def_readwrite("max_force_n", &DeviceLimits::max_force_n)
      .def_readwrite("max_stiffness_n_per_m", &DeviceLimits::max_stiffness_n_per_m)
      .def_readwrite("workspace_min_w", &DeviceLimits::workspace_min_w)
      .def_readwrite("workspace_max_w", &DeviceLimits::workspace_max_w);
  m.def("simulated_probe_limits", &SimulatedProbeLimits);
  py::class_<DeviceInfo>(m, "DeviceInfo")
      .def_readonly("kind", &DeviceInfo::kind)
      .def_readonly("name", &DeviceInfo::name)
      .def_readonly("path", &DeviceInfo::path)
      .def_readonly("limits", &DeviceInfo::limits);

  py::class_<Device>(m, "Device").def_property_readonly("info", &Device::info);
  py::class_<SimulatedDevice, Device>(m, "SimulatedDevice")
      .def(py::init([](std::vector<double> times_s, const RowsD& positions_w, DeviceLimits limits) {
             RequireShape(positions_w, 3, "positions_w");
             ScriptedPath path;
             path.times_s = std::move(times_s);
             auto p = positions_w.unchecked<2>();
             for (py::ssize_t i = 0; i < p.shape(0); ++i)
               path.positions_w.emplace_back(p(i, 0), p(i, 1), p(i, 2));
             return std::make_unique<SimulatedDevice>(std::move(path), limits);
           }),
           py::arg("times_s"), py::arg("positions_w"), py::arg("limits"))
      .def_property_readonly("duration_s",
                             [](const SimulatedDevice& d) { return d.path().duration_s(); })
      .def_property_readonly("last_force_w", &SimulatedDevice::last_force_w);

  py::class_<RenderLimits>(m, "RenderLimits")
      .def(py::init<>())
      .def_readwrite("max_force_n", &RenderLimits::max_force_n)
      .def_readwrite("max_stiffness_n_per_m", &RenderLimits::max_stiffness_n_per_m);
  m.attr("FLAG_CONTACT") = static_cast<std::uint32_t>(kContact);
  m.attr("FLAG_FORCE_CLAMPED") = static_cast<std::uint32_t>(kForceClamped);
  m.attr("FLAG_STIFFNESS_CLAMPED") = static_cast<std::uint32_t>(kStiffnessClamped);
  m.attr("FLAG_INPUT_FAULT") = static_cast<std::uint32_t>(kInputFault);
  m.attr("FLAG_DEVICE_FAULT") = kDeviceFault;

  py::class_<ForceRenderer>(m, "ForceRenderer")
      .def(py::init([](std::shared_ptr<HapticScene> scene, std::shared_ptr<SurfaceTable> surfaces,
                       RenderLimits limits) {
             return std::make_unique<ForceRenderer>(scene, surfaces, limits);
           }),
           py::arg("scene"), py::arg("surfaces"), py::arg("limits"));

  py::class_<ServoStats>(m, "ServoStats")
      .def_readonly("ticks", &ServoStats::ticks)
      .def_readonly("overruns", &ServoStats::overruns)
      .def_readonly("skipped_ticks", &ServoStats::skipped_ticks)
      .def_readonly("trace_dropped", &ServoStats::trace_dropped)
      .def_readonly("elapsed_s", &ServoStats::elapsed_s);
  py::class_<ServoLoop>(m, "ServoLoop")
      .def(py::init([](Device& device, ForceRenderer& renderer, double rate_hz,
                       std::size_t trace_capacity) {
             return std::make_unique<ServoLoop>(device, renderer,
                                                ServoConfig{rate_hz, trace_capacity});
           }),
           py::arg("device"), py::arg("renderer"), py::arg("rate_hz") = 1000.0,
           py::arg("trace_capacity") = std::size_t{1} << 16, py::keep_alive<1, 2>(),
           py::keep_alive<1, 3>())
      .def(
          "run_for",
          [](ServoLoop& loop, double duration_s) {
            std::vector<TraceSample> samples;
            {
              py::gil_scoped_release release;
              samples = loop.RunFor(duration_s);
            }
            py::array_t<TraceSample> out(static_cast<py::ssize_t>(samples.size()));
            std::copy(samples.begin(), samples.end(), out.mutable_data());
            return out;
          },
          py::arg("duration_s"))
      .def_property_readonly("stats", &ServoLoop::stats);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "HaptiCAD core and device layer (C++), bound without logic.";
  DefineSurfaces(m);
  DefineScene(m);
  DefineDevices(m);
}
