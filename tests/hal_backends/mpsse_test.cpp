// The FT232H MPSSE byte stream, byte for byte, for each bus operation (opcodes: FTDI AN_108;
// hal/host/usb/mpsse.hpp lists them).
#include "lineraster/hal/host/usb/mpsse.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace lr::mpsse {
namespace {

using Bytes = std::vector<uint8_t>;

// Default pins: CS D3, D/C C0, reset C1, no backlight. Idle levels: ADBUS = CS high (0x08),
// outputs SCK, MOSI, CS (0x0B); ACBUS = D/C high, reset released (0x03), outputs 0x03.
TEST(MpsseClock, DivisorIsTheFastestClockNotAboveTheRequest) {
  EXPECT_EQ(clock_divisor(30'000'000), 0);
  EXPECT_EQ(clock_divisor(60'000'000), 0);  // above the chip's fastest: 30 MHz
  EXPECT_EQ(clock_divisor(10'000'000), 2);
  EXPECT_EQ(clock_divisor(12'000'000), 2);  // 15 MHz would be too fast: 10 MHz
  EXPECT_EQ(clock_divisor(15'000'000), 1);
  EXPECT_EQ(clock_divisor(1'000'000), 29);
  EXPECT_EQ(clock_divisor(100), 0xFFFF);  // the slowest the chip makes
  EXPECT_EQ(clock_hz(0), 30'000'000u);
  EXPECT_EQ(clock_hz(2), 10'000'000u);
  EXPECT_EQ(clock_hz(29), 1'000'000u);
  EXPECT_EQ(clock_hz(0xFFFF), 457u);
}

TEST(MpsseInit, ThirtyMegahertz) {
  Encoder e{PinMap{}};
  Bytes out;
  e.init(30'000'000, out);
  EXPECT_EQ(out, (Bytes{0x80, 0x08, 0x0B,  // ADBUS: SCK, MOSI low, CS high
                        0x82, 0x03, 0x03,  // ACBUS: D/C high, reset high (released)
                        0x8A,              // divide-by-5 off: 60 MHz base
                        0x97,              // adaptive clocking off
                        0x8D,              // three-phase clocking off
                        0x86, 0x00, 0x00,  // divisor 0: 30 MHz
                        0x85}));           // loopback off
  EXPECT_FALSE(e.cs_asserted());
}

TEST(MpsseInit, TenMegahertz) {
  Encoder e{PinMap{}};
  Bytes out;
  e.init(10'000'000, out);
  EXPECT_EQ(out,
            (Bytes{0x80, 0x08, 0x0B, 0x82, 0x03, 0x03, 0x8A, 0x97, 0x8D, 0x86, 0x02, 0x00, 0x85}));
}

TEST(MpsseInit, AllLinesOnAdbusLeaveAcbusAlone) {
  PinMap pins;
  pins.dc = Pin{4, false};
  pins.reset = Pin{5, false};
  pins.backlight = Pin{6, false};
  Encoder e{pins};
  Bytes out;
  e.init(1'000'000, out);
  // CS | D/C | reset high = 0x38; outputs SCK, MOSI, CS, D/C, reset, backlight = 0x7B.
  EXPECT_EQ(out, (Bytes{0x80, 0x38, 0x7B, 0x8A, 0x97, 0x8D, 0x86, 29, 0x00, 0x85}));
}

TEST(MpsseCommand, ParametersDcLowThenHighInsideChipSelect) {
  Encoder e{PinMap{}};
  Bytes init;
  e.init(30'000'000, init);
  Bytes out;
  const uint8_t caset[] = {0x00, 0x00, 0x00, 0xEF};
  e.command(0x2A, caset, false, out);
  EXPECT_EQ(out, (Bytes{0x80, 0x00, 0x0B,                          // CS low
                        0x82, 0x02, 0x03,                          // D/C low
                        0x11, 0x00, 0x00, 0x2A,                    // one byte: CASET
                        0x82, 0x03, 0x03,                          // D/C high
                        0x11, 0x03, 0x00, 0x00, 0x00, 0x00, 0xEF,  // four parameter bytes
                        0x80, 0x08, 0x0B}));                       // CS high
  EXPECT_FALSE(e.cs_asserted());
}

TEST(MpsseCommand, WithoutParametersDcStaysLowAndIsNotResent) {
  Encoder e{PinMap{}};
  Bytes out;
  e.command(0x11, {}, false, out);  // SLPOUT
  EXPECT_EQ(out,
            (Bytes{0x80, 0x00, 0x0B, 0x82, 0x02, 0x03, 0x11, 0x00, 0x00, 0x11, 0x80, 0x08, 0x0B}));
  out.clear();
  e.command(0x29, {}, false, out);  // DISPON: D/C is already low
  EXPECT_EQ(out, (Bytes{0x80, 0x00, 0x0B, 0x11, 0x00, 0x00, 0x29, 0x80, 0x08, 0x0B}));
}

TEST(MpsseCommand, DcOnTheLowByteChangesWithChipSelectInOneWrite) {
  PinMap pins;
  pins.dc = Pin{4, false};
  pins.reset.reset();
  Encoder e{pins};
  Bytes out;
  const uint8_t madctl[] = {0x60};
  e.command(0x36, madctl, false, out);
  // ADBUS outputs SCK, MOSI, CS, D/C = 0x1B; idle CS | D/C = 0x18.
  EXPECT_EQ(out, (Bytes{0x80, 0x00, 0x1B, 0x11, 0x00, 0x00, 0x36,  // CS and D/C low, command
                        0x80, 0x10, 0x1B, 0x11, 0x00, 0x00, 0x60,  // D/C high, parameter
                        0x80, 0x18, 0x1B}));                       // CS high
}

TEST(MpssePixels, RamwrKeepsChipSelectForThePixelsThatFollow) {
  Encoder e{PinMap{}};
  Bytes out;
  e.command(0x2C, {}, true, out);  // RAMWR
  EXPECT_EQ(out, (Bytes{0x80, 0x00, 0x0B, 0x82, 0x02, 0x03, 0x11, 0x00, 0x00, 0x2C}));
  EXPECT_TRUE(e.cs_asserted());
  out.clear();
  const uint8_t px[] = {0xF8, 0x00, 0x07};
  e.pixels(px, out);
  EXPECT_EQ(out, (Bytes{0x82, 0x03, 0x03,                    // D/C high (CS already low)
                        0x11, 0x02, 0x00, 0xF8, 0x00, 0x07,  // three bytes
                        0x80, 0x08, 0x0B}));                 // CS high
  EXPECT_FALSE(e.cs_asserted());
}

TEST(MpssePixels, LongPayloadSplitsIntoPacketsOf64KiB) {
  Bytes data(2 * 65536 + 10);
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i * 7 + (i >> 8));
  Encoder e{PinMap{}};
  Bytes out;
  e.pixels(data, out);

  Bytes expected = {0x80, 0x00, 0x0B};  // CS low (D/C is high at rest)
  auto packet = [&](size_t begin, size_t n) {
    expected.insert(expected.end(), {0x11, static_cast<uint8_t>((n - 1) & 0xFF),
                                     static_cast<uint8_t>((n - 1) >> 8)});
    expected.insert(expected.end(), data.begin() + static_cast<std::ptrdiff_t>(begin),
                    data.begin() + static_cast<std::ptrdiff_t>(begin + n));
  };
  packet(0, 65536);  // 0x11 0xFF 0xFF: the largest packet
  packet(65536, 65536);
  packet(131072, 10);  // 0x11 0x09 0x00
  expected.insert(expected.end(), {0x80, 0x08, 0x0B});
  ASSERT_EQ(out.size(), expected.size());
  EXPECT_TRUE(out == expected);
  EXPECT_EQ(out[3], 0x11);
  EXPECT_EQ(out[4], 0xFF);
  EXPECT_EQ(out[5], 0xFF);
  EXPECT_EQ(out[3 + 2 * 65539], 0x11);
  EXPECT_EQ(out[3 + 2 * 65539 + 1], 0x09);
  EXPECT_EQ(out[3 + 2 * 65539 + 2], 0x00);
}

TEST(MpssePixels, OneByteOverAPacketMakesASecondPacketOfOne) {
  Bytes data(65537, 0x5A);
  Encoder e{PinMap{}};
  Bytes out;
  e.write_bytes(data, out);
  ASSERT_EQ(out.size(), 3 + 65536 + 3 + 1u);
  EXPECT_EQ((Bytes{out[0], out[1], out[2]}), (Bytes{0x11, 0xFF, 0xFF}));
  EXPECT_EQ((Bytes{out[65539], out[65540], out[65541], out[65542]}),
            (Bytes{0x11, 0x00, 0x00, 0x5A}));
}

TEST(MpsseLines, ResetAndBacklightToggles) {
  PinMap pins;
  pins.backlight = Pin{2, true};  // C2
  Encoder e{pins};
  Bytes out;
  e.init(30'000'000, out);
  EXPECT_EQ((Bytes{out[3], out[4], out[5]}), (Bytes{0x82, 0x03, 0x07}));  // backlight off
  out.clear();
  e.set_reset(true, out);
  EXPECT_EQ(out, (Bytes{0x82, 0x01, 0x07}));  // reset asserted: C1 low
  out.clear();
  e.set_reset(false, out);
  EXPECT_EQ(out, (Bytes{0x82, 0x03, 0x07}));
  out.clear();
  e.set_backlight(true, out);
  EXPECT_EQ(out, (Bytes{0x82, 0x07, 0x07}));  // C2 high
  out.clear();
  e.set_backlight(false, out);
  EXPECT_EQ(out, (Bytes{0x82, 0x03, 0x07}));
  out.clear();
  e.set_backlight(false, out);  // no change: nothing to send
  EXPECT_TRUE(out.empty());
}

TEST(MpsseLines, BacklightOnAdbus) {
  PinMap pins;
  pins.backlight = Pin{7, false};  // D7
  Encoder e{pins};
  Bytes out;
  e.set_backlight(true, out);
  EXPECT_EQ(out, (Bytes{0x80, 0x88, 0x8B}));
}

TEST(MpsseLines, MissingLinesSendNothing) {
  PinMap pins;
  pins.reset.reset();
  Encoder e{pins};
  Bytes out;
  e.set_reset(true, out);
  e.set_backlight(true, out);
  EXPECT_TRUE(out.empty());
}

TEST(MpsseSync, ProbeAndBadCommandReply) {
  Bytes probe;
  sync_probe(probe);
  EXPECT_EQ(probe, (Bytes{0xAA, 0x87}));  // bogus opcode, send immediate

  // Two 512-byte USB packets, each behind two modem status bytes; the answer 0xFA 0xAA
  // straddles them.
  Bytes usb(512, 0x00);
  usb[0] = 0x32;
  usb[1] = 0x60;
  usb[511] = 0xFA;
  usb.insert(usb.end(), {0x32, 0x60, 0xAA});
  Bytes payload;
  strip_modem_status(usb, 512, payload);
  EXPECT_EQ(payload.size(), 510u + 1u);
  EXPECT_TRUE(has_bad_command_reply(payload, 0xAA));
  EXPECT_FALSE(has_bad_command_reply(payload, 0xAB));
  EXPECT_FALSE(has_bad_command_reply(usb, 0xAA));  // unstripped: status bytes in between

  Bytes status_only = {0x32, 0x60};
  payload.clear();
  strip_modem_status(status_only, 512, payload);
  EXPECT_TRUE(payload.empty());
}

TEST(MpssePins, ParseAndCheck) {
  Pin p;
  std::string err;
  ASSERT_TRUE(parse_pin("C0", p, err));
  EXPECT_EQ(p, (Pin{0, true}));
  ASSERT_TRUE(parse_pin("d7", p, err));
  EXPECT_EQ(p, (Pin{7, false}));
  ASSERT_TRUE(parse_pin("AC3", p, err));
  EXPECT_EQ(p, (Pin{3, true}));
  EXPECT_EQ(pin_name(Pin{5, false}), "D5");
  EXPECT_FALSE(parse_pin("D8", p, err));
  EXPECT_EQ(err, "D8: not an FT232H GPIO pin (D3-D7 or C0-C7)");
  EXPECT_FALSE(parse_pin("C", p, err));

  PinMap pins;
  EXPECT_TRUE(check_pins(pins, err));
  pins.dc = Pin{1, false};
  EXPECT_FALSE(check_pins(pins, err));
  EXPECT_EQ(err, "dc=D1: D0-D2 are SCK, MOSI and MISO (use D3-D7 or C0-C7)");
  pins = PinMap{};
  pins.backlight = Pin{1, true};
  EXPECT_FALSE(check_pins(pins, err));
  EXPECT_EQ(err, "rst and bl are both on C1");
}

}  // namespace
}  // namespace lr::mpsse
