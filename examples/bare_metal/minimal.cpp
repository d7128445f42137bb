// A complete bare-metal program: an unlit, vertex-coloured tetrahedron rendered into RGB565
// strips on a Cortex-M (QEMU's mps2-an386 here), its pixels checked as the strips arrive; the
// verdict is printed and the run ended through semihosting. No heap, no C library start files:
// the vector table and Reset_Handler are below, the memory map is mps2_an386.ld.
#include <array>
#include <cstdint>
#include <lineraster/lineraster.hpp>

namespace {

constexpr int kW = 240, kH = 240, kStrip = 8;
using lr::Fixed;
constexpr Fixed k1 = Fixed::from_int(1);
constexpr std::array<lr::Vec3, 4> kPositions{
    {{k1, k1, k1}, {k1, -k1, -k1}, {-k1, k1, -k1}, {-k1, -k1, k1}}};
constexpr std::array<lr::Rgb8, 4> kColors{
    {{255, 64, 64}, {64, 255, 64}, {64, 64, 255}, {255, 255, 64}}};
constexpr std::array<std::array<uint16_t, 3>, 4> kTriangles{
    {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}}};
constexpr lr::Rgb8 kClear{0, 0, 0};

// Semihosting (ARM's debug interface; QEMU's -semihosting): print a string, end the run.
int semihost(int op, const void* arg) {
  register int r0 asm("r0") = op;
  register const void* r1 asm("r1") = arg;
  asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}
void print(const char* s) {
  semihost(0x04, s);
}  // SYS_WRITE0
[[noreturn]] void exit_run(bool ok) {
  semihost(0x18, reinterpret_cast<const void*>(ok ? 0x20026 : 0x20023));  // SYS_EXIT
  for (;;) {
  }
}

// Receives the strips and checks them: the corners are the clear colour, the centre is not,
// and the object covers a plausible share of the frame. A panel sink would send them instead.
using PF = lr::Rgb565Be;
struct CheckingSink final : lr::StripSink<PF> {
  alignas(4) std::array<PF::Storage, kW * kStrip> strip{};
  uint32_t covered = 0;
  bool corners_clear = true, centre_drawn = false;
  lr::Status begin_frame(uint16_t, uint16_t) override { return lr::Status::kOk; }
  lr::Status acquire(lr::StripLease<PF>& out) override {
    out = lend(strip.data(), strip.size(), 0);
    return lr::Status::kOk;
  }
  lr::Status submit(const lr::StripRect& r, lr::StripLease<PF>&& lease) override {
    std::span<PF::Storage> px;
    take_back(lease, px);
    const PF::Storage clear = PF::encode(kClear);
    for (int y = 0; y < r.height; ++y) {
      for (int x = 0; x < r.width; ++x) {
        const bool drawn = px[static_cast<size_t>(y * r.width + x)] != clear;
        const int fy = r.y + y, fx = r.x + x;
        covered += drawn ? 1u : 0u;
        if ((fx == 0 || fx == kW - 1) && (fy == 0 || fy == kH - 1)) corners_clear &= !drawn;
        if (fx == kW / 2 && fy == kH / 2) centre_drawn = drawn;
      }
    }
    return lr::Status::kOk;
  }
  lr::Status end_frame() override { return lr::Status::kOk; }
};

// Every store of the frame, in .bss (constant-initialised: no constructor runs at startup).
constexpr lr::FrameCapacities kCaps{kW, kH, kStrip, 16, 16, 1, 8};
lr::StaticFrameStorage<kCaps> store;
lr::Renderer<PF, kStrip, lr::kUntexturedSpans> renderer;  // Gouraud and flat spans only
CheckingSink sink;

}  // namespace

int main() {
  lr::Camera cam;
  cam.eye = {Fixed::from_double(0.8), Fixed::from_double(1.6), Fixed::from_int(4)};
  lr::perspective(Fixed::from_int(50), Fixed::ratio(kW, kH), Fixed::from_double(0.5),
                  Fixed::from_int(20), cam.projection);
  lr::look_at(cam.eye, {}, {Fixed{}, k1, Fixed{}}, cam.view);
  lr::DrawState state;
  state.lighting = false;  // the vertex colours, interpolated
  const lr::Mesh mesh{kPositions, {}, kColors, {}, kTriangles};
  lr::Status st = renderer.configure(store.storage(), kW, kH);
  if (st == lr::Status::kOk) st = renderer.begin_frame(cam, lr::LightSet{}, kClear);
  if (st == lr::Status::kOk) st = renderer.draw(mesh, lr::rotate_y(Fixed::from_int(20)), {}, state);
  if (st == lr::Status::kOk) st = renderer.render(sink);
  const bool covers = sink.covered > kW * kH / 10 && sink.covered < kW * kH / 2;
  const bool ok = st == lr::Status::kOk && sink.corners_clear && sink.centre_drawn && covers;
  print(st != lr::Status::kOk ? "minimal: the renderer refused the frame\n"
        : !ok                 ? "minimal: wrong pixels\n"
                              : "minimal: frame drawn, pixels as expected\n");
  return ok ? 0 : 1;
}

// ---- Startup: what a board's SDK usually provides (CMSIS startup file and linker script) ----
extern "C" {
extern uint32_t _sidata[], _sdata[], _edata[], _sbss[], _ebss[], _estack[];
extern void (*__init_array_start[])(), (*__init_array_end[])();

[[noreturn]] void Reset_Handler() {
#if defined(__ARM_FP)
  *reinterpret_cast<volatile uint32_t*>(0xE000ED88) |= 0xFu << 20;  // CPACR: FPU on
  asm volatile("dsb\n isb");
#endif
  for (uint32_t *src = _sidata, *dst = _sdata; dst < _edata;) *dst++ = *src++;
  for (uint32_t* dst = _sbss; dst < _ebss;) *dst++ = 0;
  for (auto* f = __init_array_start; f < __init_array_end; ++f) (*f)();
  exit_run(main() == 0);
}
[[noreturn]] void Fault_Handler() {
  print("minimal: fault\n");
  exit_run(false);
}

// The first 16 entries: initial stack pointer, reset, then the core's exceptions.
using Vector = void (*)();
__attribute__((section(".isr_vector"), used))
const Vector kVectors[16] = {reinterpret_cast<Vector>(_estack),
                             Reset_Handler,
                             Fault_Handler,
                             Fault_Handler,
                             Fault_Handler,
                             Fault_Handler,
                             Fault_Handler};
}
