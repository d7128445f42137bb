// lineraster-sim: renders an OBJ with the fixed-point core to PNG or PPM.
// Any wrong option or bad file: one line on stderr, exit status 2, no output written.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/lighting/lighting.hpp"
#include "core/output/pixel_format.hpp"
#include "core/scene/material.hpp"
#include "hal/host/display_spec.hpp"
#include "hal/panel.hpp"
#include "hal/panel_sink.hpp"
#include "host_sim/emulator/emulator_bus.hpp"
#include "host_sim/emulator/panel_emulator.hpp"
#include "host_sim/formats/image_io.hpp"
#include "host_sim/formats/obj_loader.hpp"
#include "host_sim/formats/texture_load.hpp"
#include "host_sim/scene/mesh_prep.hpp"
#include "host_sim/scene/scene.hpp"
#ifdef LR_HAVE_SPIDEV
#include "hal/host/linux/spidev_bus.hpp"
#endif
#ifdef LR_HAVE_FT232H
#include "hal/host/usb/ft232h_bus.hpp"
#endif

namespace {

using lr::host::Vec3d;

constexpr const char* kUsage =
    "usage: lineraster-sim --obj FILE [--out FILE.png|.ppm] [--width N] [--height N] [--fovy DEG]\n"
    "  [--near Z] [--far Z] [--eye x,y,z] [--target x,y,z] [--up x,y,z] [--fit] [--model-scale S]\n"
    "  [--model-rotate-y DEG] [--model-translate x,y,z] [--shading flat|gouraud|phong] [--unlit]\n"
    "  [--light-dir x,y,z] [--light dir:x,y,z[:r,g,b]] [--light point:x,y,z[:r,g,b[:c,l,q]]]\n"
    "  [--global-ambient r,g,b] [--local-viewer] [--two-sided] [--material NAME]\n"
    "  [--ambient r,g,b] [--diffuse r,g,b] [--specular r,g,b] [--shininess N] [--bg r,g,b]\n"
    "  [--no-depth] [--cull back|none] [--depth-out FILE.png] [--strip-height 1|2|4|8|16|32]\n"
    "  [--stats] [--texture FILE.png] [--filter nearest|bilinear] [--wrap repeat|clamp]\n"
    "  [--perspective exact|span8|span16|span32|affine] [--mipmap none|nearest|linear]\n"
    "  [--texture-format rgb565|rgb888|l8|palette8] [--subdivide N]\n"
    "Phong only (--shading phong): [--lighting exact|table] [--lighting-table N]\n"
    "  [--lighting-table-filter nearest|bilinear] [--envmap FILE.png] [--normalmap FILE.png]\n"
    "--light: repeatable, at most 4, not with --light-dir; colour r,g,b default 1,1,1; c,l,q:\n"
    "  GL attenuation 1 / (c + l d + q d^2), default 1,0,0. --lighting default exact;\n"
    "  --lighting-table: 8..256 cells per side, default 32, bilinear; needs --lighting table.\n"
    "Panels: [--display emulator:PANEL] [--display ft232h[:SERIAL]] [--panel PANEL] [--frames N]\n"
    "  [--display spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE[,bl=CHIP:LINE][,hz=N]]\n"
    "PANEL: st7789:240x240|240x320|135x240|320x240[:ROT] or ili9341:240x320|320x240[:ROT], ROT\n"
    "  0|90|180|270 (default 0); the frame is the panel's size. spidev and ft232h need --panel.\n"
    "--frames N: N frames turning the model 360/N degrees about y each, statistics per frame.\n"
    "--subdivide N: split each triangle in 4 at its edge midpoints, N times (0..4).\n";

int fail(const std::string& msg) {
  std::fprintf(stderr, "lineraster-sim: %s\n", msg.c_str());
  return 2;
}

bool parse_double(std::string_view s, double& out) {
  if (s.empty()) return false;
  std::string tmp(s);
  char* end = nullptr;
  out = std::strtod(tmp.c_str(), &end);
  return end == tmp.c_str() + tmp.size() && std::isfinite(out);
}

bool parse_int(std::string_view s, int& out) {
  double d;
  if (!parse_double(s, d) || d != std::floor(d) || d < -1e9 || d > 1e9) return false;
  out = static_cast<int>(d);
  return true;
}

bool parse_vec3(std::string_view s, Vec3d& out) {
  size_t a = s.find(','), b = a == std::string_view::npos ? a : s.find(',', a + 1);
  if (b == std::string_view::npos || s.find(',', b + 1) != std::string_view::npos) return false;
  return parse_double(s.substr(0, a), out[0]) && parse_double(s.substr(a + 1, b - a - 1), out[1]) &&
         parse_double(s.substr(b + 1), out[2]);
}

// Splits s at every ':' ("a:b:" gives "a", "b", "").
std::vector<std::string_view> split_colons(std::string_view s) {
  std::vector<std::string_view> parts;
  for (size_t start = 0;;) {
    size_t c = s.find(':', start);
    parts.push_back(s.substr(start, c == std::string_view::npos ? c : c - start));
    if (c == std::string_view::npos) return parts;
    start = c + 1;
  }
}

bool unit_color(const Vec3d& c) {
  for (double v : c)
    if (v < 0 || v > 1) return false;
  return true;
}

// --light dir:x,y,z[:r,g,b] or point:x,y,z[:r,g,b[:c,l,q]]. On failure `why` says what is
// wrong, in the words of the option's error message.
bool parse_light(std::string_view s, lr::host::LightOption& out, std::string& why) {
  why = "expected dir:x,y,z[:r,g,b] or point:x,y,z[:r,g,b[:c,l,q]]";
  const std::vector<std::string_view> p = split_colons(s);
  if (p[0] != "dir" && p[0] != "point") return false;
  out = lr::host::LightOption{};
  out.point = p[0] == "point";
  if (p.size() < 2 || p.size() > (out.point ? 4u : 3u) || !parse_vec3(p[1], out.xyz)) return false;
  if (!out.point && out.xyz[0] == 0 && out.xyz[1] == 0 && out.xyz[2] == 0) {
    why = "zero direction";
    return false;
  }
  if (p.size() >= 3 && (!parse_vec3(p[2], out.color) || !unit_color(out.color))) {
    why = "colour r,g,b in [0,1]";
    return false;
  }
  if (p.size() == 4) {
    Vec3d a;
    if (!parse_vec3(p[3], a) || a[0] < 0 || a[1] < 0 || a[2] < 0 || a[0] > 32767 || a[1] > 32767 ||
        a[2] > 32767 || a[0] + a[1] + a[2] <= 0) {
      why = "attenuation c,l,q: each in [0, 32767], not all 0";
      return false;
    }
    out.constant = a[0];
    out.linear = a[1];
    out.quadratic = a[2];
  }
  return true;
}

std::string extension(const std::string& path) {
  size_t dot = path.find_last_of('.');
  size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return e;
}

// Sends a rendered frame to a strip sink as the renderer does: begin_frame, strips of k rows top
// to bottom (acquire, fill, submit), end_frame. render_scene() renders RGB888, and every span
// of the core stores PF::encode(Rgb8), so Rgb565Be::encode of the frame's pixels is exactly what
// a Renderer<Rgb565Be, K> would have put in each strip.
lr::Status send_frame(lr::StripSink<lr::Rgb565Be>& sink, const lr::host::ImageRgb8& img, int k) {
  const auto w = static_cast<uint16_t>(img.width), h = static_cast<uint16_t>(img.height);
  lr::Status st = sink.begin_frame(w, h);
  if (st != lr::Status::kOk) return st;
  for (int y0 = 0; y0 < h; y0 += k) {
    const int rows = std::min(k, h - y0);
    lr::StripLease<lr::Rgb565Be> lease;
    st = sink.acquire(lease);
    if (st != lr::Status::kOk) return st;
    std::span<uint16_t> px = lease.pixels();
    if (px.size() < size_t{w} * static_cast<size_t>(rows)) return lr::Status::kInvalidArgument;
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < w; ++c) {
        const uint8_t* p = &img.rgb[(static_cast<size_t>(y0 + r) * w + static_cast<size_t>(c)) * 3];
        px[static_cast<size_t>(r) * w + static_cast<size_t>(c)] =
            lr::Rgb565Be::encode({p[0], p[1], p[2]});
      }
    }
    const lr::StripRect rect{0, static_cast<uint16_t>(y0), w, static_cast<uint16_t>(rows)};
    st = sink.submit(rect, std::move(lease));
    if (st != lr::Status::kOk) return st;
  }
  return sink.end_frame();
}

// A panel behind --display: its bus (the emulator's, or a real backend's), counted, the driver
// and a double-buffered sink that skips unchanged strips.
class PanelOutput {
 public:
  bool open(const lr::host::DisplaySpec& spec, const lr::PanelConfig& config, int strip_height,
            std::string& error) {
    config_ = config;
    strip_height_ = strip_height;
    lr::PanelBus* bus = nullptr;
    switch (spec.kind) {
      case lr::host::DisplayKind::kEmulator: {
        emulator_ = std::make_unique<lr::host::PanelEmulator>(config);
        lr::host::EmulatorBus::Options options;
        options.deferred = true;  // transfers complete in wait(), as on a real bus
        options.log = false;
        emulator_bus_ = std::make_unique<lr::host::EmulatorBus>(*emulator_, options);
        bus = emulator_bus_.get();
        break;
      }
      case lr::host::DisplayKind::kSpidev: {
#ifdef LR_HAVE_SPIDEV
        lr::SpidevConfig c;
        if (!lr::parse_spidev_spec(spec.device, c, error)) return false;
        spidev_ = lr::SpidevBus::open(c, error);
        if (!spidev_) return false;
        bus = spidev_.get();
        break;
#else
        error =
            "--display spidev: this lineraster-sim was built without the spidev backend "
            "(needs libgpiod 1.x: apt-get install libgpiod-dev, then rebuild)";
        return false;
#endif
      }
      case lr::host::DisplayKind::kFt232h: {
#ifdef LR_HAVE_FT232H
        lr::Ft232hConfig c;
        if (!lr::parse_ft232h_spec(spec.device, c, error)) return false;
        ft232h_ = lr::Ft232hBus::open(c, error);
        if (!ft232h_) return false;
        bus = ft232h_.get();
        break;
#else
        error =
            "--display ft232h: this lineraster-sim was built without the FT232H backend "
            "(needs libusb-1.0: apt-get install libusb-1.0-0-dev, then rebuild)";
        return false;
#endif
      }
      case lr::host::DisplayKind::kNone:
        error = "no display";
        return false;
    }
    counting_ = std::make_unique<lr::host::CountingBus>(*bus);
    panel_ = std::make_unique<lr::Panel>(*counting_, config);
    if (const lr::Status st = panel_->init(); st != lr::Status::kOk) {
      error = std::string("panel: init: ") + lr::to_string(st) + device_error();
      return false;
    }
    const size_t strip = size_t{config.image_width()} * static_cast<size_t>(strip_height);
    buffers_[0].assign(strip, 0);
    buffers_[1].assign(strip, 0);
    signatures_.assign((config.image_height() + static_cast<size_t>(strip_height) - 1) /
                           static_cast<size_t>(strip_height),
                       lr::StripSignature{});
    sink_ = std::make_unique<lr::PanelSink>(*panel_, buffers_[0], buffers_[1], signatures_);
    return true;
  }

  // One frame to the panel; the backlight goes on after the first (never showing the RAM's
  // power-on noise).
  bool send(const lr::host::ImageRgb8& img, std::string& error) {
    const lr::Status st = send_frame(*sink_, img, strip_height_);
    if (st != lr::Status::kOk) {
      error = std::string("panel: frame: ") + lr::to_string(st) + device_error();
      return false;
    }
    if (!backlight_) {
      if (const lr::Status b = panel_->backlight(true); b != lr::Status::kOk) {
        error = std::string("panel: backlight: ") + lr::to_string(b) + device_error();
        return false;
      }
      backlight_ = true;
    }
    return true;
  }

  const lr::host::BusTotals& totals() const {
    return counting_->totals();
  }
  const lr::PanelSinkStats& sink_stats() const {
    return sink_->stats();
  }
  const lr::host::PanelEmulator* emulator() const {
    return emulator_.get();
  }
  const lr::host::EmulatorBus* emulator_bus() const {
    return emulator_bus_.get();
  }

 private:
  std::string device_error() const {
    std::string e;
#ifdef LR_HAVE_SPIDEV
    if (spidev_) e = spidev_->last_error();
#endif
#ifdef LR_HAVE_FT232H
    if (ft232h_) e = ft232h_->last_error();
#endif
    return e.empty() ? e : " (" + e + ")";
  }

  lr::PanelConfig config_{};
  int strip_height_ = 8;
  std::unique_ptr<lr::host::PanelEmulator> emulator_;
  std::unique_ptr<lr::host::EmulatorBus> emulator_bus_;
#ifdef LR_HAVE_SPIDEV
  std::unique_ptr<lr::SpidevBus> spidev_;
#endif
#ifdef LR_HAVE_FT232H
  std::unique_ptr<lr::Ft232hBus> ft232h_;
#endif
  std::unique_ptr<lr::host::CountingBus> counting_;
  std::unique_ptr<lr::Panel> panel_;
  std::vector<uint16_t> buffers_[2];
  std::vector<lr::StripSignature> signatures_;
  std::unique_ptr<lr::PanelSink> sink_;
  bool backlight_ = false;
};

}  // namespace

int main(int argc, char** argv) {
  lr::host::SceneOptions o;
  std::string obj, out = "out.png", depth_out;
  bool stats = false;
  std::vector<Vec3d> lights;
  std::vector<lr::host::LightOption> light_options;
  // The first option given that only Phong shading uses, and the first that only the lighting
  // table uses (checked once every option is read, since options come in any order).
  std::string phong_only, table_only;
  lr::host::DisplaySpec display;
  lr::PanelConfig panel_config{};
  bool has_panel = false, width_given = false, height_given = false;
  int frames = 0;        // 0: no --frames
  int subdivisions = 0;  // --subdivide
  for (int i = 1; i < argc; ++i) {
    std::string_view a = argv[i];
    // A value never starts with "--": "--obj --out x.png" is a missing value, not a file "--out".
    auto value = [&](std::string_view& v) {
      if (i + 1 >= argc || std::string_view(argv[i + 1]).substr(0, 2) == "--") return false;
      v = argv[++i];
      return true;
    };
    std::string_view v;
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--fit") {
      o.fit = true;
    } else if (a == "--unlit") {
      o.unlit = true;
    } else if (a == "--local-viewer") {
      o.local_viewer = true;
    } else if (a == "--two-sided") {
      o.two_sided = true;
    } else if (a == "--no-depth") {
      o.depth_test = false;
    } else if (a == "--stats") {
      stats = true;
    } else if (a == "--obj" || a == "--out" || a == "--depth-out" || a == "--width" ||
               a == "--height" || a == "--fovy" || a == "--near" || a == "--far" || a == "--eye" ||
               a == "--target" || a == "--up" || a == "--model-scale" || a == "--model-rotate-y" ||
               a == "--model-translate" || a == "--shading" || a == "--light-dir" ||
               a == "--material" || a == "--ambient" || a == "--diffuse" || a == "--specular" ||
               a == "--shininess" || a == "--bg" || a == "--cull" || a == "--strip-height" ||
               a == "--texture" || a == "--filter" || a == "--wrap" || a == "--perspective" ||
               a == "--mipmap" || a == "--texture-format" || a == "--light" ||
               a == "--global-ambient" || a == "--lighting" || a == "--lighting-table" ||
               a == "--lighting-table-filter" || a == "--envmap" || a == "--normalmap" ||
               a == "--display" || a == "--panel" || a == "--frames" || a == "--subdivide") {
      if (!value(v)) return fail(std::string(a) + ": missing value");
      const std::string bad = std::string(a) + ": bad value '" + std::string(v) + "'";
      if (a == "--obj") {
        obj = v;
      } else if (a == "--out") {
        out = v;
        if (extension(out) != "png" && extension(out) != "ppm")
          return fail("--out: the file name must end in .png or .ppm");
      } else if (a == "--depth-out") {
        depth_out = v;
        if (extension(depth_out) != "png")
          return fail("--depth-out: the file name must end in .png");
      } else if (a == "--width" || a == "--height") {
        int n;
        if (!parse_int(v, n) || n < 1 || n > 4096) return fail(bad + " (1..4096)");
        (a == "--width" ? o.width : o.height) = n;
        (a == "--width" ? width_given : height_given) = true;
      } else if (a == "--display") {
        std::string why;
        if (!lr::host::parse_display_spec(v, display, why)) return fail(bad + " (" + why + ")");
      } else if (a == "--panel") {
        std::string why;
        if (!lr::host::parse_panel_spec(v, panel_config, why)) return fail(bad + " (" + why + ")");
        has_panel = true;
      } else if (a == "--subdivide") {
        int n;
        if (!parse_int(v, n) || n < 0 || n > 4) return fail(bad + " (0..4)");
        subdivisions = n;
      } else if (a == "--frames") {
        int n;
        if (!parse_int(v, n) || n < 1 || n > 3600) return fail(bad + " (1..3600)");
        frames = n;
      } else if (a == "--strip-height") {
        int n;
        if (!parse_int(v, n) || (n != 1 && n != 2 && n != 4 && n != 8 && n != 16 && n != 32))
          return fail(bad + " (1, 2, 4, 8, 16 or 32)");
        o.strip_height = n;
      } else if (a == "--fovy" || a == "--near" || a == "--far" || a == "--model-scale" ||
                 a == "--model-rotate-y" || a == "--shininess") {
        double d;
        if (!parse_double(v, d)) return fail(bad);
        if (a == "--fovy") {
          if (d <= 0 || d >= 180) return fail(bad + " (0 < fovy < 180)");
          o.fovy = d;
        } else if (a == "--near") {
          if (d <= 0) return fail(bad + " (near > 0)");
          o.near = d;
        } else if (a == "--far") {
          o.far = d;
        } else if (a == "--model-scale") {
          o.model_scale = d;
        } else if (a == "--model-rotate-y") {
          o.model_rotate_y = std::fmod(d, 360.0);
        } else {
          if (d < 0 || d > 128) return fail(bad + " (0..128)");
          o.material.shininess = d;
          o.use_mesh_materials = false;
        }
      } else if (a == "--eye" || a == "--target" || a == "--up" || a == "--model-translate" ||
                 a == "--light-dir") {
        Vec3d p;
        if (!parse_vec3(v, p)) return fail(bad + " (expected x,y,z)");
        if (a == "--eye")
          o.eye = p;
        else if (a == "--target")
          o.target = p;
        else if (a == "--up")
          o.up = p;
        else if (a == "--model-translate")
          o.model_translate = p;
        else {
          if (p[0] == 0 && p[1] == 0 && p[2] == 0) return fail(bad + " (zero direction)");
          lights.push_back(p);
        }
      } else if (a == "--ambient" || a == "--diffuse" || a == "--specular" || a == "--bg" ||
                 a == "--global-ambient") {
        Vec3d c;
        if (!parse_vec3(v, c) || !unit_color(c)) return fail(bad + " (expected r,g,b in [0,1])");
        if (a == "--bg") {
          o.background = c;
        } else if (a == "--global-ambient") {
          o.global_ambient = c;
        } else {
          (a == "--ambient"   ? o.material.ambient
           : a == "--diffuse" ? o.material.diffuse
                              : o.material.specular) = c;
          o.use_mesh_materials = false;
        }
      } else if (a == "--material") {
        const lr::NamedMaterial* m = lr::find_material(v);
        if (!m)
          return fail(bad + " (unknown material; e.g. gold, silver, jade, ruby, red_plastic)");
        for (int k = 0; k < 3; ++k) {
          o.material.ambient[static_cast<size_t>(k)] = m->ambient[k] * 1e-8;
          o.material.diffuse[static_cast<size_t>(k)] = m->diffuse[k] * 1e-8;
          o.material.specular[static_cast<size_t>(k)] = m->specular[k] * 1e-8;
        }
        o.material.emission = {0, 0, 0};
        o.material.shininess = m->shininess_fraction * 1e-8 * 128.0;
        o.use_mesh_materials = false;
      } else if (a == "--shading") {
        if (v == "flat")
          o.shading = lr::Shading::kFlat;
        else if (v == "gouraud")
          o.shading = lr::Shading::kGouraud;
        else if (v == "phong")
          o.shading = lr::Shading::kPhong;
        else
          return fail(bad + " (flat, gouraud or phong)");
      } else if (a == "--light") {
        lr::host::LightOption l;
        std::string why;
        if (!parse_light(v, l, why)) return fail(bad + " (" + why + ")");
        if (light_options.size() == static_cast<size_t>(lr::kMaxLights))
          return fail("--light: at most " + std::to_string(lr::kMaxLights) + " lights");
        light_options.push_back(l);
      } else if (a == "--lighting") {
        if (v == "exact")
          o.pixel_lighting = lr::PixelLighting::kExact;
        else if (v == "table")
          o.pixel_lighting = lr::PixelLighting::kTable;
        else
          return fail(bad + " (exact or table)");
        if (phong_only.empty()) phong_only = a;
      } else if (a == "--lighting-table") {
        int n;
        if (!parse_int(v, n) || n < 8 || n > 256) return fail(bad + " (8..256)");
        o.table.size = static_cast<uint16_t>(n);
        if (phong_only.empty()) phong_only = a;
        if (table_only.empty()) table_only = a;
      } else if (a == "--lighting-table-filter") {
        if (v == "nearest")
          o.table.bilinear = false;
        else if (v == "bilinear")
          o.table.bilinear = true;
        else
          return fail(bad + " (nearest or bilinear)");
        if (phong_only.empty()) phong_only = a;
        if (table_only.empty()) table_only = a;
      } else if (a == "--envmap" || a == "--normalmap") {
        (a == "--envmap" ? o.envmap : o.normalmap) = v;
        if (phong_only.empty()) phong_only = a;
      } else if (a == "--texture") {
        o.texture = v;
      } else if (a == "--texture-format") {
        if (!lr::host::parse_texel_format(v, o.texture_format))
          return fail(bad + " (rgb565, rgb888, l8 or palette8)");
      } else if (a == "--filter") {
        if (v == "nearest")
          o.filter = lr::Filter::kNearest;
        else if (v == "bilinear")
          o.filter = lr::Filter::kBilinear;
        else
          return fail(bad + " (nearest or bilinear)");
      } else if (a == "--wrap") {
        if (v == "repeat")
          o.wrap = lr::Wrap::kRepeat;
        else if (v == "clamp")
          o.wrap = lr::Wrap::kClampToEdge;
        else
          return fail(bad + " (repeat or clamp)");
      } else if (a == "--perspective") {
        if (v == "exact")
          o.perspective = lr::Perspective::kExact;
        else if (v == "span8")
          o.perspective = lr::Perspective::kSpan8;
        else if (v == "span16")
          o.perspective = lr::Perspective::kSpan16;
        else if (v == "span32")
          o.perspective = lr::Perspective::kSpan32;
        else if (v == "affine")
          o.perspective = lr::Perspective::kAffine;
        else
          return fail(bad + " (exact, span8, span16, span32 or affine)");
      } else if (a == "--mipmap") {
        if (v == "none")
          o.mipmap = lr::MipMode::kNone;
        else if (v == "nearest")
          o.mipmap = lr::MipMode::kNearest;
        else if (v == "linear")
          o.mipmap = lr::MipMode::kLinear;
        else
          return fail(bad + " (none, nearest or linear)");
      } else if (a == "--cull") {
        if (v == "back")
          o.cull = lr::Cull::kBack;
        else if (v == "none")
          o.cull = lr::Cull::kNone;
        else
          return fail(bad + " (back or none)");
      }
    } else {
      return fail("unknown option '" + std::string(a) + "' (see --help)");
    }
  }
  if (obj.empty()) return fail("--obj FILE is required (see --help)");
  if (o.far <= o.near) return fail("--far must be greater than --near");
  if (!lights.empty() && !light_options.empty())
    return fail("--light and --light-dir cannot be combined (use --light dir:x,y,z)");
  if (!lights.empty()) o.light_dirs = lights;
  o.lights = light_options;
  if (!phong_only.empty() && o.shading != lr::Shading::kPhong)
    return fail(phong_only + " needs --shading phong");
  if (!table_only.empty() && o.pixel_lighting != lr::PixelLighting::kTable)
    return fail(table_only + " needs --lighting table");

  // A panel decides the frame's size.
  const bool to_panel = display.kind != lr::host::DisplayKind::kNone;
  if (display.kind == lr::host::DisplayKind::kEmulator) {
    if (has_panel)
      return fail("--panel: not with --display emulator (the emulator's value names the panel)");
    panel_config = display.panel;
  } else if (to_panel && !has_panel) {
    return fail("--display " + display.text + " needs --panel CONTROLLER:WxH[:ROT]");
  } else if (!to_panel && has_panel) {
    return fail("--panel needs --display spidev:... or --display ft232h");
  }
  if (to_panel) {
    const int w = panel_config.image_width(), h = panel_config.image_height();
    if ((width_given && o.width != w) || (height_given && o.height != h))
      return fail("--width/--height: the panel shows " + std::to_string(w) + "x" +
                  std::to_string(h) + " (" + lr::host::describe_panel(panel_config) + ")");
    o.width = w;
    o.height = h;
  }

  lr::host::HostMesh mesh;
  std::string error;
  if (!lr::host::load_obj(obj, mesh, error)) return fail(error);
  if (subdivisions > 0) mesh = lr::host::subdivide(mesh, subdivisions);
  PanelOutput panel;  // opened after the first frame rendered: a bad scene leaves it alone

  // One frame, or --frames N turning the model about y; each frame rendered, then sent.
  lr::host::RenderResult result;
  const double base_rotation = o.model_rotate_y;
  const int count = frames > 0 ? frames : 1;
  lr::host::BusTotals sent_total;
  uint64_t strips_sent = 0, strips_narrowed = 0, strips_skipped = 0, pixels_total = 0;
  double ms_total = 0;
  for (int f = 0; f < count; ++f) {
    if (frames > 0) o.model_rotate_y = std::fmod(base_rotation + 360.0 * f / frames, 360.0);
    auto t0 = std::chrono::steady_clock::now();
    if (!lr::host::render_scene(mesh, o, result, error)) return fail(error);
    lr::host::BusTotals sent;
    if (to_panel) {
      if (f == 0) {  // the panel's start-up (reset and sleep-out delays) is not the frame's time
        const auto o0 = std::chrono::steady_clock::now();
        if (!panel.open(display, panel_config, o.strip_height, error)) return fail(error);
        t0 += std::chrono::steady_clock::now() - o0;
      }
      const lr::host::BusTotals before = panel.totals();
      if (!panel.send(result.image, error)) return fail(error);
      sent = panel.totals() - before;
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ms_total += ms;
    pixels_total += result.stats.pixels_written;
    if (frames == 0) continue;
    std::printf("{\"frame\":%d,\"rotate_y\":%g,\"triangles_binned\":%u,\"pixels_written\":%u", f,
                o.model_rotate_y, result.stats.triangles_binned, result.stats.pixels_written);
    if (to_panel) {
      const lr::PanelSinkStats& ss = panel.sink_stats();
      strips_sent += ss.strips_sent;
      strips_narrowed += ss.strips_narrowed;
      strips_skipped += ss.strips_skipped;
      sent_total.bytes += sent.bytes;
      sent_total.pixel_bytes += sent.pixel_bytes;
      sent_total.commands += sent.commands;
      sent_total.pixel_transfers += sent.pixel_transfers;
      sent_total.transactions += sent.transactions;
      std::printf(
          ",\"bytes\":%llu,\"pixel_bytes\":%llu,\"commands\":%llu,\"pixel_transfers\":%llu,"
          "\"transactions\":%llu,\"strips_sent\":%u,\"strips_narrowed\":%u,\"strips_skipped\":%u",
          static_cast<unsigned long long>(sent.bytes),
          static_cast<unsigned long long>(sent.pixel_bytes),
          static_cast<unsigned long long>(sent.commands),
          static_cast<unsigned long long>(sent.pixel_transfers),
          static_cast<unsigned long long>(sent.transactions), ss.strips_sent, ss.strips_narrowed,
          ss.strips_skipped);
    } else {
      std::printf(",\"strips\":%u,\"empty_strips\":%u", result.stats.strips,
                  result.stats.empty_strips);
    }
    std::printf(",\"ms\":%.2f}\n", ms);
  }
  if (frames > 0) {
    std::printf("{\"frames\":%d,\"pixels_written\":%llu", frames,
                static_cast<unsigned long long>(pixels_total));
    if (to_panel)
      std::printf(
          ",\"bytes\":%llu,\"pixel_bytes\":%llu,\"commands\":%llu,\"pixel_transfers\":%llu,"
          "\"transactions\":%llu,\"strips_sent\":%llu,\"strips_narrowed\":%llu,"
          "\"strips_skipped\":%llu",
          static_cast<unsigned long long>(sent_total.bytes),
          static_cast<unsigned long long>(sent_total.pixel_bytes),
          static_cast<unsigned long long>(sent_total.commands),
          static_cast<unsigned long long>(sent_total.pixel_transfers),
          static_cast<unsigned long long>(sent_total.transactions),
          static_cast<unsigned long long>(strips_sent),
          static_cast<unsigned long long>(strips_narrowed),
          static_cast<unsigned long long>(strips_skipped));
    std::printf(",\"ms\":%.2f}\n", ms_total);
  }
  // What the emulated panel found wrong in the driver's stream (warnings: the image is written).
  if (const lr::host::PanelEmulator* emu = panel.emulator()) {
    int shown = 0;
    for (const lr::host::PanelDiagnostic& d : emu->diagnostics()) {
      if (!lr::host::is_error(d.issue) || shown++ >= 10) continue;
      std::fprintf(stderr, "lineraster-sim: warning: panel: %s: %s\n", lr::host::to_string(d.issue),
                   d.text.c_str());
    }
    for (const std::string& m : panel.emulator_bus()->misuse())
      std::fprintf(stderr, "lineraster-sim: warning: bus: %s\n", m.c_str());
  }

  const lr::host::ImageRgb8 shown =
      panel.emulator() ? panel.emulator()->image() : std::move(result.image);
  if (!lr::host::write_image(out, shown, error)) return fail(error);
  if (!depth_out.empty() &&
      !lr::host::write_png_gray16(depth_out, o.width, o.height, result.depth, error)) {
    std::remove(out.c_str());
    return fail(error);
  }
  if (stats) {
    const lr::FrameStats& s = result.stats;
    std::printf(
        "{\"width\":%d,\"height\":%d,\"strip_height\":%d,\"triangles_in\":%u,\"binned_inputs\":%u,"
        "\"culled_backface\":%u,\"culled_zero_area\":%u,\"culled_offscreen\":%u,\"clipped\":%u,"
        "\"clipped_away\":%u,\"rejected_invalid\":%u,\"dropped_vertex_capacity\":%u,"
        "\"dropped_triangle_capacity\":%u,\"dropped_active_capacity\":%u,\"triangles_binned\":%u,"
        "\"vertices_transformed\":%u,\"strips\":%u,\"empty_strips\":%u,\"spans\":%u,"
        "\"pixels_tested\":%u,\"pixels_written\":%u,\"max_active\":%u,\"bytes_sent\":%llu,"
        "\"bytes_per_vertex\":%u,\"bytes_per_binned_triangle\":%u,\"bytes_per_active_triangle\":%u,"
        "\"bytes_per_strip\":%u}\n",
        o.width, o.height, o.strip_height, s.triangles_in, s.binned_inputs, s.culled_backface,
        s.culled_zero_area, s.culled_offscreen, s.clipped, s.clipped_away, s.rejected_invalid,
        s.dropped_vertex_capacity, s.dropped_triangle_capacity, s.dropped_active_capacity,
        s.triangles_binned, s.vertices_transformed, s.strips, s.empty_strips, s.spans,
        s.pixels_tested, s.pixels_written, s.max_active,
        static_cast<unsigned long long>(result.bytes), s.bytes_per_vertex,
        s.bytes_per_binned_triangle, s.bytes_per_active_triangle, s.bytes_per_strip);
  }
  return 0;
}
