#include "lineraster/host_sim/programs/frame_output.hpp"

#include "lineraster/host_sim/formats/output_file.hpp"

namespace lr::host {

bool FrameOutputs::check(std::span<const std::string> inputs, std::string& error) {
  struct Named {
    const char* option;
    const std::string* path;
  };
  std::vector<Named> single;
  if (o_.writes_out()) single.push_back({"--out", &o_.out});
  if (!o_.depth_out.empty()) single.push_back({"--depth-out", &o_.depth_out});
  for (const Named& n : single)
    if (!check_output(*n.path, inputs, error)) return false;
  const auto clash = [&](const std::string& path, const Named& other) {
    error = path + ": is also the " + other.option + " file (" + *other.path +
            "): refusing to write it twice";
    return false;
  };
  if (single.size() == 2 && same_output(*single[1].path, *single[0].path))
    return clash(*single[1].path, single[0]);
  if (!o_.out_pattern.given) return true;
  for (int f = 0; f < o_.frames; ++f) {
    const std::string name = o_.out_pattern.name(f);
    if (!check_output(name, inputs, error)) return false;
    for (const Named& n : single)
      if (same_output(name, *n.path)) return clash(name, n);
  }
  return true;
}

bool FrameOutputs::add(int frame, const ImageRgb8& shown, std::string& error) {
  if (o_.out_pattern.given) {
    const std::string name = o_.out_pattern.name(frame);
    if (!write_image(name, shown, error)) return false;
  }
  if (o_.gif_out()) {
    if (!gif_.is_open() && !gif_.open(o_.out, shown.width, shown.height, o_.gif_delay, error))
      return false;
    if (!gif_.add(shown, error)) return false;
  }
  return true;
}

bool FrameOutputs::finish(const ImageRgb8& last, const std::vector<uint16_t>& depth,
                          std::string& error) {
  if (o_.gif_out()) {
    if (!gif_.finish(error)) return false;
  } else if (o_.writes_out() && !write_image(o_.out, last, error)) {
    return false;
  }
  return o_.depth_out.empty() ||
         write_png_gray16(o_.depth_out, o_.scene.width, o_.scene.height, depth, error);
}

}  // namespace lr::host
