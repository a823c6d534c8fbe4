#!/usr/bin/env python3
"""Converts dEQP shader-case files (`*.test`, the "shader library" format of the Khronos OpenGL ES
CTS) into a corpus folder of the form of the shared `deqp-gles2` corpus: one vertex and one
fragment shader file per case, a `manifest.tsv` and a `README.md`.

Each case is turned into the two shaders the dEQP harness would compile and link, following the
WebGL conformance suite's JavaScript port of the harness (modules/shared/glsShaderLibrary.js for
the parser, modules/shared/glsShaderLibraryCase.js for the shader generation): the `${...}`
placeholders are filled the way it fills them, a `both` case becomes a `_vertex` and a `_fragment`
case whose other stage is the shader the harness generates, and a case with separate `vertex`
and `fragment` sources is a `complete` case.

Usage: deqp_tests_to_corpus.py SOURCE_DIR OUT_DIR [--suite gles3]
  SOURCE_DIR  folder holding the `.test` files (e.g. .../deqp/data/gles3/shaders)
  OUT_DIR     corpus folder to write; replaced as a whole (written to OUT_DIR.tmp, then renamed);
              must not lie inside the repository this script belongs to
  --suite     dEQP suite name (default gles3): ids start with dEQP-<SUITE>.functional.shaders.

Exit codes: 0 corpus written, 1 a `.test` file could not be parsed or the output not written,
2 usage errors (bad arguments, SOURCE_DIR without `.test` files, OUT_DIR inside the repository).
"""
import argparse
import bisect
import re
import shutil
import sys
from dataclasses import dataclass, field
from pathlib import Path

EXIT_FAILED = 1
EXIT_USAGE = 2

REPO_ROOT = Path(__file__).resolve().parents[1]

# Value data types: name -> (scalar type, scalar count, float type of the same shape), as in
# gluShaderUtil.js (getDataTypeScalarType, getDataTypeScalarSize, getDataTypeFloatScalars).
DATA_TYPES = {}
for _n in range(1, 5):
    for _prefix, _scalar in (("", "float"), ("i", "int"), ("u", "uint"), ("b", "bool")):
        _name = _scalar if _n == 1 else f"{_prefix}vec{_n}"
        DATA_TYPES[_name] = (_scalar, _n, "float" if _n == 1 else f"vec{_n}")
for _cols in range(2, 5):
    for _rows in range(2, 5):
        _name = f"mat{_cols}" if _cols == _rows else f"mat{_cols}x{_rows}"
        DATA_TYPES[_name] = ("float", _cols * _rows, _name)

# The harness's fixed comparison helpers (genCompareFunctions), in its emission order.
# Float-typed variants are used where a non-float output arrives through a float varying.
CMP_FLOAT_VARYING = {
    "bool": "bool isOk (float a, bool b) { return ((a > 0.5) == b); }",
    "bvec2": "bool isOk (vec2 a, bvec2 b) { return (greaterThan(a, vec2(0.5)) == b); }",
    "bvec3": "bool isOk (vec3 a, bvec3 b) { return (greaterThan(a, vec3(0.5)) == b); }",
    "bvec4": "bool isOk (vec4 a, bvec4 b) { return (greaterThan(a, vec4(0.5)) == b); }",
    "int": "bool isOk (float a, int b) { float atemp = a+0.5; "
           "return (float(b) <= atemp && atemp <= float(b+1)); }",
    "ivec2": "bool isOk (vec2 a, ivec2 b) { return (ivec2(floor(a + 0.5)) == b); }",
    "ivec3": "bool isOk (vec3 a, ivec3 b) { return (ivec3(floor(a + 0.5)) == b); }",
    "ivec4": "bool isOk (vec4 a, ivec4 b) { return (ivec4(floor(a + 0.5)) == b); }",
    "uint": "bool isOk (float a, uint b) { float atemp = a+0.5; "
            "return (float(b) <= atemp && atemp <= float(b+1u)); }",
    "uvec2": "bool isOk (vec2 a, uvec2 b) { return (uvec2(floor(a + 0.5)) == b); }",
    "uvec3": "bool isOk (vec3 a, uvec3 b) { return (uvec3(floor(a + 0.5)) == b); }",
    "uvec4": "bool isOk (vec4 a, uvec4 b) { return (uvec4(floor(a + 0.5)) == b); }",
}
CMP_EXACT_TYPES = ["bool", "bvec2", "bvec3", "bvec4", "int", "ivec2", "ivec3", "ivec4",
                   "uint", "uvec2", "uvec3", "uvec4"]
CMP_EPSILON = {
    "float": "bool isOk (float a, float b, float eps) { return (abs(a-b) <= (eps*abs(b) + eps)); }",
    **{f"vec{n}": f"bool isOk (vec{n} a, vec{n} b, float eps) "
                  "{ return all(lessThanEqual(abs(a-b), (eps*abs(b) + eps))); }"
       for n in (2, 3, 4)},
}
_MAT_DIFF = {
    2: "max(abs(a[0]-b[0]), abs(a[1]-b[1]))",
    3: "max(max(abs(a[0]-b[0]), abs(a[1]-b[1])), abs(a[2]-b[2]))",
    4: "max(max(abs(a[0]-b[0]), abs(a[1]-b[1])), max(abs(a[2]-b[2]), abs(a[3]-b[3])))",
}
for _name in ("mat2", "mat2x3", "mat2x4", "mat3x2", "mat3", "mat3x4", "mat4x2", "mat4x3", "mat4"):
    _cols = int(_name[3])
    _rows = int(_name[5]) if "x" in _name else _cols
    CMP_EPSILON[_name] = (f"bool isOk ({_name} a, {_name} b, float eps) {{ vec{_rows} diff = "
                          f"{_MAT_DIFF[_cols]}; "
                          f"return all(lessThanEqual(diff, vec{_rows}(eps))); }}")

# Version spellings of glsShaderLibrary.js (a case without `version` is GLSL ES 1.00).
VERSIONS = {("100", "es"): "100", ("300", "es"): "300 es", ("310", "es"): "310 es",
            **{(v, ""): v for v in ("130", "140", "150", "330", "400", "410", "420", "430",
                                     "440", "450")}}
EXPECTATIONS = {"pass": "pass", "compile_fail": "compile_fail", "link_fail": "link_fail",
                "compile_or_link_fail": "compile_or_link_fail", "build_successful": "pass"}


class ParseError(Exception):
    pass


@dataclass
class Value:
    storage: str  # input, output or uniform
    type_name: str
    name: str


@dataclass
class Requirement:
    text: str                                     # the manifest's spelling
    extensions: list = field(default_factory=list)  # any-of list for an extension requirement
    stages: tuple = ("vertex", "fragment")          # stages an extension is enabled in


@dataclass
class Case:
    name: str
    line: int
    group_path: list
    version: str = "100"
    version_line: bool = False  # whether the case states its version
    expect_raw: str = "pass"
    values: list = field(default_factory=list)  # the first `values` block, the one the harness uses
    both: str = ""
    vertex: str = ""
    fragment: str = ""
    requirements: list = field(default_factory=list)


# --- .test parser (glsShaderLibrary.js) --------------------------------------------------------

WHITESPACE = " \t\r\n"
NAME_CHARS = re.compile(r"[A-Za-z0-9_\-.]")
SYMBOLS = "=+-,|;()[]{}>"


def parse_string_literal_helper(token, end, trim_front=False):
    """Strips the delimiters, optionally the leading blank lines, and resolves backslash escapes
    (\\n, \\t, anything else stands for itself), as parseStringLiteralHelper does."""
    index_end = 0
    while True:
        index_end = token.find(end, index_end + 1)
        if not (index_end >= 0 and token[index_end - 1] == "\\"):
            break
    if index_end <= 0:
        index_end = len(token)
    text = token[len(end):index_end]
    if trim_front:
        text = re.sub(r"^\s*\n", "", text, count=1)
    out, i = [], 0
    while i < len(text):
        if text[i] == "\\":
            nxt = text[i + 1] if i + 1 < len(text) else ""
            out.append({"n": "\n", "t": "\t"}.get(nxt, nxt))
            i += 2
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def remove_extra_indentation(text):
    """Removes the first line's indentation (a tab counts 4) from every line."""
    lines = re.split(r"\r\n|\r|\n", text)
    indent = 0
    for ch in lines[0]:
        if ch not in WHITESPACE:
            break
        indent += 4 if ch == "\t" else 1
    out = []
    for line in lines:
        removed, j = 0, 0
        while removed < indent and j < len(line) and line[j] in WHITESPACE:
            removed += 4 if line[j] == "\t" else 1
            j += 1
        out.append(line[j:])
    return "\n".join(out)


class Parser:
    """Recursive-descent parser of one .test file; tokens as in advanceTokenWorker."""

    def __init__(self, text, path):
        self.text = text
        self.path = path
        self.newlines = [i for i, ch in enumerate(text) if ch == "\n"]
        self.pos = 0
        self.kind = ""  # eof, source, string, int, float, name, or the symbol itself
        self.tok = ""
        self.tok_start = 0
        self.advance()

    def line_of(self, offset):
        return bisect.bisect_left(self.newlines, offset) + 1

    def error(self, message):
        raise ParseError(f"{self.path}:{self.line_of(self.tok_start)}: {message} "
                         f"(at {self.tok!r})")

    def advance(self, expected=None):
        if expected is not None:
            self.expect(expected)
        text, p = self.text, self.pos + len(self.tok)
        while True:  # whitespace and '#' comments to the end of the line
            while p < len(text) and text[p] in WHITESPACE:
                p += 1
            if p < len(text) and text[p] == "#":
                while p < len(text) and text[p] not in "\r\n":
                    p += 1
            else:
                break
        self.pos = self.tok_start = p
        if p >= len(text):
            self.kind, self.tok = "eof", ""
            return
        ch = text[p]
        end = p + 1
        if ch.isascii() and ch.isalpha():
            while end < len(text) and NAME_CHARS.match(text[end]):
                end += 1
            self.kind = "name"
        elif ch.isdigit():
            end = p
            while end < len(text) and text[end].isdigit():
                end += 1
            self.kind = "int"
            if end < len(text) and text[end] == ".":
                end += 1
                while end < len(text) and text[end].isdigit():
                    end += 1
                if end < len(text) and text[end] in "eE":
                    end += 1
                    if end < len(text) and text[end] in "+-":
                        end += 1
                    while end < len(text) and text[end].isdigit():
                        end += 1
                self.kind = "float"
        elif text.startswith('""', p):
            end = p + 2
            while not text.startswith('""', end):
                if end >= len(text):
                    self.error("unterminated shader source")
                end += 2 if text[end] == "\\" else 1
            end += 2
            self.kind = "source"
        elif ch in "\"'":
            while end < len(text) and text[end] != ch:
                end += 2 if text[end] == "\\" else 1
            if end >= len(text):
                self.error("unterminated string")
            end += 1
            self.kind = "string"
        elif ch in SYMBOLS:
            self.kind = ch
        else:
            self.kind = "invalid"
        self.tok = text[p:end]

    def is_name(self, word):
        return self.kind == "name" and self.tok == word

    def expect(self, kind):
        if self.kind != kind and not self.is_name(kind):
            self.error(f"expected {kind}")

    def parse_file(self):
        nodes = []
        while self.kind != "eof":
            self.parse_node(nodes, [])
        return nodes

    def parse_node(self, out, group_path):
        if self.is_name("case"):
            out.append(self.parse_case(group_path))
        elif self.is_name("group"):
            self.parse_group(out, group_path)
        else:
            self.error("expected 'case' or 'group'")

    def parse_group(self, out, group_path):
        self.advance("group")
        name = self.tok  # any token may name a group
        self.advance()
        self.advance("string")  # description
        path = group_path + [name]
        while not self.is_name("end"):
            if self.kind == "eof":
                self.error("group not closed")
            self.parse_node(out, path)
        self.advance("end")

    def parse_case(self, group_path):
        line = self.line_of(self.tok_start)
        self.advance("case")
        case = Case(name=self.tok, line=line, group_path=group_path)
        self.advance()  # any token may name a case
        blocks = []
        while not self.is_name("end"):
            word = self.tok if self.kind == "name" else None
            if word == "desc":
                self.advance()
                self.advance("string")
            elif word == "expect":
                self.advance()
                self.expect("name")
                if self.tok not in EXPECTATIONS:
                    self.error("invalid expected result value")
                case.expect_raw = self.tok
                self.advance()
            elif word == "values":
                blocks.append(self.parse_value_block())
            elif word in ("both", "vertex", "fragment"):
                self.advance()
                self.expect("source")
                source = remove_extra_indentation(
                    parse_string_literal_helper(self.tok, '""', trim_front=True))
                setattr(case, word, source)
                self.advance()
            elif word == "version":
                self.advance()
                self.expect("int")
                number = self.tok
                self.advance()
                postfix = ""
                if self.kind == "name":
                    postfix = self.tok
                    self.advance()
                if (number, postfix) not in VERSIONS:
                    self.error(f"unknown GLSL version {number} {postfix}")
                case.version = VERSIONS[(number, postfix)]
                case.version_line = True
            elif word == "require":
                case.requirements.append(self.parse_requirement())
            else:
                self.error("unexpected token while parsing shader case")
        self.advance("end")
        if case.both and (case.vertex or case.fragment):
            self.error(f"case {case.name} has both a 'both' and a per-stage source")
        if not case.both and not (case.vertex and case.fragment):
            self.error(f"case {case.name} lacks a vertex or a fragment source")
        case.values = blocks[0] if blocks else []
        return case

    def parse_value_block(self):
        self.advance("values")
        self.advance("{")
        values = []
        while self.kind != "}":
            storage = self.tok if self.kind == "name" else None
            if storage not in ("input", "output", "uniform"):
                self.error("unexpected token when parsing a value block")
            self.advance()
            type_name = self.tok
            if self.kind != "name" or type_name not in DATA_TYPES:
                self.error("unexpected token when parsing value data type")
            self.advance()
            if self.kind == "name":
                name = self.tok
            elif self.kind == "string":
                name = parse_string_literal_helper(self.tok, self.tok[0])
            else:
                self.error("unexpected token when parsing value name")
            self.advance()
            self.advance("=")
            if self.kind == "[":
                self.advance("[")
                self.parse_value_element(type_name)
                while self.kind == "|":
                    self.advance("|")
                    self.parse_value_element(type_name)
                self.advance("]")
            else:
                self.parse_value_element(type_name)
            self.advance(";")
            values.append(Value(storage, type_name, name))
        self.advance("}")
        return values

    def parse_value_element(self, type_name):
        """Consumes one value (the numbers only matter for rendering, so they are not kept)."""
        scalar, size, _ = DATA_TYPES[type_name]
        if size > 1:
            self.advance(type_name)
            self.advance("(")
        for i in range(size):
            if scalar == "bool":
                if not (self.is_name("true") or self.is_name("false")):
                    self.error("expected a bool")
                self.advance()
            else:
                if self.kind == "-":
                    self.advance()
                self.advance("float" if scalar == "float" else "int")
            if i != size - 1:
                self.advance(",")
        if size > 1:
            self.advance(")")

    def parse_requirement(self):
        """`require` of the C++ CTS parser (the JS port has none): `require extension { "A" | "B" }
        [in { vertex, fragment }]`, `require limit "GL_X" > N`, or `require <capability>`."""
        self.advance("require")
        if self.is_name("extension"):
            self.advance()
            self.advance("{")
            names = [parse_string_literal_helper(self.tok, self.tok[0])]
            self.advance("string")
            while self.kind == "|":
                self.advance("|")
                names.append(parse_string_literal_helper(self.tok, self.tok[0]))
                self.advance("string")
            self.advance("}")
            stages = ("vertex", "fragment")
            if self.is_name("in"):
                self.advance()
                self.advance("{")
                stages = [self.tok]
                self.advance("name")
                while self.kind == ",":
                    self.advance(",")
                    stages.append(self.tok)
                    self.advance("name")
                self.advance("}")
            return Requirement("extension:" + "|".join(names), names, tuple(stages))
        if self.is_name("limit"):
            self.advance()
            enum = parse_string_literal_helper(self.tok, self.tok[0])
            self.advance("string")
            self.advance(">")
            reference = self.tok
            self.advance("int")
            return Requirement(f"limit:{enum}>{reference}")
        capability = self.tok
        self.advance("name")
        return Requirement(capability)


# --- shader generation (glsShaderLibraryCase.js) -----------------------------------------------

def uses_inout(version):
    return version not in ("100", "130", "140", "150")


def is_float(value):
    return DATA_TYPES[value.type_name][0] == "float"


def float_type(value):
    return DATA_TYPES[value.type_name][2]


def gen_compare_functions(values, use_float_types):
    """The isOk() helpers for the output types present (genCompareFunctions)."""
    found = {v.type_name for v in values if v.storage == "output"}
    lines = []
    for type_name in CMP_EXACT_TYPES:
        if type_name in found:
            lines.append(CMP_FLOAT_VARYING[type_name] if use_float_types else
                         f"bool isOk ({type_name} a, {type_name} b) {{ return (a == b); }}")
    lines += [text for type_name, text in CMP_EPSILON.items() if type_name in found]
    return "".join(line + "\n" for line in lines)


def gen_compare_op(dst, values, non_float_prefix):
    """Compares every output with its reference uniform and writes the verdict (genCompareOp)."""
    out, first = "", True
    for v in values:
        if v.storage != "output":
            continue
        out += "bool RES = " if first else "RES = RES && "
        first = False
        if is_float(v):
            out += f"isOk({v.name}, ref_{v.name}, 0.05);\n"
        else:
            out += f"isOk({non_float_prefix}{v.name}, ref_{v.name});\n"
    return out + (f"{dst} = vec4(1.0);\n" if first else f"{dst} = vec4(RES, RES, RES, 1.0);\n")


def gen_vertex_shader(case):
    """The vertex shader of a fragment-only case: passes each input through a varying."""
    inout = uses_inout(case.version)
    vtx_in, vtx_out = ("in", "out") if inout else ("attribute", "varying")
    res = f"#version {case.version}\nprecision highp float;\nprecision highp int;\n\n"
    res += f"{vtx_in} highp vec4 dEQP_Position;\n"
    inputs = [v for v in case.values if v.storage == "input"]
    for v in inputs:
        res += f"{vtx_in} {float_type(v)} a_{v.name};\n"
        res += f"{vtx_out} {float_type(v)} {'' if is_float(v) else 'v_'}{v.name};\n"
    res += "\nvoid main()\n {\n\tgl_Position = dEQP_Position;\n"
    for v in inputs:
        res += f"\t{'' if is_float(v) else 'v_'}{v.name} = a_{v.name};\n"
    return res + "}\n"


def gen_fragment_shader(case):
    """The fragment shader of a vertex-only case: checks each output against its reference."""
    inout = uses_inout(case.version)
    frag_in = "in" if inout else "varying"
    prec = "mediump" if case.version == "100" else "highp"
    shader = f"#version {case.version}\nprecision {prec} float;\nprecision {prec} int;\n\n"
    if inout:
        shader += "layout(location = 0) out mediump vec4 dEQP_FragColor;\n\n"
    shader += gen_compare_functions(case.values, True) + "\n"
    for v in case.values:
        if v.storage == "output":
            shader += f"{frag_in} {float_type(v)} {'' if is_float(v) else 'v_'}{v.name};\n"
            shader += f"uniform {v.type_name} ref_{v.name};\n"
    shader += "\nvoid main()\n {\n\t"
    shader += gen_compare_op("dEQP_FragColor" if inout else "gl_FragColor", case.values, "v_")
    return shader + "}\n"


def inject_extension_requirements(source, stage, case):
    """Adds `#extension X : require` before the first non-preprocessor line for each extension
    requirement affecting the stage (injectExtensionRequirements; X is the first listed name,
    where the harness takes the first one the context supports)."""
    extensions = "".join(f"#extension {r.extensions[0]} : require\n" for r in case.requirements
                         if r.extensions and stage in r.stages)
    if not extensions:
        return source
    out, injected = "", False
    for line in source.split("\n"):
        if not injected and not re.match(r"^\s*#", line):
            out += extensions
            injected = True
        out += line + "\n"
    return out


def fill(source, decl_key, decl, replacements):
    """Fills the placeholders; only the declarations have a `:single-line` form."""
    source = source.replace("${" + decl_key + "}", decl)
    source = source.replace("${" + decl_key + ":single-line}", decl.replace("\n", " "))
    for key, text in replacements.items():
        source = source.replace("${" + key + "}", text)
    return source


def specialize_vertex_shader(case):
    """The vertex stage of a `both` case under test (specializeVertexShader)."""
    inout = uses_inout(case.version)
    vtx_in, vtx_out = ("in", "out") if inout else ("attribute", "varying")
    decl = f"{vtx_in} highp vec4 dEQP_Position;\n"
    setup, output = "", "gl_Position = dEQP_Position;\n"
    for v in case.values:
        if v.storage == "input":
            if is_float(v):
                decl += f"{vtx_in} {float_type(v)} {v.name};\n"
            else:
                decl += f"{vtx_in} {float_type(v)} a_{v.name};\n"
                setup += f"{v.type_name} {v.name} = {v.type_name}(a_{v.name});\n"
        elif v.storage == "output":
            if is_float(v):
                decl += f"{vtx_out} {float_type(v)} {v.name};\n"
            else:
                decl += f"{vtx_out} {float_type(v)} v_{v.name};\n{v.type_name} {v.name};\n"
                output += f"v_{v.name} = {float_type(v)}({v.name});\n"
    source = fill(case.vertex or case.both, "DECLARATIONS", decl,
                  {"SETUP": setup, "OUTPUT": output})
    source = source.replace("${POSITION_FRAG_COLOR}", "gl_Position")
    return inject_extension_requirements(source, "vertex", case)


def specialize_fragment_shader(case):
    """The fragment stage of a `both` case under test (specializeFragmentShader)."""
    inout = uses_inout(case.version)
    frag_in = "in" if inout else "varying"
    frag_color = "dEQP_FragColor" if inout else "gl_FragColor"
    decl = gen_compare_functions(case.values, False)
    output = gen_compare_op(frag_color, case.values, "")
    if inout:
        decl += "layout(location = 0) out mediump vec4 dEQP_FragColor;\n"
    setup = ""
    for v in case.values:
        if v.storage == "input":
            if is_float(v):
                decl += f"{frag_in} {float_type(v)} {v.name};\n"
            else:
                decl += f"{frag_in} {float_type(v)} v_{v.name};\n"
                # The harness's nudge against rounding errors of interpolated integers.
                offset = " * 1.0025" if v.type_name in ("int", "ivec2", "ivec3", "ivec4") else ""
                setup += f"{v.type_name} {v.name} = {v.type_name}(v_{v.name}{offset});\n"
        elif v.storage == "output":
            decl += f"uniform {v.type_name} ref_{v.name};\n{v.type_name} {v.name};\n"
    source = fill(case.fragment or case.both, "DECLARATIONS", decl,
                  {"SETUP": setup, "OUTPUT": output})
    source = source.replace("${POSITION_FRAG_COLOR}", frag_color)
    return inject_extension_requirements(source, "fragment", case)


def specialize_vertex_only(case):
    """The vertex stage of a complete case (specializeVertexOnly); uniforms named with a '.'
    (struct members) are left to the source."""
    vtx_in = "in" if uses_inout(case.version) else "attribute"
    decl = f"{vtx_in} highp vec4 dEQP_Position;\n"
    setup, output = "", "gl_Position = dEQP_Position;\n"
    for v in case.values:
        if v.storage == "input":
            if is_float(v):
                decl += f"{vtx_in} {v.type_name} {v.name};\n"
            else:
                decl += f"{vtx_in} {float_type(v)} a_{v.name};\n"
                setup += f"{v.type_name} {v.name} = {v.type_name}(a_{v.name});\n"
        elif v.storage == "uniform" and "." not in v.name:
            decl += f"uniform {v.type_name} {v.name};\n"
    source = fill(case.vertex, "VERTEX_DECLARATIONS", decl,
                  {"VERTEX_SETUP": setup, "VERTEX_OUTPUT": output})
    return inject_extension_requirements(source, "vertex", case)


def specialize_fragment_only(case):
    """The fragment stage of a complete case (specializeFragmentOnly)."""
    inout = uses_inout(case.version)
    frag_color = "dEQP_FragColor" if inout else "gl_FragColor"
    decl = gen_compare_functions(case.values, False)
    output = gen_compare_op(frag_color, case.values, "")
    if inout:
        decl += "layout(location = 0) out mediump vec4 dEQP_FragColor;\n"
    for v in case.values:
        if v.storage == "output":
            decl += f"uniform {v.type_name} ref_{v.name};\n{v.type_name} {v.name};\n"
        elif v.storage == "uniform" and "." not in v.name:
            decl += f"uniform {v.type_name} {v.name};\n"
    source = fill(case.fragment, "FRAGMENT_DECLARATIONS", decl, {"FRAGMENT_OUTPUT": output})
    source = source.replace("${FRAG_COLOR}", frag_color)
    return inject_extension_requirements(source, "fragment", case)


def expand(case):
    """The (name suffix, case_type, test_stage, vertex source, fragment source) of each dEQP
    test a case yields: a `both` case gives _vertex and _fragment, otherwise one complete test."""
    if case.both:
        return [("_vertex", "vertex_only", "vertex", specialize_vertex_shader(case),
                 gen_fragment_shader(case)),
                ("_fragment", "fragment_only", "fragment", gen_vertex_shader(case),
                 specialize_fragment_shader(case))]
    return [("", "complete", "program", specialize_vertex_only(case),
             specialize_fragment_only(case))]


# --- corpus ------------------------------------------------------------------------------------

MANIFEST_COLUMNS = ["id", "suite", "glsl_version", "expect", "expect_raw", "case_type",
                    "test_stage", "vertex_file", "fragment_file", "requires", "in_mustpass",
                    "mustpass_issue_list", "test_file", "line"]
NO_MUSTPASS = "no mustpass list in this source"


def case_key(case):
    """What makes two cases the same test, whatever group they stand in (a split copy may
    regroup them: split-swizzles.js puts swizzles.test's cases into one group per type)."""
    return (case.name, case.version, case.expect_raw, case.both,
            case.vertex, case.fragment, repr(case.values), repr(case.requirements))


def split_parent(stem, stems):
    """The file a WebGL split copy (e.g. conversions_scalar_to_scalar.test, made by
    split-conversions.js from conversions.test) may have been cut from, or None."""
    parts = stem.split("_")
    for n in range(len(parts) - 1, 0, -1):
        candidate = "_".join(parts[:n])
        if candidate in stems:
            return candidate
    return None


def read_source_note(source_dir):
    """SOURCE.txt written by the fetch script, looked for in SOURCE_DIR's ancestors (nearest
    first), or None."""
    for folder in list(source_dir.parents)[:7]:
        note = folder / "SOURCE.txt"
        if note.is_file():
            return note, note.read_text(encoding="utf-8").strip()
    return None


def readme_text(source_dir, suite, counts, skipped, note):
    total = sum(counts.values())
    by_expect = ", ".join(f"{n:,} {e}" for e, n in sorted(counts.items()))
    origin = f"`{source_dir}`"
    if note:
        origin += f"; `{note[0]}` says:\n\n    " + note[1].replace("\n", "\n    ") + "\n"
    skip_text = "".join(f"- {n:,} case(s): {reason}\n" for reason, n in sorted(skipped.items()))
    skip_text = skip_text or "- none\n"
    # The fetch script's source is the WebGL suite's copy; a folder that says nothing of WebGL
    # (its path or its SOURCE.txt) is taken to be native dEQP data.
    webgl_copy = "webgl" in str(source_dir).lower() or bool(note and "webgl" in note[1].lower())
    copy_text = (f"""These are the WebGL conformance suite's copy of the Khronos OpenGL ES CTS (dEQP) data
`data/{suite}/shaders/*.test`; where WebGL changed a case (comments in the `.test` files say so,
e.g. preprocessor cases that must fail in WebGL, or ASCII in place of Unicode), the WebGL
expectation is kept.""" if webgl_copy else f"""These are taken to be the Khronos OpenGL ES CTS (dEQP)
data `data/{suite}/shaders/*.test` itself (neither the folder's path nor a SOURCE.txt names
WebGL), with the files' own expectations.""")
    return f"""# dEQP {suite.upper()} shader cases (external conformance corpus)

{total:,} test cases ({by_expect}) converted from the dEQP shader-case
files `*.test` in {origin}
{copy_text} Licence of the dEQP data: Apache-2.0
(https://www.apache.org/licenses/LICENSE-2.0); no licence file is copied beside this README.

Written by `bench/deqp_tests_to_corpus.py` of tidepool. Each `.test` case has been turned into
complete shader files the way the harness does it, following the WebGL suite's JavaScript port
of the dEQP harness (`deqp/modules/shared/glsShaderLibrary.js`, `glsShaderLibraryCase.js`):
- a `both` case becomes `<case>_vertex` (the source is the vertex shader; the fragment shader is
  the one the harness generates to check the outputs) and `<case>_fragment` (the source is the
  fragment shader; the generated vertex shader feeds the inputs); a case with separate `vertex`
  and `fragment` sources is one `complete` case;
- `${{DECLARATIONS}}`, `${{SETUP}}`, `${{OUTPUT}}`, `${{POSITION_FRAG_COLOR}}`,
  `${{VERTEX_DECLARATIONS}}`, `${{VERTEX_SETUP}}`, `${{VERTEX_OUTPUT}}`,
  `${{FRAGMENT_DECLARATIONS}}`, `${{FRAGMENT_OUTPUT}}`, `${{FRAG_COLOR}}` (and the `:single-line`
  forms) are filled as the JS harness fills them: GLSL ES 3.00 cases use `in`/`out` and
  `layout(location = 0) out mediump vec4 dEQP_FragColor`, 1.00 cases `attribute`/`varying` and
  `gl_FragColor`; non-float inputs and outputs travel through float varyings (`a_`/`v_` names)
  and are converted, as the JS harness does (it uses no `flat` varyings);
- a case without a `version` line is GLSL ES 1.00 to the generator, as in the harness; only a
  case's first `values` block is used, as in the harness;
- a `require` line (C++ CTS syntax; the JS parser has none) goes to `requires`, and an extension
  requirement adds `#extension <first name> : require` to the stages it names, as the harness
  does with the first extension the context supports.

Where the JS port and the C++ CTS (glsShaderLibraryCase.cpp) could differ, the JS port was
followed; the whitespace of generated code differs from the C++ harness's.

Cases left out:
{skip_text}
`manifest.tsv` columns:
- `id`: the dEQP test name (`dEQP-{suite.upper()}.functional.shaders.<file>.<groups>.<case>`);
  `suite`: {suite}; `glsl_version`: the case's `version` line or, without one, the `#version` of
  its own source (`300 es`, `100 es`).
- `expect`: `pass` (both stages compile and the program links), `compile_fail` (the stage under
  test must fail to compile), `link_fail` (each stage compiles, the program must fail to link),
  `compile_or_link_fail` (the build must fail somewhere); `expect_raw`: the `.test` file's word
  (`build_successful` is counted as `pass`).
- `case_type`: `vertex_only`, `fragment_only` or `complete`; `test_stage`: the stage under test
  (`program` for complete cases).
- `vertex_file`, `fragment_file`: paths relative to this folder.
- `requires`: the case's `require` lines, `;`-separated (`extension:A|B`, `limit:GL_X>N` or a
  capability name); empty for most.
- `in_mustpass`: `False` for every case, and `mustpass_issue_list`: `{NO_MUSTPASS}`:
  this source carries no Khronos must-pass list, so no case is known to be in it.
- `test_file`, `line`: where the case's `case` keyword stands in the original `.test` file.
"""


def manifest_version(case):
    """The language version of the case's shaders: its `version` line, or, without one (the
    harness then assumes 1.00), the `#version` its own source starts with."""
    declared = re.match(r"\s*#\s*version\s+(\d+(?:\s+es)?)", case.vertex or case.both)
    version = declared.group(1).split()[0] if declared and not case.version_line else case.version
    return f"{version} es" if version in ("100", "300", "310") else version


def convert(source_dir, suite):
    """Parses every .test file; returns (rows, files {relative path: text}, counts, skipped)."""
    parsed = {}
    for path in sorted(source_dir.glob("*.test")):
        parser = Parser(path.read_text(encoding="utf-8"), path)
        parsed[path.stem] = parser.parse_file()
    known = {stem: {case_key(c) for c in cases} for stem, cases in parsed.items()}
    rows, files, counts, skipped = [], {}, {}, {}
    for stem, cases in parsed.items():
        parent = split_parent(stem, parsed)
        for case in cases:
            tests = expand(case)
            if parent and case_key(case) in known[parent]:
                reason = f"same case as in {parent}.test (a WebGL split copy of it)"
                skipped[reason] = skipped.get(reason, 0) + len(tests)
                continue
            for suffix, case_type, stage, vert, frag in tests:
                name = ".".join(case.group_path + [case.name + suffix])
                expect = EXPECTATIONS[case.expect_raw]
                files[f"{stem}/{name}.vert"] = vert
                files[f"{stem}/{name}.frag"] = frag
                rows.append([f"dEQP-{suite.upper()}.functional.shaders.{stem}.{name}", suite,
                             manifest_version(case), expect, case.expect_raw, case_type, stage,
                             f"{stem}/{name}.vert", f"{stem}/{name}.frag",
                             ";".join(r.text for r in case.requirements), "False", NO_MUSTPASS,
                             f"data/{suite}/shaders/{stem}.test", str(case.line)])
                counts[expect] = counts.get(expect, 0) + 1
    return rows, files, counts, skipped


def inside_repository(path):
    """Whether `path` lies in this repository, where an external corpus must not be written."""
    return path == REPO_ROOT or REPO_ROOT in path.parents


def write_corpus(out_dir, columns, rows, files, readme):
    """Writes everything to OUT_DIR.tmp, then swaps it in for OUT_DIR (also used by
    webgl_glsl_to_corpus.py, whose manifest has two more columns)."""
    tmp = out_dir.with_name(out_dir.name + ".tmp")
    old = out_dir.with_name(out_dir.name + ".old")
    for leftover in (tmp, old):
        if leftover.exists():
            shutil.rmtree(leftover)
    tmp.mkdir(parents=True)
    for rel, text in files.items():
        (tmp / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp / rel).write_text(text, encoding="utf-8")
    manifest = "\t".join(columns) + "\n" + "".join("\t".join(r) + "\n" for r in rows)
    (tmp / "manifest.tsv").write_text(manifest, encoding="utf-8")
    (tmp / "README.md").write_text(readme, encoding="utf-8")
    if out_dir.exists():
        out_dir.rename(old)
    tmp.rename(out_dir)
    if old.exists():
        shutil.rmtree(old)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("source_dir", type=Path)
    parser.add_argument("out_dir", type=Path)
    parser.add_argument("--suite", default="gles3")
    args = parser.parse_args(argv)  # exits 2 on bad arguments
    source_dir = args.source_dir.resolve()
    out_dir = args.out_dir.resolve()
    if inside_repository(out_dir):
        print(f"error: OUT_DIR {out_dir} is inside the repository {REPO_ROOT}; the corpus is "
              "external data and must be written elsewhere", file=sys.stderr)
        return EXIT_USAGE
    if not source_dir.is_dir() or not any(source_dir.glob("*.test")):
        print(f"error: no .test files in {source_dir}", file=sys.stderr)
        return EXIT_USAGE
    try:
        rows, files, counts, skipped = convert(source_dir, args.suite)
    except (ParseError, OSError, UnicodeDecodeError) as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_FAILED
    readme = readme_text(source_dir, args.suite, counts, skipped, read_source_note(source_dir))
    try:
        write_corpus(out_dir, MANIFEST_COLUMNS, rows, files, readme)
    except OSError as error:
        print(f"error: writing {out_dir}: {error}", file=sys.stderr)
        return EXIT_FAILED
    written = ", ".join(f"{e} {n}" for e, n in sorted(counts.items()))
    skips = "; ".join(f"{n} {reason}" for reason, n in sorted(skipped.items())) or "none"
    print(f"{out_dir}: {len(rows)} cases written ({written}); skipped {sum(skipped.values())} "
          f"({skips})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
