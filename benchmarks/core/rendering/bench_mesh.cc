// SPDX-License-Identifier: GPL-3.0-or-later
// hapticad-bench-mesh: the contact engine's speed and correctness on one mesh, as JSON.
//
//   hapticad-bench-mesh (MESH_FILE | --icosphere TRIANGLES) [--radius MM] [--ticks N]
//       [--proxy point|sphere:R_MM] [--units mm|m] [--seed S] [--convex-pieces on|off]
//       [--warm-ahead N] [--rate-hz R [--pace sleep|spin]] [--json]
//
// Workload (issue 4): the device strokes over the surface along a seeded path at
// 50-100 mm/s, pressed 1-3 mm below it (for meshes under 50 mm in bounding radius,
// 1-3 % of it), k = 0.4 N/mm, mu 0.3/0.2, 1 kHz. The path is computed before the timed
// loop; each tick is timed on its own (steady clock, about 20 ns of overhead included).
// One thread: the tick never waits on anything else.
//
// --convex-pieces off: every sweep walks the grid or the tree (ContactOptions::convex_pieces),
// to compare; `walked_ticks` counts the contact ticks where a sweep walked either way.
//
// --warm-ahead N (a diagnostic, not a mode to quote): before each block of N ticks, a
// second renderer that has followed the same inputs runs that block untimed, so the
// timed ticks find their data in the caches. What still grows with the model is then
// the work, not the memory.
//
// --rate-hz R: the ticks run R a second, as the servo loop runs them, rather than back to
// back: each waits for its deadline by sleeping (--pace sleep, what ServoLoop does) or by
// reading the clock (--pace spin, the core never idles); after a tick more than a period
// late the lost periods are skipped, as ServoLoop skips them (`late_ticks` counts those). Back to
// back, a tick finds in the caches what the tick before read; paced, the wait in between may lose
// it.
//
// `expected_force_n` [low, high], for the icosphere only (null for a mesh file): k times the
// press depths, the larger with friction, which a smooth convex part gives. Round a sharp
// convex edge the path follows the surface while the proxy, a god object, stays on the
// face it was pressed into (it must not pop over the edge): the device goes on deeper
// under that face than the press, and the force beyond the range, as a finger pushed on
// round a box's edge would feel (a 10 mm tetrahedron pressed 0.09-0.26 mm: 2.2 N,
// against 0.11 N). `max_force_n` says nothing of the engine's correctness there.
//
// `tick_us_by_move` groups the contact ticks by how far the contact moved since the
// tick before, in triangles: `stayed` (the same triangle), `next` (one across an edge),
// `second` (two edges away) and `further`; each with its count, p50 and p99. The finer
// the mesh, the more triangles a stroke crosses in a tick, and a tick that crosses more
// tests more: this tells that growth of the work from the growth of the memory.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/prctl.h>
#include <time.h>

#include "hapticad/core/geometry/icosphere.h"
#include "hapticad/core/geometry/mesh_file.h"
#include "hapticad/core/rendering/force_renderer.h"

namespace hapticad {
namespace {

// Bounds of the options, said in their messages. The icosphere is built, repaired and
// indexed at about 470 bytes a triangle at its peak (2 M triangles: 0.94 GB); a tick's
// path, proxy and timing take about 150 bytes.
constexpr long long kMaxIcosphere = 10000000;
constexpr double kBuildBytesPerTriangle = 470.0;
constexpr long long kMaxTicks = 10000000;
constexpr double kMinRadiusMm = 0.01, kMaxRadiusMm = 10000.0;  // 10 um to 10 m
constexpr double kMinProxyMm = 0.001, kMaxProxyMm = 1000.0;    // 1 um to 1 m

struct Options {
  std::string file;
  bool icosphere_given = false;
  long long icosphere = 0;
  double radius_mm = 50.0;
  long long ticks = 20000;
  double sphere_radius_mm = 0.0;  // 0: point proxy
  bool metres = false;
  unsigned seed = 1;
  long long warm_ahead = 0;  // 0: off
  bool convex_pieces = true;
  double rate_hz = 0.0;  // 0: back to back
  bool spin = false;     // with rate_hz: wait by reading the clock rather than sleeping
  bool pace_given = false;
};

[[noreturn]] void Usage(const std::string& problem) {
  std::cerr << "hapticad-bench-mesh: " << problem << "\n"
            << "usage: hapticad-bench-mesh (MESH_FILE | --icosphere TRIANGLES) [--radius MM] "
               "[--ticks N]\n"
               "           [--proxy point|sphere:R_MM] [--units mm|m] [--seed S] "
               "[--convex-pieces on|off]\n"
               "           [--warm-ahead N] [--rate-hz R [--pace sleep|spin]] [--json]\n";
  std::exit(2);
}

double Number(const std::string& text, const char* what) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(v)) throw std::invalid_argument(text);
    return v;
  } catch (const std::exception&) {
    Usage(std::string(what) + " must be a number, got '" + text + "'");
  }
}

// A whole number from lo to hi; `why_hi` says what the maximum is for.
long long Integer(const std::string& text, const std::string& what, long long lo, long long hi,
                  const std::string& why_hi = "") {
  const double v = Number(text, what.c_str());
  if (v != std::floor(v)) Usage(what + " must be a whole number, got '" + text + "'");
  if (v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
    Usage(what + " must be from " + std::to_string(lo) + " to " + std::to_string(hi) + why_hi +
          ", got " + text);
  }
  return static_cast<long long>(v);
}

std::string Gigabytes(double bytes) {
  if (!(bytes < 1e18)) return "more than any computer holds";
  char text[32];
  std::snprintf(text, sizeof text, "about %.3g GB", bytes / 1e9);
  return text;
}

std::string Millimetres(double mm) {
  char text[32];
  std::snprintf(text, sizeof text, "%g mm", mm);
  return text;
}

// `text` as a JSON string, in its quotes: quotes, backslashes and control characters escaped
// (a file name may hold any of them), other bytes, UTF-8's, as they are.
std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", byte);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

Options Parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) Usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "--icosphere") {
      const std::string text = next();
      const double v = Number(text, "--icosphere");
      if (v != std::floor(v))
        Usage("--icosphere must be a whole number of triangles, got '" + text + "'");
      if (v < 1) Usage("--icosphere needs a positive number of triangles, got " + text);
      if (v > kMaxIcosphere) {
        Usage("--icosphere takes at most " + std::to_string(kMaxIcosphere) + " triangles (" +
              Gigabytes(kMaxIcosphere * kBuildBytesPerTriangle) + " of memory to build); " + text +
              " would need " + Gigabytes(v * kBuildBytesPerTriangle));
      }
      o.icosphere = static_cast<long long>(v);
      o.icosphere_given = true;
    } else if (a == "--radius") {
      o.radius_mm = Number(next(), "--radius");
      if (!(o.radius_mm >= kMinRadiusMm && o.radius_mm <= kMaxRadiusMm)) {
        Usage("--radius must be from " + Millimetres(kMinRadiusMm) + " to " +
              Millimetres(kMaxRadiusMm) + ", got " + Millimetres(o.radius_mm));
      }
    } else if (a == "--ticks")
      o.ticks = Integer(next(), "--ticks", 100, kMaxTicks, " (about 150 bytes a tick)");
    else if (a == "--seed")
      o.seed = static_cast<unsigned>(Integer(next(), "--seed", 0, 4294967295LL));
    else if (a == "--warm-ahead")
      o.warm_ahead = Integer(next(), "--warm-ahead", 0, kMaxTicks, " (0: off; at most --ticks)");
    else if (a == "--rate-hz") {
      o.rate_hz = Number(next(), "--rate-hz");
      if (!(o.rate_hz == 0.0 || (o.rate_hz >= 100.0 && o.rate_hz <= 100000.0)))
        Usage("--rate-hz must be 0 (back to back) or from 100 to 100000");
    } else if (a == "--pace") {
      const std::string v = next();
      if (v != "sleep" && v != "spin") Usage("--pace must be sleep or spin");
      o.spin = v == "spin";
      o.pace_given = true;
    } else if (a == "--json")
      continue;
    else if (a == "--convex-pieces") {
      const std::string v = next();
      if (v != "on" && v != "off") Usage("--convex-pieces must be on or off");
      o.convex_pieces = v == "on";
    } else if (a == "--units") {
      const std::string u = next();
      if (u != "mm" && u != "m") Usage("--units must be mm or m");
      o.metres = u == "m";
    } else if (a == "--proxy") {
      const std::string p = next();
      if (p == "point")
        o.sphere_radius_mm = 0.0;
      else if (p.rfind("sphere:", 0) == 0) {
        o.sphere_radius_mm = Number(p.substr(7), "sphere radius");
        if (!(o.sphere_radius_mm >= kMinProxyMm && o.sphere_radius_mm <= kMaxProxyMm)) {
          Usage("--proxy sphere:R_MM needs R from " + Millimetres(kMinProxyMm) + " to " +
                Millimetres(kMaxProxyMm) + ", got " + p.substr(7) +
                " (for a point proxy give --proxy point)");
        }
      } else
        Usage("--proxy must be point or sphere:R_MM");
    } else if (!a.empty() && a[0] == '-')
      Usage("unknown option " + a);
    else
      o.file = a;
  }
  if (o.file.empty() && !o.icosphere_given) Usage("give a mesh file or --icosphere TRIANGLES");
  if (!o.file.empty() && o.icosphere_given) Usage("give a mesh file or --icosphere, not both");
  if (o.pace_given && o.rate_hz == 0.0)
    Usage("--pace needs --rate-hz (back to back, no tick waits)");
  if (o.rate_hz > 0.0 && o.warm_ahead > 0) {
    Usage(
        "--warm-ahead replays a block of ticks just before them, back to back; it means nothing "
        "with --rate-hz");
  }
  if (o.warm_ahead > o.ticks) {
    Usage("--warm-ahead must be at most --ticks (" + std::to_string(o.ticks) + "), got " +
          std::to_string(o.warm_ahead));
  }
  return o;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(
      std::min<double>(v.size() - 1, std::floor(q * (v.size() - 1) + 0.5)));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

// How far apart triangles a and b lie: 0 (the same), 1 (across an edge), 2 (across an
// edge of one across an edge) or 3 (further).
int TrianglesApart(const TriangleMesh& mesh, std::uint32_t a, std::uint32_t b) {
  if (a == b) return 0;
  for (const std::uint32_t u : mesh.across(a)) {
    if (u == b) return 1;
  }
  for (const std::uint32_t u : mesh.across(a)) {
    if (u == TriangleMesh::kNone) continue;
    for (const std::uint32_t w : mesh.across(u)) {
      if (w == b) return 2;
    }
  }
  return 3;
}

int Run(const Options& o) {
  // scene in model units: mm, or m with every coordinate scaled by 1e-3
  const double unit = o.metres ? 1.0 : 1e-3;  // metres per model unit
  const double mm = 1e-3 / unit;              // model units per mm
  TriangleSoup soup = o.file.empty()
                          ? MakeIcosphere(IcosphereFrequencyFor(o.icosphere), o.radius_mm * mm)
                          : ReadMeshFile(o.file);
  if (!o.file.empty() && o.metres) {
    for (Vec3& v : soup.vertices) v *= 1e-3;  // a file is read in mm; --units m rescales
  }
  // the repair (CGAL) and the scene (mesh and tree) are timed apart: the tree build is
  // what CHAI3D's figures compare with
  using Ms = std::chrono::duration<double, std::milli>;
  const auto t0 = std::chrono::steady_clock::now();
  RepairReport report;
  soup = RepairSoup(soup, RepairOptions{}, &report);
  const auto t1 = std::chrono::steady_clock::now();
  SceneOptions no_repair;
  no_repair.repair = false;
  const auto scene = HapticScene::Build(soup, unit, no_repair);
  // and the contact structure the proxy uses (ForceRenderer would build it otherwise)
  const auto t2 = std::chrono::steady_clock::now();
  const bool point = o.sphere_radius_mm == 0.0;
  if (point) {
    scene->BuildGrid();
  } else {
    scene->BuildTree();
  }
  const auto t_structure = std::chrono::steady_clock::now();
  if (o.convex_pieces) scene->BuildPieces();
  const auto t3 = std::chrono::steady_clock::now();
  // whether the surface bounds solids (a reset inside a part): the renderer asks for it
  scene->BuildSolids();
  const double solids_ms = Ms(std::chrono::steady_clock::now() - t3).count();
  const double repair_ms = Ms(t1 - t0).count();
  const double build_ms = Ms(t3 - t1).count();
  const double mesh_ms = Ms(t2 - t1).count();
  const double pieces_ms = Ms(t3 - t_structure).count();
  const std::size_t triangles = scene->mesh().num_triangles();
  // before the stroke set-up below builds the tree for its closest points
  const std::size_t bytes = scene->CalcMemoryBytes();

  SurfaceProperties surface;
  surface.stiffness_n_per_m = 400.0;
  surface.friction.static_coefficient = 0.3;
  surface.friction.dynamic_coefficient = 0.2;
  const auto table = std::make_shared<SurfaceTable>(std::vector<SurfaceProperties>(
      static_cast<std::size_t>(std::max(1, scene->mesh().num_cad_faces())), surface));
  // no force cap: a spike must show, not be clipped
  ContactOptions options;
  options.proxy_radius_m = o.sphere_radius_mm * 1e-3;
  options.convex_pieces = o.convex_pieces;
  ForceRenderer renderer(scene, table, RenderLimits{1e6, 400.0}, options);

  // the path, before any timing: a seeded walk over the surface, re-projected each tick
  const double bounding_radius_m = 0.5 * scene->size_m();
  const double depth_lo = bounding_radius_m >= 0.05 ? 1e-3 : 0.01 * bounding_radius_m;
  const double depth_hi = bounding_radius_m >= 0.05 ? 3e-3 : 0.03 * bounding_radius_m;
  const double r_proxy = o.sphere_radius_mm * 1e-3;
  const double dt = 1e-3;
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const auto& mesh = scene->mesh();
  const std::uint32_t t_start = static_cast<std::uint32_t>(uniform(rng) * triangles) % triangles;
  const auto& tri = mesh.triangle(t_start);
  Vec3 p_w =
      scene->ToWorld((mesh.vertex(tri[0]) + mesh.vertex(tri[1]) + mesh.vertex(tri[2])) / 3.0);
  SurfaceSample here = scene->CalcClosestPoint(p_w);
  Vec3 heading = here.normal_w.cross(Vec3(gauss(rng), gauss(rng), gauss(rng))).normalized();
  double speed = 0.075, depth = 0.5 * (depth_lo + depth_hi);
  std::vector<RenderInput> path(static_cast<std::size_t>(o.ticks));
  std::vector<Vec3> surface_points(path.size()), surface_normals(path.size());
  Vec3 previous_goal = Vec3::Zero();
  for (std::size_t k = 0; k < path.size(); ++k) {
    speed = std::clamp(speed + 0.002 * gauss(rng), 0.05, 0.1);
    depth = std::clamp(depth + 0.00002 * gauss(rng), depth_lo, depth_hi);
    heading = (heading + 0.05 * here.normal_w.cross(heading) * gauss(rng)).normalized();
    here = scene->CalcClosestPoint(here.point_w + speed * dt * heading);
    heading = (heading - heading.dot(here.normal_w) * here.normal_w).normalized();
    const Vec3 goal = here.point_w + (r_proxy - depth) * here.normal_w;
    path[k].position_w = goal;
    path[k].velocity_w = k == 0 ? Vec3::Zero() : Vec3((goal - previous_goal) / dt);
    path[k].time_s = k * dt;
    surface_points[k] = here.point_w;
    surface_normals[k] = here.normal_w;
    previous_goal = goal;
  }

  // the timed run, starting from above the first point
  const RenderInput above{surface_points[0] + (r_proxy + 0.01) * surface_normals[0], Vec3::Zero(),
                          0.0};
  RenderOutput out;
  renderer.Render(above, &out);
  ForceRenderer ahead(scene, table, RenderLimits{1e6, 400.0}, options);  // --warm-ahead's
  RenderOutput ahead_out;
  ahead.Render(above, &ahead_out);
  std::vector<double> tick_us, contact_us;
  std::size_t walked = 0;  // contact ticks where a sweep walked the grid or the tree
  tick_us.reserve(path.size());
  contact_us.reserve(path.size());
  std::vector<Vec3> proxies(path.size());
  // the first constraint's triangle after each tick, or kNone without contact
  std::vector<std::uint32_t> contact_triangle(path.size(), TriangleMesh::kNone);
  double max_force = 0.0;
  std::size_t contact = 0;
  const auto block = static_cast<std::size_t>(o.warm_ahead);
  // --rate-hz: the servo loop's pacing (servo_loop.cc): a sleep to an absolute deadline
  // with 1 us of timer slack, and, after a tick more than a period late, the lost
  // periods skipped rather than run back to back
  const auto period_ns =
      o.rate_hz > 0.0 ? static_cast<long long>(std::llround(1e9 / o.rate_hz)) : 0;
  if (period_ns > 0) prctl(PR_SET_TIMERSLACK, 1000UL, 0, 0, 0);
  const auto monotonic_ns = [] {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    return static_cast<long long>(t.tv_sec) * 1000000000LL + t.tv_nsec;
  };
  long long deadline_ns = monotonic_ns();
  std::size_t late_ticks = 0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (period_ns > 0) {
      deadline_ns += period_ns;
      const long long now = monotonic_ns();
      if (now > deadline_ns + period_ns) {
        ++late_ticks;
        deadline_ns += (now - deadline_ns) / period_ns * period_ns;
      }
      if (o.spin) {
        while (monotonic_ns() < deadline_ns) {
        }
      } else {
        const timespec deadline{static_cast<time_t>(deadline_ns / 1000000000LL),
                                static_cast<long>(deadline_ns % 1000000000LL)};
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
        }
      }
    }
    if (block > 0 && k % block == 0) {
      for (std::size_t j = k; j < std::min(path.size(), k + block); ++j) {
        ahead.Render(path[j], &ahead_out);
      }
    }
    const std::uint64_t sweeps = renderer.proxy().sweeps();
    const std::uint64_t settled = renderer.proxy().settled_sweeps();
    const auto a = std::chrono::steady_clock::now();
    renderer.Render(path[k], &out);
    const auto b = std::chrono::steady_clock::now();
    const double us = std::chrono::duration<double, std::micro>(b - a).count();
    tick_us.push_back(us);
    proxies[k] = out.proxy_w;
    const ConstraintSet& constraints = renderer.proxy().constraints();
    if (constraints.count() > 0) contact_triangle[k] = constraints.plane(0).triangle;
    if (out.flags & kContact) {
      ++contact;
      contact_us.push_back(us);
      walked += renderer.proxy().sweeps() - sweeps != renderer.proxy().settled_sweeps() - settled;
    }
    max_force = std::max(max_force, out.force_w.norm());
  }

  // after the run: the contact ticks by how far the contact moved
  std::vector<double> by_move[4];
  for (std::size_t k = 1; k < path.size(); ++k) {
    if (contact_triangle[k - 1] == TriangleMesh::kNone ||
        contact_triangle[k] == TriangleMesh::kNone)
      continue;
    by_move[TrianglesApart(mesh, contact_triangle[k - 1], contact_triangle[k])].push_back(
        tick_us[k]);
  }

  // after the run: did the proxy pass through the surface between two ticks (its
  // centre's path crossed or touched a triangle; counted strictly, with how far behind
  // the triangle it ended), and did a sphere ever overlap it?
  std::size_t pop_through = 0;
  double max_far_side = 0.0;  // m
  double max_penetration = 0.0;
  for (std::size_t k = 1; k < proxies.size(); ++k) {
    SweepHit hit;
    SweepQuery crossing;
    crossing.a = scene->ToLocal(proxies[k - 1]);
    crossing.b = scene->ToLocal(proxies[k]);
    if (scene->BuildTree().FirstHit(crossing, &hit)) {
      ++pop_through;
      // how far behind the crossed triangle's plane the proxy ended, seen from where it
      // started (from on the plane: from the outside, the winding's side). 0: it only
      // touched the plane, as a proxy resting on one face does on the next face's plane
      // at an edge.
      const Vec3& n = scene->mesh().face_normal(hit.triangle);
      const Vec3& v0 = scene->mesh().vertex(scene->mesh().triangle(hit.triangle)[0]);
      const double from = n.dot(crossing.a - v0);
      const double to = n.dot(crossing.b - v0);
      max_far_side = std::max(max_far_side, from < 0.0 ? to : -to);
    }
    if (r_proxy > 0.0 && k % (proxies.size() > 200000 ? 5 : 1) == 0) {
      max_penetration =
          std::max(max_penetration, r_proxy - scene->CalcClosestPoint(proxies[k]).distance_m);
    }
  }

  std::printf("{\n");
  // every string escaped: a file name may hold a quote, a backslash or a tab
  std::printf("  \"mesh\": %s,\n", JsonString(o.file.empty() ? "icosphere" : o.file).c_str());
  std::printf("  \"units\": %s,\n", JsonString(o.metres ? "m" : "mm").c_str());
  std::printf(
      "  \"proxy\": %s,\n",
      JsonString(r_proxy > 0 ? "sphere:" + std::to_string(o.sphere_radius_mm) : "point").c_str());
  std::printf("  \"triangles\": %zu,\n", triangles);
  std::printf("  \"build_ms\": %.3f,\n", build_ms);
  std::printf("  \"mesh_ms\": %.3f,\n", mesh_ms);
  std::printf("  \"pieces_ms\": %.3f,\n", pieces_ms);
  std::printf("  \"convex_pieces\": %zu,\n",
              o.convex_pieces ? scene->BuildPieces().num_pieces() : std::size_t{0});
  std::printf("  \"structure\": %s,\n", JsonString(point ? "grid" : "tree").c_str());
  std::printf("  \"repair_ms\": %.3f,\n", repair_ms);
  std::printf("  \"solids_ms\": %.3f,\n", solids_ms);
  // from the soup read to a scene the renderer can touch: what a designer waits for
  std::printf("  \"ready_ms\": %.3f,\n", repair_ms + build_ms + solids_ms);
  std::printf("  \"repair\": %s,\n", JsonString(report.Describe()).c_str());
  std::printf("  \"bytes_per_triangle\": %.1f,\n", static_cast<double>(bytes) / triangles);
  std::printf("  \"ticks\": %zu,\n", path.size());
  std::printf("  \"warm_ahead\": %lld,\n", o.warm_ahead);
  std::printf("  \"rate_hz\": %g,\n", o.rate_hz);
  std::printf("  \"late_ticks\": %zu,\n", late_ticks);
  std::printf("  \"pace\": %s,\n", JsonString(o.rate_hz == 0.0 ? "back to back"
                                              : o.spin         ? "spin"
                                                               : "sleep")
                                       .c_str());
  std::printf("  \"contact_ticks\": %zu,\n", contact);
  std::printf("  \"tick_us\": {\"p50\": %.3f, \"p99\": %.3f, \"p999\": %.3f, \"max\": %.3f},\n",
              Percentile(contact_us, 0.5), Percentile(contact_us, 0.99),
              Percentile(contact_us, 0.999),
              contact_us.empty() ? 0.0 : *std::max_element(contact_us.begin(), contact_us.end()));
  std::printf("  \"all_tick_us\": {\"p50\": %.3f, \"p99\": %.3f},\n", Percentile(tick_us, 0.5),
              Percentile(tick_us, 0.99));
  std::printf("  \"tick_us_by_move\": {");
  const char* move_names[4] = {"stayed", "next", "second", "further"};
  for (int i = 0; i < 4; ++i) {
    std::printf("%s\"%s\": {\"ticks\": %zu, \"p50\": %.3f, \"p99\": %.3f}", i ? ", " : "",
                move_names[i], by_move[i].size(), Percentile(by_move[i], 0.5),
                Percentile(by_move[i], 0.99));
  }
  std::printf("},\n");
  std::printf("  \"walked_ticks\": %zu,\n", walked);
  std::printf("  \"settled_sweeps\": %llu,\n",
              static_cast<unsigned long long>(renderer.proxy().settled_sweeps()));
  std::printf("  \"sweeps\": %llu,\n", static_cast<unsigned long long>(renderer.proxy().sweeps()));
  std::printf("  \"pop_through\": %zu,\n", pop_through);
  std::printf("  \"max_far_side_nm\": %.3f,\n", max_far_side * 1e9);
  std::printf("  \"max_penetration_mm\": %.9f,\n", max_penetration * 1e3);
  std::printf("  \"max_force_n\": %.6f,\n", max_force);
  if (o.file.empty()) {
    std::printf("  \"expected_force_n\": [%.6f, %.6f]\n", 400.0 * depth_lo,
                400.0 * depth_hi * std::sqrt(1 + 0.3 * 0.3));
  } else {
    std::printf("  \"expected_force_n\": null\n");
  }
  std::printf("}\n");
  return 0;
}

}  // namespace
}  // namespace hapticad

int main(int argc, char** argv) {
  try {
    return hapticad::Run(hapticad::Parse(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "hapticad-bench-mesh: " << e.what() << "\n";
    return 1;
  }
}
