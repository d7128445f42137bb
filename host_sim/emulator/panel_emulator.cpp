#include "lineraster/host_sim/emulator/panel_emulator.hpp"

#include <cstdio>
#include <utility>

#include "lineraster/core/output/pixel_format.hpp"

namespace lr::host {
namespace {

constexpr int16_t kAny = -1;   // memory writes: any number of data bytes
constexpr int16_t kRead = -2;  // read commands

constexpr uint8_t kSwreset = 0x01, kSlpin = 0x10, kSlpout = 0x11, kPtlon = 0x12, kNoron = 0x13,
                  kInvoff = 0x20, kInvon = 0x21, kDispoff = 0x28, kDispon = 0x29, kCaset = 0x2A,
                  kRaset = 0x2B, kRamwr = 0x2C, kPtlar = 0x30, kMadctl = 0x36, kVscsad = 0x37,
                  kIdmoff = 0x38, kIdmon = 0x39, kColmod = 0x3A, kRamwrc = 0x3C;

constexpr uint64_t kMs = 1000000;  // ns

std::string hex2(unsigned v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", v & 0xFFu);
  return buf;
}

uint8_t expand4to5(unsigned v) {
  return static_cast<uint8_t>((v << 1) | (v >> 3));
}
uint8_t expand4to6(unsigned v) {
  return static_cast<uint8_t>((v << 2) | (v >> 2));
}
uint16_t pack565(unsigned r5, unsigned g6, unsigned b5) {
  return static_cast<uint16_t>((r5 << 11) | (g6 << 5) | b5);
}

}  // namespace

const char* to_string(PanelIssue issue) {
  switch (issue) {
    case PanelIssue::kDataBeforeCommand:
      return "data before command";
    case PanelIssue::kExtraParameters:
      return "extra parameters";
    case PanelIssue::kMissingParameters:
      return "missing parameters";
    case PanelIssue::kUnknownCommand:
      return "unknown command";
    case PanelIssue::kReadCommand:
      return "read command";
    case PanelIssue::kWindowStartAfterEnd:
      return "window start after end";
    case PanelIssue::kWindowOutsideRam:
      return "window outside RAM";
    case PanelIssue::kWindowOverflow:
      return "window overflow";
    case PanelIssue::kPixelFormat:
      return "pixel format";
    case PanelIssue::kIncompletePixel:
      return "incomplete pixel";
    case PanelIssue::kWhileInReset:
      return "while in reset";
    case PanelIssue::kTiming:
      return "timing";
    case PanelIssue::kWriteWhileAsleep:
      return "write while asleep";
    case PanelIssue::kNotModelled:
      return "not modelled";
  }
  return "?";
}

PanelEmulator::PanelEmulator(const PanelConfig& module, const Options& options)
    : module_(module), options_(options), ram_(size_t{kRamColumns} * kRamRows) {
  // Power-on: the RAM holds whatever the cells settled to (xorshift noise here), registers are
  // at their hardware-reset values, no timing constraint is pending.
  uint32_t s = options_.seed ? options_.seed : 1u;
  for (uint16_t& cell : ram_) {
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    cell = static_cast<uint16_t>(s >> 8);
  }
  reset_registers(true);
}

// The command sets (datasheet names; parameter bytes written; read commands take none).
const PanelEmulator::CommandInfo* PanelEmulator::find(uint8_t cmd) const {
  static constexpr CommandInfo kCommon[] = {
      {0x00, "NOP", 0, false},           {0x01, "SWRESET", 0, false},
      {0x04, "RDDID", kRead, false},     {0x09, "RDDST", kRead, false},
      {0x0A, "RDDPM", kRead, false},     {0x0B, "RDDMADCTL", kRead, false},
      {0x0C, "RDDCOLMOD", kRead, false}, {0x0D, "RDDIM", kRead, false},
      {0x0E, "RDDSM", kRead, false},     {0x0F, "RDDSDR", kRead, false},
      {0x10, "SLPIN", 0, false},         {0x11, "SLPOUT", 0, false},
      {0x12, "PTLON", 0, false},         {0x13, "NORON", 0, false},
      {0x20, "INVOFF", 0, false},        {0x21, "INVON", 0, false},
      {0x26, "GAMSET", 1, false},        {0x28, "DISPOFF", 0, false},
      {0x29, "DISPON", 0, false},        {0x2A, "CASET", 4, true},
      {0x2B, "RASET", 4, true},          {0x2C, "RAMWR", kAny, false},
      {0x2E, "RAMRD", kRead, false},     {0x30, "PTLAR", 4, true},
      {0x33, "VSCRDEF", 6, false},       {0x34, "TEOFF", 0, false},
      {0x35, "TEON", 1, false},          {0x36, "MADCTL", 1, true},
      {0x37, "VSCSAD", 2, true},         {0x38, "IDMOFF", 0, false},
      {0x39, "IDMON", 0, false},         {0x3A, "COLMOD", 1, true},
      {0x3C, "RAMWRC", kAny, false},     {0x3E, "RAMRDC", kRead, false},
      {0x44, "STE", 2, false},           {0x45, "GSCAN", kRead, false},
      {0x51, "WRDISBV", 1, false},       {0x52, "RDDISBV", kRead, false},
      {0x53, "WRCTRLD", 1, false},       {0x54, "RDCTRLD", kRead, false},
      {0x55, "WRCACE", 1, false},        {0x56, "RDCABC", kRead, false},
      {0x5E, "WRCABCMB", 1, false},      {0x5F, "RDCABCMB", kRead, false},
      {0xDA, "RDID1", kRead, false},     {0xDB, "RDID2", kRead, false},
      {0xDC, "RDID3", kRead, false},
  };
  // ST7789V system function command table 2 (and RDABCSDR).
  static constexpr CommandInfo kSt7789[] = {
      {0x68, "RDABCSDR", kRead, false}, {0xB0, "RAMCTRL", 2, false},
      {0xB1, "RGBCTRL", 3, false},      {0xB2, "PORCTRL", 5, false},
      {0xB3, "FRCTRL1", 3, false},      {0xB5, "PARCTRL", 1, false},
      {0xB7, "GCTRL", 1, false},        {0xB8, "GTADJ", 4, false},
      {0xBA, "DGMEN", 1, false},        {0xBB, "VCOMS", 1, false},
      {0xC0, "LCMCTRL", 1, false},      {0xC1, "IDSET", 3, false},
      {0xC2, "VDVVRHEN", 2, false},     {0xC3, "VRHS", 1, false},
      {0xC4, "VDVS", 1, false},         {0xC5, "VCMOFSET", 1, false},
      {0xC6, "FRCTRL2", 1, false},      {0xC7, "CABCCTRL", 1, false},
      {0xC8, "REGSEL1", 1, false},      {0xCA, "REGSEL2", 1, false},
      {0xCC, "PWMFRSEL", 1, false},     {0xD0, "PWCTRL1", 2, false},
      {0xD2, "VAPVANEN", 1, false},     {0xDF, "CMD2EN", 4, false},
      {0xE0, "PVGAMCTRL", 14, false},   {0xE1, "NVGAMCTRL", 14, false},
      {0xE2, "DGMLUTR", 64, false},     {0xE3, "DGMLUTB", 64, false},
      {0xE4, "GATECTRL", 3, false},     {0xE7, "SPI2EN", 1, false},
      {0xE8, "PWCTRL2", 1, false},      {0xE9, "EQCTRL", 3, false},
      {0xEC, "PROMCTRL", 1, false},     {0xFA, "PROMEN", 4, false},
      {0xFC, "NVMSET", 2, false},       {0xFE, "PROMACT", 2, false},
  };
  // ILI9341 extended command set (level 2) and RGBSET.
  static constexpr CommandInfo kIli9341[] = {
      {0x2D, "RGBSET", 128, false},  {0xB0, "IFMODE", 1, false},     {0xB1, "FRMCTR1", 2, false},
      {0xB2, "FRMCTR2", 2, false},   {0xB3, "FRMCTR3", 2, false},    {0xB4, "INVTR", 1, false},
      {0xB5, "PRCTR", 4, false},     {0xB6, "DISCTRL", 4, false},    {0xB7, "ETMOD", 1, false},
      {0xB8, "BKLCTR1", 1, false},   {0xB9, "BKLCTR2", 1, false},    {0xBA, "BKLCTR3", 1, false},
      {0xBB, "BKLCTR4", 1, false},   {0xBC, "BKLCTR5", 1, false},    {0xBE, "BKLCTR7", 1, false},
      {0xBF, "BKLCTR8", 1, false},   {0xC0, "PWCTRL1", 1, false},    {0xC1, "PWCTRL2", 1, false},
      {0xC5, "VMCTRL1", 2, false},   {0xC7, "VMCTRL2", 1, false},    {0xCB, "PWCTRLA", 5, false},
      {0xCF, "PWCTRLB", 3, false},   {0xD0, "NVMWR", 2, false},      {0xD1, "NVMPKEY", 3, false},
      {0xD2, "RDNVM", kRead, false}, {0xD3, "RDID4", kRead, false},  {0xE0, "PGAMCTRL", 15, false},
      {0xE1, "NGAMCTRL", 15, false}, {0xE2, "DGAMCTRL1", 16, false}, {0xE3, "DGAMCTRL2", 64, false},
      {0xE8, "DTCTRLA", 3, false},   {0xEA, "DTCTRLB", 2, false},    {0xED, "PWRSEQ", 4, false},
      {0xF2, "EN3GAM", 1, false},    {0xF6, "IFCTRL", 3, false},     {0xF7, "PUMPCTRL", 1, false},
  };
  for (const CommandInfo& c : kCommon)
    if (c.code == cmd) return &c;
  if (module_.controller == Controller::kSt7789) {
    for (const CommandInfo& c : kSt7789)
      if (c.code == cmd) return &c;
  } else {
    for (const CommandInfo& c : kIli9341)
      if (c.code == cmd) return &c;
  }
  return nullptr;
}

std::string PanelEmulator::command_name(uint8_t cmd) const {
  const CommandInfo* c = find(cmd);
  return c ? std::string(c->name) : hex2(cmd);
}

std::string PanelEmulator::ms(uint64_t ns) const {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g ms", static_cast<double>(ns) / 1e6);
  return buf;
}

void PanelEmulator::report_issue(PanelIssue issue, uint64_t count, const std::string& text) {
  const uint8_t cmd = current_ < 0 ? 0 : static_cast<uint8_t>(current_);
  for (size_t i = first_open_diagnostic_; i < diagnostics_.size(); ++i) {
    if (diagnostics_[i].issue == issue) {
      diagnostics_[i].count += count;
      return;
    }
  }
  diagnostics_.push_back({issue, cmd, now_ns_, count, text});
}

size_t PanelEmulator::count(PanelIssue issue) const {
  size_t n = 0;
  for (const PanelDiagnostic& d : diagnostics_) n += d.issue == issue;
  return n;
}

size_t PanelEmulator::errors() const {
  size_t n = 0;
  for (const PanelDiagnostic& d : diagnostics_) n += is_error(d.issue);
  return n;
}

std::string PanelEmulator::report() const {
  std::string out;
  for (const PanelDiagnostic& d : diagnostics_) {
    // Appended piece by piece: GCC 12 at -O3 reports a false -Wrestrict for "[" + std::string.
    out.append(1, '[').append(ms(d.time_ns)).append("] ").append(to_string(d.issue));
    out.append(": ").append(d.text);
    if (d.count != 1) out.append(" (x").append(std::to_string(d.count)).append(")");
    out.append(1, '\n');
  }
  return out;
}

void PanelEmulator::reset_registers(bool hardware) {
  if (hardware) {
    state_.madctl = 0;
    state_.colmod = 0x66;
  }
  const bool mv = state_.madctl & kMadctlMV;
  state_.sleeping = true;
  state_.display_on = false;
  state_.inverted = false;
  state_.idle = false;
  state_.partial = false;
  state_.xs = 0;
  state_.xe = mv ? kRamRows - 1 : kRamColumns - 1;
  state_.ys = 0;
  state_.ye = mv ? kRamColumns - 1 : kRamRows - 1;
  state_.partial_start = 0;
  state_.partial_end = kRamRows - 1;
  state_.scroll_start = 0;
  state_.little_endian = false;
  state_.source_reversed = false;
  state_.gate_reversed = false;
  x_ = state_.xs;
  y_ = state_.ys;
  written_ = 0;
  blocked_ = false;
  pix_n_ = 0;
}

void PanelEmulator::set_reset(bool asserted) {
  if (asserted == state_.in_reset) return;
  if (asserted) {
    end_command();
    current_ = -1;
    info_ = nullptr;
    first_open_diagnostic_ = diagnostics_.size();
    state_.in_reset = true;
    reset_asserted_at_ = now_ns_;
    return;
  }
  first_open_diagnostic_ = diagnostics_.size();
  const uint64_t pulse = now_ns_ - reset_asserted_at_;
  if (pulse < 10000)
    report_issue(PanelIssue::kTiming, 1,
                 "reset pulse of " + std::to_string(pulse / 1000) + " us (needs 10 us)");
  state_.in_reset = false;
  reset_registers(true);
  ++counters_.resets;
  any_at_ = now_ns_ + 5 * kMs;
  slpout_at_ = now_ns_ + 120 * kMs;
  slpin_at_ = swreset_at_ = 0;
  any_since_ = slpout_since_ = now_ns_;
  any_cause_ = slpout_cause_ = "the reset";
  first_open_diagnostic_ = diagnostics_.size();
}

void PanelEmulator::cs_release() {
  ++counters_.cs_releases;
}

void PanelEmulator::feed(bool dc, std::span<const uint8_t> bytes) {
  if (bytes.empty()) return;
  if (state_.in_reset) {
    report_issue(PanelIssue::kWhileInReset, bytes.size(), "bytes while RESX is held low: ignored");
    return;
  }
  if (!dc) {
    for (uint8_t b : bytes) begin_command(b);
    return;
  }
  if (info_ && info_->params == kAny) {
    for (uint8_t b : bytes) pixel_byte(b);
    return;
  }
  for (uint8_t b : bytes) data_byte(b);
}

void PanelEmulator::check_timing(uint8_t cmd) {
  const std::string name = command_name(cmd);
  if (now_ns_ < any_at_)
    report_issue(PanelIssue::kTiming, 1,
                 name + " " + ms(now_ns_ - any_since_) + " after " + any_cause_ + " (needs 5 ms)");
  if (cmd == kSlpout && state_.sleeping && now_ns_ < slpout_at_)
    report_issue(
        PanelIssue::kTiming, 1,
        "SLPOUT " + ms(now_ns_ - slpout_since_) + " after " + slpout_cause_ + " (needs 120 ms)");
  if (cmd == kSlpin && !state_.sleeping && now_ns_ < slpin_at_)
    report_issue(PanelIssue::kTiming, 1,
                 "SLPIN " + ms(now_ns_ - slpout_done_) + " after SLPOUT (needs 120 ms)");
  if (cmd == kSwreset && now_ns_ < swreset_at_)
    report_issue(PanelIssue::kTiming, 1,
                 "SWRESET " + ms(now_ns_ - slpout_done_) +
                     " after SLPOUT (needs 120 ms: not during the sleep-out sequence)");
}

void PanelEmulator::begin_command(uint8_t cmd) {
  end_command();
  first_open_diagnostic_ = diagnostics_.size();
  ++counters_.commands;
  ++counters_.per_command[cmd];
  current_ = cmd;
  info_ = find(cmd);
  params_seen_ = 0;
  check_timing(cmd);
  if (!info_) {
    report_issue(PanelIssue::kUnknownCommand, 1,
                 "unknown command " + hex2(cmd) + ": treated as NOP");
    return;
  }
  if (info_->params == kRead)
    report_issue(PanelIssue::kReadCommand, 1,
                 std::string(info_->name) + " (" + hex2(cmd) +
                     ") reads from the panel: a PanelBus cannot read, nothing comes back");
  switch (cmd) {
    case kSwreset:
      reset_registers(false);
      any_at_ = now_ns_ + 5 * kMs;
      slpout_at_ = now_ns_ + 120 * kMs;
      slpin_at_ = swreset_at_ = 0;
      any_since_ = slpout_since_ = now_ns_;
      any_cause_ = slpout_cause_ = "SWRESET";
      break;
    case kSlpin:
      if (!state_.sleeping) {
        state_.sleeping = true;
        any_at_ = now_ns_ + 5 * kMs;
        slpout_at_ = now_ns_ + 120 * kMs;
        any_since_ = slpout_since_ = now_ns_;
        any_cause_ = slpout_cause_ = "SLPIN";
      }
      break;
    case kSlpout:
      if (state_.sleeping) {
        state_.sleeping = false;
        any_at_ = now_ns_ + 5 * kMs;
        slpin_at_ = swreset_at_ = now_ns_ + 120 * kMs;
        any_since_ = slpout_done_ = now_ns_;
        any_cause_ = "SLPOUT";
      }
      break;
    case kPtlon:
      state_.partial = true;
      break;
    case kNoron:
      state_.partial = false;
      break;
    case kInvoff:
      state_.inverted = false;
      break;
    case kInvon:
      state_.inverted = true;
      break;
    case kDispoff:
      state_.display_on = false;
      break;
    case kDispon:
      state_.display_on = true;
      break;
    case kIdmoff:
      state_.idle = false;
      break;
    case kIdmon:
      state_.idle = true;
      break;
    case kRamwr:
      begin_memory_write(true);
      break;
    case kRamwrc:
      begin_memory_write(false);
      break;
    default:
      break;
  }
}

void PanelEmulator::end_command() {
  if (current_ < 0) return;
  if (info_ && info_->required && params_seen_ < static_cast<size_t>(info_->params))
    report_issue(PanelIssue::kMissingParameters,
                 static_cast<uint64_t>(info_->params) - params_seen_,
                 std::string(info_->name) + ": " + std::to_string(params_seen_) + " of " +
                     std::to_string(info_->params) +
                     " parameter bytes before the next command (the rest keep their values)");
  if (info_ && info_->params == kAny && pix_n_ > 0) {
    report_issue(
        PanelIssue::kIncompletePixel, pix_n_,
        std::string(info_->name) + ": the write ended inside a pixel; its bytes are dropped");
    pix_n_ = 0;
  }
  current_ = -1;
  info_ = nullptr;
}

void PanelEmulator::data_byte(uint8_t b) {
  if (current_ < 0) {
    report_issue(PanelIssue::kDataBeforeCommand, 1, "data bytes before any command: ignored");
    return;
  }
  ++counters_.parameter_bytes;
  if (!info_) {
    report_issue(PanelIssue::kExtraParameters, 1,
                 "data of unknown command " + hex2(static_cast<unsigned>(current_)) + ": ignored");
    return;
  }
  const size_t takes = info_ && info_->params > 0 ? static_cast<size_t>(info_->params) : 0;
  if (params_seen_ < takes) {
    apply_parameter(static_cast<uint8_t>(current_), params_seen_, b);
    ++params_seen_;
    return;
  }
  report_issue(PanelIssue::kExtraParameters, 1,
               command_name(static_cast<uint8_t>(current_)) + " takes " + std::to_string(takes) +
                   " parameter bytes: the bytes after them are ignored");
}

void PanelEmulator::apply_parameter(uint8_t cmd, size_t i, uint8_t b) {
  auto set = [&](uint16_t& v, bool high) {
    v = high ? static_cast<uint16_t>((v & 0x00FFu) | (unsigned{b} << 8))
             : static_cast<uint16_t>((v & 0xFF00u) | b);
  };
  switch (cmd) {
    case kCaset:
      set(i < 2 ? state_.xs : state_.xe, i % 2 == 0);
      break;
    case kRaset:
      set(i < 2 ? state_.ys : state_.ye, i % 2 == 0);
      break;
    case kPtlar:
      set(i < 2 ? state_.partial_start : state_.partial_end, i % 2 == 0);
      break;
    case kVscsad:
      set(state_.scroll_start, i == 0);
      if (i == 1 && state_.scroll_start != 0)
        report_issue(PanelIssue::kNotModelled, 1,
                     "VSCSAD " + std::to_string(state_.scroll_start) +
                         ": vertical scrolling is not shown by the emulator");
      break;
    case kMadctl:
      state_.madctl = b;
      break;
    case kColmod:
      state_.colmod = b;
      break;
    case 0xB0:  // ST7789 RAMCTRL: 2nd parameter bit 3 = ENDIAN (little-endian 16-bit pixels)
      if (module_.controller == Controller::kSt7789 && i == 1) state_.little_endian = b & 0x08;
      break;
    case 0xB6:  // ILI9341 DISCTRL: 2nd parameter bit 6 = GS, bit 5 = SS
      if (module_.controller == Controller::kIli9341 && i == 1) {
        state_.gate_reversed = b & 0x40;
        state_.source_reversed = b & 0x20;
      }
      break;
    default:
      break;
  }
}

void PanelEmulator::begin_memory_write(bool restart) {
  const PanelState& s = state_;
  const char* name = restart ? "RAMWR" : "RAMWRC";
  if (restart) {
    x_ = s.xs;
    y_ = s.ys;
    written_ = 0;
  }
  pix_n_ = 0;
  blocked_ = s.xs > s.xe || s.ys > s.ye;
  if (blocked_)
    report_issue(PanelIssue::kWindowStartAfterEnd, 0,
                 std::string(name) + ": window " + std::to_string(s.xs) + ".." +
                     std::to_string(s.xe) + " x " + std::to_string(s.ys) + ".." +
                     std::to_string(s.ye) +
                     " starts after its end (undefined in the datasheets): pixels dropped");
  const bool mv = s.madctl & kMadctlMV;
  const int maxx = mv ? kRamRows - 1 : kRamColumns - 1, maxy = mv ? kRamColumns - 1 : kRamRows - 1;
  if (!blocked_ && (s.xe > maxx || s.ye > maxy))
    report_issue(PanelIssue::kWindowOutsideRam, 0,
                 std::string(name) + ": window " + std::to_string(s.xs) + ".." +
                     std::to_string(s.xe) + " x " + std::to_string(s.ys) + ".." +
                     std::to_string(s.ye) + " reaches past the RAM (0.." + std::to_string(maxx) +
                     " x 0.." + std::to_string(maxy) + " with MV=" + (mv ? "1" : "0") +
                     "): pixels there are ignored");
  switch (s.colmod & 7) {
    case 5:
      break;
    case 6:
      report_issue(PanelIssue::kPixelFormat, 0,
                   std::string(name) + " with COLMOD " + hex2(s.colmod) +
                       ": 18 bits per pixel (3 bytes each), not 16");
      break;
    case 3:
      report_issue(PanelIssue::kPixelFormat, 0,
                   std::string(name) + " with COLMOD " + hex2(s.colmod) +
                       ": 12 bits per pixel (3 bytes per 2 pixels), not 16");
      break;
    case 7:
      report_issue(PanelIssue::kPixelFormat, 0,
                   std::string(name) + " with COLMOD " + hex2(s.colmod) +
                       (module_.controller == Controller::kSt7789
                            ? ": 24 bits per pixel truncated (3 bytes each), not 16"
                            : ": not a defined format: pixel data ignored"));
      break;
    default:
      report_issue(PanelIssue::kPixelFormat, 0,
                   std::string(name) + " with COLMOD " + hex2(s.colmod) +
                       ": not a defined format: pixel data ignored");
      break;
  }
  if (s.sleeping)
    report_issue(PanelIssue::kWriteWhileAsleep, 0,
                 std::string(name) +
                     " in sleep mode: the RAM takes the pixels (interface and memory keep "
                     "working), the glass shows nothing until SLPOUT");
}

void PanelEmulator::pixel_byte(uint8_t b) {
  ++counters_.pixel_bytes;
  const unsigned format = state_.colmod & 7u;
  const bool st7789 = module_.controller == Controller::kSt7789;
  if (format == 5) {
    pix_[pix_n_++] = b;
    if (pix_n_ == 2) {
      pix_n_ = 0;
      store_pixel(state_.little_endian ? static_cast<uint16_t>((unsigned{pix_[1]} << 8) | pix_[0])
                                       : static_cast<uint16_t>((unsigned{pix_[0]} << 8) | pix_[1]));
    }
  } else if (format == 6 || (format == 7 && st7789)) {
    pix_[pix_n_++] = b;
    if (pix_n_ == 3) {
      pix_n_ = 0;
      store_pixel(pack565(pix_[0] >> 3u, pix_[1] >> 2u, pix_[2] >> 3u));
    }
  } else if (format == 3) {
    pix_[pix_n_++] = b;
    if (pix_n_ == 3) {
      pix_n_ = 0;
      const unsigned r1 = pix_[0] >> 4u, g1 = pix_[0] & 15u, b1 = pix_[1] >> 4u;
      const unsigned r2 = pix_[1] & 15u, g2 = pix_[2] >> 4u, b2 = pix_[2] & 15u;
      store_pixel(pack565(expand4to5(r1), expand4to6(g1), expand4to5(b1)));
      store_pixel(pack565(expand4to5(r2), expand4to6(g2), expand4to5(b2)));
    }
  } else {
    report_issue(PanelIssue::kPixelFormat, 1, "");
  }
}

void PanelEmulator::store_pixel(uint16_t rgb565) {
  const PanelState& s = state_;
  const char* name = current_ == kRamwrc ? "RAMWRC" : "RAMWR";
  if (s.sleeping) report_issue(PanelIssue::kWriteWhileAsleep, 1, "");
  if (blocked_) {
    ++counters_.pixels_dropped;
    report_issue(PanelIssue::kWindowStartAfterEnd, 1, "");
    return;
  }
  ++written_;
  const uint64_t area = uint64_t{s.xe - s.xs + 1u} * uint64_t{s.ye - s.ys + 1u};
  if (written_ > area) {
    report_issue(
        PanelIssue::kWindowOverflow, 1,
        std::string(name) + ": more pixels than the window's " + std::to_string(area) +
            (options_.wrap_past_window_end ? ": wrapped to the window start" : ": ignored"));
    if (!options_.wrap_past_window_end) {
      ++counters_.pixels_dropped;
      return;
    }
  }
  const bool mv = s.madctl & kMadctlMV;
  const int maxx = mv ? kRamRows - 1 : kRamColumns - 1, maxy = mv ? kRamColumns - 1 : kRamRows - 1;
  if (x_ > maxx || y_ > maxy) {
    ++counters_.pixels_dropped;
    report_issue(PanelIssue::kWindowOutsideRam, 1,
                 std::string(name) + ": pixels at addresses past the RAM are ignored");
  } else {
    int column = mv ? y_ : x_, row = mv ? x_ : y_;
    if (s.madctl & kMadctlMX) column = kRamColumns - 1 - column;
    if (s.madctl & kMadctlMY) row = kRamRows - 1 - row;
    ram_[static_cast<size_t>(row) * kRamColumns + static_cast<size_t>(column)] = rgb565;
    ++counters_.pixels_stored;
  }
  if (x_ >= s.xe) {
    x_ = s.xs;
    y_ = y_ >= s.ye ? s.ys : static_cast<uint16_t>(y_ + 1);
  } else {
    ++x_;
  }
}

ImageRgb8 PanelEmulator::image(Rotation viewer) const {
  const int w = module_.width, h = module_.height;
  const bool turned = viewer == Rotation::k90 || viewer == Rotation::k270;
  ImageRgb8 img;
  img.width = turned ? h : w;
  img.height = turned ? w : h;
  img.rgb.assign(size_t(img.width) * size_t(img.height) * 3, 0);
  const PanelState& s = state_;
  if (s.in_reset || s.sleeping || !s.display_on) return img;
  const bool swap_rb = bool(s.madctl & kMadctlBGR) != module_.bgr;
  const bool invert = s.inverted != module_.invert;
  const bool mirrored =
      options_.mirrored_glass.value_or(module_.controller == Controller::kIli9341);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      // Image pixel -> native glass position (u, v) of the visible window.
      int u = x, v = y;
      switch (viewer) {
        case Rotation::k0:
          break;
        case Rotation::k90:
          u = w - 1 - y;
          v = x;
          break;
        case Rotation::k180:
          u = w - 1 - x;
          v = h - 1 - y;
          break;
        case Rotation::k270:
          u = y;
          v = h - 1 - x;
          break;
      }
      // The RAM cell that drives it with the scan directions at their defaults, then SS / GS.
      const int c0 = mirrored ? module_.col_offset + w - 1 - u : module_.col_offset + u;
      const int r0 = module_.row_offset + v;
      if (c0 >= kRamColumns || r0 >= kRamRows) continue;  // a window past the RAM: black
      const int column = s.source_reversed ? kRamColumns - 1 - c0 : c0;
      const int row = s.gate_reversed ? kRamRows - 1 - r0 : r0;
      if (s.partial) {
        const bool inside = s.partial_start <= s.partial_end
                                ? row >= s.partial_start && row <= s.partial_end
                                : row >= s.partial_start || row <= s.partial_end;
        if (!inside) continue;
      }
      Rgb8 c = Rgb565Be::decode(Rgb565Be::from_value(ram(column, row)));
      if (swap_rb) std::swap(c.r, c.b);
      if (s.idle) {
        c.r = c.r & 0x80 ? 255 : 0;
        c.g = c.g & 0x80 ? 255 : 0;
        c.b = c.b & 0x80 ? 255 : 0;
      }
      if (invert) {
        c.r = static_cast<uint8_t>(255 - c.r);
        c.g = static_cast<uint8_t>(255 - c.g);
        c.b = static_cast<uint8_t>(255 - c.b);
      }
      uint8_t* p = &img.rgb[(size_t(y) * size_t(img.width) + size_t(x)) * 3];
      p[0] = c.r;
      p[1] = c.g;
      p[2] = c.b;
    }
  }
  return img;
}

}  // namespace lr::host
