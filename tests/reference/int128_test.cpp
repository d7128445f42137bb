// The reference renderer's portable 128-bit integer (used where __int128 is missing: 32-bit ARM)
// against the built-in type: same sums, products, order and double conversion.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "tests/reference/int128.hpp"

namespace lr::ref {
namespace {

TEST(Int128, SmallValuesAndOrder) {
  const Int128 a = int64_t{-5}, b = int64_t{7};
  EXPECT_EQ(a * b, Int128{int64_t{-35}});
  EXPECT_EQ(a - b, Int128{int64_t{-12}});
  EXPECT_EQ(-a, Int128{int64_t{5}});
  EXPECT_LT(a, 0);
  EXPECT_GT(b, 0);
  EXPECT_EQ(Int128{}, 0);
  EXPECT_EQ(static_cast<double>(a * b), -35.0);
  // Beyond 64 bits: 2^62 * 2^62 = 2^124.
  const Int128 big = Int128{int64_t{1} << 62} * Int128{int64_t{1} << 62};
  EXPECT_EQ(big.hi(), uint64_t{1} << 60);
  EXPECT_EQ(big.lo(), 0u);
  EXPECT_EQ(static_cast<double>(big), 0x1p124);
  EXPECT_EQ(static_cast<double>(-big), -0x1p124);
  EXPECT_LT(-big, Int128{INT64_MIN});
}

TEST(Int128, DoubleConversionRoundsToNearestEven) {
  // 2^64 + 2^11 is half-way between 2^64 and 2^64 + 2^12: ties to even gives 2^64; one more
  // unit in the last (128-bit) place rounds up.
  EXPECT_EQ(static_cast<double>(Int128::from_words(1, uint64_t{1} << 11)), 0x1p64);
  EXPECT_EQ(static_cast<double>(Int128::from_words(1, (uint64_t{1} << 11) + 1)), 0x1p64 + 0x1p12);
  EXPECT_EQ(static_cast<double>(Int128::from_words(1, uint64_t{3} << 11)), 0x1p64 + 0x1p13);
}

#if defined(__SIZEOF_INT128__)
__extension__ typedef __int128 builtin;

builtin to_builtin(const Int128& v) {
  return static_cast<builtin>((static_cast<unsigned __int128>(v.hi()) << 64) | v.lo());
}

TEST(Int128, MatchesTheBuiltInType) {
  std::mt19937_64 rng(20240611);
  auto operand = [&] {
    // Edge-function operands: differences of coordinates up to 2^61, and also small ones.
    const int bits = static_cast<int>(rng() % 62) + 1;
    auto v = static_cast<int64_t>(rng() >> (64 - bits));
    return (rng() & 1) ? v : -v;
  };
  for (int n = 0; n < 200000; ++n) {
    const int64_t a = operand(), b = operand(), c = operand(), d = operand();
    const Int128 x = Int128{a} * b - Int128{c} * d;
    const builtin y = static_cast<builtin>(a) * b - static_cast<builtin>(c) * d;
    ASSERT_EQ(to_builtin(x), y) << a << " " << b << " " << c << " " << d;
    ASSERT_EQ(to_builtin(-x), -y);
    ASSERT_EQ(to_builtin(x + Int128{a}), y + a);
    ASSERT_EQ(x < 0, y < 0);
    ASSERT_EQ(x == 0, y == 0);
    ASSERT_EQ(x < Int128{c} * a, y < static_cast<builtin>(c) * a);
    ASSERT_EQ(static_cast<double>(x), static_cast<double>(y)) << a << " " << b;
    const Int128 div = b != 0 ? Int128{b} : Int128{1};
    const builtin bdiv = b != 0 ? b : 1;
    ASSERT_EQ(to_builtin(x / div), y / bdiv) << a << " " << b << " " << c << " " << d;
    ASSERT_EQ(to_builtin(x % div), y % bdiv) << a << " " << b << " " << c << " " << d;
    if (y != 0) {
      ASSERT_EQ(to_builtin(Int128{a} / x), a / y);
    }
  }
}
#endif

}  // namespace
}  // namespace lr::ref
