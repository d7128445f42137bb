#include "lineraster/hal/mipi_dbi.hpp"

namespace lr {

Status send_command(PanelBus& bus, const PanelCommand& command) {
  const Status st = bus.command(command.cmd, command.parameters());
  if (st != Status::kOk) return st;
  if (command.delay_ms != 0) bus.delay_ms(command.delay_ms);
  return Status::kOk;
}

Status send_commands(PanelBus& bus, std::span<const PanelCommand> table) {
  for (const PanelCommand& c : table) {
    const Status st = send_command(bus, c);
    if (st != Status::kOk) return st;
  }
  return Status::kOk;
}

namespace {
std::array<uint8_t, 4> address_range(uint16_t first, uint16_t last) {
  return {static_cast<uint8_t>(first >> 8), static_cast<uint8_t>(first & 0xFFu),
          static_cast<uint8_t>(last >> 8), static_cast<uint8_t>(last & 0xFFu)};
}
}  // namespace

Status write_window(PanelBus& bus, uint16_t x0, uint16_t y0, uint16_t x1, uint16_t y1) {
  const std::array<uint8_t, 4> columns = address_range(x0, x1);
  Status st = bus.command(dcs::kColumnSet, columns);
  if (st != Status::kOk) return st;
  const std::array<uint8_t, 4> rows = address_range(y0, y1);
  st = bus.command(dcs::kRowSet, rows);
  if (st != Status::kOk) return st;
  return bus.command(dcs::kMemoryWrite, {});
}

}  // namespace lr
