#include "slam/io/ply_file.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/binary_io.h"
#include "common/error.h"
#include "common/staged_file.h"

namespace depot::slam {
namespace {

// Bytes of a PLY scalar type; 0 for a name PLY does not define.
size_t ply_type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

struct PlyProperty {
  size_t size = 0;        // a scalar's bytes, or a list's item bytes
  size_t count_size = 0;  // a list's count bytes; 0 = a scalar
};

struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> properties;
};

// A list's count as the file stores it (unsigned for uchar/ushort/uint, and
// a negative signed count is refused by the caller).
long long read_count(const unsigned char* bytes, size_t size, bool big_endian) {
  unsigned long long v = 0;
  for (size_t i = 0; i < size; ++i) {
    const size_t k = big_endian ? i : size - 1 - i;
    v = (v << 8) | bytes[k];
  }
  return static_cast<long long>(v);
}

}  // namespace

PlyCheck check_ply_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  const auto file_size = static_cast<unsigned long long>(std::filesystem::file_size(path, ec));
  if (ec) fail(path, "cannot read its size: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot be opened");

  PlyCheck check;
  std::vector<PlyElement> elements;
  std::string line;
  int line_no = 0;
  bool ended = false;
  auto header_fail = [&](const std::string& problem) {
    fail(path + ":" + std::to_string(line_no), problem);
  };
  while (std::getline(in, line)) {
    ++line_no;
    check.header_bytes += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_no == 1) {
      if (line != "ply") fail(path, "not a PLY file (it does not start with \"ply\")");
      continue;
    }
    // A header is text: assimp reads its lines as C strings, and a NUL or
    // other control byte inside one once sent it into an endless loop on a
    // header this check had passed (found by fuzz_ply_file).
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
        header_fail(fmt::format("holds a control byte (0x{:02x}); a PLY header is text",
                                static_cast<unsigned char>(c)));
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      std::string version;
      words >> check.format >> version;
      if (check.format != "ascii" && check.format != "binary_little_endian" &&
          check.format != "binary_big_endian")
        header_fail("unknown format '" + check.format + "'");
    } else if (keyword == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      char* end = nullptr;
      errno = 0;
      const unsigned long long n = std::strtoull(count.c_str(), &end, 10);
      if (e.name.empty() || count.empty() || *end != '\0' || count[0] == '-' || errno != 0)
        header_fail("element '" + e.name + "' has no valid count");
      e.count = n;
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) header_fail("a property before any element");
      std::string type;
      words >> type;
      PlyProperty p;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        p.count_size = ply_type_size(count_type);
        p.size = ply_type_size(item_type);
        if (!p.count_size || !p.size)
          header_fail("unknown list types '" + count_type + " " + item_type + "'");
      } else {
        p.size = ply_type_size(type);
        if (!p.size) header_fail("unknown property type '" + type + "'");
      }
      std::string name, extra;
      words >> name >> extra;
      if (name.empty()) header_fail("a property without a name");
      if (!extra.empty()) header_fail("unexpected '" + extra + "' after property '" + name + "'");
      elements.back().properties.push_back(p);
    } else if (keyword == "end_header") {
      ended = true;
      break;
    } else {
      header_fail("unknown header line '" + keyword + "'");
    }
  }
  if (line_no == 0) fail(path, "is empty");
  if (!ended) fail(path, "its header has no end_header line");
  if (check.format.empty()) fail(path, "its header has no format line");
  for (const PlyElement& e : elements)
    if (e.name == "vertex") check.vertices = e.count;
  check.only_vertices = elements.size() == 1 && elements.front().name == "vertex";
  // A header whose last line has no newline ends the file.
  if (check.header_bytes > file_size) check.header_bytes = static_cast<size_t>(file_size);

  const unsigned long long body = file_size - check.header_bytes;
  auto short_fail = [&](const PlyElement& e, size_t row) {
    fail(path, "is shorter than its header declares: element '" + e.name + "' ends at row " +
                   std::to_string(row) + " of " + std::to_string(e.count) + " (cut off?)");
  };
  if (check.format == "ascii") {
    size_t row_line = line_no;
    for (const PlyElement& e : elements) {
      for (size_t row = 0; row < e.count; ++row) {
        do {
          if (!std::getline(in, line)) short_fail(e, row);
          ++row_line;
        } while (line.find_first_not_of(" \t\r") == std::string::npos);
        std::istringstream values(line);
        size_t needed = 0;
        for (const PlyProperty& p : e.properties) {
          std::string word;
          if (!(values >> word)) break;
          char* end = nullptr;
          const double v = std::strtod(word.c_str(), &end);
          if (*end != '\0')
            fail(path + ":" + std::to_string(row_line), "'" + word + "' is not a number");
          ++needed;
          if (p.count_size) {
            if (v < 0 || v != static_cast<double>(static_cast<long long>(v)) || v > 1e9)
              fail(path + ":" + std::to_string(row_line), "list count '" + word + "' is invalid");
            for (long long k = 0; k < static_cast<long long>(v); ++k)
              if (!(values >> word))
                fail(path + ":" + std::to_string(row_line), "a list is shorter than its count");
          }
        }
        if (needed < e.properties.size())
          fail(path + ":" + std::to_string(row_line),
               "has " + std::to_string(needed) + " values where element '" + e.name + "' has " +
                   std::to_string(e.properties.size()) + " properties");
      }
    }
    check.data_bytes = body;
    return check;
  }

  const bool big_endian = check.format == "binary_big_endian";
  unsigned long long offset = 0;  // into the body
  for (const PlyElement& e : elements) {
    bool has_list = false;
    unsigned long long row_bytes = 0;
    for (const PlyProperty& p : e.properties) {
      has_list = has_list || p.count_size;
      row_bytes += p.count_size ? p.count_size : p.size;
    }
    if (!has_list) {
      // Fixed rows: the count against the bytes left, without overflow.
      if (row_bytes > 0 && e.count > (body - offset) / row_bytes) {
        const size_t rows = static_cast<size_t>((body - offset) / row_bytes);
        short_fail(e, rows);
      }
      offset += row_bytes * e.count;
      continue;
    }
    in.clear();
    in.seekg(static_cast<std::streamoff>(check.header_bytes + offset));
    for (size_t row = 0; row < e.count; ++row) {
      for (const PlyProperty& p : e.properties) {
        if (!p.count_size) {
          if (p.size > body - offset) short_fail(e, row);
          offset += p.size;
          in.seekg(static_cast<std::streamoff>(p.size), std::ios::cur);
          continue;
        }
        unsigned char bytes[8] = {};
        if (p.count_size > body - offset) short_fail(e, row);
        in.read(reinterpret_cast<char*>(bytes), static_cast<std::streamsize>(p.count_size));
        if (!in) short_fail(e, row);
        offset += p.count_size;
        const long long n = read_count(bytes, p.count_size, big_endian);
        if (n < 0 || static_cast<unsigned long long>(n) > (body - offset) / p.size)
          short_fail(e, row);
        offset += static_cast<unsigned long long>(n) * p.size;
        in.seekg(static_cast<std::streamoff>(n * static_cast<long long>(p.size)), std::ios::cur);
      }
    }
  }
  check.data_bytes = offset;
  return check;
}

void write_ply(const std::string& path, const std::vector<PlyPoint>& points,
               const std::string& count_name) {
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment depot-slam\nelement vertex " +
                       std::to_string(points.size()) +
                       "\nproperty float x\nproperty float y\nproperty float z\n"
                       "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (!count_name.empty()) header += "property int " + count_name + "\n";
  header += "end_header\n";
  BinaryWriter out;
  out.put_bytes(header.data(), header.size());
  for (const PlyPoint& p : points) {
    for (int k = 0; k < 3; ++k) out.put<float>(p.position[k]);
    for (int c : {2, 1, 0}) out.put<uint8_t>(p.bgr[c]);  // BGR -> RGB
    if (!count_name.empty()) out.put<int32_t>(p.count);
  }
  StagedFile file(path);
  file.stream().write(out.bytes().data(), static_cast<std::streamsize>(out.bytes().size()));
  file.commit();
}

}  // namespace depot::slam
