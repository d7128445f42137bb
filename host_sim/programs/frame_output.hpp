// Where lineraster-sim's frames go, for one frame or --frames N:
//   --out FILE.png|.ppm   the last frame (with --out-pattern, only when --out is given)
//   --out FILE.gif        every frame, as an animated GIF (gif_writer.hpp, --gif-delay)
//   --out-pattern NAME    every frame to its own file, written as it is rendered
//   --depth-out FILE.png  the last frame's depth
// Every name is checked before the first frame is rendered (output_file.hpp: a regular file or
// a new one, none of the run's inputs), and no two may be the same file. Each file is written
// whole or not at all; a write that fails part-way through a run (a full disk) leaves the files
// already written, each complete, and the GIF is put in place only once its last frame is in.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/programs/gif_writer.hpp"
#include "lineraster/host_sim/programs/sim_options.hpp"

namespace lr::host {

class FrameOutputs {
 public:
  explicit FrameOutputs(const SimOptions& options) : o_(options) {}

  // Checks every output name against the rules, the inputs (the OBJ, its MTL files, the
  // textures and maps) and each other. False with one line.
  bool check(std::span<const std::string> inputs, std::string& error);
  // Frame f as shown (the emulated panel's image when there is one): to its --out-pattern file
  // and into the GIF. False with one line.
  bool add(int frame, const ImageRgb8& shown, std::string& error);
  // After the last frame: the GIF put in place, or --out written with `last`; --depth-out.
  // False with one line.
  bool finish(const ImageRgb8& last, const std::vector<uint16_t>& depth, std::string& error);

 private:
  const SimOptions& o_;
  GifWriter gif_;  // an unfinished GIF's temporary file goes with it
};

}  // namespace lr::host
