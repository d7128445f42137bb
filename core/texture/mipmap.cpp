#include "lineraster/core/texture/mipmap.hpp"

namespace lr {
namespace {

constexpr uint16_t half_size(uint16_t n) {
  return static_cast<uint16_t>(n > 1 ? n / 2 : 1);
}

// Input texels [first, last] that output texel i covers along an axis of n inputs and m outputs.
struct Range {
  uint32_t first, last;
};
constexpr Range box(uint32_t i, uint32_t n, uint32_t m) {
  if (n == 1) return {0, 0};
  return {2 * i, i + 1 == m ? n - 1 : 2 * i + 1};
}

// RGB565 fields expanded to 8 bits by bit replication.
constexpr uint32_t expand5(uint32_t v) {
  return (v << 3) | (v >> 2);
}
constexpr uint32_t expand6(uint32_t v) {
  return (v << 2) | (v >> 4);
}

// The palette entry (among the first 256) nearest to the 8-bit colour c; lowest index on ties.
uint8_t nearest_entry(std::span<const uint16_t> palette, const uint32_t (&c)[3]) {
  const size_t n = palette.size() < 256 ? palette.size() : 256;
  uint32_t best = UINT32_MAX;
  size_t best_index = 0;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t v = palette[k];
    const int32_t dr = static_cast<int32_t>(expand5(v >> 11)) - static_cast<int32_t>(c[0]);
    const int32_t dg = static_cast<int32_t>(expand6((v >> 5) & 63u)) - static_cast<int32_t>(c[1]);
    const int32_t db = static_cast<int32_t>(expand5(v & 31u)) - static_cast<int32_t>(c[2]);
    const uint32_t d = static_cast<uint32_t>(dr * dr + dg * dg + db * db);
    if (d < best) {
      best = d;
      best_index = k;
      if (d == 0) break;
    }
  }
  return static_cast<uint8_t>(best_index);
}

// Channels per texel in the averaging domain of each format.
constexpr int channels(TexelFormat f) {
  return f == TexelFormat::kL8 ? 1 : 3;
}

// Adds the channels of texel `index` of `src` to sum[].
template <TexelFormat F>
void accumulate(const TextureLevel& src, std::span<const uint16_t> palette, size_t index,
                uint32_t (&sum)[3]) {
  if constexpr (F == TexelFormat::kRgb565) {
    const uint32_t v = src.rgb565[index];
    sum[0] += v >> 11;
    sum[1] += (v >> 5) & 63u;
    sum[2] += v & 31u;
  } else if constexpr (F == TexelFormat::kRgb888) {
    sum[0] += src.bytes[3 * index];
    sum[1] += src.bytes[3 * index + 1];
    sum[2] += src.bytes[3 * index + 2];
  } else if constexpr (F == TexelFormat::kL8) {
    sum[0] += src.bytes[index];
  } else {
    const uint32_t v = palette[src.bytes[index]];
    sum[0] += expand5(v >> 11);
    sum[1] += expand6((v >> 5) & 63u);
    sum[2] += expand5(v & 31u);
  }
}

// Writes the averaged channels avg[] as texel `index` of the destination.
template <TexelFormat F>
void store(std::span<uint16_t> dst565, std::span<uint8_t> dst_bytes,
           std::span<const uint16_t> palette, size_t index, const uint32_t (&avg)[3]) {
  if constexpr (F == TexelFormat::kRgb565) {
    dst565[index] = static_cast<uint16_t>((avg[0] << 11) | (avg[1] << 5) | avg[2]);
  } else if constexpr (F == TexelFormat::kRgb888) {
    dst_bytes[3 * index] = static_cast<uint8_t>(avg[0]);
    dst_bytes[3 * index + 1] = static_cast<uint8_t>(avg[1]);
    dst_bytes[3 * index + 2] = static_cast<uint8_t>(avg[2]);
  } else if constexpr (F == TexelFormat::kL8) {
    dst_bytes[index] = static_cast<uint8_t>(avg[0]);
  } else {
    dst_bytes[index] = nearest_entry(palette, avg);
  }
}

// One level from the one before: `dst565` / `dst_bytes` hold exactly dw x dh texels.
template <TexelFormat F>
void downsample(const TextureLevel& src, std::span<const uint16_t> palette, uint16_t dw,
                uint16_t dh, std::span<uint16_t> dst565, std::span<uint8_t> dst_bytes) {
  const uint32_t sw = src.width, sh = src.height;
  for (uint32_t y = 0; y < dh; ++y) {
    const Range ry = box(y, sh, dh);
    for (uint32_t x = 0; x < dw; ++x) {
      const Range rx = box(x, sw, dw);
      uint32_t sum[3] = {0, 0, 0};
      for (uint32_t sy = ry.first; sy <= ry.last; ++sy) {
        for (uint32_t sx = rx.first; sx <= rx.last; ++sx)
          accumulate<F>(src, palette, size_t{sy} * sw + sx, sum);
      }
      const uint32_t count = (ry.last - ry.first + 1) * (rx.last - rx.first + 1);
      uint32_t avg[3] = {0, 0, 0};
      for (int c = 0; c < channels(F); ++c) {
        avg[c] = (sum[c] + count / 2) / count;
      }
      store<F>(dst565, dst_bytes, palette, size_t{y} * dw + x, avg);
    }
  }
}

void downsample_any(TexelFormat f, const TextureLevel& src, std::span<const uint16_t> palette,
                    uint16_t dw, uint16_t dh, std::span<uint16_t> dst565,
                    std::span<uint8_t> dst_bytes) {
  switch (f) {
    case TexelFormat::kRgb565:
      downsample<TexelFormat::kRgb565>(src, palette, dw, dh, dst565, dst_bytes);
      break;
    case TexelFormat::kRgb888:
      downsample<TexelFormat::kRgb888>(src, palette, dw, dh, dst565, dst_bytes);
      break;
    case TexelFormat::kL8:
      downsample<TexelFormat::kL8>(src, palette, dw, dh, dst565, dst_bytes);
      break;
    case TexelFormat::kPalette8:
      downsample<TexelFormat::kPalette8>(src, palette, dw, dh, dst565, dst_bytes);
      break;
  }
}

}  // namespace

size_t mip_chain_size(const Texture& t) {
  uint16_t w = t.levels[0].width, h = t.levels[0].height;
  const int levels = mip_level_count(w, h);
  size_t total = 0;
  for (int i = 1; i < levels; ++i) {
    w = half_size(w);
    h = half_size(h);
    total += level_texels(w, h) * bytes_per_texel(t.format);
  }
  // kRgb565 storage counts uint16 values, not bytes.
  return t.format == TexelFormat::kRgb565 ? total / 2 : total;
}

Status build_mip_chain(Texture& texture, std::span<uint16_t> rgb565_storage,
                       std::span<uint8_t> byte_storage) {
  Texture level0 = texture;
  level0.level_count = 1;
  if (validate(level0) != Status::kOk) return Status::kInvalidArgument;
  const bool is565 = texture.format == TexelFormat::kRgb565;
  const size_t needed = mip_chain_size(texture);
  if ((is565 ? rgb565_storage.size() : byte_storage.size()) < needed) return Status::kCapacity;

  const int count = mip_level_count(level0.levels[0].width, level0.levels[0].height);
  const size_t per_texel = is565 ? 1 : bytes_per_texel(texture.format);
  size_t offset = 0;
  for (int i = 1; i < count; ++i) {
    const TextureLevel& src = level0.levels[static_cast<size_t>(i - 1)];
    const uint16_t w = half_size(src.width), h = half_size(src.height);
    const size_t n = level_texels(w, h) * per_texel;
    TextureLevel& dst = level0.levels[static_cast<size_t>(i)];
    dst = TextureLevel{};
    dst.width = w;
    dst.height = h;
    std::span<uint16_t> out565;
    std::span<uint8_t> out_bytes;
    if (is565) {
      out565 = rgb565_storage.subspan(offset, n);
      dst.rgb565 = out565;
    } else {
      out_bytes = byte_storage.subspan(offset, n);
      dst.bytes = out_bytes;
    }
    downsample_any(texture.format, src, texture.palette, w, h, out565, out_bytes);
    offset += n;
  }
  for (int i = 1; i < count; ++i)
    texture.levels[static_cast<size_t>(i)] = level0.levels[static_cast<size_t>(i)];
  for (int i = count; i < kMaxMipLevels; ++i) texture.levels[static_cast<size_t>(i)] = {};
  texture.level_count = static_cast<uint8_t>(count);
  return Status::kOk;
}

}  // namespace lr
