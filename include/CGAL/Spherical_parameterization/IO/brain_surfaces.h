// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Brain-surface files: FreeSurfer's binary triangle surfaces (lh.white, lh.pial, lh.sphere, ...), read and written
// here (the format needs no library), and GIfTI surfaces (.surf.gii) through Debian's GIFTI library when it is
// available (CGAL_SPHERICAL_PARAMETERIZATION_USE_GIFTI). Both keep the vertex order and the triangles, so that
// per-vertex data (curvature, thickness, labels) stays attached to the mapped surface.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_IO_BRAIN_SURFACES_H
#define CGAL_SPHERICAL_PARAMETERIZATION_IO_BRAIN_SURFACES_H

#include <CGAL/Spherical_parameterization/IO/read_polygon_soup.h>

#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_GIFTI
extern "C" { // a C library whose header does not say so
#include <gifti/gifti_io.h>
}
#endif

#include <array>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace IO {

/// \ingroup PkgSphericalParameterizationRef
/// What a FreeSurfer surface holds besides its vertices and triangles, kept so that a written surface carries it on.
struct FreeSurfer_surface_info
{
  std::string created_by; ///< The text after the magic number ("created by ... on ...").
  std::string trailer;    ///< The bytes after the triangles (volume geometry and other tags), copied as they are.
};

namespace internal {

// FreeSurfer's triangle-surface magic number, 0xFFFFFE on three big-endian bytes.
inline bool has_FreeSurfer_magic(const char* begin, const char* end)
{
  return end - begin >= 3 && static_cast<unsigned char>(begin[0]) == 0xFF
         && static_cast<unsigned char>(begin[1]) == 0xFF && static_cast<unsigned char>(begin[2]) == 0xFE;
}

inline std::uint32_t big_endian_32(const char* p)
{
  const unsigned char* b = reinterpret_cast<const unsigned char*>(p);
  return (std::uint32_t(b[0]) << 24) | (std::uint32_t(b[1]) << 16) | (std::uint32_t(b[2]) << 8) | std::uint32_t(b[3]);
}

inline void put_big_endian_32(std::ostream& out, std::uint32_t value)
{
  const char bytes[4] = {static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8),
                         static_cast<char>(value)};
  out.write(bytes, 4);
}

} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Parses a FreeSurfer binary triangle surface held in memory: the magic bytes FF FF FE, a "created by" line ended
/// by two newlines, the vertex and face counts, the coordinates as big-endian float32 and the triangles as
/// big-endian int32; what follows the triangles is kept in `info->trailer`.
template <typename Point, typename Polygon>
File_read parse_FreeSurfer_surface(const char* begin, const char* end, std::vector<Point>& points,
                                   std::vector<Polygon>& polygons, FreeSurfer_surface_info* info = nullptr)
{
  using internal::file_error;
  points.clear();
  polygons.clear();
  if(begin == end)
    return file_error(File_status::EMPTY_FILE, "the file is empty");
  if(!internal::has_FreeSurfer_magic(begin, end))
    return file_error(File_status::UNKNOWN_FORMAT,
                      "not a FreeSurfer triangle surface (its first bytes are not FF FF FE)");
  const char* p = begin + 3;
  const char* line_end = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
  if(line_end == nullptr || line_end + 1 >= end || line_end[1] != '\n')
    return file_error(File_status::TRUNCATED, "the file ends inside its \"created by\" line");
  const std::string created_by(p, line_end);
  p = line_end + 2;
  if(end - p < 8)
    return file_error(File_status::TRUNCATED, "the file ends before its vertex and face counts");
  const std::uint32_t nv = internal::big_endian_32(p), nf = internal::big_endian_32(p + 4);
  p += 8;
  if(nv > 0x7FFFFFFFu || nf > 0x7FFFFFFFu)
    return file_error(File_status::INVALID_DATA, "the vertex or face count is negative ("
                                                     + std::to_string(static_cast<std::int32_t>(nv)) + ", "
                                                     + std::to_string(static_cast<std::int32_t>(nf)) + ")");
  const std::uint64_t needed = 12ull * nv + 12ull * nf;
  if(static_cast<std::uint64_t>(end - p) < needed)
    return file_error(File_status::TRUNCATED, "the file ends before its " + std::to_string(nv) + " vertices and "
                                                  + std::to_string(nf) + " triangles");
  points.reserve(nv);
  for(std::uint32_t v = 0; v < nv; ++v, p += 12)
  {
    float c[3];
    for(int k = 0; k < 3; ++k)
    {
      const std::uint32_t bits = internal::big_endian_32(p + 4 * k);
      std::memcpy(&c[k], &bits, 4);
      if(!std::isfinite(c[k]))
        return file_error(File_status::INVALID_DATA,
                          "coordinate " + std::to_string(k) + " of vertex " + std::to_string(v) + " is not finite");
    }
    points.emplace_back(c[0], c[1], c[2]);
  }
  polygons.reserve(nf);
  for(std::uint32_t f = 0; f < nf; ++f, p += 12)
  {
    Polygon polygon;
    for(int k = 0; k < 3; ++k)
    {
      const std::uint32_t index = internal::big_endian_32(p + 4 * k);
      if(index >= nv)
        return file_error(File_status::INVALID_DATA, "triangle " + std::to_string(f) + " refers to vertex "
                                                         + std::to_string(static_cast<std::int32_t>(index)) + ", of "
                                                         + std::to_string(nv));
      polygon.push_back(index);
    }
    polygons.push_back(std::move(polygon));
  }
  if(info != nullptr)
  {
    info->created_by = created_by;
    info->trailer.assign(p, end);
  }
  return File_read();
}

/// \ingroup PkgSphericalParameterizationRef
/// Reads the FreeSurfer binary triangle surface `path` (gzip-compressed too, where zlib is available).
template <typename Point, typename Polygon>
File_read read_FreeSurfer_surface(const std::string& path, std::vector<Point>& points, std::vector<Polygon>& polygons,
                                  FreeSurfer_surface_info* info = nullptr)
{
  std::string bytes;
  File_read read = read_file_contents(path, bytes);
  if(!read)
    return read;
  read = parse_FreeSurfer_surface(bytes.data(), bytes.data() + bytes.size(), points, polygons, info);
  read.message = read ? std::to_string(points.size()) + " vertices, " + std::to_string(polygons.size()) + " faces"
                      : path + ": " + read.message;
  return read;
}

/// \ingroup PkgSphericalParameterizationRef
/// Writes a FreeSurfer binary triangle surface (coordinates rounded to float32, as the format stores them, and
/// multiplied by `radius`: FreeSurfer's spheres have radius 100). `info` gives the "created by" line and the tags
/// to append (those of the input surface keep the volume geometry).
template <typename Point, typename Polygon>
bool write_FreeSurfer_surface(std::ostream& out, const std::vector<Point>& points,
                              const std::vector<Polygon>& triangles,
                              const FreeSurfer_surface_info& info = FreeSurfer_surface_info(), double radius = 1.)
{
  out.write("\xFF\xFF\xFE", 3);
  const std::string created_by =
      info.created_by.empty() ? std::string("created by CGAL Spherical_parameterization") : info.created_by;
  out << created_by << "\n\n";
  internal::put_big_endian_32(out, static_cast<std::uint32_t>(points.size()));
  internal::put_big_endian_32(out, static_cast<std::uint32_t>(triangles.size()));
  for(const Point& p : points)
    for(int k = 0; k < 3; ++k)
    {
      const float c = static_cast<float>(radius * CGAL::to_double(p[k]));
      std::uint32_t bits;
      std::memcpy(&bits, &c, 4);
      internal::put_big_endian_32(out, bits);
    }
  for(const Polygon& t : triangles)
  {
    if(t.size() != 3)
      return false;
    for(int k = 0; k < 3; ++k)
      internal::put_big_endian_32(out, static_cast<std::uint32_t>(t[static_cast<std::size_t>(k)]));
  }
  out.write(info.trailer.data(), static_cast<std::streamsize>(info.trailer.size()));
  return static_cast<bool>(out);
}

#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_GIFTI
/// \ingroup PkgSphericalParameterizationRef
/// Reads a GIfTI surface (`.surf.gii`: a POINTSET array of n x 3 coordinates and a TRIANGLE array of m x 3
/// indices, in any encoding and byte order the GIFTI library reads) with Debian's GIFTI library. `metadata`, when
/// given, receives the file's metadata (name, value pairs of the GIfTI element).
template <typename Point, typename Polygon>
File_read read_GIfTI_surface(const std::string& path, std::vector<Point>& points, std::vector<Polygon>& polygons,
                             std::vector<std::pair<std::string, std::string>>* metadata = nullptr)
{
  using internal::file_error;
  points.clear();
  polygons.clear();
  gifti_set_verb(0);
  gifti_image* image = gifti_read_image(path.c_str(), 1);
  if(image == nullptr)
    return file_error(File_status::INVALID_DATA, path + ": not a readable GIfTI file");
  struct Release
  {
    gifti_image* image;
    ~Release() { gifti_free_image(image); }
  } release{image};
  giiDataArray* coordinates = gifti_find_DA(image, NIFTI_INTENT_POINTSET, 0);
  giiDataArray* triangles = gifti_find_DA(image, NIFTI_INTENT_TRIANGLE, 0);
  if(coordinates == nullptr || triangles == nullptr)
    return file_error(File_status::INVALID_DATA, path + ": a GIfTI surface needs a POINTSET and a TRIANGLE array");
  auto shape = [](const giiDataArray* a, long long& rows) {
    rows = a->num_dim >= 1 ? a->dims[0] : 0;
    return a->num_dim == 2 && a->dims[1] == 3 && a->data != nullptr && a->nvals == 3 * rows;
  };
  long long nv = 0, nf = 0;
  if(!shape(coordinates, nv) || !shape(triangles, nf))
    return file_error(File_status::INVALID_DATA,
                      path + ": the POINTSET and TRIANGLE arrays must be n x 3 with their data");
  // Column-major arrays store the first coordinate of every row, then the second, ...
  const bool row_major = coordinates->ind_ord != GIFTI_IND_ORD_COL_MAJOR;
  const bool triangles_row_major = triangles->ind_ord != GIFTI_IND_ORD_COL_MAJOR;
  auto coordinate = [&](long long v, int k) -> double {
    const long long at = row_major ? 3 * v + k : k * nv + v;
    switch(coordinates->datatype)
    {
    case NIFTI_TYPE_FLOAT32:
      return static_cast<const float*>(coordinates->data)[at];
    case NIFTI_TYPE_FLOAT64:
      return static_cast<const double*>(coordinates->data)[at];
    default:
      return std::nan("");
    }
  };
  auto index = [&](long long f, int k) -> long long {
    const long long at = triangles_row_major ? 3 * f + k : k * nf + f;
    switch(triangles->datatype)
    {
    case NIFTI_TYPE_INT32:
      return static_cast<const std::int32_t*>(triangles->data)[at];
    case NIFTI_TYPE_UINT32:
      return static_cast<const std::uint32_t*>(triangles->data)[at];
    case NIFTI_TYPE_INT64:
      return static_cast<const std::int64_t*>(triangles->data)[at];
    default:
      return -1;
    }
  };
  points.reserve(static_cast<std::size_t>(nv));
  for(long long v = 0; v < nv; ++v)
  {
    const double x = coordinate(v, 0), y = coordinate(v, 1), z = coordinate(v, 2);
    if(!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      return file_error(File_status::INVALID_DATA,
                        path + ": vertex " + std::to_string(v)
                            + " is not finite (or the coordinates are not float32 or float64)");
    points.emplace_back(x, y, z);
  }
  polygons.reserve(static_cast<std::size_t>(nf));
  for(long long f = 0; f < nf; ++f)
  {
    Polygon polygon;
    for(int k = 0; k < 3; ++k)
    {
      const long long i = index(f, k);
      if(i < 0 || i >= nv)
        return file_error(File_status::INVALID_DATA, path + ": triangle " + std::to_string(f) + " refers to vertex "
                                                         + std::to_string(i) + ", of " + std::to_string(nv)
                                                         + " (or the indices are not integers)");
      polygon.push_back(static_cast<std::size_t>(i));
    }
    polygons.push_back(std::move(polygon));
  }
  if(points.empty())
    return file_error(File_status::EMPTY_FILE, path + ": the surface has no vertex");
  if(metadata != nullptr)
  {
    metadata->clear();
    for(int k = 0; k < image->meta.length; ++k)
      if(image->meta.name[k] != nullptr && image->meta.value[k] != nullptr)
        metadata->emplace_back(image->meta.name[k], image->meta.value[k]);
  }
  File_read read;
  read.message = std::to_string(points.size()) + " vertices, " + std::to_string(polygons.size()) + " faces";
  return read;
}

/// \ingroup PkgSphericalParameterizationRef
/// Writes a GIfTI surface: POINTSET (float32, or float64 when `float64`; times `radius`) and TRIANGLE (int32)
/// arrays, row-major, gzip-compressed base64, with the GIFTI library, and `metadata` (name, value pairs) in the
/// GIfTI element's metadata. Returns false with `error` set on failure.
template <typename Point, typename Polygon>
bool write_GIfTI_surface(const std::string& path, const std::vector<Point>& points,
                         const std::vector<Polygon>& triangles, bool float64, double radius, std::string& error,
                         const std::vector<std::pair<std::string, std::string>>& metadata = {})
{
  gifti_set_verb(0);
  gifti_image* image = gifti_create_image(0, 0, 0, 0, nullptr, 0);
  if(image == nullptr)
  {
    error = "the GIFTI library could not create an image";
    return false;
  }
  struct Release
  {
    gifti_image* image;
    ~Release() { gifti_free_image(image); }
  } release{image};
  for(const auto& entry : metadata)
    if(gifti_add_to_meta(&image->meta, entry.first.c_str(), entry.second.c_str(), 1) != 0)
    {
      error = "the GIFTI library could not add the metadata '" + entry.first + "'";
      return false;
    }
  if(gifti_add_empty_darray(image, 2) != 0)
  {
    error = "the GIFTI library could not add the arrays";
    return false;
  }
  giiDataArray* arrays[2] = {image->darray[0], image->darray[1]};
  const int intents[2] = {NIFTI_INTENT_POINTSET, NIFTI_INTENT_TRIANGLE};
  const int types[2] = {float64 ? NIFTI_TYPE_FLOAT64 : NIFTI_TYPE_FLOAT32, NIFTI_TYPE_INT32};
  const long long rows[2] = {static_cast<long long>(points.size()), static_cast<long long>(triangles.size())};
  for(int a = 0; a < 2; ++a)
  {
    giiDataArray* array = arrays[a];
    gifti_set_DA_defaults(array);
    array->intent = intents[a];
    array->datatype = types[a];
    array->ind_ord = GIFTI_IND_ORD_ROW_MAJOR;
    array->num_dim = 2;
    array->dims[0] = static_cast<int>(rows[a]);
    array->dims[1] = 3;
    array->encoding = GIFTI_ENCODING_B64GZ;
    array->endian = gifti_get_this_endian();
    array->nvals = 3 * rows[a];
    int swap_size = 0;
    gifti_datatype_sizes(array->datatype, &array->nbyper, &swap_size);
  }
  const int all[2] = {0, 1};
  if(gifti_alloc_DA_data(image, all, 2) != 0)
  {
    error = "the GIFTI library could not allocate the arrays";
    return false;
  }
  for(std::size_t v = 0; v < points.size(); ++v)
    for(int k = 0; k < 3; ++k)
    {
      const double c = radius * CGAL::to_double(points[v][k]);
      if(float64)
        static_cast<double*>(arrays[0]->data)[3 * v + static_cast<std::size_t>(k)] = c;
      else
        static_cast<float*>(arrays[0]->data)[3 * v + static_cast<std::size_t>(k)] = static_cast<float>(c);
    }
  for(std::size_t f = 0; f < triangles.size(); ++f)
  {
    if(triangles[f].size() != 3)
    {
      error = "face " + std::to_string(f) + " is not a triangle";
      return false;
    }
    for(int k = 0; k < 3; ++k)
      static_cast<std::int32_t*>(arrays[1]->data)[3 * f + static_cast<std::size_t>(k)] =
          static_cast<std::int32_t>(triangles[f][static_cast<std::size_t>(k)]);
  }
  if(gifti_write_image(image, path.c_str(), 1) != 0)
  {
    error = "the GIFTI library could not write '" + path + "'";
    return false;
  }
  return true;
}
#endif

} // namespace IO
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_IO_BRAIN_SURFACES_H
