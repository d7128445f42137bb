#include "lineraster/core/texture/texture.hpp"

namespace lr {

Status validate(const Texture& t) {
  if (t.level_count < 1 || t.level_count > kMaxMipLevels) return Status::kInvalidArgument;
  const uint16_t w0 = t.levels[0].width, h0 = t.levels[0].height;
  if (w0 < 1 || h0 < 1 || w0 > kMaxTextureSize || h0 > kMaxTextureSize)
    return Status::kInvalidArgument;
  uint16_t w = w0, h = h0;
  for (int i = 0; i < t.level_count; ++i) {
    const TextureLevel& l = t.levels[static_cast<size_t>(i)];
    if (l.width != w || l.height != h) return Status::kInvalidArgument;
    const size_t n = level_texels(w, h);
    if (t.format == TexelFormat::kRgb565) {
      if (l.rgb565.size() < n) return Status::kInvalidArgument;
    } else {
      if (l.bytes.size() < n * bytes_per_texel(t.format)) return Status::kInvalidArgument;
      if (t.format == TexelFormat::kPalette8) {
        for (size_t k = 0; k < n; ++k)
          if (l.bytes[k] >= t.palette.size()) return Status::kInvalidArgument;
      }
    }
    w = static_cast<uint16_t>(w > 1 ? w / 2 : 1);
    h = static_cast<uint16_t>(h > 1 ? h / 2 : 1);
  }
  return Status::kOk;
}

}  // namespace lr
