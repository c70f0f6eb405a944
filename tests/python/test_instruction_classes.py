"""scripts/instruction-classes: the class of each kind of instruction, and the counts read from a
callgrind file (a call's inclusive cost skipped, other objects counted as library), on a small
hand-written file and disassembly. The tool itself needs valgrind and minutes; it is a benchmark.

    /usr/bin/python3 -m pytest tests/python/test_instruction_classes.py
"""

import importlib.machinery
import importlib.util

import pytest

from conftest import SCRIPTS


def load_tool():
    loader = importlib.machinery.SourceFileLoader("instruction_classes", str(SCRIPTS / "instruction-classes"))
    spec = importlib.util.spec_from_loader("instruction_classes", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


tool = load_tool()


@pytest.mark.parametrize("mnemonic, operands, expected", [
    ("vfmadd231pd", "ymm0,ymm1,YMMWORD PTR [rax+0x8]", "fp arithmetic"),
    ("vmulsd", "xmm0,xmm1,xmm2", "fp arithmetic"),
    ("vsqrtpd", "ymm0,ymm1", "fp arithmetic"),
    ("vcmppd", "ymm0,ymm1,ymm2,0x1", "fp arithmetic"),
    ("vmovupd", "ymm0,YMMWORD PTR [rdx+rax*8]", "fp loads"),
    ("vbroadcastsd", "ymm2,QWORD PTR [r8+0x58]", "fp loads"),
    ("vinsertf128", "ymm0,ymm0,XMMWORD PTR [rcx],0x1", "fp loads"),
    ("vmovupd", "YMMWORD PTR [rdx+rax*8],ymm0", "fp stores"),
    ("vmovsd", "QWORD PTR [rbx+0x10],xmm3", "fp stores"),
    ("vbroadcastsd", "ymm10,xmm10", "fp register moves"),
    ("vpermpd", "ymm1,ymm2,0x44", "fp register moves"),
    ("vmovapd", "ymm3,ymm4", "fp register moves"),
    ("vmovapd", "YMMWORD PTR [rbp-0x170],ymm3", "stack"),
    ("vmovsd", "xmm0,QWORD PTR [rsp+0x48]", "stack"),
    ("mov", "QWORD PTR [rsp+0x10],rdi", "stack"),
    ("push", "rbp", "stack"),
    ("pop", "r12", "stack"),
    ("mov", "rax,QWORD PTR [rbp+rdx*8+0x10]", "integer, address"),
    ("vmovupd", "ymm0,YMMWORD PTR [rbp+rax*8]", "fp loads"),
    ("vmovsd", "xmm1,QWORD PTR [rbp-0x48]", "stack"),
    ("vpshufd", "xmm0,xmm1,0x4e", "fp register moves"),
    ("vpunpcklqdq", "xmm0,xmm1,xmm2", "fp register moves"),
    ("vgatherdpd", "ymm0,QWORD PTR [rax+xmm1*8],ymm2", "fp loads"),
    ("vmaskmovpd", "YMMWORD PTR [rdi],ymm1,ymm0", "fp stores"),
    ("vzeroupper", "", "fp arithmetic"),
    ("mov", "rax,QWORD PTR [rbx+0x8]", "integer, address"),
    ("lea", "rsi,[rsp+0x10]", "integer, address"),
    ("imul", "rax,rdx", "integer, address"),
    ("cmova", "rax,rdx", "integer, address"),
    ("jne", "245c55 <f>", "branches"),
    ("cmp", "rdx,r8", "branches"),
    ("call", "eca0 <GOMP_parallel@plt>", "branches"),
])
def test_instruction_class(mnemonic, operands, expected):
    assert tool.instruction_class(mnemonic, operands) == expected


CALLGRIND = """version: 1
positions: instr line
events: Ir

ob=/usr/lib/x86_64-linux-gnu/libc.so.6
fn=memset
0x7000 0 40

ob=/build/src/mpmshock
fn=step
0x1000 0 10
0x1004 0 10
cob=/usr/lib/x86_64-linux-gnu/libc.so.6
cfn=memset
calls=1 0x7000 0
0x1008 0 40
0x100c 0 7

fn=stress
0x2000 0 5
0x1000 0 1
"""

DISASSEMBLY = {
    0x1000: ("vfmadd231pd", "ymm0,ymm1,ymm2"),
    0x1004: ("vmovupd", "YMMWORD PTR [rdx],ymm0"),
    0x1008: ("call", "7000 <memset@plt>"),
    0x100c: ("add", "rax,0x20"),
    0x2000: ("vmovsd", "xmm0,QWORD PTR [rbp-0x8]"),
}


def test_counts_from_callgrind(tmp_path):
    path = tmp_path / "callgrind.out"
    path.write_text(CALLGRIND)
    at, elsewhere = tool.executed(path, "mpmshock")
    # The call's line (40 at 0x1008) is memset's inclusive cost, already counted in libc's own lines.
    assert at == {0x1000: 11, 0x1004: 10, 0x100c: 7, 0x2000: 5}
    assert elsewhere == 40
    counts = tool.classify(at, elsewhere, DISASSEMBLY)
    assert counts["fp arithmetic"] == 11
    assert counts["fp stores"] == 10
    assert counts["integer, address"] == 7
    assert counts["stack"] == 5
    assert counts["library"] == 40
    assert counts["branches"] == 0  # the call instruction's own execution is not in this file
    assert sum(counts.values()) == 73


@pytest.mark.parametrize("text, expected", [
    ("vfmadd231pd ymm0,ymm1,ymm2", ("vfmadd231pd", "ymm0,ymm1,ymm2")),
    ("notrack jmp rax", ("jmp", "rax")),
    ("rep stos BYTE PTR es:[rdi],al", ("stos", "BYTE PTR es:[rdi],al")),
    ("lock cmpxchg DWORD PTR [rdx],ecx", ("cmpxchg", "DWORD PTR [rdx],ecx")),
    ("ret", ("ret", "")),
])
def test_prefixes_dropped(text, expected):
    assert tool.split_instruction(text) == expected


def test_jump_table_is_a_branch():
    assert tool.instruction_class(*tool.split_instruction("notrack jmp rax")) == "branches"


def test_build_without_avx_is_refused():
    sse = {0x1000: ("addsd", "xmm0,xmm1"), 0x1004: ("movapd", "xmm2,xmm3")}
    with pytest.raises(ValueError, match="without AVX"):
        tool.classify({0x1000: 5, 0x1004: 5}, 0, sse)


def test_compressed_callgrind_file_is_refused(tmp_path):
    path = tmp_path / "callgrind.out"
    path.write_text(CALLGRIND.replace("ob=/build/src/mpmshock", "ob=(2) /build/src/mpmshock"))
    with pytest.raises(ValueError, match="compress-strings=no"):
        tool.executed(path, "mpmshock")
    path.write_text(CALLGRIND.replace("positions: instr line", "positions: line"))
    with pytest.raises(ValueError, match="dump-instr"):
        tool.executed(path, "mpmshock")


def test_foreign_addresses_are_an_error(tmp_path):
    with pytest.raises(ValueError, match="not in the binary's disassembly"):
        tool.classify({0x9999: 3}, 0, DISASSEMBLY)
