// One GPIO line driven as an output through the GPIO character device (/dev/gpiochipN) with
// libgpiod 1.6's C API (Debian 12: libgpiod-dev). SpidevBus uses three of them (D/C, reset,
// backlight); a test program can use one on its own.
//
// A line is named as CHIP:OFFSET, CHIP being gpiochipN, N, /dev/gpiochipN or a chip label
// ("gpiochip0:24", "0:24", "pinctrl-bcm2835:24"), or by its line name ("GPIO24"), looked up on
// every chip in /dev.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>

struct gpiod_chip;
struct gpiod_line;

namespace lr {

// A line spec taken apart (syntax only, nothing opened).
struct GpioLineSpec {
  std::string chip;  // empty when the line is given by name
  unsigned offset = 0;
  std::string name;  // set when the line is given by name
};

// Splits "CHIP:OFFSET" or "NAME". False and a one-line error (without the spec: the caller
// names it) for an empty spec, a bare number ("24": which chip?), an offset that is not a
// number or above 65535.
bool parse_gpio_line_spec(std::string_view spec, GpioLineSpec& out, std::string& error);

class GpioLine {
 public:
  // Requests the line as an output for `consumer` (shown by gpioinfo) driven to `initial`.
  // nullptr and one line naming the problem and its fix, e.g.
  //   "gpiochip99: no such GPIO chip (gpiodetect lists the chips)"
  //   "gpiochip0: permission denied (add the user to the gpio group or run as root)"
  //   "gpiochip0 line 99: no such line (gpiochip0 has 54 lines)"
  //   "gpiochip0 line 24: busy (used by spi0 CS0)"
  //   "LCD_DC: no GPIO line of that name (gpioinfo lists the line names)"
  static std::unique_ptr<GpioLine> open(std::string_view spec, const char* consumer, bool initial,
                                        std::string& error);
  ~GpioLine();
  GpioLine(const GpioLine&) = delete;
  GpioLine& operator=(const GpioLine&) = delete;

  // Drives the line; false when the kernel refused (errno kept).
  bool set(bool high);
  // The value last driven.
  bool value() const { return value_; }
  // "gpiochip0 line 24" (with " (NAME)" when found by name).
  const std::string& description() const { return description_; }

 private:
  GpioLine(gpiod_chip* chip, gpiod_line* line, bool value, std::string description)
      : chip_(chip), line_(line), value_(value), description_(std::move(description)) {}
  gpiod_chip* chip_;
  gpiod_line* line_;
  bool value_;
  std::string description_;
};

}  // namespace lr
