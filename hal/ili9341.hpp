// Ilitek ILI9341: 240 x 320 RGB graphics RAM, MIPI DCS plus extended command set, 4-line SPI.
//
// Timings (ILI9341 datasheet): after SWRESET 5 ms before the next command and 120 ms before
// SLPOUT; after SLPOUT 5 ms before the next command and 120 ms before SLPIN. The driver waits
// 120 ms after each.
//
// Unlike the ST7789 the ILI9341 starts with power settings that do not suit the common glass, so
// the setup table programs the power sequence, VCOM, frame rate, display function and the gamma
// curves (sent after the software reset, before SLPOUT). The values are the ones the ILI9341's
// reference initialisation uses (and with it the Linux kernel's ili9341 driver for the 2.4"/2.8"
// Adafruit modules and TFT_eSPI); each entry names its register.
//
// Glass: ILI9341 modules show RAM column c at glass column 239 - c (their source outputs run
// right to left), so every driver for them sets MX for the upright image: the kernel's ili9341
// (yx240qv29) and mi0283qt drivers, Adafruit_ILI9341 and TFT_eSPI all use MX at rotation 0, MV at
// 90 (clockwise), MY at 180 and MX|MY|MV at 270. That is the ST7789's table with MX flipped,
// which is what madctl_mirror says.
#pragma once

#include <array>

#include "lineraster/hal/mipi_dbi.hpp"

namespace lr::ili9341 {

// Extended command set (datasheet chapter 8.3).
inline constexpr uint8_t kFrameRateNormal = 0xB1;  // FRMCTR1
inline constexpr uint8_t kDisplayFunction = 0xB6;  // DISCTRL
inline constexpr uint8_t kEntryMode = 0xB7;        // ETMOD
inline constexpr uint8_t kPowerControl1 = 0xC0;    // PWCTRL1
inline constexpr uint8_t kPowerControl2 = 0xC1;    // PWCTRL2
inline constexpr uint8_t kVcomControl1 = 0xC5;     // VMCTRL1
inline constexpr uint8_t kVcomControl2 = 0xC7;     // VMCTRL2
inline constexpr uint8_t kPowerControlA = 0xCB;    // PWCTRLA
inline constexpr uint8_t kPowerControlB = 0xCF;    // PWCTRLB
inline constexpr uint8_t kPositiveGamma = 0xE0;    // PGAMCTRL
inline constexpr uint8_t kNegativeGamma = 0xE1;    // NGAMCTRL
inline constexpr uint8_t kDriverTimingA = 0xE8;    // DTCTRLA
inline constexpr uint8_t kDriverTimingB = 0xEA;    // DTCTRLB
inline constexpr uint8_t kPowerOnSequence = 0xED;  // PWRSEQ
inline constexpr uint8_t kEnable3Gamma = 0xF2;     // 3-gamma function enable
inline constexpr uint8_t kPumpRatio = 0xF7;        // PUMPCTRL

inline constexpr std::array<PanelCommand, 17> kSetup{{
    // Power control B: PCEQ on, discharge path (ESD protection) enabled.
    make_command(kPowerControlB, {0x00, 0xC1, 0x30}),
    // Power-on sequence: soft start, the order of the supplies, DDVDH enhancement.
    make_command(kPowerOnSequence, {0x64, 0x03, 0x12, 0x81}),
    // Driver timing A: gate non-overlap, EQ and pre-charge timing.
    make_command(kDriverTimingA, {0x85, 0x00, 0x78}),
    // Power control A: vcore 1.6 V, DDVDH 5.6 V.
    make_command(kPowerControlA, {0x39, 0x2C, 0x00, 0x34, 0x02}),
    // Pump ratio: DDVDH = 2 x VCI.
    make_command(kPumpRatio, {0x20}),
    // Driver timing B: gate driver timing 0 units.
    make_command(kDriverTimingB, {0x00, 0x00}),
    // Power control 1: GVDD 4.60 V.
    make_command(kPowerControl1, {0x23}),
    // Power control 2: step-up factor of the gate supplies.
    make_command(kPowerControl2, {0x10}),
    // VCOM control 1: VCOMH 4.25 V, VCOML -1.5 V.
    make_command(kVcomControl1, {0x3E, 0x28}),
    // VCOM control 2: VCOM offset (nVM = 1, VMF = 6).
    make_command(kVcomControl2, {0x86}),
    // Frame rate (normal mode): fosc / 1, 27 clocks per line: 70 Hz.
    make_command(kFrameRateNormal, {0x00, 0x1B}),
    // Display function: interval scan in non-display area, REV (normally white glass), gate scan
    // G1 to G320, source S1 to S720, 320 lines ((0x27 + 1) x 8), PCDIV 0.
    make_command(kDisplayFunction, {0x08, 0x82, 0x27, 0x00}),
    // Entry mode: low-voltage detection off, normal display.
    make_command(kEntryMode, {0x07}),
    // 3-gamma off, gamma curve 1 (2.2).
    make_command(kEnable3Gamma, {0x00}),
    make_command(dcs::kGammaSet, {0x01}),
    // Positive and negative gamma correction (15 points each).
    make_command(kPositiveGamma, {0x0F, 0x31, 0x2B, 0x0C, 0x0E, 0x08, 0x4E, 0xF1, 0x37, 0x07, 0x10,
                                  0x03, 0x0E, 0x09, 0x00}),
    make_command(kNegativeGamma, {0x00, 0x0E, 0x14, 0x03, 0x11, 0x07, 0x31, 0xC1, 0x48, 0x08, 0x0F,
                                  0x0C, 0x31, 0x36, 0x0F}),
}};

inline constexpr ControllerInfo kInfo{
    .name = "ILI9341",
    .ram_columns = 240,
    .ram_rows = 320,
    .setup = kSetup,
    .madctl_mirror = dcs::kMX,
    .reset_delay_ms = 120,
    .sleep_out_delay_ms = 120,
    .sleep_in_delay_ms = 120,
    .display_on_delay_ms = 20,
};

}  // namespace lr::ili9341
