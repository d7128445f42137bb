// A consumer for OrderedStripSink (ordered_sink.hpp) that writes the frame to a file on the
// host: a binary PPM (P6, 8 bits per channel), strip by strip through semihosting as the strips
// arrive. The file is the same bytes lineraster-sim writes with --out NAME.ppm for the same
// frame, so the two can be compared with cmp. Every pixel is also folded into FNV-1a (over the
// PPM's pixel bytes), printed by the firmware so a run without the file can still be compared.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/semihost.hpp"
#include "lineraster/core/math/hash.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/core/output/strip_sink.hpp"

namespace lr::fw {

template <class PF>
class PpmFile {
 public:
  // `path` (relative to the host's working directory) must outlive the object.
  explicit PpmFile(const char* path) : path_(path) {}

  Status begin(uint16_t width, uint16_t height) {
    hash_ = {};
    bytes_ = 0;
    handle_ = semihost::open_write(path_);
    if (handle_ < 0) return Status::kDisplayError;
    char header[32];
    const uint32_t n = ppm_header(header, width, height);
    return semihost::write_file(handle_, header, n) ? Status::kOk : fail();
  }

  Status strip(const StripRect&, std::span<const typename PF::Storage> pixels) {
    // Through a small chunk: the pixel format's storage need not be 3 packed bytes.
    std::array<uint8_t, 3 * kChunkPixels> bytes;
    for (size_t done = 0; done < pixels.size();) {
      const size_t n = pixels.size() - done < kChunkPixels ? pixels.size() - done : kChunkPixels;
      Fnv1a32 h = hash_;
      for (size_t i = 0; i < n; ++i) {
        const Rgb8 c = PF::decode(pixels[done + i]);
        bytes[3 * i] = c.r;
        bytes[3 * i + 1] = c.g;
        bytes[3 * i + 2] = c.b;
        h.add(c.r);
        h.add(c.g);
        h.add(c.b);
      }
      hash_ = h;
      if (!semihost::write_file(handle_, bytes.data(), static_cast<uint32_t>(3 * n))) return fail();
      bytes_ += static_cast<uint32_t>(3 * n);
      done += n;
    }
    return Status::kOk;
  }

  Status end() {
    const bool closed = semihost::close_file(handle_);
    handle_ = -1;
    return closed ? Status::kOk : Status::kDisplayError;
  }

  // FNV-1a (32 bit) of the frame's RGB888 bytes, rows top to bottom.
  uint32_t checksum() const { return hash_.value; }
  uint32_t pixel_bytes() const { return bytes_; }

 private:
  static constexpr size_t kChunkPixels = 128;  // 384 bytes of stack per write

  Status fail() {
    semihost::close_file(handle_);
    handle_ = -1;
    return Status::kDisplayError;
  }

  // "P6\n<w> <h>\n255\n", as lineraster-sim writes it.
  static uint32_t ppm_header(char* out, unsigned w, unsigned h) {
    uint32_t n = 0;
    auto put = [&](char c) { out[n++] = c; };
    auto put_dec = [&](unsigned v) {
      char digits[5];
      int k = 0;
      do {
        digits[k++] = static_cast<char>('0' + v % 10u);
        v /= 10u;
      } while (v != 0);
      while (k > 0) put(digits[--k]);
    };
    put('P');
    put('6');
    put('\n');
    put_dec(w);
    put(' ');
    put_dec(h);
    put('\n');
    for (char c : {'2', '5', '5', '\n'}) put(c);
    return n;
  }

  const char* path_;
  int handle_ = -1;
  Fnv1a32 hash_;
  uint32_t bytes_ = 0;
};

}  // namespace lr::fw
