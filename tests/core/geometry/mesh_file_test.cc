// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/mesh_file.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

// A unit cube, wound outward: the same mesh written in each format below.
const std::vector<Vec3> kCubeVertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0),
                                         Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 1),
                                         Vec3(1, 1, 1), Vec3(0, 1, 1)};
const std::vector<std::array<int, 3>> kCubeTriangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                                        {0, 1, 5}, {0, 5, 4}, {2, 3, 7}, {2, 7, 6},
                                                        {1, 2, 6}, {1, 6, 5}, {0, 4, 7}, {0, 7, 3}};

std::string Number(double v) {
  std::string s = std::to_string(v);
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s;
}

// The cube's vertex lines "x y z", then its face lines "3 a b c": OFF's and ASCII PLY's body.
std::string CubeVertexAndFaceLines() {
  std::string s;
  for (const Vec3& v : kCubeVertices) {
    s += Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + "\n";
  }
  for (const auto& t : kCubeTriangles) {
    s += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) +
         "\n";
  }
  return s;
}

std::string CubeOff() { return "OFF\n8 12 0\n" + CubeVertexAndFaceLines(); }

std::string CubeObj() {
  std::string s;
  for (const Vec3& v : kCubeVertices) {
    s += "v " + Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + "\n";
  }
  for (const auto& t : kCubeTriangles) {
    s += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
         std::to_string(t[2] + 1) + "\n";
  }
  return s;
}

std::string CubeAsciiStl() {
  std::string s = "solid cube\n";
  for (const auto& t : kCubeTriangles) {
    s += " facet normal 0 0 0\n  outer loop\n";
    for (const int i : t) {
      const Vec3& v = kCubeVertices[static_cast<std::size_t>(i)];
      s += "   vertex " + Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + "\n";
    }
    s += "  endloop\n endfacet\n";
  }
  return s + "endsolid cube\n";
}

template <class T>
void Append(std::string* bytes, T value) {  // little-endian, as x86 and the formats have it
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes->append(raw, sizeof(T));
}

// `claimed`: the triangle count the header states (the cube's 12 by default).
std::string CubeBinaryStl(std::uint32_t claimed = 12) {
  std::string s(80, ' ');
  s.replace(0, 10, "binary stl");
  Append(&s, claimed);
  for (const auto& t : kCubeTriangles) {
    for (int k = 0; k < 3; ++k) Append(&s, 0.0f);  // normal
    for (const int i : t) {
      const Vec3& v = kCubeVertices[static_cast<std::size_t>(i)];
      for (int k = 0; k < 3; ++k) Append(&s, static_cast<float>(v[k]));
    }
    Append(&s, std::uint16_t{0});
  }
  return s;
}

std::string PlyHeader(const std::string& format) {
  return "ply\nformat " + format +
         " 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string CubeAsciiPly() { return PlyHeader("ascii") + CubeVertexAndFaceLines(); }

std::string CubeBinaryPly() {
  std::string s = PlyHeader("binary_little_endian");
  for (const Vec3& v : kCubeVertices) {
    for (int k = 0; k < 3; ++k) Append(&s, static_cast<float>(v[k]));
  }
  for (const auto& t : kCubeTriangles) {
    Append(&s, std::uint8_t{3});
    for (const int i : t) Append(&s, std::int32_t{i});
  }
  return s;
}

// The enclosed volume (divergence theorem): 1 for the cube read with its winding.
double Volume(const TriangleSoup& soup) {
  double six_v = 0.0;
  for (const auto& t : soup.triangles) {
    six_v += soup.vertices[static_cast<std::size_t>(t[0])].dot(
        soup.vertices[static_cast<std::size_t>(t[1])].cross(
            soup.vertices[static_cast<std::size_t>(t[2])]));
  }
  return six_v / 6.0;
}

class MeshFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("hapticad_mesh_file_" + std::to_string(::getpid()) + "_" + info->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& bytes) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  // The message ReadMeshFile throws for `path`, without the path it starts with; "" if
  // it reads the file.
  std::string ErrorAt(const std::string& path) {
    try {
      ReadMeshFile(path);
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;  // names the file first
      return message.substr(std::min(message.size(), path.size() + 2));
    }
    return "";
  }
  std::string ErrorFor(const std::string& name, const std::string& bytes) {
    return ErrorAt(Write(name, bytes));
  }

  std::filesystem::path dir_;
};

TEST_F(MeshFile, ReadsTheCubeFromEveryFormatWithItsWinding) {
  const std::pair<const char*, std::string> files[] = {
      {"cube.off", CubeOff()},      {"cube.obj", CubeObj()},
      {"cube.stl", CubeAsciiStl()}, {"cube_binary.stl", CubeBinaryStl()},
      {"cube.ply", CubeAsciiPly()}, {"cube_binary.ply", CubeBinaryPly()},
      {"CUBE_UPPER.OFF", CubeOff()}};  // the extension picks the reader, in any case
  for (const auto& [name, bytes] : files) {
    const TriangleSoup soup = ReadMeshFile(Write(name, bytes));
    EXPECT_EQ(soup.vertices.size(), 8u) << name;
    ASSERT_EQ(soup.triangles.size(), 12u) << name;
    EXPECT_NEAR(Volume(soup), 1.0, 1e-12) << name;
    EXPECT_EQ(soup.cad_faces, std::vector<std::int32_t>(12, 0)) << name;
    EXPECT_TRUE(soup.corner_normals.empty()) << name;
  }
}

TEST_F(MeshFile, FansPolygonsAndKeepsWhatTheRepairJudges) {
  // a quad, a pentagon, the quad again and a degenerate triangle: kept as written
  const TriangleSoup soup = ReadMeshFile(
      Write("polygons.off",
            "OFF\n5 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 2 0\n4 0 1 2 3\n5 0 1 2 4 3\n4 0 1 2 3\n"
            "3 0 0 1\n"));
  const std::vector<std::array<std::int32_t, 3>> fanned = {
      {0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 4}, {0, 4, 3}, {0, 1, 2}, {0, 2, 3}, {0, 0, 1}};
  EXPECT_EQ(soup.triangles, fanned);
  EXPECT_EQ(soup.cad_faces.size(), fanned.size());
  EXPECT_EQ(soup.vertices[4], Vec3(0.5, 2, 0));
}

TEST_F(MeshFile, SaysWhyAFileCannotBeUsed) {
  EXPECT_EQ(ErrorAt((dir_ / "missing.off").string()), "no such file");
  std::filesystem::create_directories(dir_ / "folder.stl");
  EXPECT_EQ(ErrorAt((dir_ / "folder.stl").string()),
            "is a folder, not a mesh file (give an OFF, OBJ, STL or PLY file)");
  EXPECT_EQ(ErrorFor("empty.stl", ""), "the file is empty");
  EXPECT_EQ(ErrorFor("empty.obj", ""), "the file is empty");
  EXPECT_EQ(ErrorFor("no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), "the mesh has no faces");
  EXPECT_EQ(ErrorFor("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"),
            "line 4: 'nan' is not a finite number; every vertex needs three finite coordinates");
  std::string nan_stl = CubeBinaryStl();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan_stl[84 + 2 * 50 + 12 + 4], &nan, sizeof nan);  // face 3, vertex 1, y
  EXPECT_EQ(ErrorFor("nan_binary.stl", nan_stl),
            "face 3 has a vertex that is not finite (0, nan, 1); every vertex needs three "
            "finite coordinates");
  // a complete file that is malformed is not said to be cut off
  EXPECT_EQ(ErrorFor("garbage.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"),
            "cannot read a mesh (OFF, OBJ, STL or PLY expected)");
  EXPECT_EQ(ErrorFor("cube.3mf", CubeOff()), "cannot read a mesh (OFF, OBJ, STL or PLY expected)");
}

TEST_F(MeshFile, AFaceNamingAVertexTheFileDoesNotHaveIsSaidWhere) {
  // "cannot read a mesh" blamed the format; an OBJ index one past the last vertex got
  // through CGAL to the repair
  const std::string off = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  EXPECT_EQ(ErrorFor("past.off", off),
            "line 7: face 2 names vertex 3, but the file has 3 vertices (OFF counts from 0)");
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  EXPECT_EQ(ErrorFor("past.obj", obj),
            "line 5: face 2 names vertex 4, but the file has 3 vertices before it (OBJ counts "
            "from 1; -1 is the last)");
  EXPECT_EQ(ErrorFor("far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -7\n"),
            "line 4: face 1 names vertex -7, but the file has 3 vertices before it (OBJ counts "
            "from 1; -1 is the last)");
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n";
  const std::string said = ErrorFor("past.ply", ply);
  EXPECT_NE(said.find("names vertex 9"), std::string::npos) << said;
  EXPECT_NE(said.find("3 vertices"), std::string::npos) << said;
  // a good file is read as before
  EXPECT_EQ(
      ReadMeshFile(Write("fine.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -1\n")).triangles.size(),
      1u);
}

TEST_F(MeshFile, ABinaryStlCutShortSaysHowManyTrianglesItHolds) {
  // the header claims 1200 triangles, the file holds 37 (the cube's 12, over and over)
  std::string claims = CubeBinaryStl(1200);
  const std::string triangles = claims.substr(84);
  claims.resize(84);
  for (int k = 0; k < 37; ++k) claims += triangles.substr(50 * (k % 12), 50);
  EXPECT_EQ(ErrorFor("claims.stl", claims),
            "binary STL claims 1200 triangles but holds 37 (1934 bytes, where 1200 triangles "
            "take 60084); the file is truncated");
  // cut inside its 6th triangle, right after the header, and inside the header
  const std::string cube = CubeBinaryStl();
  EXPECT_EQ(ErrorFor("cut.stl", cube.substr(0, 84 + 5 * 50 + 20)),
            "binary STL claims 12 triangles but holds 5 and 20 bytes of the 6th (354 bytes, "
            "where 12 triangles take 684); the file is truncated");
  EXPECT_EQ(ErrorFor("header.stl", cube.substr(0, 84)),
            "binary STL claims 12 triangles but holds 0 (84 bytes, where 12 triangles take "
            "684); the file is truncated");
  EXPECT_EQ(ErrorFor("short.stl", cube.substr(0, 60)),
            "binary STL ends inside its 84-byte header (an 80-byte title and the triangle "
            "count): the file has 60 bytes; the file is truncated");
  // a binary file whose title starts with "solid" (some exporters write that) is still
  // binary: its NULs say so
  std::string solid_title = cube;
  solid_title.replace(0, 10, "solid cube");
  EXPECT_EQ(ErrorFor("solid_title.stl", solid_title.substr(0, 84 + 3 * 50)),
            "binary STL claims 12 triangles but holds 3 (234 bytes, where 12 triangles take "
            "684); the file is truncated");
  EXPECT_EQ(ReadMeshFile(Write("solid_title_whole.stl", solid_title)).triangles.size(), 12u);
}

TEST_F(MeshFile, ABinaryStlHoldingMoreThanItsCountIsRefusedNotCut) {
  // CGAL reads the count and drops the rest: the cube's 12 triangles under a count of 6
  // read as half a cube, under a count of 0 (some exporters write that) as no mesh
  EXPECT_EQ(ErrorFor("six.stl", CubeBinaryStl(6)),
            "binary STL claims 6 triangles but holds 12 (684 bytes, where 6 take 384); its "
            "header's count is wrong or the file was joined to another, and reading the count "
            "would drop the rest");
  EXPECT_EQ(ErrorFor("zero.stl", CubeBinaryStl(0)),
            "binary STL claims 0 triangles but holds 12 (684 bytes, where 0 take 84); its "
            "header's count is wrong or the file was joined to another, and reading the count "
            "would drop the rest");
  // bytes after the last triangle, fewer than one more, are padding: read as before
  EXPECT_EQ(
      ReadMeshFile(Write("padded.stl", CubeBinaryStl() + std::string(49, '\0'))).triangles.size(),
      12u);
}

TEST_F(MeshFile, ABinaryStlNanCornerIsRefusedBeforeCgalCanMergeItAway) {
  // every use of the cube's corner (1, 1, 1) made (nan, nan, nan): CGAL merged it into
  // another corner and the repair got 9 triangles of a different solid
  std::string stl = CubeBinaryStl();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::uint64_t first = 0;
  for (std::size_t t = 0; t < kCubeTriangles.size(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      if (kCubeTriangles[t][c] != 6) continue;
      if (first == 0) first = t + 1;
      for (std::size_t k = 0; k < 3; ++k) {
        std::memcpy(&stl[84 + 50 * t + 12 + 12 * c + 4 * k], &nan, sizeof nan);
      }
    }
  }
  ASSERT_GT(first, 0u);
  EXPECT_EQ(ErrorFor("nan_corner.stl", stl),
            "face " + std::to_string(first) +
                " has a vertex that is not finite (nan, nan, nan); every vertex needs three "
                "finite coordinates");
  // an infinite coordinate alike, in the last triangle
  std::string inf = CubeBinaryStl();
  const float infinity = std::numeric_limits<float>::infinity();
  std::memcpy(&inf[84 + 50 * 11 + 12 + 24 + 8], &infinity, sizeof infinity);
  const std::string said = ErrorFor("inf_corner.stl", inf);
  EXPECT_EQ(said.rfind("face 12 has a vertex that is not finite (", 0), 0u) << said;
  EXPECT_NE(said.find("inf)"), std::string::npos) << said;
}

TEST_F(MeshFile, AnAsciiStlCutShortSaysWhichFacetItEndsIn) {
  const std::string stl = CubeAsciiStl();
  // cut after the 2nd vertex of the 6th facet
  std::size_t at = 0;
  for (int k = 0; k < 5 * 3 + 2; ++k) at = stl.find("vertex", at) + 1;
  at = stl.find('\n', at);
  EXPECT_EQ(ErrorFor("cut.stl", stl.substr(0, at)),
            "ASCII STL ends inside its 6th facet (after 2 of its 3 vertices), with no "
            "'endsolid'; the file is truncated");
  // cut inside the 3rd vertex's coordinates: that vertex is not complete
  EXPECT_EQ(ErrorFor("cut_number.stl", stl.substr(0, at + 12)),
            "ASCII STL ends inside its 6th facet (after 2 of its 3 vertices), with no "
            "'endsolid'; the file is truncated");
  // every facet, no "endsolid"
  EXPECT_EQ(ErrorFor("no_end.stl", stl.substr(0, stl.find("endsolid"))),
            "ASCII STL ends after 12 facets with no 'endsolid'; the file is truncated");
  // shorter than a binary header: CGAL reads it as an empty file
  EXPECT_EQ(ErrorFor("short.stl", stl.substr(0, 40)),
            "ASCII STL ends inside its 1st facet (after 0 of its 3 vertices), with no "
            "'endsolid'; the file is truncated");
}

TEST_F(MeshFile, AnOffCutShortSaysWhatItDeclaredAndWhatItHolds) {
  const std::string off = CubeOff();
  // inside the 6th face's line, between two lines of faces, inside the vertices, inside
  // the counts
  EXPECT_EQ(ErrorFor("face.off", off.substr(0, off.find("3 4 6 7") + 4)),
            "OFF declares 8 vertices and 12 faces but holds 8 vertices and 3 faces (and part of "
            "the 4th face); the file is truncated");
  EXPECT_EQ(ErrorFor("line.off", off.substr(0, off.find("3 4 6 7"))),
            "OFF declares 8 vertices and 12 faces but holds 8 vertices and 3 faces; the file is "
            "truncated");
  EXPECT_EQ(ErrorFor("vertex.off", off.substr(0, off.find("1 1 1") + 2)),
            "OFF declares 8 vertices and 12 faces but holds 6 vertices and 0 faces (and part of "
            "the 7th vertex); the file is truncated");
  EXPECT_EQ(ErrorFor("counts.off", "OFF\n8 1"),
            "OFF ends inside its header (the vertex, face and edge counts); the file is "
            "truncated");
  // Windows line ends, the counts on the keyword's line
  EXPECT_EQ(ErrorFor("crlf.off", "OFF 3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1"),
            "OFF declares 3 vertices and 1 face but holds 3 vertices and 0 faces (and part of "
            "the 1st face); the file is truncated");
}

TEST_F(MeshFile, APlyCutShortSaysWhatItDeclaredAndWhatItHolds) {
  const std::string ascii = CubeAsciiPly();
  const std::size_t data = ascii.find("end_header\n") + 11;
  EXPECT_EQ(ErrorFor("face.ply", ascii.substr(0, ascii.find("3 4 6 7") + 4)),
            "PLY declares 8 vertices and 12 faces but holds 8 vertices and 3 faces (and part of "
            "the 4th face); the file is truncated");
  EXPECT_EQ(ErrorFor("data.ply", ascii.substr(0, data)),
            "PLY declares 8 vertices and 12 faces but holds 0 vertices and 0 faces; the file is "
            "truncated");
  EXPECT_EQ(ErrorFor("header.ply", ascii.substr(0, ascii.find("property list") + 11)),
            "PLY ends inside its header (no 'end_header' line); the file is truncated");
  const std::string binary = CubeBinaryPly();
  const std::size_t faces = binary.find("end_header\n") + 11 + 8 * 12;  // 8 vertices, 12 bytes
  EXPECT_EQ(ErrorFor("face_binary.ply", binary.substr(0, faces + 9 * 13 + 5)),
            "PLY declares 8 vertices and 12 faces but holds 8 vertices and 9 faces (and part of "
            "the 10th face); the file is truncated");
  EXPECT_EQ(ErrorFor("vertex_binary.ply", binary.substr(0, faces - 12 - 1)),
            "PLY declares 8 vertices and 12 faces but holds 6 vertices and 0 faces (and part of "
            "the 7th vertex); the file is truncated");
  EXPECT_EQ(ErrorFor("lines_binary.ply", binary.substr(0, faces + 12 * 13 - 13)),
            "PLY declares 8 vertices and 12 faces but holds 8 vertices and 11 faces; the file is "
            "truncated");
}

// Big-endian int32s, as binary OFF has them.
std::string BigEndian(std::initializer_list<std::int32_t> values) {
  std::string s;
  for (const std::int32_t v : values) {
    const auto u = static_cast<std::uint32_t>(v);
    for (int shift = 24; shift >= 0; shift -= 8) s += static_cast<char>(u >> shift & 0xff);
  }
  return s;
}

// CGAL sized a vector from each of these counts before reading what it counts: 48 GB for
// 2e9 faces or vertices, 8 TB for 1e12 corners, 16 GB for 2^31 - 1 (the old reader threw
// std::bad_alloc, or took minutes and all the memory). Refused from the file's size instead.
TEST_F(MeshFile, AnOffCountItsFileCannotHoldIsRefusedBeforeAnythingIsSizedFromIt) {
  std::string cube_vertices = CubeVertexAndFaceLines();
  cube_vertices.resize(cube_vertices.find("3 "));
  // one face where 2e9 are declared: the file is named as cut, as a shorter claim is
  EXPECT_EQ(ErrorFor("faces.off", "OFF\n8 2000000000 0\n" + cube_vertices + "3 0 2 1\n"),
            "OFF declares 8 vertices and 2000000000 faces but holds 8 vertices and 1 face; the "
            "file is truncated");
  EXPECT_EQ(ErrorFor("vertices.off", "OFF\n2000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "OFF declares 2000000000 vertices and 1 face but holds 4 vertices and 0 faces; the "
            "file is truncated");
  // where the records cannot be counted, what the counts take against what the file has
  EXPECT_EQ(ErrorFor("skeleton.off", "SKEL\n2000000000 1\n0 0 0\n"),
            "SKEL declares 2000000000 vertices and 1 face, which take at least 12000000001 bytes, "
            "but the file has 7 after its header; its counts are wrong or it is truncated");
  std::string binary_vertices;
  for (const Vec3& v : kCubeVertices) {
    for (int k = 0; k < 3; ++k) {
      float f = static_cast<float>(v[k]);
      std::int32_t bits = 0;
      std::memcpy(&bits, &f, sizeof bits);
      binary_vertices += BigEndian({bits});
    }
  }
  const std::string binary = "OFF BINARY\n" + BigEndian({8, 2000000000, 0}) + binary_vertices;
  EXPECT_EQ(ErrorFor("faces_binary.off", binary + BigEndian({3, 0, 2, 1})),
            "OFF declares 8 vertices and 2000000000 faces, which take at least 8000000096 bytes, "
            "but the file has 112 after its header; its counts are wrong or it is truncated");
  // a face's corner count
  EXPECT_EQ(ErrorFor("corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000000 0 1 2\n"),
            "line 6: face 1 declares 1000000000000 corners, more than the file's 48 bytes can "
            "hold (a corner takes at least 2)");
  const std::string one_face = "OFF BINARY\n" + BigEndian({8, 1, 0}) + binary_vertices;
  EXPECT_EQ(ErrorFor("corners_binary.off", one_face + BigEndian({2147483647, 0, 2, 1})),
            "face 1 declares 2147483647 corners, more than the file's 135 bytes can hold (a "
            "corner takes at least 4)");
  // the same files with what they declare are read
  EXPECT_EQ(
      ReadMeshFile(Write("face_binary.off", one_face + BigEndian({3, 0, 2, 1}))).triangles.size(),
      1u);
  EXPECT_EQ(ReadMeshFile(Write("corners_fit.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2"))
                .triangles.size(),
            1u);
}

TEST_F(MeshFile, APlyCountItsFileCannotHoldIsRefusedBeforeAnythingIsSizedFromIt) {
  const std::string ascii = CubeAsciiPly();
  std::string claims = ascii;
  claims.replace(claims.find("vertex 8"), 8, "vertex 2000000000");
  EXPECT_EQ(ErrorFor("vertices.ply", claims),
            "PLY declares 2000000000 vertices and 12 faces but holds 24 vertices and 0 faces; "
            "the file is truncated");
  std::string binary = CubeBinaryPly();
  binary.replace(binary.find("face 12"), 7, "face 2000000000");
  EXPECT_EQ(ErrorFor("faces_binary.ply", binary),
            "PLY declares 8 vertices and 2000000000 faces but holds 8 vertices and 12 faces; the "
            "file is truncated");
  // a vertex element with no property: CGAL made a point of each of its items
  const std::string bare =
      "ply\nformat ascii 1.0\nelement vertex 2000000000\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n3 0 1 2\n";
  EXPECT_EQ(ErrorFor("bare.ply", bare),
            "PLY declares 2000000000 vertices with no property, more than the 8 bytes after its "
            "header; its counts are wrong");
  // a list's count, with a count type that can claim more than a file holds
  std::string wide = ascii;
  wide.replace(wide.find("list uchar int"), 14, "list uint int");
  std::string uint_count = wide;
  uint_count.replace(uint_count.find("\n3 4 5 6\n") + 1, 1, "4294967295");
  EXPECT_EQ(ErrorFor("list.ply", uint_count),
            "PLY's 3rd face declares 4294967295 items in its list 'vertex_indices', more than the "
            "153 bytes after its header can hold (an item takes at least 2)");
  std::string int_binary = PlyHeader("binary_big_endian");
  int_binary.replace(int_binary.find("list uchar int"), 14, "list int int");
  for (const Vec3& v : kCubeVertices) {
    for (int k = 0; k < 3; ++k) {
      float f = static_cast<float>(v[k]);
      std::int32_t bits = 0;
      std::memcpy(&bits, &f, sizeof bits);
      int_binary += BigEndian({bits});
    }
  }
  std::string faces;
  for (const auto& t : kCubeTriangles) faces += BigEndian({3, t[0], t[1], t[2]});
  EXPECT_EQ(ReadMeshFile(Write("int_binary.ply", int_binary + faces)).triangles.size(), 12u);
  EXPECT_EQ(
      ErrorFor("list_binary.ply", int_binary + BigEndian({2147483647, 0, 2, 1}) + faces.substr(16)),
      "PLY's 1st face declares 2147483647 items in its list 'vertex_indices', more than the "
      "288 bytes after its header can hold (an item takes at least 4)");
  EXPECT_EQ(ErrorFor("negative_binary.ply", int_binary + faces.substr(0, 16) +
                                                BigEndian({-5, 0, 2, 1}) + faces.substr(32)),
            "PLY's 2nd face declares -5 items in its list 'vertex_indices'; a count cannot be "
            "negative");
  EXPECT_EQ(ReadMeshFile(Write("wide.ply", wide)).triangles.size(), 12u);
}

TEST_F(MeshFile, AnObjCutInsideALineIsRefusedAndOneCutBetweenLinesIsNot) {
  const std::string obj = CubeObj();
  // CGAL took these, dropping the face or vertex that was cut
  EXPECT_EQ(ErrorFor("face.obj", obj.substr(0, obj.find("f 1 2 6") + 5)),
            "OBJ ends inside a face: its last line 'f 1 2' names 2 corners (a face has at least "
            "3); the file is truncated");
  EXPECT_EQ(ErrorFor("bare_f.obj", obj.substr(0, obj.find("f 1 2 6") + 1)),
            "OBJ ends inside a face: its last line 'f' names 0 corners (a face has at least 3); "
            "the file is truncated");
  EXPECT_EQ(ErrorFor("vertex.obj", obj.substr(0, obj.find("v 1 1 1") + 5)),
            "OBJ ends inside a vertex: its last line 'v 1 1' has 2 of the 3 coordinates; the "
            "file is truncated");
  // cut before its faces: CGAL refuses it without a word
  EXPECT_EQ(ErrorFor("no_faces.obj", obj.substr(0, obj.find('f'))),
            "OBJ has 8 vertices ('v' lines) but no face ('f' line): a point cloud, or a file "
            "cut off before its faces");
  // OBJ declares no counts: cut between two lines it is a smaller mesh, and a last line
  // without a line end is a whole one
  EXPECT_EQ(ReadMeshFile(Write("lines.obj", obj.substr(0, obj.find("f 1 2 6")))).triangles.size(),
            4u);
  const std::string no_end = obj.substr(0, obj.size() - 1);
  EXPECT_EQ(ReadMeshFile(Write("no_end.obj", no_end)).triangles.size(), 12u);
  EXPECT_EQ(ReadMeshFile(Write("slashes.obj", no_end + "\nf 1/1/1 3/1/1 2/1/1")).triangles.size(),
            13u);
}

}  // namespace
}  // namespace hapticad
