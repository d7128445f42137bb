#include "lineraster/hal/host/usb/mpsse.hpp"

#include <algorithm>

namespace lr::mpsse {
namespace {

constexpr uint8_t kSck = 1u << 0;
constexpr uint8_t kMosi = 1u << 1;

uint8_t bit_of(Pin p) {
  return static_cast<uint8_t>(1u << p.bit);
}

}  // namespace

uint16_t clock_divisor(uint32_t hz) {
  if (hz >= kMaxClockHz) return 0;
  if (hz == 0) return 0xFFFF;
  // Smallest d with 60 MHz / ((1 + d) * 2) <= hz: 1 + d = ceil(30 MHz / hz).
  const uint64_t n = (uint64_t{kMaxClockHz} + hz - 1) / hz;
  return static_cast<uint16_t>(std::min<uint64_t>(n - 1, 0xFFFF));
}

uint32_t clock_hz(uint16_t divisor) {
  return kMaxClockHz / (uint32_t{divisor} + 1);
}

bool parse_pin(std::string_view text, Pin& out, std::string& error) {
  std::string_view t = text;
  if (t.size() == 3 && (t[0] == 'A' || t[0] == 'a')) t.remove_prefix(1);
  if (t.size() == 2 && t[1] >= '0' && t[1] <= '7') {
    const char bus = t[0];
    if (bus == 'D' || bus == 'd' || bus == 'C' || bus == 'c') {
      out = Pin{static_cast<uint8_t>(t[1] - '0'), bus == 'C' || bus == 'c'};
      return true;
    }
  }
  error = std::string(text) + ": not an FT232H GPIO pin (D3-D7 or C0-C7)";
  return false;
}

std::string pin_name(Pin pin) {
  return std::string(1, pin.acbus ? 'C' : 'D') + static_cast<char>('0' + pin.bit);
}

bool check_pins(const PinMap& pins, std::string& error) {
  struct Named {
    const char* role;
    Pin pin;
  };
  std::vector<Named> used{{"cs", pins.cs}, {"dc", pins.dc}};
  if (pins.reset) used.push_back({"rst", *pins.reset});
  if (pins.backlight) used.push_back({"bl", *pins.backlight});
  for (size_t i = 0; i < used.size(); ++i) {
    const Pin p = used[i].pin;
    if (p.bit > 7) {
      error = std::string(used[i].role) + ": pin bit " + std::to_string(p.bit) + " (0-7)";
      return false;
    }
    if (!p.acbus && p.bit <= 2) {
      error = std::string(used[i].role) + "=" + pin_name(p) +
              ": D0-D2 are SCK, MOSI and MISO (use D3-D7 or C0-C7)";
      return false;
    }
    for (size_t j = 0; j < i; ++j) {
      if (used[j].pin == p) {
        error = std::string(used[j].role) + " and " + used[i].role + " are both on " + pin_name(p);
        return false;
      }
    }
  }
  return true;
}

Encoder::Encoder(const PinMap& pins) : pins_(pins) {
  low_dir_ = kSck | kMosi;  // ADBUS2 (MISO) stays an input
  auto output = [this](Pin p, bool high) {
    (p.acbus ? high_dir_ : low_dir_) |= bit_of(p);
    set_level(p, high);
  };
  output(pins_.cs, true);
  output(pins_.dc, true);
  if (pins_.reset) output(*pins_.reset, true);
  if (pins_.backlight) output(*pins_.backlight, false);
  sent_low_ = low_;
  sent_high_ = high_;
}

bool Encoder::level(Pin p) const {
  return ((p.acbus ? high_ : low_) & bit_of(p)) != 0;
}

void Encoder::set_level(Pin p, bool high) {
  uint8_t& byte = p.acbus ? high_ : low_;
  byte = static_cast<uint8_t>(high ? (byte | bit_of(p)) : (byte & ~bit_of(p)));
}

void Encoder::flush(std::vector<uint8_t>& out) {
  if (low_ != sent_low_) {
    out.insert(out.end(), {kSetLowByte, low_, low_dir_});
    sent_low_ = low_;
  }
  if (high_ != sent_high_) {
    out.insert(out.end(), {kSetHighByte, high_, high_dir_});
    sent_high_ = high_;
  }
}

void Encoder::init(uint32_t hz, std::vector<uint8_t>& out) {
  set_level(pins_.cs, true);
  low_ = static_cast<uint8_t>(low_ & ~(kSck | kMosi));
  out.insert(out.end(), {kSetLowByte, low_, low_dir_});
  if (high_dir_ != 0) out.insert(out.end(), {kSetHighByte, high_, high_dir_});
  sent_low_ = low_;
  sent_high_ = high_;
  const uint16_t d = clock_divisor(hz);
  out.insert(out.end(),
             {kDivideBy5Off, kAdaptiveClockOff, kThreePhaseOff, kSetDivisor,
              static_cast<uint8_t>(d & 0xFF), static_cast<uint8_t>(d >> 8), kLoopbackOff});
}

void Encoder::write_bytes(std::span<const uint8_t> data, std::vector<uint8_t>& out) {
  while (!data.empty()) {
    const size_t n = std::min(data.size(), kMaxPacket);
    const size_t len = n - 1;  // the chip clocks length + 1 bytes
    out.insert(out.end(), {kWriteBytesFallingMsb, static_cast<uint8_t>(len & 0xFF),
                           static_cast<uint8_t>(len >> 8)});
    out.insert(out.end(), data.begin(), data.begin() + static_cast<std::ptrdiff_t>(n));
    data = data.subspan(n);
  }
}

void Encoder::command(uint8_t cmd, std::span<const uint8_t> params, bool keep_cs,
                      std::vector<uint8_t>& out) {
  // D/C and CS change together, before the first clock edge: one write when they share a byte.
  set_level(pins_.dc, false);
  set_level(pins_.cs, false);
  flush(out);
  const uint8_t byte[1] = {cmd};
  write_bytes(byte, out);
  if (!params.empty()) {
    set_level(pins_.dc, true);
    flush(out);
    write_bytes(params, out);
  }
  if (!keep_cs) deselect(out);
}

void Encoder::select_data(std::vector<uint8_t>& out) {
  set_level(pins_.dc, true);
  set_level(pins_.cs, false);
  flush(out);
}

void Encoder::deselect(std::vector<uint8_t>& out) {
  set_level(pins_.cs, true);
  flush(out);
}

void Encoder::pixels(std::span<const uint8_t> data, std::vector<uint8_t>& out) {
  select_data(out);
  write_bytes(data, out);
  deselect(out);
}

void Encoder::set_reset(bool asserted, std::vector<uint8_t>& out) {
  if (!pins_.reset) return;
  set_level(*pins_.reset, !asserted);
  flush(out);
}

void Encoder::set_backlight(bool on, std::vector<uint8_t>& out) {
  if (!pins_.backlight) return;
  set_level(*pins_.backlight, on);
  flush(out);
}

void sync_probe(std::vector<uint8_t>& out) {
  out.insert(out.end(), {kBogusOpcode, kSendImmediate});
}

bool has_bad_command_reply(std::span<const uint8_t> payload, uint8_t opcode) {
  for (size_t i = 0; i + 1 < payload.size(); ++i) {
    if (payload[i] == kBadCommandReply && payload[i + 1] == opcode) return true;
  }
  return false;
}

void strip_modem_status(std::span<const uint8_t> usb_data, size_t max_packet,
                        std::vector<uint8_t>& payload) {
  if (max_packet <= 2) return;
  for (size_t at = 0; at < usb_data.size(); at += max_packet) {
    const size_t end = std::min(usb_data.size(), at + max_packet);
    if (end > at + 2)
      payload.insert(payload.end(), usb_data.begin() + static_cast<std::ptrdiff_t>(at + 2),
                     usb_data.begin() + static_cast<std::ptrdiff_t>(end));
  }
}

}  // namespace lr::mpsse
