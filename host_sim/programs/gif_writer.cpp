#include "lineraster/host_sim/programs/gif_writer.hpp"

#include <array>
#include <cerrno>
#include <cstring>
#include <vector>

#ifdef LR_HAVE_GIF
#include <gif_lib.h>

#include "lineraster/host_sim/programs/palette_quantize.hpp"
#endif

namespace lr::host {

std::string gif_missing_error(const std::string& path) {
  return path + ": GIF output needs giflib (Debian: libgif-dev), which this build did not find";
}

#ifdef LR_HAVE_GIF

namespace {

int write_to_stream(GifFileType* gif, const GifByteType* data, int length) {
  auto* f = static_cast<std::FILE*>(gif->UserData);
  return static_cast<int>(std::fwrite(data, 1, static_cast<size_t>(length), f));
}

// giflib's reason, or the system's when a write failed.
std::string gif_error(int code) {
  if (code == E_GIF_ERR_WRITE_FAILED && errno != 0)
    return std::string("write failed: ") + std::strerror(errno);
  const char* text = GifErrorString(code);
  return text != nullptr ? text : "giflib error " + std::to_string(code);
}

// NETSCAPE2.0 application extension: loop count 0, forever.
constexpr std::array<GifByteType, 11> kLoopApplication = {'N', 'E', 'T', 'S', 'C', 'A',
                                                          'P', 'E', '2', '.', '0'};
constexpr std::array<GifByteType, 3> kLoopForever = {1, 0, 0};

}  // namespace

bool gif_supported() {
  return true;
}

GifWriter::~GifWriter() {
  close_gif();
}

void GifWriter::close_gif() {
  if (gif_ == nullptr) return;
  int code = 0;
  EGifCloseFile(gif_, &code);  // frees it whatever happened
  gif_ = nullptr;
}

bool GifWriter::open(const std::string& path, int width, int height, int delay,
                     std::string& error) {
  close_gif();
  path_ = path;
  width_ = width;
  height_ = height;
  delay_ = delay;
  if (!out_.open(path, error)) return false;
  int code = 0;
  gif_ = EGifOpen(out_.stream(), write_to_stream, &code);
  if (gif_ == nullptr) {
    out_.discard();
    error = path + ": " + gif_error(code);
    return false;
  }
  EGifSetGifVersion(gif_, true);  // GIF89a: the delays and the loop need it
  errno = 0;
  if (EGifPutScreenDesc(gif_, width, height, 8, 0, nullptr) == GIF_ERROR ||
      EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
      EGifPutExtensionBlock(gif_, kLoopApplication.size(), kLoopApplication.data()) == GIF_ERROR ||
      EGifPutExtensionBlock(gif_, kLoopForever.size(), kLoopForever.data()) == GIF_ERROR ||
      EGifPutExtensionTrailer(gif_) == GIF_ERROR) {
    error = path + ": " + gif_error(gif_->Error);
    close_gif();
    out_.discard();
    return false;
  }
  return true;
}

bool GifWriter::add(const ImageRgb8& frame, std::string& error) {
  if (gif_ == nullptr) {
    error = path_ + ": the GIF is not open";
    return false;
  }
  if (frame.width != width_ || frame.height != height_) {
    error = path_ + ": a frame of " + std::to_string(frame.width) + "x" +
            std::to_string(frame.height) + " in a GIF of " + std::to_string(width_) + "x" +
            std::to_string(height_);
    return false;
  }
  PalettedImage q = quantize_median_cut(frame);
  // A colour table holds a power of two entries (2..256); the unused ones are black.
  const int count = 1 << GifBitSize(static_cast<int>(q.palette.size()));
  ColorMapObject* map = GifMakeMapObject(count, nullptr);
  if (map == nullptr) {
    error = path_ + ": " + gif_error(E_GIF_ERR_NOT_ENOUGH_MEM);
    return false;
  }
  for (int i = 0; i < count; ++i) {
    const size_t k = static_cast<size_t>(i);
    map->Colors[i] = k < q.palette.size()
                         ? GifColorType{q.palette[k][0], q.palette[k][1], q.palette[k][2]}
                         : GifColorType{0, 0, 0};
  }
  GraphicsControlBlock gcb{};
  gcb.DisposalMode = DISPOSE_DO_NOT;
  gcb.UserInputFlag = false;
  gcb.DelayTime = delay_;
  gcb.TransparentColor = NO_TRANSPARENT_COLOR;
  std::array<GifByteType, 4> ext{};
  EGifGCBToExtension(&gcb, ext.data());
  errno = 0;
  bool ok = EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, ext.size(), ext.data()) != GIF_ERROR &&
            EGifPutImageDesc(gif_, 0, 0, width_, height_, false, map) != GIF_ERROR;
  for (int y = 0; ok && y < height_; ++y)
    ok = EGifPutLine(gif_, q.indices.data() + static_cast<size_t>(y) * static_cast<size_t>(width_),
                     width_) != GIF_ERROR;
  GifFreeMapObject(map);
  if (!ok) {
    error = path_ + ": " + gif_error(gif_->Error);
    return false;
  }
  return true;
}

bool GifWriter::finish(std::string& error) {
  if (gif_ == nullptr) {
    error = path_ + ": the GIF is not open";
    return false;
  }
  int code = 0;
  errno = 0;
  const bool closed = EGifCloseFile(gif_, &code) != GIF_ERROR;
  gif_ = nullptr;
  if (!closed) {
    out_.discard();
    error = path_ + ": " + gif_error(code);
    return false;
  }
  return out_.commit(error);
}

#else  // no giflib

bool gif_supported() {
  return false;
}

GifWriter::~GifWriter() = default;

void GifWriter::close_gif() {}

bool GifWriter::open(const std::string& path, int, int, int, std::string& error) {
  error = gif_missing_error(path);
  return false;
}

bool GifWriter::add(const ImageRgb8&, std::string& error) {
  error = gif_missing_error(path_);
  return false;
}

bool GifWriter::finish(std::string& error) {
  error = gif_missing_error(path_);
  return false;
}

#endif

}  // namespace lr::host
