// The FT232H's MPSSE command stream for a panel bus, as pure functions of the bus operations (no
// I/O): what Ft232hBus writes to the chip's bulk OUT endpoint. Opcodes from FTDI's AN_108
// ("Command Processor for MPSSE and MCU Host Bus Emulation Modes"):
//
//   0x80 value dir   set ADBUS0-7 (the "low byte": D0-D7 on an FT232H breakout)
//   0x82 value dir   set ACBUS0-7 (the "high byte": C0-C7)
//   0x11 Ll Lh data  clock bytes out on the falling edge, MSB first, no read; L+1 bytes (1-65536)
//   0x86 Dl Dh       clock divisor: SCK = 60 MHz / ((1 + D) * 2) with divide-by-5 off
//   0x8A             divide-by-5 off (60 MHz master clock; FT232H/FT2232H/FT4232H only)
//   0x97             adaptive clocking off
//   0x8D             three-phase data clocking off
//   0x85             loopback (DO to DI) off
//   0x87             send immediate: flush the chip's answers to the host now
//   0xAA             not an opcode: the chip answers 0xFA 0xAA ("bad command"), used to check
//                    that the MPSSE is in step with the host
//
// SPI mode 0: SCK idles low, data changes on the falling edge and is sampled by the panel on
// the rising edge (0x11). ADBUS0 = SCK, ADBUS1 = MOSI (DO), ADBUS2 = MISO (DI, unused, input);
// chip select, D/C, reset and backlight are plain GPIO bits driven with 0x80/0x82.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace lr::mpsse {

inline constexpr uint8_t kSetLowByte = 0x80;
inline constexpr uint8_t kSetHighByte = 0x82;
inline constexpr uint8_t kWriteBytesFallingMsb = 0x11;
inline constexpr uint8_t kLoopbackOff = 0x85;
inline constexpr uint8_t kSetDivisor = 0x86;
inline constexpr uint8_t kSendImmediate = 0x87;
inline constexpr uint8_t kDivideBy5Off = 0x8A;
inline constexpr uint8_t kThreePhaseOff = 0x8D;
inline constexpr uint8_t kAdaptiveClockOff = 0x97;
inline constexpr uint8_t kBogusOpcode = 0xAA;
inline constexpr uint8_t kBadCommandReply = 0xFA;

inline constexpr size_t kMaxPacket = 65536;  // bytes per 0x11 command
inline constexpr uint32_t kBaseClockHz = 60'000'000;
inline constexpr uint32_t kMaxClockHz = kBaseClockHz / 2;  // divisor 0: 30 MHz

// The divisor of the fastest clock not above hz (hz >= 30 MHz: 0); clamped to 0xFFFF (458 Hz),
// the slowest the chip makes.
uint16_t clock_divisor(uint32_t hz);
// SCK for a divisor: 60 MHz / ((1 + divisor) * 2).
uint32_t clock_hz(uint16_t divisor);

// A GPIO pin: bit 0-7 of ADBUS (Dn) or of ACBUS (Cn).
struct Pin {
  uint8_t bit = 0;
  bool acbus = false;
  friend constexpr bool operator==(const Pin&, const Pin&) = default;
};
// "D4", "C0" (also "AD4", "AC0", lower case accepted); false and an error otherwise.
bool parse_pin(std::string_view text, Pin& out, std::string& error);
std::string pin_name(Pin pin);  // "D4", "C0"

// Where the panel's lines are wired. Defaults: CS on D3 (the MPSSE's chip select), D/C on C0,
// reset on C1, no backlight line (the Adafruit FT232H breakout's labels).
struct PinMap {
  Pin cs{3, false};
  Pin dc{0, true};
  std::optional<Pin> reset = Pin{1, true};
  std::optional<Pin> backlight;
};
// D0-D2 are SCK, MOSI and MISO; every line on its own pin.
bool check_pins(const PinMap& pins, std::string& error);

// Turns bus operations into MPSSE bytes appended to `out`, tracking the pin levels it has
// written so that only changes are sent: pins that change together (D/C and CS before a
// command) go out in one 0x80 and/or one 0x82 write (ADBUS first), all before the first clock.
class Encoder {
 public:
  explicit Encoder(const PinMap& pins);

  // Drives every pin (SCK and MOSI low, CS high, D/C high, reset released, backlight as last
  // set: off at first) and sets the clock: 0x80, 0x82 (when a line is on ACBUS), 0x8A, 0x97,
  // 0x8D, 0x86 with clock_divisor(hz), 0x85.
  void init(uint32_t hz, std::vector<uint8_t>& out);

  // One command byte with D/C low, its parameters (if any) with D/C high, CS low around both.
  // With keep_cs, CS stays low afterwards, for pixel data to follow (RAMWR).
  void command(uint8_t cmd, std::span<const uint8_t> params, bool keep_cs,
               std::vector<uint8_t>& out);

  // Pixel data: select_data() (D/C high, CS low: whatever is not already so), write_bytes()
  // (one 0x11 packet per kMaxPacket bytes), deselect() (CS high). pixels() does all three.
  void select_data(std::vector<uint8_t>& out);
  void write_bytes(std::span<const uint8_t> data, std::vector<uint8_t>& out);
  void deselect(std::vector<uint8_t>& out);
  void pixels(std::span<const uint8_t> data, std::vector<uint8_t>& out);

  // Reset asserted drives its pin low (the panel's RESX is active low); backlight on drives
  // its pin high. Without the line nothing is appended.
  void set_reset(bool asserted, std::vector<uint8_t>& out);
  void set_backlight(bool on, std::vector<uint8_t>& out);

  bool cs_asserted() const { return !level(pins_.cs); }
  const PinMap& pins() const { return pins_; }

 private:
  bool level(Pin p) const;
  void set_level(Pin p, bool high);
  void flush(std::vector<uint8_t>& out);  // the bytes whose levels changed since last written

  PinMap pins_;
  uint8_t low_ = 0, high_ = 0;          // levels wanted
  uint8_t low_dir_ = 0, high_dir_ = 0;  // outputs
  uint8_t sent_low_ = 0, sent_high_ = 0;
};

// The MPSSE synchronisation probe: the bogus opcode 0xAA and a send immediate.
void sync_probe(std::vector<uint8_t>& out);
// Whether `payload` (bytes read back, modem status removed) holds the chip's answer to an
// unknown opcode: 0xFA followed by that opcode.
bool has_bad_command_reply(std::span<const uint8_t> payload, uint8_t opcode);
// The FTDI IN endpoint starts every USB packet (max_packet bytes) with two modem status bytes;
// appends what follows them to `payload`.
void strip_modem_status(std::span<const uint8_t> usb_data, size_t max_packet,
                        std::vector<uint8_t>& payload);

}  // namespace lr::mpsse
