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
#include <limits>
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
  std::string name;
  std::string count_type;  // a list's; empty for a scalar
  int count_bytes = 0;     // a list's count type's size; 0 for a scalar
  int bytes = 0;           // the scalar's (or each list item's) size
  std::string type;        // the scalar's (or each list item's)
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  bool ended = false;       // "end_header" was read
  std::size_t data_at = 0;  // the byte after "end_header"'s line
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

// The header at the start of `bytes`; false when they are no PLY, or a header line before
// the last of `bytes` makes no sense (a malformed file, not a cut one).
bool ReadPlyHeader(const std::string& bytes, PlyHeader* header) {
  std::size_t at = 0;
  bool first = true;
  while (at < bytes.size()) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    const std::vector<std::string> words = Words(bytes.substr(at, end - at));
    const bool last = end == bytes.size();
    at = std::min(end + 1, bytes.size());
    if (first) {
      if (words.empty() || words[0] != "ply") return false;
      first = false;
      continue;
    }
    if (words.empty()) continue;
    if (words[0] == "end_header") {
      header->ended = true;
      break;
    }
    bool understood = true;
    if (words[0] == "format" && words.size() >= 2) {
      header->format = words[1];
    } else if (words[0] == "element") {
      char* stop = nullptr;
      PlyElement e;
      if (words.size() >= 3) {
        e.name = words[1];
        e.count = std::strtoull(words[2].c_str(), &stop, 10);
      }
      understood = stop != nullptr && *stop == '\0';
      header->elements.push_back(e);
    } else if (words[0] == "property" && !header->elements.empty()) {
      PlyProperty p;
      if (words.size() >= 5 && words[1] == "list") {
        p.count_type = words[2];
        p.count_bytes = PlyTypeBytes(words[2]);
        p.type = words[3];
        p.name = words[4];
      } else if (words.size() >= 3 && words[1] != "list") {
        p.type = words[1];
        p.name = words[2];
      }
      p.bytes = PlyTypeBytes(p.type);
      understood = p.bytes != 0 && (words[1] != "list" || p.count_bytes != 0);
      header->elements.back().properties.push_back(p);
    }
    if (!understood && !last) return false;
  }
  header->data_at = at;
  return !first;
}

std::string DescribeCutPly(const std::string& bytes) {
  PlyHeader header;
  if (!ReadPlyHeader(bytes, &header)) return {};
  if (!header.ended)
    return "PLY ends inside its header (no 'end_header' line)" + std::string(kTruncated);
  const std::string& format = header.format;
  const std::vector<PlyElement>& elements = header.elements;
  std::size_t at = header.data_at;
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

// Counts no file of its size holds. CGAL sizes its vectors from what a file declares before
// it reads what was declared: OFF's vertex and face counts (a 150-byte OFF declaring 1e9
// faces took a minute and 23 GB before CGAL found it short), each OFF face's corner count and
// each PLY list's length (2e9: a vector of 16 or 8 GB), and a PLY 'vertex' element's count (a
// point an item, even with no property to read). So each is checked first against the file's
// size, at the fewest bytes an item can take there. No file CGAL reads is refused but one
// whose element without properties has more items than the file has bytes (CGAL would loop
// over them all, making a point of each vertex).

constexpr std::size_t kHeadBytes = 65536;  // a longer header is left unchecked
constexpr std::uint64_t kMaxBytes = std::numeric_limits<std::uint64_t>::max();

// a * b + c, at most the largest uint64 (the counts come from files)
std::uint64_t MulAdd(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  if (b != 0 && a > (kMaxBytes - c) / b) return kMaxBytes;
  return a * b + c;
}

// A file whose counts need more bytes than it has: what it holds, where that can be counted
// ("OFF declares 8 vertices and 1000000000 faces but holds 8 vertices and 1 face; the file is
// truncated"), else "OFF declares ..., which take at least N bytes, but the file has M after
// its header; its counts are wrong or it is truncated".
std::string BeyondSize(const std::string& path, const std::string& format,
                       const std::vector<std::string>& names,
                       const std::vector<std::uint64_t>& counts, std::uint64_t needed,
                       std::uint64_t have) {
  const std::string cut = DescribeTruncation(path);  // reads the file: its size, not the claim
  if (!cut.empty()) return cut;
  std::string said = format + " declares ";
  for (std::size_t e = 0; e < names.size(); ++e) {
    said += (e == 0 ? "" : e + 1 == names.size() ? " and " : ", ") + Counted(counts[e], names[e]);
  }
  return said + ", which take at least " + std::to_string(needed) + " bytes, but the file has " +
         std::to_string(have) + " after its header; its counts are wrong or it is truncated";
}

// OFF's header as CGAL reads it (File_header_OFF): comment lines, a keyword
// [ST][C][N][4][n]OFF or the same with SKEL, "BINARY" before binary data, then, as text or as
// big-endian int32s, the dimension (with 'n'), the vertex and face counts, and for OFF the
// edge count.
struct OffHeader {
  bool binary = false;
  bool plain = false;  // "OFF": a binary vertex is 3 floats and nothing else
  bool skel = false;
  std::int64_t vertices = 0, faces = 0;
  std::size_t data_at = 0;  // the byte after the counts
};

// False when `head`, the file's first bytes, holds no such header, or counts CGAL refuses
// itself (text: negative, or beyond an int).
bool ReadOffHeader(const std::string& head, OffHeader* header) {
  std::size_t at = 0;
  const auto word = [&]() {  // the next word, past white space and '#' comments
    while (at < head.size()) {
      if (std::isspace(static_cast<unsigned char>(head[at]))) {
        ++at;
      } else if (head[at] == '#') {
        at = std::min(head.find('\n', at), head.size());
      } else {
        break;
      }
    }
    const std::size_t start = at;
    while (at < head.size() && !std::isspace(static_cast<unsigned char>(head[at])) &&
           head[at] != '#') {
      ++at;
    }
    return head.substr(start, at - start);
  };
  const std::string keyword = word();
  std::size_t k = keyword.rfind("ST", 0) == 0 ? 2 : 0;
  bool dimensional = false;
  for (const char flag : {'C', 'N', '4', 'n'}) {
    if (k < keyword.size() && keyword[k] == flag) {
      dimensional = flag == 'n';
      ++k;
    }
  }
  const std::string kind = keyword.substr(k);
  if (kind != "OFF" && kind != "SKEL") return false;
  header->plain = keyword == "OFF";
  header->skel = kind == "SKEL";
  const std::size_t numbers = (dimensional ? 1 : 0) + (kind == "OFF" ? 3 : 2);
  std::vector<std::int64_t> counts;
  const std::size_t before = at;
  if (word() == "BINARY") {
    header->binary = true;
    at = std::min(head.find('\n', at), head.size()) + 1;  // CGAL skips the rest of the line
    if (head.size() < at + 4 * numbers) return false;
    for (std::size_t n = 0; n < numbers; ++n, at += 4) {
      std::uint32_t v = 0;
      for (int b = 0; b < 4; ++b) v = v << 8 | static_cast<unsigned char>(head[at + b]);
      counts.push_back(static_cast<std::int32_t>(v));
    }
  } else {
    at = before;
    while (counts.size() < numbers) {
      const std::string w = word();
      char* end = nullptr;
      const long long n = std::strtoll(w.c_str(), &end, 10);
      if (w.empty() || *end != '\0' || n < 0 || n > std::numeric_limits<std::int32_t>::max())
        return false;
      counts.push_back(n);
    }
  }
  header->vertices = counts[dimensional ? 1 : 0];
  header->faces = counts[dimensional ? 2 : 1];
  header->data_at = at;
  return true;
}

// An OFF's counts against its size (a text vertex takes at least 6 bytes, "0 0 0" and its
// line end, a face 2; binary, 12 and 4), then each face's corner count (a corner takes at
// least 2 bytes, binary 4). Empty when they fit or the header is not understood.
std::string DescribeOffBeyondSize(const std::string& path, std::uint64_t size) {
  const std::string head = ReadBytes(path, kHeadBytes);
  OffHeader h;
  if (!ReadOffHeader(head, &h) || h.data_at > size) return {};
  if (h.data_at >= head.size() && head.size() < size) return {};  // a count may go on past `head`
  if (h.vertices < 0) {  // binary: CGAL would size its points from it as an unsigned count
    return "binary OFF declares " + std::to_string(h.vertices) + " vertices";
  }
  if (h.faces < 0) return {};  // CGAL refuses it
  const auto vertices = static_cast<std::uint64_t>(h.vertices);
  const auto faces = static_cast<std::uint64_t>(h.faces);
  const std::uint64_t have = size - h.data_at;
  const std::uint64_t vertex_bytes = h.binary ? 12 : 6, face_bytes = h.binary ? 4 : 2;
  std::uint64_t needed = MulAdd(faces, face_bytes, MulAdd(vertices, vertex_bytes, 0));
  if (!h.binary && needed > 0) --needed;  // the last line needs no line end
  if (needed > have) {
    return BeyondSize(path, h.skel ? "SKEL" : "OFF", {"vertex", "face"}, {vertices, faces}, needed,
                      have);
  }
  const std::uint64_t corner_bytes = h.binary ? 4 : 2;
  const auto too_many = [&](const std::string& where, std::uint64_t face,
                            const std::string& corners) {
    return where + "face " + std::to_string(face) + " declares " + corners +
           " corners, more than the file's " + std::to_string(size) +
           " bytes can hold (a corner takes at least " + std::to_string(corner_bytes) + ")";
  };
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(h.data_at));
  if (h.binary) {
    if (!h.plain) return {};  // where the variants' faces start is not worked out here
    in.ignore(static_cast<std::streamsize>(12 * vertices));
    for (std::uint64_t f = 1; f <= faces; ++f) {
      unsigned char raw[4];
      if (!in.read(reinterpret_cast<char*>(raw), 4)) return {};
      const auto corners =
          static_cast<std::int32_t>(std::uint32_t{raw[0]} << 24 | std::uint32_t{raw[1]} << 16 |
                                    std::uint32_t{raw[2]} << 8 | raw[3]);
      if (corners < 0 || static_cast<std::uint64_t>(corners) * 4 > size) {
        return too_many("", f, std::to_string(corners));
      }
      in.ignore(4 * static_cast<std::streamsize>(corners));
    }
    return {};
  }
  // as CGAL reads text: a record a line, past blank and comment lines; a face's first number
  // is its corner count
  std::uint64_t number =
      1 + static_cast<std::uint64_t>(std::count(head.begin(), head.begin() + h.data_at, '\n'));
  std::uint64_t record = 0;
  std::string line;
  for (; record < vertices + faces && std::getline(in, line); ++number) {
    const std::size_t start = line.find_first_not_of(" \t\r\f\v");
    if (start == std::string::npos || line[start] == '#') continue;
    if (record++ < vertices) continue;
    char* end = nullptr;
    const double corners = std::strtod(line.c_str() + start, &end);
    // not a number, or a negative one: CGAL refuses it
    if (end != line.c_str() + start && std::isfinite(corners) && corners * 2 > size) {
      return too_many("line " + std::to_string(number) + ": ", record - vertices,
                      line.substr(start, static_cast<std::size_t>(end - (line.c_str() + start))));
    }
  }
  return {};
}

// A PLY number type as CGAL reads it (PLY_read_number): its size in binary, and in ASCII
// `>>` into the type (a char's through a short), so an integer beyond [lo, hi] is read as
// another number, or not at all.
struct PlyNumber {
  int bytes = 0;
  bool real = false;
  std::int64_t lo = 0, hi = 0;
};

PlyNumber PlyNumberOf(const std::string& type) {
  PlyNumber n;
  n.bytes = PlyTypeBytes(type);
  n.real = type == "float" || type == "float32" || type == "double" || type == "float64";
  const bool is_signed = type == "char" || type == "int8" || type == "short" || type == "int16" ||
                         type == "int" || type == "int32";
  if (!n.real && n.bytes > 0) {
    const int bits = 8 * n.bytes;
    n.lo = is_signed ? -(std::int64_t{1} << (bits - 1)) : 0;
    n.hi = (std::int64_t{1} << (is_signed ? bits - 1 : bits)) - 1;
  }
  return n;
}

// The next ASCII number at `*at` in a NUL-ended text; an integer's in `value`. False at the
// end, or at a word CGAL reads otherwise: not a number, or an integer beyond the type (a uint
// excepted: CGAL takes "-5" as 2^32 - 5, a count refused here as -5). The walk stops there:
// CGAL fails at it, or reads the words out of step.
bool ReadPlyAscii(const char** at, const PlyNumber& type, std::int64_t* value) {
  char* end = nullptr;
  errno = 0;
  if (type.real) {
    std::strtod(*at, &end);
  } else {
    *value = std::strtoll(*at, &end, 10);
  }
  if (end == *at || errno == ERANGE ||
      (*end != '\0' && !std::isspace(static_cast<unsigned char>(*end)))) {
    return false;
  }
  *at = end;
  const bool uint = type.bytes == 4 && type.lo == 0;
  return type.real || ((uint || *value >= type.lo) && *value <= type.hi);
}

// A PLY's element counts against its size (an item takes at least its binary size, its
// lists' counts in it, or in ASCII 2 bytes a property), then, where a list's count may claim
// more than a file holds (a signed or a 4-byte count type), each list's. Empty when they fit
// or the header is not understood.
std::string DescribePlyBeyondSize(const std::string& path, std::uint64_t size) {
  PlyHeader h;
  if (!ReadPlyHeader(ReadBytes(path, kHeadBytes), &h) || !h.ended || h.data_at > size) return {};
  const bool ascii = h.format == "ascii";
  const bool big_endian = h.format == "binary_big_endian";
  if (!ascii && !big_endian && h.format != "binary_little_endian") return {};
  const std::uint64_t have = size - h.data_at;
  std::vector<std::string> names;
  std::vector<std::uint64_t> counts;
  std::uint64_t needed = 0;
  std::size_t checked = 0;  // the elements up to the last with a list to check
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    const PlyElement& element = h.elements[e];
    std::uint64_t item = 0;
    for (const PlyProperty& p : element.properties) {
      item += ascii ? 2 : static_cast<std::uint64_t>(p.count_bytes != 0 ? p.count_bytes : p.bytes);
      if (p.count_bytes != 0 && (PlyNumberOf(p.count_type).lo < 0 || p.count_bytes == 4)) {
        checked = e + 1;
      }
    }
    // CGAL reads every item, and makes a point of a vertex, even with nothing to read
    if (item == 0 && element.count > have) {
      return "PLY declares " + Counted(element.count, element.name) +
             " with no property, more than the " + std::to_string(have) +
             " bytes after its header; its counts are wrong";
    }
    names.push_back(element.name);
    counts.push_back(element.count);
    needed = MulAdd(element.count, item, needed);
  }
  if (ascii && needed > 0) --needed;  // the last number needs no space after it
  if (needed > have) return BeyondSize(path, "PLY", names, counts, needed, have);
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(h.data_at));
  std::string text;  // ASCII: the data, read at once (the file's size, less than CGAL's soup)
  if (ascii && checked > 0) {
    text.resize(static_cast<std::size_t>(have));
    in.read(text.data(), static_cast<std::streamsize>(have));
    text.resize(static_cast<std::size_t>(in.gcount()));
  }
  const char* cursor = text.c_str();
  // the next number; false at the end of the data
  const auto next = [&](const PlyNumber& type, std::int64_t* value) {
    if (ascii) return ReadPlyAscii(&cursor, type, value);
    unsigned char raw[8];
    if (!in.read(reinterpret_cast<char*>(raw), type.bytes)) return false;
    std::uint64_t v = 0;
    for (int k = 0; k < type.bytes; ++k) v = v << 8 | raw[big_endian ? k : type.bytes - 1 - k];
    const int bits = 8 * type.bytes;
    *value = static_cast<std::int64_t>(v);
    if (type.lo < 0 && (v >> (bits - 1)) != 0) *value -= std::int64_t{1} << bits;
    return true;
  };
  std::int64_t value = 0, ignored = 0;
  for (std::size_t e = 0; e < checked; ++e) {
    const PlyElement& element = h.elements[e];
    std::vector<std::pair<PlyNumber, PlyNumber>> types;  // each property's count's and item's
    std::uint64_t fixed = 0;                             // binary: an item's bytes, without lists
    for (const PlyProperty& p : element.properties) {
      types.emplace_back(PlyNumberOf(p.count_type), PlyNumberOf(p.type));
      fixed = p.count_bytes != 0 || fixed == kMaxBytes ? kMaxBytes : fixed + p.bytes;
    }
    if (!ascii && fixed != kMaxBytes) {  // items of one size: skipped at once
      in.ignore(static_cast<std::streamsize>(element.count * fixed));  // at most `have`
      continue;
    }
    for (std::uint64_t i = 0; i < element.count; ++i) {
      for (std::size_t k = 0; k < types.size(); ++k) {
        const auto& [count_type, item_type] = types[k];
        if (count_type.bytes == 0) {
          if (!next(item_type, &ignored)) return {};
          continue;
        }
        if (!next(count_type, &value)) return {};
        const std::uint64_t item = ascii ? 2 : static_cast<std::uint64_t>(item_type.bytes);
        if (value < 0 || static_cast<std::uint64_t>(value) > have / item) {
          const std::string list =
              "PLY's " + Ordinal(i + 1) + " " + Counted(1, element.name).substr(2) + " declares " +
              std::to_string(value) + " items in its list '" + element.properties[k].name + "'";
          if (value < 0) return list + "; a count cannot be negative";
          return list + ", more than the " + std::to_string(have) +
                 " bytes after its header can hold (an item takes at least " +
                 std::to_string(item) + ")";
        }
        if (!ascii) {
          in.ignore(value * item_type.bytes);
          continue;
        }
        for (std::int64_t n = 0; n < value; ++n) {
          if (!next(item_type, &ignored)) return {};
        }
      }
    }
  }
  return {};
}

// Refuses a file whose counts its size cannot hold (see above) before CGAL reads it.
void CheckCountsAgainstSize(const std::string& path) {
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(path, error);
  if (error) return;
  const std::string ext = Extension(path);
  const std::string said = ext == "off"   ? DescribeOffBeyondSize(path, size)
                           : ext == "ply" ? DescribePlyBeyondSize(path, size)
                                          : std::string();
  if (!said.empty()) throw std::runtime_error(path + ": " + said);
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
  CheckCountsAgainstSize(path);
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
