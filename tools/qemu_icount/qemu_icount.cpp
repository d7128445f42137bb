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
// Profile (profile=PATH, optionally profile_begin=0xADDR, profile_end=0xADDR, profile_skip=K,
// profile_count=N): how often each instruction address executed inside the selected periods,
// written to PATH at exit as "0xADDR COUNT" lines sorted by address. Every translated TB gets a
// record: its instructions' addresses (read at translation) and an execution counter that an
// inline add increments on every execution (a callback, for TBs at a marker or period boundary).
// A period's begin subtracts every record's counter from the record's profiled count, its end
// adds it back, so the profiled count is the executions inside the periods. At exit each record's
// count is added to each of its instruction addresses: a TB translated twice, or two TBs sharing
// instructions, add up per address. The profile's sum equals the counter's difference over the
// same periods by construction: both add the same TBs' instruction counts.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cinttypes>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <utility>
#include <vector>

#include "qemu_plugin_api.h"

extern "C" {
LR_QEMU_PLUGIN_EXPORT int qemu_plugin_version = LR_QEMU_PLUGIN_API_VERSION;
}

namespace {

constexpr size_t kMaxMarkers = 64;
constexpr size_t kNoMarker = SIZE_MAX;

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

// One translated TB: every TB when profiling, else only the TBs at a marker.
struct TbRecord {
  uint64_t executions;  // every execution: the inline add, or ++ in on_callback_tb
  uint64_t profiled;    // executions inside recorded periods (see the top of the file)
  size_t first_insn;    // index of the TB's first instruction address in g_insn_vaddrs
  size_t n_insns;
  size_t marker;  // index into g_markers, or kNoMarker
  bool begins;    // starts at profile_begin
  bool ends;      // starts at profile_end
};
// A deque: growing it never moves a record, and the inline adds hold their addresses.
// The containers are allocated when QEMU loads the plugin and never destroyed: QEMU calls the
// atexit callback from its own atexit() handler, registered before the plugin was loaded, so a
// namespace-scope object would already have been destroyed when on_atexit() reads it.
std::deque<TbRecord>& g_tbs = *new std::deque<TbRecord>;

struct Profile {
  bool on = false;
  const char* path = nullptr;
  FILE* file = nullptr;  // opened at install, so that a bad path fails at start
  bool has_begin = false, has_end = false;
  uint64_t begin = 0, end = 0;  // TB start addresses, low bit cleared
  uint64_t skip = 0;            // periods not recorded before the first recorded one
  uint64_t count = UINT64_MAX;  // periods recorded after those
  // Run-time state.
  bool in_period = false;
  bool recording = false;  // in a period that is recorded
  uint64_t periods = 0;    // periods started
  uint64_t recorded = 0;   // recorded periods ended (or open at exit)
  uint64_t period_start_count = 0;
  uint64_t counted = 0;  // the counter's differences over the recorded periods
};
Profile g_profile;
std::vector<uint64_t>& g_insn_vaddrs = *new std::vector<uint64_t>;  // of every TB record

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

void start_period() {
  Profile& p = g_profile;
  p.in_period = true;
  p.recording = p.periods >= p.skip && p.periods - p.skip < p.count;
  ++p.periods;
  if (!p.recording) return;
  p.period_start_count = g_count;
  for (TbRecord& r : g_tbs) r.profiled -= r.executions;  // modulo 2^64, added back at the end
}

void end_period() {
  Profile& p = g_profile;
  if (p.recording) {
    for (TbRecord& r : g_tbs) r.profiled += r.executions;
    p.counted += g_count - p.period_start_count;
    ++p.recorded;
  }
  p.in_period = false;
  p.recording = false;
}

// Runs when a TB at a marker or a period boundary starts: the count so far excludes the TB itself.
void on_callback_tb(unsigned int /*vcpu_index*/, void* userdata) {
  TbRecord& r = *static_cast<TbRecord*>(userdata);
  if (r.marker != kNoMarker) {
    Marker& m = g_markers[r.marker];
    ++m.hits;
    out("icount: marker 0x%" PRIx64 "%s%s at %" PRIu64 "\n", m.address, name_sep(m), m.name,
        g_count);
  }
  // Before this execution is counted: a begin's own instructions are in its period, an end's not.
  if (!g_profile.in_period) {
    if (r.begins) start_period();
  } else if (r.ends) {
    end_period();
  }
  ++r.executions;
  g_count += r.n_insns;
}

void on_tb_translate(qemu_plugin_id_t /*id*/, struct qemu_plugin_tb* tb) {
  const size_t n = qemu_plugin_tb_n_insns(tb);
  const uint64_t start = qemu_plugin_tb_vaddr(tb) & ~uint64_t{1};
  size_t marker = kNoMarker;
  for (size_t i = 0; i < g_marker_count; ++i) {
    if (g_markers[i].match == start) marker = i;
  }
  const Profile& p = g_profile;
  const bool begins = p.on && p.has_begin && p.begin == start;
  const bool ends = p.on && p.has_end && p.end == start;
  const bool callback = marker != kNoMarker || begins || ends;
  if (!callback && !p.on) {
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &g_count, n);
    return;
  }
  TbRecord& r = g_tbs.emplace_back(TbRecord{0, 0, g_insn_vaddrs.size(), n, marker, begins, ends});
  if (p.on) {
    for (size_t i = 0; i < n; ++i) {
      g_insn_vaddrs.push_back(qemu_plugin_insn_vaddr(qemu_plugin_tb_get_insn(tb, i)));
    }
  }
  if (callback) {
    qemu_plugin_register_vcpu_tb_exec_cb(tb, on_callback_tb, QEMU_PLUGIN_CB_NO_REGS, &r);
  } else {
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &g_count, n);
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &r.executions, 1);
  }
}

// Writes "0xADDR COUNT" per instruction address executed in the recorded periods, by address.
void write_profile() {
  Profile& p = g_profile;
  const bool open_at_exit = p.recording;
  if (p.in_period) end_period();  // a period still open at exit ends there
  std::vector<std::pair<uint64_t, uint64_t>> counts;
  for (const TbRecord& r : g_tbs) {
    if (r.profiled == 0) continue;
    for (size_t i = 0; i < r.n_insns; ++i) {
      counts.emplace_back(g_insn_vaddrs[r.first_insn + i], r.profiled);
    }
  }
  // By address only (equal addresses are summed below); on pointers, not vector iterators, whose
  // C++20 operator<=> would add an exported (GNU unique) symbol to the library.
  std::sort(counts.data(), counts.data() + counts.size(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  uint64_t sum = 0;
  bool ok = true;
  for (size_t i = 0; i < counts.size();) {
    const uint64_t address = counts[i].first;
    uint64_t executions = 0;
    for (; i < counts.size() && counts[i].first == address; ++i) executions += counts[i].second;
    sum += executions;
    ok = std::fprintf(p.file, "0x%" PRIx64 " %" PRIu64 "\n", address, executions) > 0 && ok;
  }
  ok = std::fclose(p.file) == 0 && ok;
  p.file = nullptr;
  if (!ok) out("icount: profile %s: write error\n", p.path);
  // The sum differs from the counter's only if records were lost: a bug, said so on the line.
  char mismatch[64] = "";
  if (sum != p.counted) {
    std::snprintf(mismatch, sizeof mismatch, " (the counter says %" PRIu64 ")", p.counted);
  }
  out("icount: profile %s: %" PRIu64 " period%s%s, %" PRIu64 " instructions%s\n", p.path,
      p.recorded, p.recorded == 1 ? "" : "s", open_at_exit ? " (the last open at exit)" : "", sum,
      mismatch);
}

void on_atexit(qemu_plugin_id_t /*id*/, void* /*userdata*/) {
  for (size_t i = 0; i < g_marker_count; ++i) {
    const Marker& m = g_markers[i];
    if (m.hits == 0) {
      out("icount: marker 0x%" PRIx64 "%s%s never executed\n", m.address, name_sep(m), m.name);
    }
  }
  if (g_profile.on) write_profile();
  out("icount: total %" PRIu64 " instructions\n", g_count);
}

// Parses "0xHEX" at value into *address; *rest points after the digits. ARG names the argument
// in the message. Returns false (with a message) when malformed.
bool parse_address(const char* arg, const char* value, uint64_t* address, const char** rest) {
  if (value[0] != '0' || (value[1] != 'x' && value[1] != 'X') ||
      !std::isxdigit(static_cast<unsigned char>(value[2]))) {
    std::fprintf(stderr, "qemu_icount: %s: the address must be hexadecimal with 0x\n", arg);
    return false;
  }
  char* end = nullptr;
  errno = 0;
  const unsigned long long parsed = std::strtoull(value + 2, &end, 16);
  if (errno != 0) {
    std::fprintf(stderr, "qemu_icount: %s: address out of range\n", arg);
    return false;
  }
  *address = parsed;
  *rest = end;
  return true;
}

// Parses "0xHEX" or "0xHEX:NAME" into m. Returns false (with a message) when malformed.
bool parse_marker(const char* arg, Marker* m) {
  const char* value = arg + 7;  // after "marker="
  uint64_t address = 0;
  const char* end = nullptr;
  if (!parse_address(arg, value, &address, &end)) return false;
  if (*end != '\0' && *end != ':') {
    std::fprintf(stderr, "qemu_icount: %s: malformed address (expected 0xHEX or 0xHEX:NAME)\n",
                 arg);
    return false;
  }
  m->address = address;
  m->match = address & ~uint64_t{1};
  m->name = *end == ':' ? end + 1 : "";
  m->hits = 0;
  return true;
}

// profile_begin= / profile_end=: "0xHEX" only.
bool parse_boundary(const char* arg, const char* value, uint64_t* match) {
  uint64_t address = 0;
  const char* end = nullptr;
  if (!parse_address(arg, value, &address, &end)) return false;
  if (*end != '\0') {
    std::fprintf(stderr, "qemu_icount: %s: malformed address (expected 0xHEX)\n", arg);
    return false;
  }
  *match = address & ~uint64_t{1};
  return true;
}

// profile_skip= (min 0) / profile_count= (min 1): decimal.
bool parse_decimal(const char* arg, const char* value, uint64_t min, uint64_t* result) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long parsed = std::strtoull(value, &end, 10);
  if (!std::isdigit(static_cast<unsigned char>(value[0])) || *end != '\0' || errno != 0 ||
      parsed < min) {
    std::fprintf(stderr, "qemu_icount: %s: expected a decimal number >= %" PRIu64 "\n", arg, min);
    return false;
  }
  *result = parsed;
  return true;
}

// "key=" prefix test: the value after it, or nullptr.
const char* value_of(const char* arg, const char* key) {
  const size_t n = std::strlen(key);
  return std::strncmp(arg, key, n) == 0 ? arg + n : nullptr;
}

bool parse_args(int argc, char** argv) {
  Profile& p = g_profile;
  bool selects = false;  // a profile_* argument other than profile=
  for (int i = 0; i < argc; ++i) {
    const char* arg = argv[i];
    const char* v = nullptr;
    if ((v = value_of(arg, "profile=")) != nullptr) {
      if (v[0] == '\0' || std::strcmp(v, "on") == 0) {
        std::fprintf(stderr,
                     "qemu_icount: %s: expected profile=PATH, the file the profile is written to "
                     "(write ./on for a file named on)\n",
                     arg);
        return false;
      }
      p.on = true;
      p.path = v;
    } else if ((v = value_of(arg, "profile_begin=")) != nullptr) {
      if (!parse_boundary(arg, v, &p.begin)) return false;
      p.has_begin = selects = true;
    } else if ((v = value_of(arg, "profile_end=")) != nullptr) {
      if (!parse_boundary(arg, v, &p.end)) return false;
      p.has_end = selects = true;
    } else if ((v = value_of(arg, "profile_skip=")) != nullptr) {
      if (!parse_decimal(arg, v, 0, &p.skip)) return false;
      selects = true;
    } else if ((v = value_of(arg, "profile_count=")) != nullptr) {
      if (!parse_decimal(arg, v, 1, &p.count)) return false;
      selects = true;
    } else if (value_of(arg, "marker=") != nullptr) {
      if (g_marker_count == kMaxMarkers) {
        std::fprintf(stderr, "qemu_icount: more than %zu markers\n", kMaxMarkers);
        return false;
      }
      Marker m{};
      if (!parse_marker(arg, &m)) return false;
      for (size_t k = 0; k < g_marker_count; ++k) {
        if (g_markers[k].match == m.match) {
          std::fprintf(stderr,
                       "qemu_icount: %s: same address as marker 0x%" PRIx64
                       " (the low, Thumb, bit is ignored)\n",
                       arg, g_markers[k].address);
          return false;
        }
      }
      g_markers[g_marker_count++] = m;
    } else {
      std::fprintf(stderr,
                   "qemu_icount: unknown argument '%s' (expected marker=0xADDR[:NAME], "
                   "profile=PATH, profile_begin=0xADDR, profile_end=0xADDR, profile_skip=K, "
                   "profile_count=N)\n",
                   arg);
      return false;
    }
  }
  if (selects && !p.on) {
    std::fprintf(stderr, "qemu_icount: profile_begin/_end/_skip/_count need profile=PATH\n");
    return false;
  }
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
  if (!parse_args(argc, argv)) return -1;
  Profile& p = g_profile;
  if (p.on) {
    p.file = std::fopen(p.path, "w");
    if (p.file == nullptr) {
      std::fprintf(stderr, "qemu_icount: profile=%s: cannot open for writing: %s\n", p.path,
                   std::strerror(errno));
      return -1;
    }
    if (!p.has_begin) start_period();  // no begin: the first period starts at reset
  }
  qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_translate);
  qemu_plugin_register_atexit_cb(id, on_atexit, nullptr);
  return 0;
}
