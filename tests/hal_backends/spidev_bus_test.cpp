// SpidevBus without hardware: the spec parser (good and bad specs, exact one-line errors) and
// opening what is not there (/dev/spidev9.9, gpiochip99), which must fail with the one line
// that says what is missing and how to fix it.
#include "lineraster/hal/host/linux/spidev_bus.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace lr {
namespace {

constexpr const char* kForm =
    "expected /dev/spidevB.C,dc=LINE[,rst=LINE][,bl=LINE][,hz=N][,mode=0-3], LINE being "
    "CHIP:OFFSET such as gpiochip0:24 or a line name";
constexpr const char* kLineForm = "expected CHIP:OFFSET such as gpiochip0:24, or a line name";

TEST(SpidevSpec, FullSpec) {
  SpidevConfig c;
  std::string err;
  ASSERT_TRUE(parse_spidev_spec(
      "/dev/spidev0.0,dc=gpiochip0:24,rst=gpiochip0:25,bl=gpiochip0:18,hz=40000000,mode=3", c, err))
      << err;
  EXPECT_EQ(c.device, "/dev/spidev0.0");
  EXPECT_EQ(c.dc, "gpiochip0:24");
  EXPECT_EQ(c.reset, "gpiochip0:25");
  EXPECT_EQ(c.backlight, "gpiochip0:18");
  EXPECT_EQ(c.hz, 40'000'000u);
  EXPECT_EQ(c.mode, 3);
}

TEST(SpidevSpec, DefaultsAndLineNames) {
  SpidevConfig c;
  c.chunk_bytes = 1024;  // not part of the spec: kept
  std::string err;
  ASSERT_TRUE(parse_spidev_spec("/dev/spidev1.2,bl=LCD_BL,dc=GPIO24", c, err)) << err;
  EXPECT_EQ(c.device, "/dev/spidev1.2");
  EXPECT_EQ(c.dc, "GPIO24");
  EXPECT_EQ(c.reset, "");
  EXPECT_EQ(c.backlight, "LCD_BL");
  EXPECT_EQ(c.hz, 32'000'000u);
  EXPECT_EQ(c.mode, 0);
  EXPECT_EQ(c.chunk_bytes, 1024u);
}

TEST(SpidevSpec, BadSpecsSayWhatIsWrong) {
  const std::string dev = "/dev/spidev0.0,dc=gpiochip0:24";
  const struct {
    std::string spec;
    std::string error;
  } cases[] = {
      {"", std::string("empty SPI device spec (") + kForm + ")"},
      {"dc=gpiochip0:24",
       std::string("dc=gpiochip0:24: the SPI device comes first (") + kForm + ")"},
      {"/dev/spidev0.0",
       "/dev/spidev0.0: dc= missing (the panel's D/C line, e.g. dc=gpiochip0:24)"},
      {"/dev/spidev0.0,rst=gpiochip0:25",
       "/dev/spidev0.0: dc= missing (the panel's D/C line, e.g. dc=gpiochip0:24)"},
      {dev + ",mode=4", "mode=4: the SPI mode is 0, 1, 2 or 3"},
      {dev + ",mode=", "mode=: the SPI mode is 0, 1, 2 or 3"},
      {dev + ",hz=fast",
       "hz=fast: the SPI clock in hertz, a whole number above 0 (e.g. hz=32000000)"},
      {dev + ",hz=0", "hz=0: the SPI clock in hertz, a whole number above 0 (e.g. hz=32000000)"},
      {dev + ",hz=99999999999",
       "hz=99999999999: the SPI clock in hertz, a whole number above 0 (e.g. hz=32000000)"},
      {"/dev/spidev0.0,dc=24", std::string("dc=24: which chip? (") + kLineForm + ")"},
      {"/dev/spidev0.0,dc=", std::string("dc=: empty GPIO line (") + kLineForm + ")"},
      {"/dev/spidev0.0,dc=gpiochip0:x",
       std::string("dc=gpiochip0:x: the line offset must be a number (") + kLineForm + ")"},
      {"/dev/spidev0.0,dc=:4", std::string("dc=:4: chip missing (") + kLineForm + ")"},
      {"/dev/spidev0.0,dc=gpiochip0:70000",
       "dc=gpiochip0:70000: line offset out of range (0-65535)"},
      {dev + ",rst=gpiochip0:24", "dc and rst name the same line gpiochip0:24"},
      {dev + ",rst=gpiochip0:25,bl=gpiochip0:25", "rst and bl name the same line gpiochip0:25"},
      {dev + ",dc=gpiochip0:1", "dc= given twice"},
      {dev + ",speed=1", "speed=1: unknown option (dc=, rst=, bl=, hz=, mode=)"},
      {dev + ",fast", std::string("fast: not key=value (") + kForm + ")"},
      {dev + ",", std::string(": not key=value (") + kForm + ")"},
  };
  for (const auto& t : cases) {
    SpidevConfig c;
    c.device = "untouched";
    std::string err;
    EXPECT_FALSE(parse_spidev_spec(t.spec, c, err)) << t.spec;
    EXPECT_EQ(err, t.error) << t.spec;
    EXPECT_EQ(c.device, "untouched") << t.spec;
  }
}

TEST(SpidevOpen, MissingDeviceSaysHowToEnableSpi) {
  SpidevConfig c;
  c.device = "/dev/spidev9.9";
  c.dc = "gpiochip0:24";
  std::string err;
  EXPECT_EQ(SpidevBus::open(c, err), nullptr);
  EXPECT_EQ(err,
            "/dev/spidev9.9: no such device (enable SPI: dtparam=spi=on on a Raspberry Pi, or "
            "load spidev)");
}

TEST(SpidevOpen, ADeviceThatIsNotSpidev) {
  SpidevConfig c;
  c.device = "/dev/null";
  c.dc = "gpiochip0:24";
  std::string err;
  EXPECT_EQ(SpidevBus::open(c, err), nullptr);
  EXPECT_EQ(err, "/dev/null: not an SPI device (spidev refused SPI_IOC_WR_MODE)");
}

TEST(SpidevOpen, ConfigChecksComeFirst) {
  SpidevConfig c;
  std::string err;
  EXPECT_EQ(SpidevBus::open(c, err), nullptr);
  EXPECT_EQ(err, "no SPI device given (e.g. /dev/spidev0.0)");
  c.device = "/dev/spidev9.9";
  EXPECT_EQ(SpidevBus::open(c, err), nullptr);
  EXPECT_EQ(err, "/dev/spidev9.9: no D/C line given (the panel's D/C pin, e.g. dc=gpiochip0:24)");
  c.dc = "gpiochip0:24";
  c.mode = 4;
  EXPECT_EQ(SpidevBus::open(c, err), nullptr);
  EXPECT_EQ(err, "/dev/spidev9.9: SPI mode 4 (the mode is 0, 1, 2 or 3)");
}

TEST(GpioLineOpen, MissingChip) {
  std::string err;
  EXPECT_EQ(GpioLine::open("gpiochip99:24", "lineraster-test", true, err), nullptr);
  EXPECT_EQ(err, "gpiochip99: no such GPIO chip (gpiodetect lists the chips)");
  EXPECT_EQ(GpioLine::open("99:24", "lineraster-test", true, err), nullptr);
  EXPECT_EQ(err, "gpiochip99: no such GPIO chip (gpiodetect lists the chips)");
  EXPECT_EQ(GpioLine::open("/dev/gpiochip99:24", "lineraster-test", true, err), nullptr);
  EXPECT_EQ(err, "/dev/gpiochip99: no such GPIO chip (gpiodetect lists the chips)");
  EXPECT_EQ(GpioLine::open("24", "lineraster-test", true, err), nullptr);
  EXPECT_EQ(err, std::string("24: which chip? (") + kLineForm + ")");
}

TEST(GpioLineOpen, UnknownLineName) {
  std::string err;
  EXPECT_EQ(GpioLine::open("LINERASTER_NO_SUCH_LINE", "lineraster-test", true, err), nullptr);
  std::error_code ec;
  if (std::filesystem::exists("/dev/gpiochip0", ec)) {
    EXPECT_EQ(err,
              "LINERASTER_NO_SUCH_LINE: no GPIO line of that name (gpioinfo lists the line "
              "names)");
  } else {
    EXPECT_EQ(err,
              "LINERASTER_NO_SUCH_LINE: no GPIO line of that name (no /dev/gpiochip*: no "
              "GPIO chip)");
  }
}

}  // namespace
}  // namespace lr
