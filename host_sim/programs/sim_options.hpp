// lineraster-sim's command line: what it asks for, read through the option table of
// sim_options.cpp (one row per option; the rules are option_table.hpp's) and then checked as a
// whole (the options that need others, the panel's frame size).
#pragma once

#include <string>
#include <vector>

#include "lineraster/hal/host/display_spec.hpp"
#include "lineraster/hal/panel_config.hpp"
#include "lineraster/host_sim/programs/frame_pattern.hpp"
#include "lineraster/host_sim/scene/scene.hpp"

namespace lr::host {

// Everything the command line asks for; the defaults are the CLI's.
struct SimOptions {
  SceneOptions scene;  // width and height are the panel's when a display is given
  std::string obj, out = "out.png", depth_out;
  bool out_given = false;    // --out was given (with --out-pattern, --out is then written too)
  FramePattern out_pattern;  // --out-pattern: each frame to its own file
  int gif_delay = 4;         // --gif-delay: hundredths of a second per frame of a GIF --out
  bool help = false;         // --help / -h: print the usage, nothing else
  bool version = false;      // --version: print the version, nothing else
  bool stats = false;        // --stats: the frame's statistics as one JSON line
  int frames = 0;            // --frames N; 0: one frame, no per-frame lines

  // Whether --out gets a file: always, unless only --out-pattern names the outputs.
  bool writes_out() const { return out_given || !out_pattern.given; }
  // Whether --out is an animated GIF (its name ends in .gif).
  bool gif_out() const;
  int subdivisions = 0;
  DisplaySpec display;  // kind kNone: the frame goes to --out only
  PanelConfig panel{};  // the panel behind --display (from --panel or the emulator's value)

  // Recorded while reading, resolved by the checks once every option is read (they come in
  // any order).
  std::vector<Vec3d> light_dirs;    // --light-dir
  std::vector<LightOption> lights;  // --light
  std::string phong_only;           // the first option given that only Phong shading uses
  std::string table_only;           // the first option given that only the lighting table uses
  bool has_panel = false, width_given = false, height_given = false, gif_delay_given = false;
};

// Reads and checks argv. False with a one-line message (without the program's name); with
// --help or --version, true and `help` or `version` set (the options after it are not read,
// none is checked).
bool parse_sim_options(int argc, const char* const* argv, SimOptions& out, std::string& error);

// The --help text (docs/host-tools.md shows it verbatim: tests/cli).
const char* sim_usage();

}  // namespace lr::host
