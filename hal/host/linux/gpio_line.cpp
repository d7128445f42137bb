#include "lineraster/hal/host/linux/gpio_line.hpp"

#include <dirent.h>
#include <gpiod.h>

#include <algorithm>
#include <cerrno>
#include <string>
#include <system_error>
#include <vector>

namespace lr {
namespace {

bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string errno_text(int e) {
  return std::generic_category().message(e);
}

// How a chip is named in messages: "gpiochip3" for "3", as given otherwise.
std::string chip_display(const std::string& chip) {
  return all_digits(chip) ? "gpiochip" + chip : chip;
}

std::string chip_open_error(const std::string& shown, int e) {
  if (e == ENOENT || e == ENODEV) return shown + ": no such GPIO chip (gpiodetect lists the chips)";
  if (e == EACCES || e == EPERM) {
    return shown + ": permission denied (add the user to the gpio group or run as root)";
  }
  return shown + ": cannot open (" + errno_text(e) + ")";
}

gpiod_chip* open_chip(const std::string& chip) {
  errno = 0;
  if (all_digits(chip)) {
    return gpiod_chip_open_by_number(static_cast<unsigned>(std::stoul(chip)));
  }
  if (chip.front() == '/') return gpiod_chip_open(chip.c_str());
  if (chip.rfind("gpiochip", 0) == 0) return gpiod_chip_open_by_name(chip.c_str());
  return gpiod_chip_open_lookup(chip.c_str());  // a chip label ("pinctrl-bcm2835")
}

// /dev/gpiochipN in the order of N.
std::vector<std::string> list_chips() {
  std::vector<std::pair<unsigned long, std::string>> found;
  if (DIR* d = opendir("/dev")) {
    while (const dirent* e = readdir(d)) {
      const std::string_view n = e->d_name;
      if (n.rfind("gpiochip", 0) == 0 && all_digits(n.substr(8))) {
        found.emplace_back(std::stoul(std::string(n.substr(8))), std::string(n));
      }
    }
    closedir(d);
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> names;
  for (auto& f : found) names.push_back(std::move(f.second));
  return names;
}

}  // namespace

bool parse_gpio_line_spec(std::string_view spec, GpioLineSpec& out, std::string& error) {
  constexpr const char* kForm = "expected CHIP:OFFSET such as gpiochip0:24, or a line name";
  if (spec.empty()) {
    error = std::string("empty GPIO line (") + kForm + ")";
    return false;
  }
  if (all_digits(spec)) {
    error = std::string("which chip? (") + kForm + ")";
    return false;
  }
  const size_t colon = spec.rfind(':');
  if (colon == std::string_view::npos) {
    if (spec.find_first_of(",= ") != std::string_view::npos) {
      error = std::string("not a GPIO line name (") + kForm + ")";
      return false;
    }
    out = GpioLineSpec{{}, 0, std::string(spec)};
    return true;
  }
  const std::string_view chip = spec.substr(0, colon);
  const std::string_view offset = spec.substr(colon + 1);
  if (chip.empty()) {
    error = std::string("chip missing (") + kForm + ")";
    return false;
  }
  if (!all_digits(offset)) {
    error = std::string("the line offset must be a number (") + kForm + ")";
    return false;
  }
  if (offset.size() > 5 || std::stoul(std::string(offset)) > 65535) {
    error = "line offset out of range (0-65535)";
    return false;
  }
  out = GpioLineSpec{std::string(chip), static_cast<unsigned>(std::stoul(std::string(offset))), {}};
  return true;
}

std::unique_ptr<GpioLine> GpioLine::open(std::string_view spec, const char* consumer, bool initial,
                                         std::string& error) {
  try {
    GpioLineSpec parsed;
    if (!parse_gpio_line_spec(spec, parsed, error)) {
      error = std::string(spec) + ": " + error;
      return nullptr;
    }

    gpiod_chip* chip = nullptr;
    gpiod_line* line = nullptr;
    std::string shown;  // chip name for messages
    std::string description;
    if (!parsed.chip.empty()) {
      shown = chip_display(parsed.chip);
      chip = open_chip(parsed.chip);
      if (!chip) {
        error = chip_open_error(shown, errno);
        return nullptr;
      }
      description = shown + " line " + std::to_string(parsed.offset);
      if (parsed.offset >= gpiod_chip_num_lines(chip)) {
        error = description + ": no such line (" + shown + " has " +
                std::to_string(gpiod_chip_num_lines(chip)) + " lines)";
        gpiod_chip_close(chip);
        return nullptr;
      }
      line = gpiod_chip_get_line(chip, parsed.offset);
      if (!line) {
        error = description + ": cannot get the line (" + errno_text(errno) + ")";
        gpiod_chip_close(chip);
        return nullptr;
      }
    } else {
      // By name: the first chip in /dev that has a line of that name.
      const std::vector<std::string> chips = list_chips();
      std::string denied;
      for (const std::string& c : chips) {
        gpiod_chip* candidate = gpiod_chip_open(("/dev/" + c).c_str());
        if (!candidate) {
          if ((errno == EACCES || errno == EPERM) && denied.empty()) denied = c;
          continue;
        }
        if (gpiod_line* l = gpiod_chip_find_line(candidate, parsed.name.c_str())) {
          chip = candidate;
          line = l;
          shown = c;
          break;
        }
        gpiod_chip_close(candidate);
      }
      if (!line) {
        if (!denied.empty()) {
          error = chip_open_error(denied, EACCES);
        } else if (chips.empty()) {
          error = parsed.name + ": no GPIO line of that name (no /dev/gpiochip*: no GPIO chip)";
        } else {
          error = parsed.name + ": no GPIO line of that name (gpioinfo lists the line names)";
        }
        return nullptr;
      }
      description =
          shown + " line " + std::to_string(gpiod_line_offset(line)) + " (" + parsed.name + ")";
    }

    if (gpiod_line_request_output(line, consumer, initial ? 1 : 0) != 0) {
      const int e = errno;
      if (e == EBUSY) {
        gpiod_line_update(line);
        const char* user = gpiod_line_consumer(line);
        error = description + ": busy (used by " +
                (user && *user ? std::string(user)
                               : "another program or a driver; gpioinfo " + shown + " shows it") +
                ")";
      } else if (e == EACCES || e == EPERM) {
        error = chip_open_error(shown, e);
      } else {
        error = description + ": cannot drive as an output (" + errno_text(e) + ")";
      }
      gpiod_chip_close(chip);
      return nullptr;
    }
    std::unique_ptr<GpioLine> result(new (std::nothrow)
                                         GpioLine(chip, line, initial, std::move(description)));
    if (!result) {
      gpiod_chip_close(chip);
      error = "out of memory";
    }
    return result;
  } catch (const std::exception& e) {
    error = std::string("GPIO line ") + std::string(spec) + ": " + e.what();
    return nullptr;
  }
}

GpioLine::~GpioLine() {
  gpiod_line_release(line_);
  gpiod_chip_close(chip_);
}

bool GpioLine::set(bool high) {
  if (gpiod_line_set_value(line_, high ? 1 : 0) != 0) return false;
  value_ = high;
  return true;
}

}  // namespace lr
