// qemu_icount: a QEMU TCG plugin that counts the guest instructions a program executes, exactly,
// and prints the running count whenever the guest reaches a marker address.
//
// Usage (see README.md next to this file; scripts/icount.sh resolves marker symbols):
//   qemu-system-arm ... -d plugin -plugin libqemu_icount.so,marker=0x401:lr_icount_begin,...
//
// How it counts: when QEMU translates a block of guest code (a TB), the plugin attaches to it an
// inline "add the TB's instruction count to a 64-bit counter", which runs every time the TB
// executes, chained or not. For a TB that starts at a marker address the plugin attaches a
// callback instead, which first prints the counter and then adds the TB's instruction count. So a
// marker line's count is every instruction executed before the marker's first instruction, and the
// difference between two marker lines counts the instructions from the first marker's first
// instruction (included) to the second marker's first instruction (excluded).
//
// Limits (by construction of TB-level counting; README.md has the details):
//   - One vCPU: the counter is a plain uint64_t and the ADD is not atomic. The plugin refuses a
//     system emulation with more than one vCPU (user mode: single-threaded guests only).
//   - A TB is counted whole when it starts, so a TB cut short by a fault counts the instructions
//     after the faulting one although they did not run (and they count again when they run after
//     the handler); exception and interrupt handlers count into the region they interrupt. A
//     semihosting BKPT ends its TB and counts as one instruction, but the host does the work. A
//     measured region must therefore contain no faults, no interrupts and no semihosting calls.
//   - A marker fires only where a TB starts at its address: a function entry reached by a call
//     (BL/BLX) always starts a TB; an address reached by falling through from the instruction
//     before it may be in the middle of a TB and is then not seen.
//   - QEMU 7.2 prints qemu_plugin_outs() text only with `-d plugin` (to stderr, or to -D FILE).
//
// Profile (argument profile=on): every TB also counts its own executions, and each marker line is
// followed by one line per TB that ran since the previous marker,
//   icount: tb 0xSTART INSNS EXECUTIONS
// so that the instructions between two markers can be attributed to functions by TB start
// address (scripts/icount_profile.py). Counting stays exact; only output grows.
#include <cctype>
#include <cerrno>
#include <cinttypes>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "qemu_plugin_api.h"

extern "C" {
LR_QEMU_PLUGIN_EXPORT int qemu_plugin_version = LR_QEMU_PLUGIN_API_VERSION;
}

namespace {

constexpr size_t kMaxMarkers = 64;
// A TB holds at most 512 guest instructions (TCG_MAX_INSNS); the callback's user data packs the
// marker index and the TB's instruction count into one pointer-sized integer: no allocation.
constexpr uintptr_t kInsnBits = 16;
constexpr uintptr_t kInsnMask = (uintptr_t{1} << kInsnBits) - 1;

struct Marker {
  uint64_t address;  // as given (may carry the Thumb bit)
  uint64_t match;    // the address compared with TB starts: low bit cleared
  const char* name;  // "" when none was given; points into QEMU's argv, valid for our lifetime
  uint64_t hits;
};

Marker g_markers[kMaxMarkers];
size_t g_marker_count = 0;

// Guest instructions executed so far (every TB that has started executing, all of it).
uint64_t g_count = 0;

// Profile: one record per translated TB (a retranslated TB gets a second record with the same
// start; the script adds them up). Allocated once at install: the plugin is a host program.
struct TbRecord {
  uint64_t start;
  uint64_t insns;
  uint64_t executions;  // incremented inline on every execution
  uint64_t reported;    // executions already printed
};
bool g_profile = false;
constexpr size_t kMaxTbRecords = size_t{1} << 20;
TbRecord* g_tbs = nullptr;
size_t g_tb_count = 0;
bool g_tb_overflow = false;

void out(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
void out(const char* fmt, ...) {
  char line[1024];  // room for long (mangled C++) marker names; a longer line keeps its newline
  va_list args;
  va_start(args, fmt);
  const int n = std::vsnprintf(line, sizeof line, fmt, args);
  va_end(args);
  if (n >= static_cast<int>(sizeof line)) line[sizeof line - 2] = '\n';
  qemu_plugin_outs(line);
}

// " NAME" or "" for the output lines.
const char* name_sep(const Marker& m) {
  return m.name[0] != '\0' ? " " : "";
}

// Runs when a marker's TB starts: the count so far excludes the TB itself.
void on_marker_tb(unsigned int /*vcpu_index*/, void* userdata) {
  const auto packed = reinterpret_cast<uintptr_t>(userdata);
  Marker& m = g_markers[packed >> kInsnBits];
  ++m.hits;
  out("icount: marker 0x%" PRIx64 "%s%s at %" PRIu64 "\n", m.address, name_sep(m), m.name, g_count);
  g_count += packed & kInsnMask;
  if (g_profile) {
    for (size_t i = 0; i < g_tb_count; ++i) {
      TbRecord& r = g_tbs[i];
      if (r.executions == r.reported) continue;
      out("icount: tb 0x%" PRIx64 " %" PRIu64 " %" PRIu64 "\n", r.start, r.insns,
          r.executions - r.reported);
      r.reported = r.executions;
    }
    if (g_tb_overflow) out("icount: profile incomplete: more than %zu TBs\n", kMaxTbRecords);
  }
}

void on_tb_translate(qemu_plugin_id_t /*id*/, struct qemu_plugin_tb* tb) {
  const size_t n = qemu_plugin_tb_n_insns(tb);
  const uint64_t start = qemu_plugin_tb_vaddr(tb) & ~uint64_t{1};
  for (size_t i = 0; i < g_marker_count; ++i) {
    if (g_markers[i].match == start && n <= kInsnMask) {
      const uintptr_t packed = (uintptr_t{i} << kInsnBits) | n;
      qemu_plugin_register_vcpu_tb_exec_cb(tb, on_marker_tb, QEMU_PLUGIN_CB_NO_REGS,
                                           reinterpret_cast<void*>(packed));
      return;
    }
  }
  qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &g_count, n);
  if (g_profile) {
    if (g_tb_count == kMaxTbRecords) {
      g_tb_overflow = true;
      return;
    }
    TbRecord& r = g_tbs[g_tb_count++];
    r = TbRecord{start, n, 0, 0};
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &r.executions, 1);
  }
}

void on_atexit(qemu_plugin_id_t /*id*/, void* /*userdata*/) {
  for (size_t i = 0; i < g_marker_count; ++i) {
    const Marker& m = g_markers[i];
    if (m.hits == 0) {
      out("icount: marker 0x%" PRIx64 "%s%s never executed\n", m.address, name_sep(m), m.name);
    }
  }
  out("icount: total %" PRIu64 " instructions\n", g_count);
}

// Parses "0xHEX" or "0xHEX:NAME" into m. Returns false (with a message) when malformed.
bool parse_marker(const char* value, Marker* m) {
  if (value[0] != '0' || (value[1] != 'x' && value[1] != 'X') ||
      !std::isxdigit(static_cast<unsigned char>(value[2]))) {
    std::fprintf(stderr, "qemu_icount: marker=%s: the address must be hexadecimal with 0x\n",
                 value);
    return false;
  }
  char* end = nullptr;
  errno = 0;
  const unsigned long long address = std::strtoull(value + 2, &end, 16);
  if (errno != 0 || (*end != '\0' && *end != ':')) {
    std::fprintf(stderr,
                 "qemu_icount: marker=%s: malformed address (expected 0xHEX or 0xHEX:NAME)\n",
                 value);
    return false;
  }
  m->address = address;
  m->match = address & ~uint64_t{1};
  m->name = *end == ':' ? end + 1 : "";
  m->hits = 0;
  return true;
}

}  // namespace

extern "C" LR_QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id,
                                                         const qemu_info_t* info, int argc,
                                                         char** argv) {
  if (info->system_emulation && (info->system.smp_vcpus != 1 || info->system.max_vcpus != 1)) {
    std::fprintf(
        stderr,
        "qemu_icount: needs exactly one vCPU (the counter is not atomic); this machine has "
        "%d (max %d)\n",
        info->system.smp_vcpus, info->system.max_vcpus);
    return -1;
  }
  g_marker_count = 0;
  for (int i = 0; i < argc; ++i) {
    const char* arg = argv[i];
    if (std::strcmp(arg, "profile=on") == 0) {
      g_profile = true;
      continue;
    }
    if (std::strncmp(arg, "marker=", 7) != 0) {
      std::fprintf(stderr,
                   "qemu_icount: unknown argument '%s' (expected marker=0xADDR[:NAME] or "
                   "profile=on)\n",
                   arg);
      return -1;
    }
    if (g_marker_count == kMaxMarkers) {
      std::fprintf(stderr, "qemu_icount: more than %zu markers\n", kMaxMarkers);
      return -1;
    }
    Marker m{};
    if (!parse_marker(arg + 7, &m)) return -1;
    for (size_t k = 0; k < g_marker_count; ++k) {
      if (g_markers[k].match == m.match) {
        std::fprintf(stderr,
                     "qemu_icount: marker=%s: same address as marker 0x%" PRIx64
                     " (the low, Thumb, bit is ignored)\n",
                     arg + 7, g_markers[k].address);
        return -1;
      }
    }
    g_markers[g_marker_count++] = m;
  }
  if (g_profile) {
    g_tbs = static_cast<TbRecord*>(std::calloc(kMaxTbRecords, sizeof(TbRecord)));
    if (g_tbs == nullptr) {
      std::fprintf(stderr, "qemu_icount: profile=on: out of memory\n");
      return -1;
    }
  }
  qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_translate);
  qemu_plugin_register_atexit_cb(id, on_atexit, nullptr);
  return 0;
}
