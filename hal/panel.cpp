#include "lineraster/hal/panel.hpp"

namespace lr {

namespace {
// Reset line: asserted at least 10 us (both datasheets), released, then the same 120 ms as after
// SWRESET before the controller takes commands.
constexpr uint32_t kResetPulseMs = 1;
}  // namespace

Status Panel::init(bool hardware_reset) {
  if (!valid_config(config_)) return Status::kInvalidArgument;
  const ControllerInfo& info = controller_info(config_.controller);
  ++epoch_;  // whatever happens next, the RAM no longer holds what it held

  if (hardware_reset) {
    Status st = bus_.set_reset(true);
    if (st != Status::kOk) return st;
    bus_.delay_ms(kResetPulseMs);
    st = bus_.set_reset(false);
    if (st != Status::kOk) return st;
    bus_.delay_ms(info.reset_delay_ms);
  }
  // Also after a hardware reset: without a reset line set_reset() does nothing.
  Status st = bus_.command(dcs::kSoftReset, {});
  if (st != Status::kOk) return st;
  bus_.delay_ms(info.reset_delay_ms);

  st = send_commands(bus_, info.setup);
  if (st != Status::kOk) return st;

  st = bus_.command(dcs::kSleepOut, {});
  if (st != Status::kOk) return st;
  bus_.delay_ms(info.sleep_out_delay_ms);

  st = send(dcs::kPixelFormat, dcs::kPixelFormat16);
  if (st != Status::kOk) return st;
  st = send(dcs::kAddressMode, madctl_for(config_));
  if (st != Status::kOk) return st;
  if (config_.invert) {
    st = bus_.command(dcs::kInvertOn, {});
    if (st != Status::kOk) return st;
  }
  st = bus_.command(dcs::kNormalMode, {});
  if (st != Status::kOk) return st;
  return display_on(true);
}

Status Panel::sleep(bool enter) {
  const ControllerInfo& info = controller_info(config_.controller);
  const Status st = bus_.command(enter ? dcs::kSleepIn : dcs::kSleepOut, {});
  if (st != Status::kOk) return st;
  bus_.delay_ms(enter ? info.sleep_in_delay_ms : info.sleep_out_delay_ms);
  return Status::kOk;
}

Status Panel::display_on(bool on) {
  const ControllerInfo& info = controller_info(config_.controller);
  const Status st = bus_.command(on ? dcs::kDisplayOn : dcs::kDisplayOff, {});
  if (st != Status::kOk) return st;
  if (on) bus_.delay_ms(info.display_on_delay_ms);
  return Status::kOk;
}

Status Panel::set_rotation(Rotation r) {
  PanelConfig next = config_;
  next.rotation = r;
  if (!valid_config(next)) return Status::kInvalidArgument;
  config_ = next;
  ++epoch_;
  return send(dcs::kAddressMode, madctl_for(config_));
}

Status Panel::begin_write(const StripRect& r) {
  AddressWindow w;
  if (!address_window(config_, r, w)) return Status::kInvalidArgument;
  return write_window(bus_, w.x0, w.y0, w.x1, w.y1);
}

}  // namespace lr
