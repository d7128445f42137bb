// Wavefront OBJ + MTL loader for the host simulator (host only: uses the heap, no exceptions used
// for errors). Produces a HostMesh (see host_mesh.hpp) with one vertex per unique (position, uv,
// normal) corner used by the faces.
//
// OBJ statements understood:
//   v x y z [w]        position; w is accepted and ignored (no rational / homogeneous division)
//   v x y z r g b      position with a linear vertex colour; colours are clamped to [0, 1]; if any
//                      `v` has a colour, every `v` must have one (else an error)
//   vt u v [w]         texture coordinate (w ignored)
//   vn x y z           normal; normalized on reading; a zero-length normal: see below
//   f a b c ...        face; corners `v`, `v/vt`, `v//vn`, `v/vt/vn` (forms may be mixed; an empty
//                      vt or vn field counts as absent); negative indices are relative to the
//                      elements defined so far; indices must refer to elements defined before the
//                      face (the OBJ rule); convex faces with more than 3 corners are fanned
//                      (v0, vi, vi+1), concave ones ear-clipped in their plane
//                      (polygon_triangulation.hpp); faces with repeated corners are kept.
//                      `fo` = `f`.
//   mtllib a.mtl ...   one or more MTL files, relative to the OBJ's folder (a name with spaces is
//                      accepted when the whole rest of the line names an existing file); read at
//                      once, so mtllib must come before the usemtl that uses its materials
//   usemtl name        current material for the following faces (unknown name: see below)
//   o, g, s, vp        accepted and ignored (names and smoothing groups are not kept); any other
//                      statement (l, p, curv, cstype ...) is ignored with one warning per keyword
//   # comment          anywhere on a line; blank lines; CRLF line ends; a UTF-8 BOM; a line ending
//                      in a backslash continues on the next line (errors name the first line)
// Ignored without error: any other statement (vp, l, p, cstype, deg, bmat, step, curv, curv2, surf,
// parm, trim, hole, scrv, sp, end, con, mg, bevel, c_interp, d_interp, lod, usemap, maplib,
// shadow_obj, trace_obj, ctech, stech, ...).
//
// MTL statements understood (keywords case-insensitive): newmtl, Ka, Kd, Ks, Ke (1 or 3 numbers,
// clamped to [0, 1]; the `spectral` and `xyz` forms are ignored), Ns (shininess = clamp(Ns, 0,
// 128)), d (`-halo` skipped; clamped to [0, 1]), Tr (d = 1 - Tr), map_Kd (options -blendu -blendv
// -bm -boost -cc -clamp -imfchan -mm -o -s -t -texres -type are skipped; the rest of the line is
// the file name, resolved relative to the MTL's folder; the file is not opened here). Everything
// else (illum, Ni, Tf, map_Ka, map_Ks, bump, PBR extensions, ...) is ignored. A material statement
// before any newmtl is an error. A material name defined again (in the same or a later MTL)
// replaces the earlier definition in place.
//
// Smooth normals (corners without vn) follow docs/conventions.md#lighting: the normalized sum,
// over every face that uses the position, of the face's area vector (for a triangle the cross
// product of two edges, not normalized; for a polygon the sum of those of its fan, i.e. twice its
// vector area; a face counts once per position even if the position repeats in it). A zero sum
// gives (0, 0, 1). Positions are scaled by a power of two before the sum so that huge coordinates
// cannot overflow.
//
// Errors are one line "FILE:LINE: what is wrong" (LINE 1-based; for "no faces" the last line).
// Numbers are read with std::from_chars (a leading '+' is accepted); trailing garbage, NaN/Inf and
// values too large for a double are errors; values too small for a double read as 0. OBJ and MTL
// files larger than 1 GiB, and devices, are refused before reading.
//
// Accepted with a warning (HostMesh::warnings, "FILE:LINE: what was done"), as other loaders
// accept them: `usemtl` without a library or naming a material it does not define (the default
// material), `usemtl` with no name (the material named '', else the default), `newmtl` with no
// name, a zero-length `vn` (its corners get the faces' smooth normal).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "lineraster/host_sim/formats/host_mesh.hpp"

namespace lr::host {

// Loads a Wavefront OBJ (and the MTL files it names) into a HostMesh. On failure returns false and
// sets `error` to one line "FILE:LINE: what is wrong" (FILE as given, LINE 1-based), or
// "FILE: cannot open: <strerror>" when the OBJ itself cannot be read, and leaves `out` untouched.
bool load_obj(const std::string& path, HostMesh& out, std::string& error);

// Same from text already in memory (`name` is used in error messages, `base_dir` to resolve mtllib;
// an empty base_dir means the current directory).
bool parse_obj(std::string_view text, const std::string& name, const std::string& base_dir,
               HostMesh& out, std::string& error);

// Parses one MTL file's text. On success replaces `out` with its materials (in order of
// definition); map_Kd paths are resolved relative to `base_dir`. On failure returns false, sets
// `error` to "NAME:LINE: what is wrong" and leaves `out` untouched.
bool parse_mtl(std::string_view text, const std::string& name, const std::string& base_dir,
               std::vector<HostMaterial>& out, std::string& error,
               std::vector<std::string>* warnings = nullptr);

}  // namespace lr::host
