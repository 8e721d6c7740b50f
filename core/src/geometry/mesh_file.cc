// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL translation unit (walled off in hapticad_cgal).
#include "hapticad/core/geometry/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

namespace hapticad {
namespace {

constexpr const char* kFiniteVertices = "every vertex needs three finite coordinates";

// CGAL refuses a text mesh with a coordinate such as nan or inf without saying where:
// the first line (1-based) holding a number that is not finite, and that number; 0 when
// there is none or the file is not text.
std::size_t FindNonFiniteLine(const std::string& path, std::string* token) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.find('\0') != std::string::npos) return 0;  // binary
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    // names, comments and (STL) normals are not vertices
    if (word[0] == '#' || word == "o" || word == "g" || word == "usemtl" || word == "mtllib" ||
        word == "solid" || word == "endsolid" || word == "facet" || word == "comment" ||
        word == "obj_info" || word == "element" || word == "property" || word == "format")
      continue;
    do {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end != word.c_str() && *end == '\0' && !std::isfinite(v)) {
        *token = word;
        return number;
      }
    } while (words >> word);
  }
  return 0;
}

// Truncated files. CGAL answers a file that ends early with a bare `false` (or, for a short STL or
// an OBJ cut inside a line, quietly with fewer faces). Where a format says how much it holds (OFF's
// and PLY's counts, binary STL's triangle count) or how a record ends (ASCII STL's keywords, OBJ's
// lines), the file is read again to name what is missing.

constexpr const char* kTruncated = "; the file is truncated";

// The extension CGAL picks the reader by: after the last '.', lowercased.
std::string Extension(const std::string& path) {
  const std::size_t dot = path.rfind('.');
  if (dot == std::string::npos) return {};
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The file's first `limit` bytes (all of it by default).
std::string ReadBytes(const std::string& path, std::size_t limit = std::string::npos) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes;
  std::istreambuf_iterator<char> it(in), end;
  for (; it != end && bytes.size() < limit; ++it) bytes.push_back(*it);
  return bytes;
}

std::vector<std::string> Words(const std::string& text) {
  std::istringstream in(text);
  return std::vector<std::string>(std::istream_iterator<std::string>(in),
                                  std::istream_iterator<std::string>());
}

bool IsNumber(const std::string& word) {
  char* end = nullptr;
  std::strtod(word.c_str(), &end);
  return !word.empty() && end != word.c_str() && *end == '\0';
}

// "1st", "2nd", "3rd", "4th", ... "11th", "12th", "13th", "21st"
std::string Ordinal(std::uint64_t n) {
  const char* suffix = "th";
  if (n % 100 < 11 || n % 100 > 13) {
    if (n % 10 == 1) suffix = "st";
    if (n % 10 == 2) suffix = "nd";
    if (n % 10 == 3) suffix = "rd";
  }
  return std::to_string(n) + suffix;
}

// "8 vertices", "1 face", "3 'edge' elements"
std::string Counted(std::uint64_t n, const std::string& element) {
  std::string noun;
  if (element == "vertex") {
    noun = n == 1 ? "vertex" : "vertices";
  } else if (element == "face") {
    noun = n == 1 ? "face" : "faces";
  } else {
    noun = "'" + element + (n == 1 ? "' element" : "' elements");
  }
  return std::to_string(n) + " " + noun;
}

// How many of each element a file declares and how many it holds: "declares 8 vertices
// and 12 faces but holds 8 vertices and 5 faces (and part of the 6th face)". `partial`:
// the element after the last complete one was begun.
std::string DeclaresButHolds(const std::string& format, const std::vector<std::string>& names,
                             const std::vector<std::uint64_t>& declared,
                             const std::vector<std::uint64_t>& held, bool partial) {
  std::string said = format + " declares ";
  std::string has = " but holds ";
  std::string part;
  for (std::size_t e = 0; e < names.size(); ++e) {
    const std::string sep = e == 0 ? "" : e + 1 == names.size() ? " and " : ", ";
    said += sep + Counted(declared[e], names[e]);
    has += sep + Counted(held[e], names[e]);
    if (partial && part.empty() && held[e] < declared[e]) {
      part =
          " (and part of the " + Ordinal(held[e] + 1) + " " + Counted(1, names[e]).substr(2) + ")";
    }
  }
  return said + has + part + kTruncated;
}

// Binary STL: an 80-byte title, a 32-bit little-endian triangle count, 50 bytes a triangle.
// `head`: at least the file's first 84 bytes, when it has them.
std::string DescribeCutBinaryStl(const std::string& head, std::uint64_t size) {
  constexpr std::uint64_t kHeader = 84;
  constexpr std::uint64_t kTriangle = 50;
  if (size < kHeader) {
    return "binary STL ends inside its 84-byte header (an 80-byte title and the triangle "
           "count): the file has " +
           std::to_string(size) + " bytes" + kTruncated;
  }
  std::uint64_t claimed = 0;
  for (int k = 3; k >= 0; --k) claimed = claimed << 8 | static_cast<unsigned char>(head[80 + k]);
  const std::uint64_t needed = kHeader + kTriangle * claimed;
  if (size >= needed) return {};
  const std::uint64_t held = (size - kHeader) / kTriangle;
  const std::uint64_t rest = (size - kHeader) % kTriangle;
  std::string out = "binary STL claims " + std::to_string(claimed) + " triangles but holds " +
                    std::to_string(held);
  if (rest != 0) {
    out += " and " + std::to_string(rest) + " bytes of the " + Ordinal(held + 1);
  }
  return out + " (" + std::to_string(size) + " bytes, where " + std::to_string(claimed) +
         " triangles take " + std::to_string(needed) + ")" + kTruncated;
}

// ASCII STL: "solid name", then per facet "facet normal x y z outer loop", three "vertex
// x y z", "endloop endfacet", and "endsolid". Empty when it is not cut off.
std::string DescribeCutAsciiStl(const std::string& bytes) {
  const std::vector<std::string> words = Words(bytes);
  std::uint64_t facets = 0;
  int vertices = 0;  // complete in the facet begun
  bool in_facet = false;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (words[i] == "endsolid") return {};
    if (words[i] == "facet") {
      in_facet = true;
      vertices = 0;
    } else if (words[i] == "endfacet") {
      in_facet = false;
      ++facets;
    } else if (words[i] == "vertex" && i + 3 < words.size() && IsNumber(words[i + 1]) &&
               IsNumber(words[i + 2]) && IsNumber(words[i + 3])) {
      ++vertices;
      i += 3;
    }
  }
  if (in_facet) {
    return "ASCII STL ends inside its " + Ordinal(facets + 1) + " facet (after " +
           std::to_string(vertices) + " of its 3 vertices), with no 'endsolid'" + kTruncated;
  }
  return "ASCII STL ends after " + std::to_string(facets) + " facet" + (facets == 1 ? "" : "s") +
         " with no 'endsolid'" + kTruncated;
}

// As CGAL reads it: ASCII when the first word is "solid"; but a binary file's title may
// start with "solid" too, and its data has NULs where ASCII STL has none.
bool IsAsciiStl(const std::string& head) {
  const std::vector<std::string> first = Words(head.substr(0, 64));
  return !first.empty() && first[0] == "solid" && head.find('\0') == std::string::npos;
}

std::string DescribeCutStl(const std::string& path) {
  const std::string head = ReadBytes(path, 4096);
  if (IsAsciiStl(head)) return DescribeCutAsciiStl(ReadBytes(path));
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  return error ? std::string() : DescribeCutBinaryStl(head, size);
}

// "PATH: face 3 has a vertex that is not finite (0, nan, 1); every vertex needs ..."
std::string NonFiniteVertex(const std::string& path, std::uint64_t face, const Vec3& v) {
  std::ostringstream where;
  where << path << ": face " << face << " has a vertex that is not finite (" << v.x() << ", "
        << v.y() << ", " << v.z() << "); " << kFiniteVertices;
  return where.str();
}

// Binary STL has no shared vertices: CGAL merges equal corners into one, and a NaN corner,
// which compares neither less nor greater, can be merged into another and vanish, leaving
// a mesh quietly different from the file. So the file is checked before CGAL reads it:
// every corner finite, and no more triangles after the count than the count says (CGAL
// reads the count and drops the rest; some exporters write a count of 0). A file shorter
// than its count is left to CGAL, which refuses it (DescribeCutBinaryStl says why).
void CheckBinaryStl(const std::string& path) {
  constexpr std::size_t kHeader = 84, kTriangle = 50;
  const std::string head = ReadBytes(path, 4096);
  if (IsAsciiStl(head) || head.size() < kHeader) return;
  std::ifstream in(path, std::ios::binary);
  in.seekg(80);
  unsigned char count[4];
  in.read(reinterpret_cast<char*>(count), 4);
  const std::uint64_t claimed = std::uint64_t{count[0]} | std::uint64_t{count[1]} << 8 |
                                std::uint64_t{count[2]} << 16 | std::uint64_t{count[3]} << 24;
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(path, error);
  if (error) return;
  const std::uint64_t whole = (size - kHeader) / kTriangle;
  if (whole > claimed) {
    throw std::runtime_error(
        path + ": binary STL claims " + std::to_string(claimed) + " triangle" +
        (claimed == 1 ? "" : "s") + " but holds " + std::to_string(whole) + " (" +
        std::to_string(size) + " bytes, where " + std::to_string(claimed) + " take " +
        std::to_string(kHeader + kTriangle * claimed) +
        "); its header's count is wrong or the file was joined to another, and reading the "
        "count would drop the rest");
  }
  // the corners of the triangles CGAL will read, a block at a time
  std::vector<char> block(kTriangle * 4096);
  for (std::uint64_t first = 0; first < std::min(claimed, whole); first += 4096) {
    const std::uint64_t n = std::min<std::uint64_t>(4096, std::min(claimed, whole) - first);
    in.read(block.data(), static_cast<std::streamsize>(n * kTriangle));
    if (!in) return;
    for (std::uint64_t t = 0; t < n; ++t) {
      float xyz[9];  // after the facet's normal (3 floats)
      std::memcpy(xyz, block.data() + t * kTriangle + 12, sizeof xyz);
      for (int c = 0; c < 3; ++c) {
        const Vec3 v(xyz[3 * c], xyz[3 * c + 1], xyz[3 * c + 2]);
        if (!v.allFinite()) throw std::runtime_error(NonFiniteVertex(path, first + t + 1, v));
      }
    }
  }
}

// OFF: "OFF", the vertex, face and edge counts, then a vertex a line (3 coordinates, or
// more in the COFF/NOFF variants) and a face a line (its vertex count, the indices, maybe
// a colour). Empty when the file is not cut off, or is not plain ASCII OFF.
std::string DescribeCutOff(const std::string& bytes) {
  std::vector<std::vector<std::string>> lines;  // words of each line with any, no comments
  std::istringstream in(bytes);
  std::string line;
  while (std::getline(in, line)) {
    const std::vector<std::string> words = Words(line.substr(0, line.find('#')));
    if (!words.empty()) lines.push_back(words);
  }
  if (lines.empty()) return {};
  const std::string& keyword = lines[0][0];
  if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0 ||
      keyword.find_first_of("n4") != std::string::npos) {
    return {};  // not OFF, or the n-dimensional variants
  }
  // the three counts follow the keyword, on its line or the next ones
  std::vector<std::uint64_t> counts;
  std::size_t record = 0;  // the first line after the counts
  std::size_t word = 1;
  for (; record < lines.size() && counts.size() < 3; ++record, word = 0) {
    for (; word < lines[record].size() && counts.size() < 3; ++word) {
      if (lines[record][word] == "BINARY") return {};
      char* end = nullptr;
      const unsigned long long n = std::strtoull(lines[record][word].c_str(), &end, 10);
      if (*end != '\0') return {};
      counts.push_back(n);
    }
  }
  if (counts.size() < 3) {
    return "OFF ends inside its header (the vertex, face and edge counts)" +
           std::string(kTruncated);
  }
  const std::uint64_t num_vertices = counts[0], num_faces = counts[1];
  std::uint64_t complete = 0;
  bool partial = false;
  for (; record < lines.size(); ++record) {
    const auto& words = lines[record];
    bool whole = false;
    if (complete < num_vertices) {
      whole = words.size() >= 3;
    } else {
      char* end = nullptr;
      const unsigned long long corners = std::strtoull(words[0].c_str(), &end, 10);
      whole = *end == '\0' && words.size() >= 1 + corners;
    }
    if (!whole) {
      if (record + 1 != lines.size()) return {};  // malformed inside: not a cut
      partial = true;
      break;
    }
    ++complete;
  }
  if (complete >= num_vertices + num_faces) return {};
  const std::uint64_t vertices = std::min(complete, num_vertices);
  return DeclaresButHolds("OFF", {"vertex", "face"}, {num_vertices, num_faces},
                          {vertices, complete - vertices}, partial);
}

// PLY: a header ("ply", "format ...", "element NAME COUNT" each followed by its
// "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME" lines, "end_header"),
// then the elements in order, ASCII or binary.
struct PlyProperty {
  int count_bytes = 0;  // a list's count type; 0 for a scalar
  int bytes = 0;        // the scalar's (or each list item's) size
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

int PlyTypeBytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

std::string DescribeCutPly(const std::string& bytes) {
  std::size_t at = 0;
  std::string format;
  std::vector<PlyElement> elements;
  bool header_ended = false;
  bool first = true;
  while (at < bytes.size()) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    const std::vector<std::string> words = Words(bytes.substr(at, end - at));
    // a header line that makes no sense is a malformed file, unless the file ends in it
    const bool last = end == bytes.size();
    at = std::min(end + 1, bytes.size());
    if (first) {
      if (words.empty() || words[0] != "ply") return {};
      first = false;
      continue;
    }
    if (words.empty()) continue;
    if (words[0] == "end_header") {
      header_ended = true;
      break;
    }
    bool understood = true;
    if (words[0] == "format" && words.size() >= 2) {
      format = words[1];
    } else if (words[0] == "element") {
      char* stop = nullptr;
      PlyElement e;
      if (words.size() >= 3) {
        e.name = words[1];
        e.count = std::strtoull(words[2].c_str(), &stop, 10);
      }
      understood = stop != nullptr && *stop == '\0';
      elements.push_back(e);
    } else if (words[0] == "property" && !elements.empty()) {
      PlyProperty p;
      if (words.size() >= 5 && words[1] == "list") {
        p.count_bytes = PlyTypeBytes(words[2]);
        p.bytes = PlyTypeBytes(words[3]);
      } else if (words.size() >= 3 && words[1] != "list") {
        p.bytes = PlyTypeBytes(words[1]);
      }
      understood = p.bytes != 0 && (words[1] != "list" || p.count_bytes != 0);
      elements.back().properties.push_back(p);
    }
    if (!understood && !last) return {};
  }
  if (first) return {};
  if (!header_ended)
    return "PLY ends inside its header (no 'end_header' line)" + std::string(kTruncated);
  const bool ascii = format == "ascii";
  const bool big_endian = format == "binary_big_endian";
  if (!ascii && !big_endian && format != "binary_little_endian") return {};
  std::vector<std::string> words;  // ASCII: the data's words
  std::size_t next = 0;
  if (ascii) {
    words = Words(bytes.substr(at));
    // a word that is not a number is a malformed file, not a cut one
    if (!std::all_of(words.begin(), words.end(), IsNumber)) return {};
  }
  // reads one count (an ASCII word or a binary integer); false at the end of the data
  const auto read_count = [&](int count_bytes, std::uint64_t* n) {
    if (ascii) {
      if (next >= words.size()) return false;
      char* stop = nullptr;
      *n = std::strtoull(words[next++].c_str(), &stop, 10);
      return *stop == '\0';
    }
    if (bytes.size() - at < static_cast<std::size_t>(count_bytes)) return false;
    *n = 0;
    for (int k = 0; k < count_bytes; ++k) {
      const int byte = big_endian ? k : count_bytes - 1 - k;
      *n = *n << 8 | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(byte)]);
    }
    at += static_cast<std::size_t>(count_bytes);
    return true;
  };
  const auto skip = [&](std::uint64_t items, int item_bytes) {
    if (ascii) {
      if (words.size() - next < items) return false;
      next += static_cast<std::size_t>(items);
      return true;
    }
    if ((bytes.size() - at) / static_cast<std::size_t>(item_bytes) < items) return false;
    at += static_cast<std::size_t>(items) * static_cast<std::size_t>(item_bytes);
    return true;
  };
  std::vector<std::string> names;
  std::vector<std::uint64_t> declared, held;
  bool cut = false, partial = false;
  for (const PlyElement& e : elements) {
    names.push_back(e.name);
    declared.push_back(e.count);
    held.push_back(0);
    for (std::uint64_t i = 0; !cut && i < e.count; ++i) {
      const std::size_t at_start = at, next_start = next;
      for (const PlyProperty& p : e.properties) {
        std::uint64_t items = 1;
        if (p.count_bytes != 0 && !read_count(p.count_bytes, &items)) {
          cut = true;
          break;
        }
        if (!skip(items, p.bytes)) {
          cut = true;
          break;
        }
      }
      if (cut) {
        partial = ascii ? next_start < words.size() : at_start < bytes.size();
        break;
      }
      ++held.back();
    }
  }
  if (!cut) return {};
  return DeclaresButHolds("PLY", names, declared, held, partial);
}

// OBJ says nothing of how much it holds: a file cut between lines cannot be told from
// a whole one. A cut inside its last line leaves a vertex with fewer than 3 coordinates
// or a face with fewer than 3 corners (which CGAL takes, and which become no triangle).
std::string DescribeCutObjLine(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in.tellg();
  if (size <= 0) return {};
  const std::streamoff tail = std::min<std::streamoff>(size, 4096);
  in.seekg(size - tail);
  std::string text(static_cast<std::size_t>(tail), '\0');
  in.read(text.data(), tail);
  if (text.back() == '\n' || text.back() == '\r') return {};  // ends with a whole line
  const std::size_t start = text.find_last_of("\r\n");
  const std::string last = text.substr(start == std::string::npos ? 0 : start + 1);
  const std::vector<std::string> words = Words(last);
  if (words.empty()) return {};
  std::size_t numbers = 0;
  while (numbers + 1 < words.size() &&
         IsNumber(words[numbers + 1].substr(0, words[numbers + 1].find('/')))) {
    ++numbers;
  }
  if (words[0] == "v" && numbers < 3) {
    return "OBJ ends inside a vertex: its last line '" + last + "' has " + std::to_string(numbers) +
           " of the 3 coordinates" + kTruncated;
  }
  if (words[0] == "f" && numbers < 3) {
    return "OBJ ends inside a face: its last line '" + last + "' names " + std::to_string(numbers) +
           " corner" + (numbers == 1 ? "" : "s") + " (a face has at least 3)" + kTruncated;
  }
  return {};
}

// An OBJ CGAL refused: cut before its faces (vertices and no 'f' line)?
std::string DescribeObjWithoutFaces(const std::string& bytes) {
  std::istringstream in(bytes);
  std::string line;
  std::uint64_t vertices = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> words = Words(line);
    if (words.empty()) continue;
    if (words[0] == "f") return {};
    if (words[0] == "v") ++vertices;
  }
  if (vertices == 0) return {};
  return "OBJ has " + Counted(vertices, "vertex") +
         " ('v' lines) but no face ('f' line): a point cloud, or a file cut off before "
         "its faces";
}

// What a file of a format that says how much it holds is missing; empty when nothing is
// or the format cannot tell.
std::string DescribeTruncation(const std::string& path) {
  const std::string ext = Extension(path);
  if (ext == "obj") {
    const std::string line = DescribeCutObjLine(path);
    return line.empty() ? DescribeObjWithoutFaces(ReadBytes(path)) : line;
  }
  if (ext == "stl") return DescribeCutStl(path);
  if (ext == "off") return DescribeCutOff(ReadBytes(path));
  if (ext == "ply") return DescribeCutPly(ReadBytes(path));
  return {};
}

// The first face of an OBJ or OFF that names a vertex the file does not have (CGAL
// refuses most such files without saying why, and lets an OBJ index one past the last
// vertex through): "line L: face F names vertex V, but the file has N vertices"; empty
// when there is none or the format is another.
std::string DescribeBadIndex(const std::string& path) {
  const std::string ext = Extension(path);
  std::istringstream in(ReadBytes(path));
  std::string line;
  std::uint64_t number = 0;
  std::uint64_t face = 0;
  const auto bad = [&](const std::string& index, std::int64_t vertices) {
    return "line " + std::to_string(number) + ": face " + std::to_string(face) + " names vertex " +
           index + ", but the file has " +
           Counted(static_cast<std::uint64_t>(std::max<std::int64_t>(vertices, 0)), "vertex") +
           (ext == "obj" ? " before it (OBJ counts from 1; -1 is the last)"
                         : " (OFF counts from 0)");
  };
  if (ext == "obj") {
    std::int64_t vertices = 0;
    while (std::getline(in, line)) {
      ++number;
      const std::vector<std::string> words = Words(line);
      if (words.empty()) continue;
      if (words[0] == "v") ++vertices;
      if (words[0] != "f") continue;
      ++face;
      for (std::size_t k = 1; k < words.size(); ++k) {
        const std::string index = words[k].substr(0, words[k].find('/'));
        char* end = nullptr;
        const long long i = std::strtoll(index.c_str(), &end, 10);
        if (*end != '\0') return {};  // not a number: not this kind of fault
        const long long resolved = i < 0 ? vertices + i + 1 : i;
        if (i == 0 || resolved < 1 || resolved > vertices) return bad(index, vertices);
      }
    }
    return {};
  }
  if (ext != "off") return {};
  std::vector<std::pair<std::uint64_t, std::vector<std::string>>> lines;  // number, words
  while (std::getline(in, line)) {
    ++number;
    std::vector<std::string> words = Words(line.substr(0, line.find('#')));
    if (!words.empty()) lines.emplace_back(number, std::move(words));
  }
  if (lines.empty()) return {};
  const std::string& keyword = lines[0].second[0];
  if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0 ||
      keyword.find_first_of("n4") != std::string::npos) {
    return {};
  }
  std::vector<std::uint64_t> counts;  // after the keyword, on its line or the next ones
  std::size_t record = 0;
  for (std::size_t word = 1; record < lines.size() && counts.size() < 3; ++record, word = 0) {
    for (; word < lines[record].second.size() && counts.size() < 3; ++word) {
      char* end = nullptr;
      counts.push_back(std::strtoull(lines[record].second[word].c_str(), &end, 10));
      if (*end != '\0') return {};
    }
  }
  if (counts.size() < 3) return {};
  const std::uint64_t vertices = counts[0];
  for (std::size_t r = record + vertices; r < lines.size(); ++r) {
    const auto& [at, words] = lines[r];
    number = at;
    ++face;
    const unsigned long long corners = std::strtoull(words[0].c_str(), nullptr, 10);
    for (std::size_t k = 1; k < words.size() && k <= corners; ++k) {
      char* end = nullptr;
      const unsigned long long i = std::strtoull(words[k].c_str(), &end, 10);
      if (*end != '\0' || words[k][0] == '-' || i >= vertices) {
        return bad(words[k], static_cast<std::int64_t>(vertices));
      }
    }
  }
  return {};
}

}  // namespace

TriangleSoup ReadMeshFile(const std::string& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw std::runtime_error(path + ": no such file");
  if (std::filesystem::is_directory(status)) {
    throw std::runtime_error(path +
                             ": is a folder, not a mesh file (give an OFF, OBJ, STL or PLY file)");
  }
  if (!std::ifstream(path, std::ios::binary)) {
    throw std::runtime_error(path + ": cannot be opened (" + std::strerror(errno) + ")");
  }
  if (std::filesystem::file_size(path, error) == 0 && !error) {
    throw std::runtime_error(path + ": the file is empty");
  }
  if (Extension(path) == "stl") CheckBinaryStl(path);
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false))) {
    std::string token;
    if (const std::size_t line = FindNonFiniteLine(path, &token)) {
      throw std::runtime_error(path + ": line " + std::to_string(line) + ": '" + token +
                               "' is not a finite number; " + kFiniteVertices);
    }
    const std::string cut = DescribeTruncation(path);
    if (!cut.empty()) throw std::runtime_error(path + ": " + cut);
    const std::string index = DescribeBadIndex(path);
    if (!index.empty()) throw std::runtime_error(path + ": " + index);
    throw std::runtime_error(path + ": cannot read a mesh (OFF, OBJ, STL or PLY expected)");
  }
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    for (const std::size_t v : polygons[f]) {
      if (v >= points.size()) {  // CGAL let it through (an OBJ index one past the last)
        const std::string index = DescribeBadIndex(path);
        throw std::runtime_error(
            path + ": " +
            (index.empty()
                 ? "face " + std::to_string(f + 1) + " names vertex " + std::to_string(v) +
                       " (counting from 0), but the file has " + Counted(points.size(), "vertex")
                 : index));
      }
    }
  }
  // CGAL takes an OBJ cut inside its last line, dropping what was cut
  if (Extension(path) == "obj") {
    const std::string cut = DescribeCutObjLine(path);
    if (!cut.empty()) throw std::runtime_error(path + ": " + cut);
  }
  TriangleSoup soup;
  soup.vertices.reserve(points.size());
  for (const Point& p : points) soup.vertices.emplace_back(p.x(), p.y(), p.z());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& polygon = polygons[f];
    // a binary file reads any bit pattern as a number: said as the text formats say it
    for (const std::size_t v : polygon) {
      if (v < soup.vertices.size() && !soup.vertices[v].allFinite()) {
        throw std::runtime_error(NonFiniteVertex(path, f + 1, soup.vertices[v]));
      }
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      soup.triangles.push_back({static_cast<std::int32_t>(polygon[0]),
                                static_cast<std::int32_t>(polygon[k]),
                                static_cast<std::int32_t>(polygon[k + 1])});
    }
  }
  if (soup.triangles.empty()) {
    // CGAL reads an STL shorter than a binary header as an empty one
    const std::string cut = DescribeTruncation(path);
    throw std::runtime_error(path + ": " + (cut.empty() ? "the mesh has no faces" : cut));
  }
  soup.cad_faces.assign(soup.triangles.size(), 0);
  return soup;
}

}  // namespace hapticad
