"""Unit tests of scripts/stack_usage.py on small synthetic inputs: .ci files as GCC writes them
(-fcallgraph-info=su), a symbol list standing in for the ELF's function symbols, and objdump
text for the functions without a .ci node. No toolchain and no third-party module needed:

    python3 -m unittest discover -s tests/footprint -v
"""

import contextlib
import io
import os
import sys
import tempfile
import textwrap
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import stack_usage  # noqa: E402


def node(title, frame, qualifier="static", source="/src/a.cpp"):
    return (f'node: {{ title: "{title}" label: "void {title}()\\n{source}:1:1\\n{frame} bytes '
            f'({qualifier})" }}\n')


def external(title):
    return f'node: {{ title: "{title}" label: "void {title}()\\n<built-in>" shape : ellipse }}\n'


def edge(src, dst):
    return f'edge: {{ sourcename: "{src}" targetname: "{dst}" label: "/src/a.cpp:2:3" }}\n'


def graph(source, *parts):
    return f'graph: {{ title: "{source}"\n' + "".join(parts) + "}\n"


class StackUsageTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.build = os.path.join(self.dir, "build")
        os.makedirs(self.build)

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, name, text):
        path = os.path.join(self.dir, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(textwrap.dedent(text))
        return path

    def run_tool(self, ci, symbols, disasm="", args=()):
        """(exit status, stdout, stderr) of stack_usage.py on these inputs."""
        for name, text in ci.items():
            self.write(os.path.join("build", name), text)
        syms = self.write("syms.txt", symbols)
        dis = self.write("dis.txt", disasm)
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = stack_usage.main(["-", self.build, "--symbols", syms, "--disasm", dis,
                                   "--tool-prefix", "none-", *args])
        return rc, out.getvalue(), err.getvalue()

    def test_chain(self):
        ci = {"a.ci": graph("/src/a.cpp", node("a", 16), node("b", 32), node("c", 8),
                            edge("a", "b"), edge("b", "c"))}
        rc, out, err = self.run_tool(ci, "100 10 T a\n200 10 T b\n300 10 T c\n",
                                     args=["--entry", "a"])
        self.assertEqual(rc, 0, err)
        self.assertIn("a: 56 B via a -> b -> c", out)

    def test_diamond_takes_the_deeper_branch(self):
        ci = {"a.ci": graph("/src/a.cpp", node("a", 8), node("b", 100), node("c", 20),
                            node("d", 4), edge("a", "b"), edge("a", "c"), edge("b", "d"),
                            edge("c", "d"))}
        rc, out, err = self.run_tool(
            ci, "100 10 T a\n200 10 T b\n300 10 T c\n400 10 T d\n", args=["--entry", "a"])
        self.assertEqual(rc, 0, err)
        self.assertIn("a: 112 B via a -> b -> d", out)

    def test_recursion_is_an_error(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("a", 16), node("b", 16),
                            edge("main", "a"), edge("a", "b"), edge("b", "a"))}
        rc, out, err = self.run_tool(ci, "100 10 T main\n200 10 T a\n300 10 T b\n",
                                     args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("recursion: a -> b -> a", err)
        self.assertEqual(out, "")

    def test_self_recursion_is_an_error(self):
        ci = {"a.ci": graph("/src/a.cpp", node("f", 16), edge("f", "f"))}
        rc, _, err = self.run_tool(ci, "100 10 T f\n", args=["--entry", "f"])
        self.assertEqual(rc, 1)
        self.assertIn("recursion: f -> f", err)

    def test_unresolved_indirect_call_is_an_error(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("dispatch", 24),
                            external("__indirect_call"), edge("main", "dispatch"),
                            edge("dispatch", "__indirect_call"))}
        rc, _, err = self.run_tool(ci, "100 10 T main\n200 10 T dispatch\n",
                                   args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("dispatch: unresolved indirect call", err)

    def test_indirect_call_takes_the_deepest_candidate(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("dispatch", 24),
                            node("h_small", 16), node("h_big", 200), node("other", 4000),
                            edge("main", "dispatch"), edge("dispatch", "__indirect_call"))}
        syms = "100 10 T main\n200 10 T dispatch\n300 10 T h_small\n400 10 T h_big\n" \
               "500 10 T other\n"
        rc, out, err = self.run_tool(ci, syms, args=["--entry", "main", "--indirect", "^h_"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 232 B via main -> dispatch -> (*) h_big", out)

    def test_indirect_from_applies_to_its_callers_only(self):
        # run() calls spans through pointers, spans call fetchers through pointers: one rule for
        # both would make a span a candidate of itself (a false recursion).
        ci = {"a.ci": graph("/src/a.cpp", node("run", 16), node("span", 100), node("fetch", 40),
                            edge("run", "__indirect_call"), edge("span", "__indirect_call"))}
        syms = "100 10 T run\n200 10 T span\n300 10 T fetch\n"
        rc, out, err = self.run_tool(ci, syms, args=[
            "--entry", "run", "--indirect-from", "^run$", "^span$",
            "--indirect-from", "^span$", "^fetch$"])
        self.assertEqual(rc, 0, err)
        self.assertIn("run: 156 B via run -> (*) span -> (*) fetch", out)

    def test_dynamic_frame_is_an_error(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("vla", 24, "dynamic"),
                            edge("main", "vla"))}
        rc, _, err = self.run_tool(ci, "100 10 T main\n200 10 T vla\n", args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("vla: dynamic (unbounded) stack frame", err)

    def test_dynamic_bounded_frame_is_its_bound(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("f", 48, "dynamic,bounded"),
                            edge("main", "f"))}
        rc, out, err = self.run_tool(ci, "100 10 T main\n200 10 T f\n", args=["--entry", "main"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 56 B", out)

    def test_unknown_callee_is_an_error(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), external("missing"),
                            edge("main", "missing"))}
        rc, _, err = self.run_tool(ci, "100 10 T main\n", args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("main: calls missing", err)
        self.assertIn("unknown function", err)

    def test_run_time_helper_the_image_does_not_define_is_no_call(self):
        # GCC's call graph keeps a libcall its later passes removed (a signed 64-bit division
        # that became unsigned): not in the image, so not called.
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), external("__aeabi_ldivmod"),
                            edge("main", "__aeabi_ldivmod"))}
        rc, out, err = self.run_tool(ci, "100 10 T main\n", args=["--entry", "main"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 8 B", out)

    def test_function_without_ci_or_code_is_an_error(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), external("helper"),
                            edge("main", "helper"))}
        rc, _, err = self.run_tool(ci, "100 10 T main\n200 10 T helper\n",
                                   args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("helper: no frame size", err)

    def test_libgcc_frame_and_calls_from_the_disassembly(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), external("__aeabi_ldivmod"),
                            edge("main", "__aeabi_ldivmod"))}
        syms = "100 10 T main\n200 20 T __aeabi_ldivmod\n300 10 T __udivmoddi4\n"
        dis = """\
            00000200 <__aeabi_ldivmod>:
                 200:	sub.w	ip, sp, #8
                 204:	strd	ip, lr, [sp, #-16]!
                 208:	bl	300 <__udivmoddi4>
                 20c:	ldr.w	lr, [sp, #4]
                 210:	add	sp, #16
                 212:	bx	lr

            00000300 <__udivmoddi4>:
                 300:	stmdb	sp!, {r4, r5, r6, r7, r8, r9, sl, lr}
                 304:	vpush	{d8-d9}
                 308:	sub	sp, #12
                 30a:	ldmia.w	sp!, {r4, r5, r6, r7, r8, r9, sl, pc}
            """
        rc, out, err = self.run_tool(ci, syms, dis, args=["--entry", "main"])
        self.assertEqual(rc, 0, err)
        # 8 + 16 + (32 + 16 + 12)
        self.assertIn("main: 84 B via main -> __aeabi_ldivmod -> __udivmoddi4", out)

    def test_arguments_reserved_before_the_push_add_to_the_ci_frame(self):
        # f takes a by-value object partly in registers: its code reserves 8 B for them before
        # it pushes its registers, which its .ci frame (40 B) leaves out; g's `sub sp` is its
        # locals, counted in its .ci frame already (no push follows it).
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("f", 40), node("g", 16),
                            edge("main", "f"), edge("main", "g"))}
        dis = """\
            00000200 <f>:
                 200:	sub	sp, #8
                 202:	stmdb	sp!, {r4, r5, r6, r7, r8, r9, sl, lr}
                 206:	ldmia.w	sp!, {r4, r5, r6, r7, r8, r9, sl, lr}
                 20a:	add	sp, #8
                 20c:	bx	lr

            00000300 <g>:
                 300:	sub	sp, #16
                 302:	add	sp, #16
                 304:	bx	lr
            """
        rc, out, err = self.run_tool(ci, "100 10 T main\n200 14 T f\n300 6 T g\n", dis,
                                     args=["--entry", "main", "--verbose"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 56 B via main -> f\n", out)  # 8 + 40 + 8

    def test_unfollowable_sp_write_is_an_error(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), edge("main", "asm_fn"))}
        dis = """\
            00000200 <asm_fn>:
                 200:	push	{r7, lr}
                 202:	mov	sp, r7
                 204:	pop	{r7, pc}
            """
        rc, _, err = self.run_tool(ci, "100 10 T main\n200 6 T asm_fn\n", dis,
                                   args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("asm_fn: no .ci node and its code moves sp", err)

    def test_tail_call_costs_the_callee_only(self):
        # f's epilogue runs before `b.w g`: g's frame replaces f's on the stack.
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("f", 64), node("g", 16),
                            edge("main", "f"), edge("f", "g"))}
        dis = """\
            00000200 <f>:
                 200:	push	{r4, lr}
                 202:	pop	{r4, lr}
                 204:	b.w	300 <g>
            """
        rc, out, err = self.run_tool(ci, "100 10 T main\n200 8 T f\n300 10 T g\n", dis,
                                     args=["--entry", "main"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 72 B via main -> f\n", out)

    def test_register_branch_without_pop_is_indirect(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), edge("main", "thunk"))}
        dis = """\
            00000200 <thunk>:
                 200:	ldr	r3, [r0, #0]
                 202:	bx	r3
            """
        rc, _, err = self.run_tool(ci, "100 10 T main\n200 4 T thunk\n", dis,
                                   args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("thunk: unresolved indirect branch", err)

    def test_table_load_into_pc_without_a_table_in_the_function_is_indirect(self):
        # ldr.w pc with the table elsewhere (GCC's ARMv8-M switches keep it in .rodata): a
        # switch only when image words point into the function; here none do.
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), edge("main", "dispatch"))}
        dis = """\
            00000200 <dispatch>:
                 200:	ldr.w	pc, [r3, r0, lsl #2]
                 204:	bx	lr
            """
        rc, _, err = self.run_tool(ci, "100 10 T main\n200 6 T dispatch\n", dis,
                                   args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("dispatch: unresolved indirect branch", err)

    def test_switch_table_followed_by_a_literal_pool_is_a_switch(self):
        # The table's words point into the function; the literal after it (0x80808081) does not
        # and is not an entry.
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("dispatch", 16),
                            edge("main", "dispatch"))}
        dis = """\
            00000200 <dispatch>:
                 200:	ldr.w	pc, [r3, r0, lsl #2]
                 204:	.word	0x0000020d
                 208:	.word	0x0000020f
                 20c:	.word	0x80808081
                 210:	bx	lr
            """
        rc, out, err = self.run_tool(ci, "100 10 T main\n200 18 T dispatch\n", dis,
                                     args=["--entry", "main"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 24 B via main -> dispatch\n", out)

    def test_table_of_words_outside_the_function_is_indirect(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), edge("main", "dispatch"))}
        dis = """\
            00000200 <dispatch>:
                 200:	ldr.w	pc, [r3, r0, lsl #2]
                 204:	.word	0x00000101
                 208:	.word	0x0000020f
                 20c:	bx	lr
            """
        rc, _, err = self.run_tool(ci, "100 10 T main\n200 14 T dispatch\n", dis,
                                   args=["--entry", "main"])
        self.assertEqual(rc, 1)
        self.assertIn("dispatch: unresolved indirect branch", err)

    def test_popped_register_branch_is_a_return(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), edge("main", "__aeabi_idivmod"))}
        dis = """\
            00000200 <__aeabi_idivmod>:
                 200:	push	{r0, r1, lr}
                 202:	pop	{r1, r2, r3}
                 204:	bx	r3
            """
        rc, out, err = self.run_tool(ci, "100 10 T main\n200 6 T __aeabi_idivmod\n", dis,
                                     args=["--entry", "main"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 20 B", out)

    def test_local_functions_are_told_apart_by_their_file(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("/src/a.cpp:helper", 16),
                            edge("main", "/src/a.cpp:helper"), edge("main", "use_b")),
              "b.ci": graph("/src/b.cpp", node("use_b", 8), node("/src/b.cpp:helper", 300),
                            edge("use_b", "/src/b.cpp:helper"))}
        syms = "100 10 T main\n200 10 t helper a.cpp\n300 10 T use_b\n400 10 t helper b.cpp\n"
        rc, out, err = self.run_tool(ci, syms, args=["--entry", "main"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 316 B via main -> use_b -> helper", out)

    def test_functions_the_linker_dropped_are_ignored(self):
        ci = {"a.ci": graph("/src/a.cpp", node("main", 8), node("unused", 5000),
                            edge("unused", "gone"))}
        rc, out, err = self.run_tool(ci, "100 10 T main\n", args=["--entry", "main"])
        self.assertEqual(rc, 0, err)
        self.assertIn("main: 8 B", out)

    def test_handler_is_charged_the_exception_frame(self):
        ci = {"a.ci": graph("/src/a.cpp", node("Reset_Handler", 8), node("main", 100),
                            node("HardFault_Handler", 16), edge("Reset_Handler", "main"))}
        syms = "100 10 T Reset_Handler\n200 10 T main\n300 10 T HardFault_Handler\n"
        rc, out, err = self.run_tool(ci, syms, args=["--entry", "Reset_Handler", "--handler",
                                                     "HardFault_Handler",
                                                     "--exception-frame", "36"])
        self.assertEqual(rc, 0, err)
        self.assertIn("HardFault_Handler: 52 B = 36 B exception entry + 16 B", out)
        self.assertIn("total: 160 B", out)


class NamesTest(unittest.TestCase):
    def test_short_name(self):
        s = stack_usage.short_name
        self.assertEqual(s("lr::Renderer<lr::Rgb565Be, 8, 0ul>::render(lr::StripSink<"
                           "lr::Rgb565Be>&, lr::DepthSink*)"),
                         "lr::Renderer<lr::Rgb565Be, 8, 0ul>::render")
        self.assertEqual(s("(anonymous namespace)::check(lr::Status, char const*) "
                           "[clone .part.0]"), "(anonymous namespace)::check [.part.0]")
        self.assertEqual(s("lr::Foo::get() const"), "lr::Foo::get")
        self.assertEqual(s("main"), "main")

    def test_stack_effects(self):
        e = stack_usage.stack_effect
        self.assertEqual(e("push", "{r4, r5, r6, lr}"), 16)
        self.assertEqual(e("stmdb", "sp!, {r4, r5, r6, r7, r8, r9, sl, lr}"), 32)
        self.assertEqual(e("vpush", "{d8-d15}"), 64)
        self.assertEqual(e("sub", "sp, #108\t@ 0x6c"), 108)
        self.assertEqual(e("sub.w", "sp, sp, #2000"), 2000)
        self.assertEqual(e("str.w", "lr, [sp, #-4]!"), 4)
        self.assertIsNone(e("add", "sp, #16"))
        self.assertIsNone(e("pop", "{r4, pc}"))
        self.assertIsNone(e("ldr", "r3, [sp, #40]\t@ 0x28"))
        self.assertIsNone(e("cmp", "sp, r3"))
        self.assertEqual(e("mov", "sp, r7"), -1)
        self.assertEqual(e("sub", "sp, r3"), -1)


if __name__ == "__main__":
    unittest.main()
