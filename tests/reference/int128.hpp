// An exact signed 128-bit integer for the reference renderer's edge functions on targets whose
// compiler has no __int128 (32-bit ARM, the armhf test build). Two's complement in two 64-bit
// words, arithmetic modulo 2^128 like the built-in type; only what the reference uses: sums,
// differences, products, negation, comparison, division truncated toward zero (as the built-in
// type; the divisor must not be zero) and a correctly rounded conversion to double (the same
// double the built-in type converts to, so the reference renders the same on every target).
// tests/reference/int128_test.cpp checks it against __int128 on the host.
#pragma once

#include <bit>
#include <cmath>
#include <compare>
#include <cstdint>

namespace lr::ref {

class Int128 {
 public:
  constexpr Int128() = default;
  constexpr Int128(int64_t v)  // NOLINT: implicit, like the built-in integer conversions
      : lo_(static_cast<uint64_t>(v)), hi_(v < 0 ? ~uint64_t{0} : 0) {}
  static constexpr Int128 from_words(uint64_t hi, uint64_t lo) {
    Int128 r;
    r.hi_ = hi;
    r.lo_ = lo;
    return r;
  }
  constexpr uint64_t hi() const { return hi_; }
  constexpr uint64_t lo() const { return lo_; }

  friend constexpr Int128 operator+(const Int128& a, const Int128& b) {
    const uint64_t lo = a.lo_ + b.lo_;
    return from_words(a.hi_ + b.hi_ + (lo < a.lo_ ? 1 : 0), lo);
  }
  friend constexpr Int128 operator-(const Int128& a, const Int128& b) {
    return from_words(a.hi_ - b.hi_ - (a.lo_ < b.lo_ ? 1 : 0), a.lo_ - b.lo_);
  }
  friend constexpr Int128 operator-(const Int128& a) { return Int128{} - a; }
  friend constexpr Int128 operator*(const Int128& a, const Int128& b) {
    // Low 128 bits of the product: the full 64 x 64 product of the low words plus the low
    // halves of the cross products (the same modulo 2^128 for signed and unsigned operands).
    uint64_t hi = 0;
    const uint64_t lo = mul_64x64(a.lo_, b.lo_, hi);
    return from_words(hi + a.hi_ * b.lo_ + a.lo_ * b.hi_, lo);
  }
  friend constexpr Int128 operator/(const Int128& a, const Int128& b) {
    return divmod(a, b, nullptr);
  }
  friend constexpr Int128 operator%(const Int128& a, const Int128& b) {
    Int128 r;
    divmod(a, b, &r);
    return r;
  }
  friend constexpr bool operator==(const Int128& a, const Int128& b) = default;
  friend constexpr std::strong_ordering operator<=>(const Int128& a, const Int128& b) {
    const auto ah = static_cast<int64_t>(a.hi_), bh = static_cast<int64_t>(b.hi_);
    if (ah != bh) return ah <=> bh;
    return a.lo_ <=> b.lo_;
  }

  // Round to nearest, ties to even, as the conversion of the built-in type.
  explicit operator double() const {
    const bool negative = static_cast<int64_t>(hi_) < 0;
    const Int128 m = negative ? -*this : *this;  // magnitude (2^127 stays 2^127 as unsigned)
    double d;
    if (m.hi_ == 0) {
      d = static_cast<double>(m.lo_);
    } else {
      // Keep the top 64 bits and fold every bit shifted out into the lowest one (sticky bit):
      // it lies below the rounding position, so the one rounding of uint64 -> double is exact.
      const int shift = 64 - std::countl_zero(m.hi_);  // 1..64
      const uint64_t top = shift == 64 ? m.hi_ : (m.hi_ << (64 - shift)) | (m.lo_ >> shift);
      const uint64_t lost = shift == 64 ? m.lo_ : m.lo_ & ((uint64_t{1} << shift) - 1);
      d = std::ldexp(static_cast<double>(top | (lost != 0 ? 1 : 0)), shift);
    }
    return negative ? -d : d;
  }

 private:
  constexpr bool negative() const { return static_cast<int64_t>(hi_) < 0; }

  // Quotient truncated toward zero; the remainder takes the dividend's sign. Restoring binary
  // long division on the magnitudes: slow, and only test and reference code uses it.
  static constexpr Int128 divmod(const Int128& a, const Int128& b, Int128* rem) {
    const Int128 n = a.negative() ? -a : a, d = b.negative() ? -b : b;
    Int128 q, r;
    for (int i = 127; i >= 0; --i) {
      r = from_words((r.hi_ << 1) | (r.lo_ >> 63), (r.lo_ << 1) | (bit(n, i) ? 1 : 0));
      if (!less_unsigned(r, d)) {
        r = r - d;
        if (i >= 64)
          q.hi_ |= uint64_t{1} << (i - 64);
        else
          q.lo_ |= uint64_t{1} << i;
      }
    }
    if (rem != nullptr) *rem = a.negative() ? -r : r;
    return a.negative() != b.negative() ? -q : q;
  }
  static constexpr bool bit(const Int128& v, int i) {
    return ((i >= 64 ? v.hi_ >> (i - 64) : v.lo_ >> i) & 1) != 0;
  }
  static constexpr bool less_unsigned(const Int128& a, const Int128& b) {
    return a.hi_ != b.hi_ ? a.hi_ < b.hi_ : a.lo_ < b.lo_;
  }

  static constexpr uint64_t mul_64x64(uint64_t a, uint64_t b, uint64_t& hi) {
    const uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
    const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    const uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
    hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    return (mid << 32) | (p00 & 0xFFFFFFFFu);
  }

  uint64_t lo_ = 0, hi_ = 0;
};

}  // namespace lr::ref
