// Wavefront OBJ + MTL loader: see obj_loader.hpp for what is understood and how errors are
// reported.
#include "lineraster/host_sim/formats/obj_loader.hpp"

#include "lineraster/host_sim/formats/polygon_triangulation.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <system_error>
#include <unordered_map>
#include <utility>

#include <sys/stat.h>

namespace lr::host {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
constexpr size_t kMaxFileBytes = size_t{1} << 30;  // OBJ and MTL files larger than 1 GiB: error

// ---------------------------------------------------------------------------------------------
// Small text helpers

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

void split_ws(std::string_view s, std::vector<std::string_view>& tokens) {
  tokens.clear();
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    const size_t start = i;
    while (i < s.size() && !is_space(s[i])) ++i;
    if (i > start) tokens.push_back(s.substr(start, i - start));
  }
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

// A token quoted for an error message: at most 40 characters, control characters replaced, so that
// the message stays one short line whatever the input holds.
std::string quote(std::string_view s) {
  std::string q = "'";
  const size_t n = std::min<size_t>(s.size(), 40);
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    q += (c < 0x20 || c == 0x7f) ? '?' : static_cast<char>(c);
  }
  if (s.size() > n) q += "...";
  q += "'";
  return q;
}

// Paths: '\' (from Windows exporters) becomes '/'; relative paths are joined to `base`.
std::string join_path(const std::string& base, std::string_view rel) {
  std::string r(rel);
  std::replace(r.begin(), r.end(), '\\', '/');
  if (base.empty() || (!r.empty() && r.front() == '/')) return r;
  if (base.back() == '/') return base + r;
  return base + "/" + r;
}

std::string dir_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return std::string();
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// Why read_file failed, for "PATH: cannot open: ..." messages.
std::string read_error(int err) {
  if (err == EFBIG) return "larger than the 1 GiB limit";
  if (err == ENODEV) return "a device, not a file";
  return std::strerror(err);
}

// Reads a whole file (at most kMaxFileBytes). On failure returns false with `err` = errno of the
// failing call, EFBIG for a file too large and ENODEV for a device (read_error() says so). A
// regular file's size is checked before reading, so a huge one is refused at once; a device
// (/dev/zero, /dev/urandom) is refused; pipes are read up to the limit.
bool read_file(const std::string& path, std::string& text, int& err) {
  if (path.find('\0') != std::string::npos) {
    err = ENOENT;
    return false;
  }
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    err = errno != 0 ? errno : EIO;
    return false;
  }
  struct stat st {};
  if (fstat(fileno(f), &st) == 0) {
    const bool device = S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode);
    if (device || (S_ISREG(st.st_mode) && static_cast<uint64_t>(st.st_size) > kMaxFileBytes)) {
      std::fclose(f);
      err = device ? ENODEV : EFBIG;
      return false;
    }
  }
  std::string data;
  char buf[65536];
  bool too_large = false;
  for (;;) {
    const size_t n = std::fread(buf, 1, sizeof buf, f);
    if (data.size() + n > kMaxFileBytes) {
      too_large = true;  // also stops endless sources such as /dev/zero
      break;
    }
    data.append(buf, n);
    if (n < sizeof buf) break;
  }
  const bool failed = too_large || std::ferror(f) != 0;
  err = too_large ? EFBIG : failed ? (errno != 0 ? errno : EIO) : 0;
  std::fclose(f);
  if (failed) return false;
  text = std::move(data);
  return true;
}

// ---------------------------------------------------------------------------------------------
// Lines: LF or CRLF ends, '#' comments, backslash continuation, UTF-8 BOM.

class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {
    if (text_.size() >= 3 && text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
  }

  // Next logical line with comments stripped; `first_line` = 1-based number of its first line.
  bool next(std::string_view& line, int& first_line) {
    if (pos_ >= text_.size()) return false;
    first_line = line_no_ + 1;
    std::string_view raw = raw_line();
    if (!ends_with_backslash(raw)) {
      line = strip_comment(raw);
      return true;
    }
    joined_.clear();
    for (;;) {
      while (is_space(raw.back())) raw.remove_suffix(1);
      raw.remove_suffix(1);  // the backslash
      joined_.append(raw);
      joined_.push_back(' ');
      if (pos_ >= text_.size()) break;
      raw = raw_line();
      if (!ends_with_backslash(raw)) {
        joined_.append(raw);
        break;
      }
    }
    line = strip_comment(joined_);
    return true;
  }

  int lines_read() const { return line_no_; }

 private:
  std::string_view raw_line() {
    const size_t nl = text_.find('\n', pos_);
    const size_t end = nl == std::string_view::npos ? text_.size() : nl;
    std::string_view raw = text_.substr(pos_, end - pos_);
    pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
    ++line_no_;
    while (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
    return raw;
  }
  static bool ends_with_backslash(std::string_view raw) {
    // Trailing blanks after the backslash are tolerated.
    while (!raw.empty() && is_space(raw.back())) raw.remove_suffix(1);
    return !raw.empty() && raw.back() == '\\';
  }
  static std::string_view strip_comment(std::string_view s) {
    const size_t hash = s.find('#');
    if (hash != std::string_view::npos) s = s.substr(0, hash);
    return s;
  }

  std::string_view text_;
  size_t pos_ = 0;
  int line_no_ = 0;
  std::string joined_;
};

// ---------------------------------------------------------------------------------------------
// Numbers

enum class NumStatus { kOk, kBad, kTooLarge };

// True when a decimal literal (sign already removed, syntax already checked by from_chars) has a
// magnitude below 1, i.e. from_chars' out-of-range means underflow rather than overflow.
bool literal_below_one(std::string_view s) {
  size_t i = 0;
  long long exp10 = 0;
  bool nonzero = false;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
    if (nonzero || s[i] != '0') {
      nonzero = true;
      ++exp10;
    }
    ++i;
  }
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
      if (!nonzero) {
        if (s[i] == '0') {
          --exp10;
        } else {
          nonzero = true;
        }
      }
      ++i;
    }
  }
  long long e = 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    bool neg = false;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
      if (e < 100000000) e = e * 10 + (s[i] - '0');
      ++i;
    }
    if (neg) e = -e;
  }
  return exp10 + e <= 0;
}

NumStatus parse_double(std::string_view s, double& v) {
  if (!s.empty() && s.front() == '+') {
    s.remove_prefix(1);
    if (s.empty() || s.front() == '+' || s.front() == '-') return NumStatus::kBad;
  }
  if (s.empty()) return NumStatus::kBad;
  double value = 0.0;
  const char* end = s.data() + s.size();
  const auto res = std::from_chars(s.data(), end, value);
  if (res.ec == std::errc::invalid_argument || res.ptr != end) return NumStatus::kBad;
  if (res.ec == std::errc::result_out_of_range) {
    const bool neg = s.front() == '-';
    if (!literal_below_one(neg ? s.substr(1) : s)) return NumStatus::kTooLarge;
    value = neg ? -0.0 : 0.0;
  }
  v = value;
  return NumStatus::kOk;
}

NumStatus parse_int(std::string_view s, long long& v) {
  if (!s.empty() && s.front() == '+') {
    s.remove_prefix(1);
    if (s.empty() || s.front() == '+' || s.front() == '-') return NumStatus::kBad;
  }
  if (s.empty()) return NumStatus::kBad;
  long long value = 0;
  const char* end = s.data() + s.size();
  const auto res = std::from_chars(s.data(), end, value);
  if (res.ec == std::errc::invalid_argument || res.ptr != end) return NumStatus::kBad;
  if (res.ec == std::errc::result_out_of_range) return NumStatus::kTooLarge;
  v = value;
  return NumStatus::kOk;
}

// Error sink: "NAME:LINE: message".
struct Where {
  const std::string& name;
  int line;
};

bool fail(std::string& error, const Where& w, const std::string& msg) {
  error = w.name + ":" + std::to_string(w.line) + ": " + msg;
  return false;
}

// What other loaders accept and this one does too, with one line "FILE:LINE: what was done".
void warn(std::vector<std::string>& warnings, const Where& w, const std::string& msg) {
  warnings.push_back(w.name + ":" + std::to_string(w.line) + ": " + msg);
}

// Reads tokens[first..] as finite doubles into `vals`.
bool read_numbers(const std::vector<std::string_view>& tokens, size_t first, double* vals,
                  const Where& w, std::string& error) {
  for (size_t i = first; i < tokens.size(); ++i) {
    double v = 0.0;
    switch (parse_double(tokens[i], v)) {
      case NumStatus::kOk:
        break;
      case NumStatus::kBad:
        return fail(error, w, "bad number " + quote(tokens[i]));
      case NumStatus::kTooLarge:
        return fail(error, w, "number out of range " + quote(tokens[i]));
    }
    if (!std::isfinite(v)) return fail(error, w, "number is not finite " + quote(tokens[i]));
    vals[i - first] = v;
  }
  return true;
}

// Rest of the line after the keyword, trimmed (names and paths may contain spaces).
std::string_view rest_after(std::string_view line, std::string_view keyword_token) {
  const size_t off = static_cast<size_t>(keyword_token.data() - line.data()) + keyword_token.size();
  return trim(line.substr(off));
}

double clamp01(double v) {
  return std::clamp(v, 0.0, 1.0);
}

// Unit vector of v, or false when v is zero (or not finite). Scales first so nothing overflows.
bool normalize(Vec3d& v) {
  const double m = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  if (!(m > 0.0) || !std::isfinite(m)) return false;
  const double x = v[0] / m, y = v[1] / m, z = v[2] / m;
  const double len = std::sqrt(x * x + y * y + z * z);
  v = {x / len, y / len, z / len};
  return true;
}

// ---------------------------------------------------------------------------------------------
// MTL

bool parse_mtl_impl(std::string_view text, const std::string& name, const std::string& base_dir,
                    std::vector<HostMaterial>& out, std::string& error,
                    std::vector<std::string>& warnings) {
  std::vector<HostMaterial> mats;
  HostMaterial* cur = nullptr;
  std::vector<std::string_view> tok;
  LineReader reader(text);
  std::string_view line;
  int line_no = 0;
  while (reader.next(line, line_no)) {
    const Where w{name, line_no};
    split_ws(line, tok);
    if (tok.empty()) continue;
    const std::string_view kw = tok[0];
    if (iequals(kw, "newmtl")) {
      const std::string_view mname = rest_after(line, kw);
      // Blender writes materials without a name: "usemtl" alone selects them.
      if (mname.empty()) warn(warnings, w, "newmtl without a name: the material is named ''");
      mats.emplace_back();
      cur = &mats.back();
      cur->name = std::string(mname);
      continue;
    }
    const bool colour =
        iequals(kw, "Ka") || iequals(kw, "Kd") || iequals(kw, "Ks") || iequals(kw, "Ke");
    const bool known = colour || iequals(kw, "Ns") || iequals(kw, "d") || iequals(kw, "Tr") ||
                       iequals(kw, "map_Kd");
    if (!known) continue;
    if (!cur) return fail(error, w, quote(kw) + " before any newmtl");
    if (colour) {
      if (tok.size() >= 2 && (iequals(tok[1], "spectral") || iequals(tok[1], "xyz"))) continue;
      if (tok.size() != 2 && tok.size() != 4) {
        return fail(
            error, w,
            std::string(kw) + ": expected 1 or 3 numbers, got " + std::to_string(tok.size() - 1));
      }
      double v[3] = {0, 0, 0};
      if (!read_numbers(tok, 1, v, w, error)) return false;
      if (tok.size() == 2) v[1] = v[2] = v[0];
      const Vec3d c{clamp01(v[0]), clamp01(v[1]), clamp01(v[2])};
      if (iequals(kw, "Ka")) cur->ambient = c;
      if (iequals(kw, "Kd")) cur->diffuse = c;
      if (iequals(kw, "Ks")) cur->specular = c;
      if (iequals(kw, "Ke")) cur->emission = c;
    } else if (iequals(kw, "map_Kd")) {
      // Skip options; the rest of the line (spaces kept) is the file name.
      static const struct {
        const char* opt;
        int min_args, max_args;
      } kOptions[] = {{"-blendu", 1, 1}, {"-blendv", 1, 1}, {"-bm", 1, 1},      {"-boost", 1, 1},
                      {"-cc", 1, 1},     {"-clamp", 1, 1},  {"-imfchan", 1, 1}, {"-mm", 2, 2},
                      {"-o", 1, 3},      {"-s", 1, 3},      {"-t", 1, 3},       {"-texres", 1, 1},
                      {"-type", 1, 1}};
      size_t i = 1;
      while (i < tok.size() && tok[i].size() > 1 && tok[i][0] == '-') {
        int min_args = 0, max_args = 0;
        for (const auto& o : kOptions) {
          if (iequals(tok[i], o.opt)) {
            min_args = o.min_args;
            max_args = o.max_args;
          }
        }
        ++i;
        for (int a = 0; a < max_args && i < tok.size(); ++a) {
          double dummy = 0.0;
          // Optional numeric arguments (-o/-s/-t u [v [w]]) stop at the first non-number.
          if (a >= min_args && parse_double(tok[i], dummy) != NumStatus::kOk) break;
          ++i;
        }
      }
      if (i >= tok.size()) return fail(error, w, "map_Kd needs a file name");
      const size_t off = static_cast<size_t>(tok[i].data() - line.data());
      cur->map_kd = join_path(base_dir, trim(line.substr(off)));
    } else {
      // Ns, d, Tr: one number (d may start with -halo).
      size_t first = 1;
      if (iequals(kw, "d") && tok.size() >= 2 && iequals(tok[1], "-halo")) first = 2;
      if (tok.size() != first + 1) {
        return fail(
            error, w,
            std::string(kw) + ": expected 1 number, got " + std::to_string(tok.size() - first));
      }
      double v = 0.0;
      if (!read_numbers(tok, first, &v, w, error)) return false;
      if (iequals(kw, "Ns")) cur->shininess = std::clamp(v, 0.0, 128.0);
      if (iequals(kw, "d")) cur->alpha = clamp01(v);
      if (iequals(kw, "Tr")) cur->alpha = 1.0 - clamp01(v);
    }
  }
  out = std::move(mats);
  return true;
}

// ---------------------------------------------------------------------------------------------
// OBJ

struct CornerKey {
  uint32_t p, t, n;
  bool operator==(const CornerKey& o) const { return p == o.p && t == o.t && n == o.n; }
};

struct CornerKeyHash {
  size_t operator()(const CornerKey& k) const {
    uint64_t h = k.p;
    h = h * 0x9E3779B97F4A7C15ull ^ k.t;
    h = h * 0x9E3779B97F4A7C15ull ^ k.n;
    h ^= h >> 29;
    return static_cast<size_t>(h * 0xBF58476D1CE4E5B9ull);
  }
};

class ObjParser {
 public:
  ObjParser(const std::string& name, const std::string& base_dir, std::string& error)
      : name_(name), base_dir_(base_dir), error_(error) {}

  bool parse(std::string_view text, HostMesh& out) {
    LineReader reader(text);
    std::string_view line;
    int line_no = 0;
    while (reader.next(line, line_no)) {
      const Where w{name_, line_no};
      split_ws(line, tok_);
      if (tok_.empty()) continue;
      const std::string_view kw = tok_[0];
      bool ok = true;
      if (kw == "v") {
        ok = on_v(w);
      } else if (kw == "vt") {
        ok = on_vt(w);
      } else if (kw == "vn") {
        ok = on_vn(w);
      } else if (kw == "f" || kw == "fo") {
        ok = on_f(w);
      } else if (kw == "mtllib") {
        ok = on_mtllib(line, w);
      } else if (kw == "usemtl") {
        ok = on_usemtl(line, w);
      } else if (kw != "o" && kw != "g" && kw != "s" && kw != "vp") {
        // Names, groups, smoothing and parameter vertices are of no use here and silent; any
        // other statement (lines, points, curves, surfaces...) is ignored with one warning per
        // keyword.
        const std::string key(kw.substr(0, 32));
        if (std::find(ignored_.begin(), ignored_.end(), key) == ignored_.end()) {
          ignored_.push_back(key);
          warn(warnings_, w, "'" + key + "' statements are not drawn: ignored");
        }
      }
      if (!ok) return false;
    }
    if (triangles_.empty()) {
      return fail(error_, Where{name_, std::max(1, reader.lines_read())}, "no faces");
    }
    return build(out);
  }

 private:
  bool on_v(const Where& w) {
    const size_t n = tok_.size() - 1;
    if (n != 3 && n != 4 && n != 6) {
      return fail(error_, w,
                  std::string(n < 3 ? "too few" : "wrong number of") +
                      " numbers in v: expected 3, 4 (x y z w) or 6 (x y z r g b), got " +
                      std::to_string(n));
    }
    double v[6] = {0, 0, 0, 0, 0, 0};
    if (!read_numbers(tok_, 1, v, w, error_)) return false;
    const int has_colour = n == 6 ? 1 : 0;
    if (colour_state_ < 0) {
      colour_state_ = has_colour;
    } else if (colour_state_ != has_colour) {
      return fail(error_, w,
                  has_colour ? "inconsistent vertex colours: this vertex has r g b, earlier ones "
                               "have none"
                             : "inconsistent vertex colours: this vertex has no r g b, earlier "
                               "ones have");
    }
    if (positions_.size() >= kNone - 1) return fail(error_, w, "too many positions");
    positions_.push_back({v[0], v[1], v[2]});
    position_lines_.push_back(static_cast<uint32_t>(w.line));
    if (has_colour) colors_.push_back({clamp01(v[3]), clamp01(v[4]), clamp01(v[5])});
    return true;
  }

  bool on_vt(const Where& w) {
    const size_t n = tok_.size() - 1;
    if (n != 2 && n != 3) {
      return fail(error_, w,
                  std::string(n < 2 ? "too few" : "too many") +
                      " numbers in vt: expected 2 or 3, got " + std::to_string(n));
    }
    double v[3] = {0, 0, 0};
    if (!read_numbers(tok_, 1, v, w, error_)) return false;
    if (uvs_.size() >= kNone - 1) return fail(error_, w, "too many texture coordinates");
    uvs_.push_back({v[0], v[1]});
    return true;
  }

  bool on_vn(const Where& w) {
    const size_t n = tok_.size() - 1;
    if (n != 3) {
      return fail(error_, w,
                  std::string(n < 3 ? "too few" : "too many") + " numbers in vn: expected 3, got " +
                      std::to_string(n));
    }
    double v[3] = {0, 0, 0};
    if (!read_numbers(tok_, 1, v, w, error_)) return false;
    Vec3d nv{v[0], v[1], v[2]};
    if (normals_.size() >= kNone - 1) return fail(error_, w, "too many normals");
    // A zero normal stays (0, 0, 0): the corners that use it get the faces' smooth normal.
    if (!normalize(nv)) {
      warn(warnings_, w, "vn has zero length: its corners get the faces' normal");
      nv = Vec3d{0, 0, 0};
    }
    normals_.push_back(nv);
    return true;
  }

  // Resolves a 1-based or negative (relative) OBJ index against `count` elements.
  bool resolve(std::string_view field, size_t count, const char* what, const Where& w,
               uint32_t& out) {
    long long idx = 0;
    switch (parse_int(field, idx)) {
      case NumStatus::kOk:
        break;
      case NumStatus::kBad:
        return fail(error_, w, std::string("bad ") + what + " index " + quote(field));
      case NumStatus::kTooLarge:
        return fail(error_, w,
                    std::string(what) + " index " + quote(field) + " out of range (" +
                        std::to_string(count) + " defined)");
    }
    if (idx == 0) {
      return fail(error_, w, std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
    }
    const long long c = static_cast<long long>(count);
    if (idx > c || idx < -c) {
      return fail(error_, w,
                  std::string(what) + " index " + std::to_string(idx) + " out of range (" +
                      std::to_string(count) + " defined)");
    }
    out = static_cast<uint32_t>(idx > 0 ? idx - 1 : c + idx);
    return true;
  }

  bool on_f(const Where& w) {
    const size_t n = tok_.size() - 1;
    if (n < 3) {
      return fail(error_, w, "face needs at least 3 vertices, got " + std::to_string(n));
    }
    face_corners_.clear();
    for (size_t i = 1; i < tok_.size(); ++i) {
      const std::string_view t = tok_[i];
      std::string_view fields[3];
      size_t nf = 0, start = 0;
      for (;;) {
        const size_t slash = t.find('/', start);
        if (nf == 3) return fail(error_, w, "bad face vertex " + quote(t));
        fields[nf++] = t.substr(start, slash == std::string_view::npos ? slash : slash - start);
        if (slash == std::string_view::npos) break;
        start = slash + 1;
      }
      CornerKey k{kNone, kNone, kNone};
      if (fields[0].empty()) return fail(error_, w, "bad face vertex " + quote(t));
      if (!resolve(fields[0], positions_.size(), "position", w, k.p)) return false;
      if (nf > 1 && !fields[1].empty()) {
        if (!resolve(fields[1], uvs_.size(), "texture coordinate", w, k.t)) return false;
        any_uv_ = true;
      }
      if (nf > 2 && !fields[2].empty()) {
        if (!resolve(fields[2], normals_.size(), "normal", w, k.n)) return false;
        // A zero-length vn is no normal: the corner is the one without it (smooth normal).
        if (normals_[k.n] == Vec3d{0, 0, 0}) k.n = kNone;
      }
      uint32_t vi = 0;
      const auto it = corner_map_.find(k);
      if (it != corner_map_.end()) {
        vi = it->second;
      } else {
        if (corners_.size() >= kNone - 1) return fail(error_, w, "too many vertices");
        vi = static_cast<uint32_t>(corners_.size());
        corners_.push_back(k);
        corner_map_.emplace(k, vi);
      }
      face_corners_.push_back(vi);
    }
    // The face's triangles in its plane (a fan when it is convex).
    face_points_.clear();
    for (const uint32_t vi : face_corners_) face_points_.push_back(positions_[corners_[vi].p]);
    face_triangles_.clear();
    if (!triangulate_polygon(face_points_, face_triangles_))
      warn(warnings_, w,
           "a concave face of " + std::to_string(face_points_.size()) +
               " corners: fanned from its first corner (ear clipping stops at " +
               std::to_string(kMaxEarClippedCorners) + " corners), its triangles may leave it");
    for (const auto& t : face_triangles_) {
      triangles_.push_back({face_corners_[t[0]], face_corners_[t[1]], face_corners_[t[2]]});
      triangle_material_.push_back(current_material_);
    }
    // Remember the face (its corners' vertices) for the smooth normals.
    face_start_.push_back(static_cast<uint32_t>(face_vertices_.size()));
    face_vertices_.insert(face_vertices_.end(), face_corners_.begin(), face_corners_.end());
    return true;
  }

  bool load_mtl_file(const std::string& path, const Where& w) {
    std::string text;
    int err = 0;
    if (!read_file(path, text, err)) {
      return fail(error_, w,
                  "cannot open material library " + quote(path) + ": " + read_error(err));
    }
    std::vector<HostMaterial> mats;
    if (!parse_mtl_impl(text, path, dir_of(path), mats, error_, warnings_)) return false;
    mtl_files_.push_back(path);
    for (HostMaterial& m : mats) {
      const auto it = std::find_if(materials_.begin(), materials_.end(),
                                   [&](const HostMaterial& x) { return x.name == m.name; });
      if (it != materials_.end()) {
        *it = std::move(m);
      } else {
        materials_.push_back(std::move(m));
      }
    }
    return true;
  }

  bool on_mtllib(std::string_view line, const Where& w) {
    const std::string_view rest = rest_after(line, tok_[0]);
    if (rest.empty()) return fail(error_, w, "mtllib needs a file name");
    if (tok_.size() > 2) {
      // A single name with spaces, if such a file exists.
      const std::string whole = join_path(base_dir_, rest);
      if (std::FILE* f = std::fopen(whole.c_str(), "rb")) {
        std::fclose(f);
        return load_mtl_file(whole, w);
      }
    }
    for (size_t i = 1; i < tok_.size(); ++i) {
      if (!load_mtl_file(join_path(base_dir_, tok_[i]), w)) return false;
    }
    return true;
  }

  bool on_usemtl(std::string_view line, const Where& w) {
    const std::string_view mname = rest_after(line, tok_[0]);
    for (size_t i = 0; i < materials_.size(); ++i) {
      if (materials_[i].name == mname) {
        current_material_ = static_cast<int32_t>(i);
        return true;
      }
    }
    // No library, or a name it does not define: what follows gets the default material.
    current_material_ = -1;
    warn(warnings_, w,
         (materials_.empty() ? "usemtl " + quote(mname) + " without a material library"
                             : "unknown material " + quote(mname)) +
             ": the default material is used");
    return true;
  }

  // Vertices numbered in order of first use by the triangles (as a file of those triangles
  // reads back): a face's corners are numbered as read, but its ear-clipped triangles may use
  // them in another order.
  void number_by_first_use() {
    std::vector<uint32_t> to_new(corners_.size(), kNone);
    uint32_t next = 0;
    for (const auto& t : triangles_)
      for (const uint32_t v : t)
        if (to_new[v] == kNone) to_new[v] = next++;
    for (uint32_t& v : to_new)
      if (v == kNone) v = next++;  // a corner no triangle uses (none: kept for safety)
    std::vector<CornerKey> corners(corners_.size());
    for (size_t i = 0; i < corners_.size(); ++i) corners[to_new[i]] = corners_[i];
    corners_ = std::move(corners);
    for (auto& t : triangles_)
      for (uint32_t& v : t) v = to_new[v];
    for (uint32_t& v : face_vertices_) v = to_new[v];
  }

  bool build(HostMesh& out) {
    number_by_first_use();
    HostMesh mesh;
    const size_t nv = corners_.size();
    mesh.positions.resize(nv);
    mesh.normals.resize(nv);
    if (colour_state_ == 1) mesh.colors.resize(nv);
    if (any_uv_) mesh.uvs.resize(nv);
    bool need_smooth = false;
    for (size_t i = 0; i < nv; ++i) {
      const CornerKey& k = corners_[i];
      mesh.positions[i] = positions_[k.p];
      if (colour_state_ == 1) mesh.colors[i] = colors_[k.p];
      if (any_uv_) mesh.uvs[i] = k.t != kNone ? uvs_[k.t] : Vec2d{0.0, 0.0};
      if (k.n != kNone) {
        mesh.normals[i] = normals_[k.n];
      } else {
        need_smooth = true;
      }
    }
    if (need_smooth) {
      const std::vector<Vec3d> smooth = smooth_normals();
      for (size_t i = 0; i < nv; ++i) {
        if (corners_[i].n == kNone) mesh.normals[i] = smooth[corners_[i].p];
      }
    }
    mesh.triangles = std::move(triangles_);
    mesh.triangle_material = std::move(triangle_material_);
    mesh.materials = std::move(materials_);
    mesh.material_libraries = std::move(mtl_files_);
    mesh.warnings = std::move(warnings_);
    mesh.source = name_;
    mesh.lines.resize(nv);
    for (size_t i = 0; i < nv; ++i) mesh.lines[i] = position_lines_[corners_[i].p];
    out = std::move(mesh);
    return true;
  }

  // Per position: normalized sum of the area vectors of the faces using it (see the header).
  std::vector<Vec3d> smooth_normals() const {
    // Scale by a power of two (exact) so that coordinates are below 1 in magnitude.
    double m = 0.0;
    for (const Vec3d& p : positions_) {
      m = std::max({m, std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
    }
    const int shift = m > 0.0 ? -(std::ilogb(m) + 1) : 0;
    auto scaled = [&](uint32_t vi) {
      const Vec3d& p = positions_[corners_[vi].p];
      return Vec3d{std::ldexp(p[0], shift), std::ldexp(p[1], shift), std::ldexp(p[2], shift)};
    };
    std::vector<Vec3d> sum(positions_.size(), Vec3d{0.0, 0.0, 0.0});
    std::vector<uint32_t> stamp(positions_.size(), kNone);
    for (size_t f = 0; f < face_start_.size(); ++f) {
      const size_t b = face_start_[f];
      const size_t e = f + 1 < face_start_.size() ? face_start_[f + 1] : face_vertices_.size();
      const Vec3d p0 = scaled(face_vertices_[b]);
      Vec3d area{0.0, 0.0, 0.0};
      for (size_t i = b + 1; i + 1 < e; ++i) {
        const Vec3d p1 = scaled(face_vertices_[i]);
        const Vec3d p2 = scaled(face_vertices_[i + 1]);
        const Vec3d a{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        const Vec3d c{p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        area[0] += a[1] * c[2] - a[2] * c[1];
        area[1] += a[2] * c[0] - a[0] * c[2];
        area[2] += a[0] * c[1] - a[1] * c[0];
      }
      for (size_t i = b; i < e; ++i) {
        const uint32_t p = corners_[face_vertices_[i]].p;
        if (stamp[p] == static_cast<uint32_t>(f)) continue;  // once per face
        stamp[p] = static_cast<uint32_t>(f);
        for (size_t c = 0; c < 3; ++c) sum[p][c] += area[c];
      }
    }
    for (Vec3d& n : sum) {
      if (!normalize(n)) n = {0.0, 0.0, 1.0};
    }
    return sum;
  }

  const std::string& name_;
  const std::string& base_dir_;
  std::string& error_;
  std::vector<std::string_view> tok_;

  std::vector<Vec3d> positions_, colors_, normals_;
  std::vector<Vec2d> uvs_;
  int colour_state_ = -1;  // -1: no v yet, 0: without colours, 1: with colours
  bool any_uv_ = false;

  std::vector<CornerKey> corners_;  // unified vertices
  std::unordered_map<CornerKey, uint32_t, CornerKeyHash> corner_map_;
  std::vector<uint32_t> face_corners_;
  std::vector<uint32_t> face_start_, face_vertices_;
  std::vector<std::array<uint32_t, 3>> triangles_;
  std::vector<int32_t> triangle_material_;
  std::vector<std::string> mtl_files_;  // the MTL files read
  std::vector<std::string> warnings_;
  std::vector<uint32_t> position_lines_;  // per `v`: its line
  std::vector<std::string> ignored_;      // the keywords ignored so far (one warning each)
  std::vector<Vec3d> face_points_;        // the current face's corner positions
  std::vector<std::array<uint32_t, 3>> face_triangles_;  // and its triangles
  std::vector<HostMaterial> materials_;
  int32_t current_material_ = -1;
};

}  // namespace

bool parse_mtl(std::string_view text, const std::string& name, const std::string& base_dir,
               std::vector<HostMaterial>& out, std::string& error,
               std::vector<std::string>* warnings) {
  std::vector<std::string> ignored;
  return parse_mtl_impl(text, name, base_dir, out, error, warnings ? *warnings : ignored);
}

bool parse_obj(std::string_view text, const std::string& name, const std::string& base_dir,
               HostMesh& out, std::string& error) {
  ObjParser parser(name, base_dir, error);
  return parser.parse(text, out);
}

bool load_obj(const std::string& path, HostMesh& out, std::string& error) {
  std::string text;
  int err = 0;
  if (!read_file(path, text, err)) {
    error = path + ": cannot open: " + read_error(err);
    return false;
  }
  return parse_obj(text, path, dir_of(path), out, error);
}

}  // namespace lr::host
