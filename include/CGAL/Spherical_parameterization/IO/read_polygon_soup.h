// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Reading a mesh file as a polygon soup, with a precise verdict when the file is not a mesh.
//
// OFF (also gzip-compressed, e.g. `mesh.off.gz`) is read by a parser of its own: it says what is wrong (empty,
// not OFF, truncated after so many vertices, a bad number on line L), never trusts the counts of the header for
// an allocation, and reads an 871k-face mesh in a fraction of a second. Other formats go to
// `CGAL::IO::read_polygon_soup()`. Gzip needs zlib: define `CGAL_SPHERICAL_PARAMETERIZATION_USE_ZLIB` and link it
// (the CMake target `CGAL::Spherical_parameterization` does when zlib is found).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_IO_READ_POLYGON_SOUP_H
#define CGAL_SPHERICAL_PARAMETERIZATION_IO_READ_POLYGON_SOUP_H

#include <CGAL/IO/polygon_soup_io.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_ZLIB
#include <zlib.h>
#endif

namespace CGAL {
namespace Spherical_parameterization {
namespace IO {

/// \ingroup PkgSphericalParameterizationRef
/// Why a file could not be read as a mesh.
enum class File_status
{
  OK = 0,
  CANNOT_OPEN,       ///< The file does not exist or is not readable.
  EMPTY_FILE,        ///< The file holds no data (or only white space and comments).
  UNKNOWN_FORMAT,    ///< Not a format that can be read (e.g. an OFF file whose header is not `OFF`).
  TRUNCATED,         ///< The data ends before the counts of the header are reached (or a gzip stream is cut).
  INVALID_DATA,      ///< A number is malformed, a count is negative, or a face refers to a missing vertex.
  GZIP_NOT_SUPPORTED ///< A gzip file, and zlib was not compiled in.
};

/// \ingroup PkgSphericalParameterizationRef
/// The enumerator's name, e.g. `"TRUNCATED"`.
inline const char* get_file_status_name(File_status status)
{
  // In the enumerators' order.
  static const char* const names[] = {"OK",        "CANNOT_OPEN",  "EMPTY_FILE",        "UNKNOWN_FORMAT",
                                      "TRUNCATED", "INVALID_DATA", "GZIP_NOT_SUPPORTED"};
  static_assert(sizeof(names) / sizeof(names[0]) == static_cast<std::size_t>(File_status::GZIP_NOT_SUPPORTED) + 1,
                "one name per File_status");
  const std::size_t k = static_cast<std::size_t>(status);
  return k < sizeof(names) / sizeof(names[0]) ? names[k] : "UNKNOWN";
}

/// \ingroup PkgSphericalParameterizationRef
/// The verdict of a read: a status and a message that says where the file went wrong.
struct File_read
{
  File_status status = File_status::OK;
  std::string message;
  explicit operator bool() const { return status == File_status::OK; }
};

namespace internal {

inline File_read file_error(File_status status, const std::string& message)
{
  File_read read;
  read.status = status;
  read.message = message;
  return read;
}

inline bool is_gzip(const std::string& bytes)
{
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f
         && static_cast<unsigned char>(bytes[1]) == 0x8b;
}

// A cursor over the text that knows its line number: every message says where the file went wrong.
class Text_cursor
{
public:
  Text_cursor(const char* begin, const char* end) : m_p(begin), m_end(end) {}

  std::size_t line() const { return m_line; }
  bool at_end() const { return m_p == m_end; }

  // Skips white space (newlines too) and comments ('#' to the end of the line).
  void skip_blank()
  {
    while(m_p != m_end)
    {
      if(*m_p == '#')
      {
        while(m_p != m_end && *m_p != '\n')
          ++m_p;
      }
      else if(*m_p == '\n')
      {
        ++m_line;
        ++m_p;
      }
      else if(is_space(*m_p))
        ++m_p;
      else
        break;
    }
  }

  // Skips spaces and a comment, but not the end of the line: true when the line has another token.
  bool more_on_line()
  {
    while(m_p != m_end && *m_p != '\n' && is_space(*m_p))
      ++m_p;
    if(m_p != m_end && *m_p == '#')
      while(m_p != m_end && *m_p != '\n')
        ++m_p;
    return m_p != m_end && *m_p != '\n';
  }

  void next_line()
  {
    while(m_p != m_end && *m_p != '\n')
      ++m_p;
    if(m_p != m_end)
    {
      ++m_p;
      ++m_line;
    }
  }

  std::string token()
  {
    const char* start = m_p;
    while(m_p != m_end && !is_space(*m_p) && *m_p != '\n' && *m_p != '#')
      ++m_p;
    return std::string(start, m_p);
  }

  bool read_double(double& x)
  {
    const char* start = m_p;
    if(m_p != m_end && *m_p == '+')
      ++m_p; // from_chars refuses a leading '+'
    const std::from_chars_result r = std::from_chars(m_p, m_end, x);
    if(r.ec == std::errc::result_out_of_range)
    {
      // Out of the double range: keep it as an infinity (or zero), for the input check to name.
      char* stop = nullptr;
      const std::string text(m_p, r.ptr);
      x = std::strtod(text.c_str(), &stop);
    }
    else if(r.ec != std::errc())
    {
      m_p = start;
      return false;
    }
    m_p = r.ptr;
    return ends_token();
  }

  bool read_count(unsigned long long& n)
  {
    const char* start = m_p;
    if(m_p != m_end && *m_p == '+')
      ++m_p;
    const std::from_chars_result r = std::from_chars(m_p, m_end, n);
    if(r.ec != std::errc())
    {
      m_p = start;
      return false;
    }
    m_p = r.ptr;
    return ends_token();
  }

  std::string here() const { return "line " + std::to_string(m_line); }

private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
  bool ends_token() const { return m_p == m_end || is_space(*m_p) || *m_p == '\n' || *m_p == '#'; }

  const char* m_p;
  const char* m_end;
  std::size_t m_line = 1;
};

} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Parses the text of an ASCII OFF file (`OFF`, `COFF`, `NOFF`, `STOFF` ... headers; colours, normals and texture
/// coordinates after the coordinates, and colours after the indices of a face, are skipped). The vertex and face
/// counts of the header are checked against the data, and no allocation trusts them. Point must be constructible
/// from three doubles; Polygon a sequence container of indices.
template <typename Point, typename Polygon>
File_read parse_OFF(const char* begin, const char* end, std::vector<Point>& points, std::vector<Polygon>& polygons)
{
  using internal::file_error;
  points.clear();
  polygons.clear();
  internal::Text_cursor in(begin, end);
  in.skip_blank();
  if(in.at_end())
    return file_error(File_status::EMPTY_FILE, "the file is empty");

  const std::string header = in.token();
  const std::size_t off = header.size() >= 3 ? header.size() - 3 : std::string::npos;
  bool known = off != std::string::npos && header.compare(off, 3, "OFF") == 0;
  std::string prefix = known ? header.substr(0, off) : std::string();
  // Optional ST (texture), C (colour), N (normal), in that order; no 4D, n-dimensional or binary variants.
  if(known)
  {
    std::string rest = prefix;
    for(const char* part : {"ST", "C", "N"})
      if(rest.compare(0, std::char_traits<char>::length(part), part) == 0)
        rest.erase(0, std::char_traits<char>::length(part));
    known = rest.empty();
  }
  if(!known)
    return file_error(File_status::UNKNOWN_FORMAT, "not an ASCII OFF file: the header is '" + header.substr(0, 40)
                                                       + "', expected OFF (or COFF, NOFF, STOFF...)");
  if(in.more_on_line() && in.token() == "BINARY")
    return file_error(File_status::UNKNOWN_FORMAT, "binary OFF is not supported");

  unsigned long long nv = 0, nf = 0, ne = 0;
  in.skip_blank();
  if(in.at_end())
    return file_error(File_status::TRUNCATED, "the file ends after its header: no vertex and face counts");
  if(!in.read_count(nv))
    return file_error(File_status::INVALID_DATA, in.here() + ": the vertex count is not a non-negative integer");
  in.skip_blank();
  if(in.at_end())
    return file_error(File_status::TRUNCATED, "the file ends before the face count");
  if(!in.read_count(nf))
    return file_error(File_status::INVALID_DATA, in.here() + ": the face count is not a non-negative integer");
  if(in.more_on_line() && !in.read_count(ne))
    return file_error(File_status::INVALID_DATA, in.here() + ": the edge count is not a non-negative integer");
  in.next_line();

  // A vertex needs at least 6 bytes ("0 0 0\n") and a face 8: a header that claims more cannot be honoured, and
  // reserving for it would let a 20-byte file ask for terabytes.
  const std::size_t bytes = static_cast<std::size_t>(end - begin);
  points.reserve(static_cast<std::size_t>(std::min<unsigned long long>(nv, bytes / 6)));
  polygons.reserve(static_cast<std::size_t>(std::min<unsigned long long>(nf, bytes / 8)));

  for(unsigned long long v = 0; v < nv; ++v)
  {
    in.skip_blank();
    if(in.at_end())
      return file_error(File_status::TRUNCATED, "the file ends after " + std::to_string(v) + " of the "
                                                    + std::to_string(nv) + " vertices announced by its header");
    double xyz[3];
    for(int k = 0; k < 3; ++k)
    {
      if(k > 0 && !in.more_on_line())
      {
        in.skip_blank();
        if(in.at_end())
          return file_error(File_status::TRUNCATED,
                            "the file ends inside vertex " + std::to_string(v) + " of " + std::to_string(nv));
        return file_error(File_status::INVALID_DATA,
                          in.here() + ": vertex " + std::to_string(v) + " has fewer than 3 coordinates");
      }
      if(!in.read_double(xyz[k]))
        return file_error(File_status::INVALID_DATA, in.here() + ": coordinate " + std::to_string(k) + " of vertex "
                                                         + std::to_string(v) + " is not a number");
    }
    points.emplace_back(xyz[0], xyz[1], xyz[2]);
    in.next_line(); // colours, normals, texture coordinates
  }

  for(unsigned long long f = 0; f < nf; ++f)
  {
    in.skip_blank();
    if(in.at_end())
      return file_error(File_status::TRUNCATED, "the file ends after " + std::to_string(f) + " of the "
                                                    + std::to_string(nf) + " faces announced by its header");
    unsigned long long degree = 0;
    if(!in.read_count(degree))
      return file_error(File_status::INVALID_DATA,
                        in.here() + ": face " + std::to_string(f) + " does not start with its number of vertices");
    Polygon polygon;
    for(unsigned long long k = 0; k < degree; ++k)
    {
      unsigned long long index = 0;
      if(!in.more_on_line())
      {
        in.skip_blank();
        if(in.at_end())
          return file_error(File_status::TRUNCATED,
                            "the file ends inside face " + std::to_string(f) + " of " + std::to_string(nf));
        return file_error(File_status::INVALID_DATA, in.here() + ": face " + std::to_string(f) + " announces "
                                                         + std::to_string(degree) + " vertices and lists "
                                                         + std::to_string(k));
      }
      if(!in.read_count(index))
        return file_error(File_status::INVALID_DATA, in.here() + ": vertex " + std::to_string(k) + " of face "
                                                         + std::to_string(f) + " is not a non-negative integer");
      if(index >= nv)
        return file_error(File_status::INVALID_DATA, in.here() + ": face " + std::to_string(f) + " refers to vertex "
                                                         + std::to_string(index) + ", but there are "
                                                         + std::to_string(nv) + " vertices");
      polygon.push_back(static_cast<typename Polygon::value_type>(index));
    }
    polygons.push_back(std::move(polygon));
    in.next_line(); // a colour may follow the indices
  }
  return File_read();
}

/// \ingroup PkgSphericalParameterizationRef
/// Reads the bytes of `path` into `contents`, decompressed when the file is gzip (recognized by its magic bytes,
/// whatever its name).
inline File_read read_file_contents(const std::string& path, std::string& contents)
{
  using internal::file_error;
  contents.clear();
  // A folder opens as a file on some systems, with a meaningless size.
  std::error_code ignored;
  if(std::filesystem::is_directory(path, ignored))
    return file_error(File_status::CANNOT_OPEN, "'" + path + "' is a folder");
  std::ifstream in(path, std::ios::binary);
  if(!in)
    return file_error(File_status::CANNOT_OPEN, "cannot open '" + path + "'");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if(!in || size < 0)
    return file_error(File_status::CANNOT_OPEN, "cannot read '" + path + "'");
  in.seekg(0, std::ios::beg);
  contents.resize(static_cast<std::size_t>(size));
  if(size > 0 && !in.read(&contents[0], size))
    return file_error(File_status::CANNOT_OPEN, "cannot read '" + path + "'");
  if(!internal::is_gzip(contents))
    return File_read();
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_ZLIB
  const std::string compressed = std::move(contents);
  contents.clear();
  z_stream stream{};
  // 16 + MAX_WBITS: a gzip header, not a raw zlib stream.
  if(inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK)
    return file_error(File_status::INVALID_DATA, "zlib could not start");
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = static_cast<uInt>(compressed.size());
  std::vector<char> buffer(1 << 20);
  int code = Z_OK;
  while(code == Z_OK)
  {
    stream.next_out = reinterpret_cast<Bytef*>(buffer.data());
    stream.avail_out = static_cast<uInt>(buffer.size());
    code = inflate(&stream, Z_NO_FLUSH);
    contents.append(buffer.data(), buffer.size() - stream.avail_out);
  }
  const bool input_exhausted = stream.avail_in == 0;
  inflateEnd(&stream);
  if(code != Z_STREAM_END)
  {
    contents.clear();
    // Z_BUF_ERROR with all the input used: the stream stops before its end.
    if(code == Z_BUF_ERROR && input_exhausted)
      return file_error(File_status::TRUNCATED, "the gzip stream of '" + path + "' is cut short");
    return file_error(File_status::INVALID_DATA, "'" + path + "' is not a valid gzip file"
                                                     + (stream.msg ? std::string(": ") + stream.msg : std::string()));
  }
  return File_read();
#else
  contents.clear();
  return file_error(File_status::GZIP_NOT_SUPPORTED,
                    "'" + path + "' is gzip-compressed, and this program was built without zlib");
#endif
}

namespace internal {
inline bool has_extension(std::string name, const std::string& extension)
{
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name.size() >= extension.size()
         && name.compare(name.size() - extension.size(), extension.size(), extension) == 0;
}
} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Reads the mesh file `path` as a polygon soup: OFF (`.off`, `.off.gz` or any gzip file) with the package's
/// parser, OBJ, PLY and STL with `CGAL::IO::read_polygon_soup()` (whose verdict is only yes or no).
template <typename Point, typename Polygon>
File_read read_polygon_soup(const std::string& path, std::vector<Point>& points, std::vector<Polygon>& polygons)
{
  using internal::file_error;
  points.clear();
  polygons.clear();
  std::string contents;
  File_read read = read_file_contents(path, contents);
  if(!read)
    return read;
  const bool off_name = internal::has_extension(path, ".off") || internal::has_extension(path, ".off.gz")
                        || internal::has_extension(path, ".gz");
  if(off_name || contents.empty())
  {
    read = parse_OFF(contents.data(), contents.data() + contents.size(), points, polygons);
    if(read)
      read.message = std::to_string(points.size()) + " vertices, " + std::to_string(polygons.size()) + " faces";
    else
      read.message = path + ": " + read.message;
    return read;
  }
  if(!CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false)))
    return file_error(File_status::UNKNOWN_FORMAT,
                      path + ": not a readable OBJ, PLY or STL file (empty, truncated or another format)");
  if(points.empty() && polygons.empty())
    return file_error(File_status::EMPTY_FILE, path + ": the file holds no vertex");
  read.message = std::to_string(points.size()) + " vertices, " + std::to_string(polygons.size()) + " faces";
  return read;
}

} // namespace IO
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_IO_READ_POLYGON_SOUP_H
