// An emulated SPI panel: an ST7789 or ILI9341 controller and the module around it, fed with
// what a driver puts on the wires (command bytes with D/C low, parameter and pixel bytes with D/C
// high, chip-select framing, the reset line, time). It keeps the controller's graphics RAM
// (240 x 320, RGB565) and registers and answers with the image the module would show.
//
// The controller, as the datasheets define it (Sitronix ST7789V, with the tables it shares with
// its ST7735 sibling, and Ilitek ILI9341; where they leave a case open, the emulator says what it
// assumes):
//   * CASET (2Ah) / RASET (2Bh) set the address window XS..XE, YS..YE (16-bit values, each byte
//     stored as it arrives); RAMWR (2Ch) resets the counters to (XS, YS), RAMWRC (3Ch) continues
//     where the last write stopped. The column counter runs first: at XE it goes back to XS and
//     the row counter steps; after (XE, YE) both return to (XS, YS) (what the controllers do; the
//     DCS text says extra pixels are ignored: Options::wrap_past_window_end = false does that).
//     Both are reported as kWindowOverflow.
//   * MADCTL (36h) maps the counters to RAM ("Memory Data Write/Read Direction" table):
//       MV = 0: column = x, row = y;  MV = 1: column = y, row = x;  then
//       MX: column = 239 - column;     MY: row = 319 - row.
//     With MV = 0 the window addresses 0..239 x 0..319, with MV = 1 0..319 x 0..239; "when XS or
//     XE is greater than the maximum address, data of out of range will be ignored": pixels whose
//     counters fall outside are dropped (kWindowOutsideRam), the counters still advance.
//     ML and MH only change the refresh order: no effect on the image. BGR swaps red and blue
//     on the way to the glass.
//   * COLMOD (3Ah), interface format in bits 2..0: 5 = 16 bits (RGB565, two bytes, high byte
//     first), 6 = 18 bits (three bytes, 6 bits each in bits 7..2), 3 = 12 bits (three bytes for
//     two pixels), 7 (ST7789: 16M truncated, three bytes); any other value: pixel data ignored.
//     Anything but 16 bits is reported (kPixelFormat); RAM keeps 16 bits per pixel, so 18/24-bit
//     data is stored at 565 precision. ST7789 RAMCTRL (B0h) ENDIAN (2nd parameter, bit 3) makes
//     16-bit pixels little-endian.
//   * SWRESET (01h): registers to their defaults except MADCTL and COLMOD ("S/W reset: no
//     change"), sleep in, display off; the RAM keeps its contents. The reset line (RESX) resets
//     MADCTL to 00h and COLMOD to 66h as well. At power-on the RAM holds noise (pseudo-random).
//   * SLPIN / SLPOUT, DISPOFF / DISPON, INVOFF / INVON, IDMOFF / IDMON (8 colours: each channel's
//     top bit), PTLON / NORON with PTLAR (rows outside the partial area are black), ILI9341
//     DISCTRL (B6h) SS / GS (source / gate scan reversed: the glass mirrored).
//   * Undefined commands are treated as NOP (the Sitronix command list's note); read commands
//     are accepted, but a PanelBus cannot read, so they are reported.
//   * Sleep: "only the MCU interface and memory work": RAM writes while asleep land in RAM
//     (reported as a note, kWriteWhileAsleep), the glass shows nothing.
//   * Data pause: releasing chip select between bytes pauses a command; data after CS is asserted
//     again continues it. A command ends only at the next command byte.
//
// The module (a PanelConfig): the visible window (RAM columns col_offset .. col_offset + width - 1
// and rows row_offset .. row_offset + height - 1), whether the glass is BGR (then MADCTL's BGR
// must be set for true colours) and whether it shows inverted colours until INVON (IPS panels:
// PanelConfig::invert). Rotation 0 is the module held in its native portrait orientation: RAM
// row 0 at the top and, on ST7789 modules, RAM column 0 on the left. ILI9341 modules (Adafruit
// 2.4" / 2.8" and their clones) have the glass bonded the other way round: their source outputs
// run right to left, RAM column 0 is on the right, and every driver for them sets MX to show an
// upright image at rotation 0 (Linux's ili9341 and mi0283qt, Adafruit_ILI9341, TFT_eSPI).
// Options::mirrored_glass says which (default: by controller). DISCTRL's SS / GS reverse the
// scan on top of that. The image is what a viewer sees holding the module turned for
// config.rotation: image() at rotation 90 is config.height x config.width, the glass turned so
// that an image the driver rotated clockwise is upright. Display off, asleep or held in reset:
// black.
//
// Timing (datasheets: SWRESET, SLPIN, SLPOUT, reset timing). Time passes only through
// advance_ns() (EmulatorBus: delay_ms and, optionally, the SPI byte time). Commands sent too
// early are executed anyway and reported as kTiming:
//   * a reset pulse (RESX low) of at least 10 us;
//   * 5 ms after releasing RESX, after SWRESET, SLPOUT or SLPIN before any command;
//   * 120 ms after releasing RESX, after SWRESET or SLPIN before SLPOUT (the datasheets tie the
//     SWRESET case to the sleep mode it came in; the emulator asks for it after every SWRESET,
//     which is safe either way);
//   * 120 ms after SLPOUT before SLPIN or SWRESET ("cannot be sent during the Sleep Out
//     sequence").
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lineraster/hal/panel_config.hpp"
#include "lineraster/host_sim/formats/image_io.hpp"

namespace lr::host {

// What the emulator found wrong (or worth a note) in the stream.
enum class PanelIssue : uint8_t {
  kDataBeforeCommand,    // data bytes with no command to take them (after power-on or a reset)
  kExtraParameters,      // more parameter bytes than the command takes: ignored
  kMissingParameters,    // a command ended before all its parameters: the rest keep old values
  kUnknownCommand,       // not in the controller's command set: treated as NOP, data ignored
  kReadCommand,          // a read command: the bus has no read path
  kWindowStartAfterEnd,  // XS > XE or YS > YE at a memory write: undefined, pixels dropped
  kWindowOutsideRam,     // the window reaches past the RAM: those pixels dropped
  kWindowOverflow,       // more pixels than the window holds: wrapped (or dropped)
  kPixelFormat,          // a memory write with COLMOD other than 16 bits per pixel
  kIncompletePixel,      // a memory write ended inside a pixel: its bytes dropped
  kWhileInReset,         // bytes while RESX is held low: ignored
  kTiming,               // a command before the datasheet's delay
  kWriteWhileAsleep,     // note: RAM written in sleep mode (allowed; the glass shows nothing)
  kNotModelled,          // note: a valid setting the emulator does not show (vertical scroll)
};
const char* to_string(PanelIssue issue);
// Notes are not errors: kWriteWhileAsleep and kNotModelled.
constexpr bool is_error(PanelIssue issue) {
  return issue != PanelIssue::kWriteWhileAsleep && issue != PanelIssue::kNotModelled;
}

struct PanelDiagnostic {
  PanelIssue issue{};
  uint8_t command = 0;   // the command concerned (the one in progress), 0 when none
  uint64_t time_ns = 0;  // emulated time of the first occurrence
  uint64_t count = 1;    // bytes or pixels concerned (one entry per command instance)
  std::string text;      // one line
};

// Controller registers and modes.
struct PanelState {
  bool in_reset = false;  // RESX held low
  bool sleeping = true;
  bool display_on = false;
  bool inverted = false;  // INVON
  bool idle = false;      // IDMON
  bool partial = false;   // PTLON (NORON clears it)
  uint8_t madctl = 0;
  uint8_t colmod = 0x66;
  uint16_t xs = 0, xe = 239, ys = 0, ye = 319;  // address window
  uint16_t partial_start = 0, partial_end = 319;
  uint16_t scroll_start = 0;     // VSCSAD (not shown)
  bool little_endian = false;    // ST7789 RAMCTRL ENDIAN
  bool source_reversed = false;  // ILI9341 DISCTRL SS
  bool gate_reversed = false;    // ILI9341 DISCTRL GS
};

// MADCTL bits.
inline constexpr uint8_t kMadctlMY = 0x80, kMadctlMX = 0x40, kMadctlMV = 0x20, kMadctlML = 0x10,
                         kMadctlBGR = 0x08, kMadctlMH = 0x04;

class PanelEmulator {
 public:
  static constexpr int kRamColumns = 240, kRamRows = 320;

  struct Options {
    uint32_t seed = 0x5eed1234;  // power-on RAM noise
    bool wrap_past_window_end = true;
    // RAM column 0 at the right edge of the glass (see above). Unset: true for the ILI9341.
    std::optional<bool> mirrored_glass;
  };

  struct Counters {
    uint64_t commands = 0;         // command bytes taken (not in reset)
    uint64_t parameter_bytes = 0;  // data bytes of commands other than memory writes
    uint64_t pixel_bytes = 0;      // data bytes of memory writes
    uint64_t pixels_stored = 0;    // pixels that reached the RAM
    uint64_t pixels_dropped = 0;   // pixels of memory writes that did not
    uint64_t cs_releases = 0;      // chip-select frames ended
    uint64_t resets = 0;           // RESX pulses
    std::array<uint32_t, 256> per_command{};
  };

  explicit PanelEmulator(const PanelConfig& module) : PanelEmulator(module, Options{}) {}
  PanelEmulator(const PanelConfig& module, const Options& options);

  // The wires. dc false: every byte is a command; true: parameter or pixel data.
  void feed(bool dc, std::span<const uint8_t> bytes);
  void command(uint8_t cmd) { feed(false, std::span<const uint8_t>(&cmd, 1)); }
  void data(std::span<const uint8_t> bytes) { feed(true, bytes); }
  void cs_release();
  // RESX: asserted = held low. Releasing it performs the hardware reset.
  void set_reset(bool asserted);
  void advance_ns(uint64_t ns) { now_ns_ += ns; }
  void advance_ms(uint32_t ms) { now_ns_ += uint64_t{ms} * 1000000u; }
  uint64_t now_ns() const { return now_ns_; }

  // What the module shows, for the module's rotation or a given one.
  ImageRgb8 image() const { return image(module_.rotation); }
  ImageRgb8 image(Rotation viewer) const;
  // One RAM cell (RGB565 value), column 0..239, row 0..319.
  uint16_t ram(int column, int row) const {
    return ram_[static_cast<size_t>(row) * kRamColumns + static_cast<size_t>(column)];
  }
  void fill_ram(uint16_t value) { ram_.assign(ram_.size(), value); }

  const PanelConfig& module() const { return module_; }
  const PanelState& state() const { return state_; }
  const Counters& counters() const { return counters_; }
  const std::vector<PanelDiagnostic>& diagnostics() const { return diagnostics_; }
  size_t count(PanelIssue issue) const;
  size_t errors() const;  // diagnostics that are not notes
  void clear_diagnostics() { diagnostics_.clear(); }
  // Every diagnostic, one per line ("" when none).
  std::string report() const;
  // The command's datasheet name ("CASET"), or "0xNN" when the controller has none.
  std::string command_name(uint8_t cmd) const;

 private:
  struct CommandInfo {
    uint8_t code;
    const char* name;
    int16_t params;  // bytes it takes; -1: any (memory writes); -2: a read command
    bool required;   // all parameters needed (window, format and mode registers)
  };
  const CommandInfo* find(uint8_t cmd) const;
  void begin_command(uint8_t cmd);
  void end_command();
  void data_byte(uint8_t b);
  void apply_parameter(uint8_t cmd, size_t index, uint8_t b);
  void begin_memory_write(bool restart);
  void pixel_byte(uint8_t b);
  void store_pixel(uint16_t rgb565);
  void check_timing(uint8_t cmd);
  void reset_registers(bool hardware);
  // A diagnostic for the command in progress: adds `count` to an open entry of the same issue
  // or opens one with `text`.
  void report_issue(PanelIssue issue, uint64_t count, const std::string& text);
  std::string ms(uint64_t ns) const;

  PanelConfig module_;
  Options options_;
  std::vector<uint16_t> ram_;
  PanelState state_;
  Counters counters_;
  std::vector<PanelDiagnostic> diagnostics_;
  size_t first_open_diagnostic_ = 0;  // entries before it belong to finished commands
  uint64_t now_ns_ = 0;

  // The command in progress.
  int current_ = -1;  // -1: none
  const CommandInfo* info_ = nullptr;
  size_t params_seen_ = 0;
  // Memory write state.
  uint16_t x_ = 0, y_ = 0;
  uint64_t written_ = 0;  // pixels of this write since RAMWR (window overflow)
  bool blocked_ = false;  // window start after end: pixels dropped
  std::array<uint8_t, 3> pix_{};
  size_t pix_n_ = 0;

  // Timing: earliest times, and what set them.
  uint64_t any_at_ = 0, slpout_at_ = 0, slpin_at_ = 0, swreset_at_ = 0;
  const char* any_cause_ = "";
  const char* slpout_cause_ = "";
  uint64_t any_since_ = 0, slpout_since_ = 0, slpout_done_ = 0;
  uint64_t reset_asserted_at_ = 0;
};

}  // namespace lr::host
