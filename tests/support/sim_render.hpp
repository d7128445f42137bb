// What lineraster-sim renders for a command line, rendered in the test: the arguments read by the
// program's own parser (host_sim/programs/sim_options.cpp, compiled into the test) and the scene
// rendered by render_scene, as host_sim/programs/cli_main.cpp does for one frame. With --display
// the frame is the Rgb565Be one a panel is sent (SceneOptions::rgb565) and its image that frame
// decoded by bit replication: what the emulated panel shows.
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/programs/sim_options.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"

namespace lr::test {

// args: the options, separated by spaces (no quoting).
inline host::RenderResult sim_render(const std::string& args) {
  std::vector<std::string> words{"lineraster-sim"};
  std::istringstream in(args);
  for (std::string w; in >> w;) words.push_back(w);
  std::vector<const char*> argv;
  for (const std::string& w : words) argv.push_back(w.c_str());
  host::SimOptions o;
  std::string error;
  host::RenderResult r;
  EXPECT_TRUE(host::parse_sim_options(static_cast<int>(argv.size()), argv.data(), o, error))
      << error;
  host::HostMesh mesh;
  EXPECT_TRUE(host::load_obj(o.obj, mesh, error)) << error;
  if (o.subdivisions > 0) mesh = host::subdivide(mesh, o.subdivisions);
  EXPECT_TRUE(host::render_scene(mesh, o.scene, r, error)) << error;
  return r;
}

}  // namespace lr::test
