#include "firmware/linux/panel_app.hpp"

namespace lr::app {

PanelApp::PanelApp(PanelBus& bus, const PanelConfig& config) : panel_(bus, config) {}

Status PanelApp::start(std::string& error) {
  if (const Status st = panel_.init(); st != Status::kOk) {
    error = std::string("panel init: ") + to_string(st);
    return st;
  }
  const int w = panel_.image_width(), h = panel_.image_height();
  if (!scene_.configure(w, h, error)) return Status::kInvalidArgument;
  const size_t strip = static_cast<size_t>(w) * DemoScene::kStripRows;
  buffers_[0].assign(strip, 0);
  buffers_[1].assign(strip, 0);
  // One signature per strip, so that every strip of a frame can be skipped when unchanged.
  signatures_.assign((static_cast<size_t>(h) + DemoScene::kStripRows - 1) / DemoScene::kStripRows,
                     StripSignature{});
  sink_ = std::make_unique<PanelSink>(panel_, buffers_[0], buffers_[1], signatures_,
                                      kTransferTimeoutMs);
  return Status::kOk;
}

Status PanelApp::frame(uint32_t index, FrameReport& out, std::string& error) {
  if (!sink_) {
    error = "frame before start";
    return Status::kInvalidArgument;
  }
  out.index = index;
  out.degrees = DemoScene::degrees(index);
  const Status st = scene_.render(index, *sink_);
  out.sink = sink_->stats();
  out.render = scene_.stats();
  if (st != Status::kOk) {
    error = "frame " + std::to_string(index) + ": " + to_string(st);
    return st;
  }
  if (!backlight_) {
    if (const Status b = panel_.backlight(true); b != Status::kOk) {
      error = std::string("backlight: ") + to_string(b);
      return b;
    }
    backlight_ = true;
  }
  return Status::kOk;
}

}  // namespace lr::app
