/*
 * The part of QEMU's TCG plugin API that qemu_icount.cpp uses, declared by this project (Debian's
 * QEMU packages ship no qemu-plugin.h).
 *
 * These declarations mirror the ABI of plugin API version 1 (QEMU_PLUGIN_VERSION 1, the version
 * QEMU 7.2 implements): the same type layouts, enumerator values and function signatures as
 * include/qemu/qemu-plugin.h of that API version. Only what this plugin calls is declared; add a
 * function here only after checking its signature against that header. The functions are
 * exported by the QEMU executable (check with `nm -D $(command -v qemu-system-arm)`) and resolved
 * when QEMU loads the plugin, so the plugin links with them undefined.
 *
 * A plugin exports two symbols: `int qemu_plugin_version` (the API version it was written for;
 * QEMU refuses a plugin outside its supported range) and qemu_plugin_install().
 */
#ifndef LR_TOOLS_QEMU_ICOUNT_QEMU_PLUGIN_API_H
#define LR_TOOLS_QEMU_ICOUNT_QEMU_PLUGIN_API_H

#include <stddef.h>
#include <stdint.h>

#ifndef __cplusplus
#include <stdbool.h>
#endif

#define LR_QEMU_PLUGIN_API_VERSION 1

#define LR_QEMU_PLUGIN_EXPORT __attribute__((visibility("default")))

#ifdef __cplusplus
extern "C" {
#endif

/* The plugin's handle, given to qemu_plugin_install(). */
typedef uint64_t qemu_plugin_id_t;

/* What QEMU tells the plugin at install time (valid only during that call). */
typedef struct qemu_info_t {
  const char* target_name; /* guest architecture, e.g. "arm" */
  struct {
    int min; /* oldest plugin API version this QEMU accepts */
    int cur; /* newest */
  } version;
  bool system_emulation; /* full system (softmmu) rather than user mode */
  union {
    struct {
      int smp_vcpus; /* vCPUs at start */
      int max_vcpus;
    } system; /* meaningful only when system_emulation */
  };
} qemu_info_t;

/* Opaque handles of a translation block and of one of its instructions, valid during the
 * translation callback only. */
struct qemu_plugin_tb;
struct qemu_plugin_insn;

/* Whether an execution callback reads or writes guest registers (this plugin: never). */
enum qemu_plugin_cb_flags {
  QEMU_PLUGIN_CB_NO_REGS,
  QEMU_PLUGIN_CB_R_REGS,
  QEMU_PLUGIN_CB_RW_REGS,
};

/* Inline operations generated into the translated code (version 1 has only this one). */
enum qemu_plugin_op {
  QEMU_PLUGIN_INLINE_ADD_U64,
};

typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void* userdata);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void* userdata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb* tb);

/* Exported by the plugin. */
extern LR_QEMU_PLUGIN_EXPORT int qemu_plugin_version;
LR_QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t* info,
                                              int argc, char** argv);

/* Provided by QEMU. */
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_tb_exec_cb(struct qemu_plugin_tb* tb, qemu_plugin_vcpu_udata_cb_t cb,
                                          enum qemu_plugin_cb_flags flags, void* userdata);
void qemu_plugin_register_vcpu_tb_exec_inline(struct qemu_plugin_tb* tb, enum qemu_plugin_op op,
                                              void* ptr, uint64_t imm);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb* tb);
uint64_t qemu_plugin_tb_vaddr(const struct qemu_plugin_tb* tb);
/* The TB's instruction number idx (0-based, < qemu_plugin_tb_n_insns) and its guest address. */
struct qemu_plugin_insn* qemu_plugin_tb_get_insn(const struct qemu_plugin_tb* tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn* insn);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void* userdata);
void qemu_plugin_outs(const char* string);

#ifdef __cplusplus
}
#endif

#endif /* LR_TOOLS_QEMU_ICOUNT_QEMU_PLUGIN_API_H */
