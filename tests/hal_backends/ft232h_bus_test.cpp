// Ft232hBus and UsbBulk without hardware: the "ft232h[:serial]" spec and opening a device that
// is not plugged in (ffff:ffff), which must fail with the one line that says so.
#include "lineraster/hal/host/usb/ft232h_bus.hpp"

#include <gtest/gtest.h>

#include <string>

#include "lineraster/hal/host/usb/usb_bulk.hpp"

namespace lr {
namespace {

constexpr const char* kForm =
    "expected ft232h[:SERIAL][,hz=N][,cs=PIN][,dc=PIN][,rst=PIN|none][,bl=PIN|none], PIN being "
    "D3-D7 or C0-C7";

TEST(Ft232hSpec, Defaults) {
  Ft232hConfig c;
  std::string err;
  ASSERT_TRUE(parse_ft232h_spec("ft232h", c, err)) << err;
  EXPECT_EQ(c.vid, 0x0403);
  EXPECT_EQ(c.pid, 0x6014);
  EXPECT_EQ(c.serial, "");
  EXPECT_EQ(c.hz, 30'000'000u);
  EXPECT_EQ(c.pins.cs, (mpsse::Pin{3, false}));
  EXPECT_EQ(c.pins.dc, (mpsse::Pin{0, true}));
  EXPECT_EQ(c.pins.reset, (mpsse::Pin{1, true}));
  EXPECT_FALSE(c.pins.backlight);
}

TEST(Ft232hSpec, SerialAndOptions) {
  Ft232hConfig c;
  c.usb_timeout_ms = 77;  // not part of the spec: kept
  std::string err;
  ASSERT_TRUE(parse_ft232h_spec("ft232h:FT6ZQ1B2,hz=10000000,dc=D4,rst=none,bl=C2", c, err)) << err;
  EXPECT_EQ(c.serial, "FT6ZQ1B2");
  EXPECT_EQ(c.hz, 10'000'000u);
  EXPECT_EQ(c.pins.dc, (mpsse::Pin{4, false}));
  EXPECT_FALSE(c.pins.reset);
  EXPECT_EQ(c.pins.backlight, (mpsse::Pin{2, true}));
  EXPECT_EQ(c.usb_timeout_ms, 77u);
}

TEST(Ft232hSpec, BadSpecsSayWhatIsWrong) {
  const struct {
    std::string spec;
    std::string error;
  } cases[] = {
      {"", std::string("empty FT232H spec (") + kForm + ")"},
      {"ft2232h", std::string("ft2232h: not an FT232H spec (") + kForm + ")"},
      {"ft232hx", std::string("ft232hx: not an FT232H spec (") + kForm + ")"},
      {"ft232h:", std::string("empty serial number after ft232h: (") + kForm + ")"},
      {"ft232h,hz=0", "hz=0: the SPI clock in hertz, a whole number above 0 (e.g. hz=30000000)"},
      {"ft232h,dc=D1", "dc=D1: D0-D2 are SCK, MOSI and MISO (use D3-D7 or C0-C7)"},
      {"ft232h,dc=D9", "dc=D9: not an FT232H GPIO pin (D3-D7 or C0-C7)"},
      {"ft232h,dc=none", "dc=none: not an FT232H GPIO pin (D3-D7 or C0-C7)"},
      {"ft232h,cs=C0", "cs and dc are both on C0"},
      {"ft232h,bl=C1", "rst and bl are both on C1"},
      {"ft232h,bl=C2,bl=C3", "bl= given twice"},
      {"ft232h,mode=0", "mode=0: unknown option (hz=, cs=, dc=, rst=, bl=)"},
      {"ft232h,fast", std::string("fast: not key=value (") + kForm + ")"},
  };
  for (const auto& t : cases) {
    Ft232hConfig c;
    c.serial = "untouched";
    std::string err;
    EXPECT_FALSE(parse_ft232h_spec(t.spec, c, err)) << t.spec;
    EXPECT_EQ(err, t.error) << t.spec;
    EXPECT_EQ(c.serial, "untouched") << t.spec;
  }
}

TEST(Ft232hOpen, NoDeviceSaysPlugItIn) {
  Ft232hConfig c;
  c.vid = 0xffff;
  c.pid = 0xffff;
  std::string err;
  EXPECT_EQ(Ft232hBus::open(c, err), nullptr);
  EXPECT_EQ(err, "no USB device ffff:ffff (is the FT232H plugged in?)");
  c.serial = "FT000000";
  EXPECT_EQ(Ft232hBus::open(c, err), nullptr);
  EXPECT_EQ(err, "no USB device ffff:ffff (is the FT232H plugged in?)");
}

TEST(Ft232hOpen, BadPinsAreRefusedBeforeAnyUsb) {
  Ft232hConfig c;
  c.pins.dc = mpsse::Pin{2, false};
  std::string err;
  EXPECT_EQ(Ft232hBus::open(c, err), nullptr);
  EXPECT_EQ(err, "dc=D2: D0-D2 are SCK, MOSI and MISO (use D3-D7 or C0-C7)");
}

TEST(UsbBulkOpen, NoDeviceNamesWhatToPlugIn) {
  UsbBulkConfig c;
  c.vid = 0xffff;
  c.pid = 0xffff;
  c.what = "the USB gadget";
  std::string err;
  EXPECT_EQ(UsbBulk::open(c, err), nullptr);
  EXPECT_EQ(err, "no USB device ffff:ffff (is the USB gadget plugged in?)");
  EXPECT_EQ(usb_id(0x0403, 0x6014), "0403:6014");
}

}  // namespace
}  // namespace lr
