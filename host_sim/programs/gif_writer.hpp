// lineraster-sim's animated GIF (--frames N --out FILE.gif), through Debian's giflib
// (libgif-dev; optional at build time, as libjpeg is).
//
// Each frame is quantised to its own palette of at most 256 colours (palette_quantize.hpp: median
// cut, no dithering) and stored whole (a local colour table, no transparency), shown for `delay`
// hundredths of a second; the animation loops forever (the NETSCAPE2.0 extension). The file is
// written under output_file.hpp's rules: nothing is left of a GIF that was not finished.
#pragma once

#include <string>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/formats/output_file.hpp"

struct GifFileType;  // giflib's, kept out of this header

namespace lr::host {

// Whether this build has giflib. Without it, GifWriter::open() fails with one line saying so.
bool gif_supported();

// The one line of a build without giflib, for `path`.
std::string gif_missing_error(const std::string& path);

// Frame delays a GIF can state: hundredths of a second (browsers show 0 and 1 as 10).
inline constexpr int kMinGifDelay = 2, kMaxGifDelay = 6000;

class GifWriter {
 public:
  GifWriter() = default;
  ~GifWriter();  // unfinished: the temporary file is removed, the target untouched
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;

  // Creates the GIF (output_file.hpp's temporary file) for frames of width x height pixels.
  // False with one line "PATH: why".
  bool open(const std::string& path, int width, int height, int delay, std::string& error);
  bool is_open() const { return gif_ != nullptr; }
  // One frame, of the size given to open(). False with one line.
  bool add(const ImageRgb8& frame, std::string& error);
  // The trailer, then the file put in place. False with one line (nothing left behind).
  bool finish(std::string& error);

 private:
  void close_gif();

  std::string path_;
  OutputFile out_;
  GifFileType* gif_ = nullptr;
  int width_ = 0, height_ = 0, delay_ = 0;
};

}  // namespace lr::host
