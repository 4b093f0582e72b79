#!/usr/bin/python3
"""Generate the mechanical part of the Python and Fortran bindings from capi/include/wefm/wefm.h.

    /usr/bin/python3 scripts/gen_bindings.py            # rewrite the generated files in the tree
    /usr/bin/python3 scripts/gen_bindings.py --check    # regenerate into a temporary folder and
                                                        # diff with the committed files (exit 1 if stale)
    /usr/bin/python3 scripts/gen_bindings.py --header H --out DIR   # another header, another root

Why the header is the single source (and not an API description that would generate the header too,
as Gmsh's api/gen.py does): wefm.h is the hand-written, documented contract. Its prose (conventions,
per-function errors) is what users and the Doxygen reference read, its ABI is pinned by capi/abi/ and
checked by ctest, and C and C++ callers include it as written. A description file generating it
would have to carry all that prose in a second syntax and would turn every comment edit into a
generator run. The header is regular enough to parse instead: `typedef enum`, `typedef struct` with
plain fields, `#define NAME <integer expression>`, `typedef R (*name)(...)` callbacks and one
`WEFM_API R wefm_name(...);` per function. Anything outside that grammar (an unknown type, a pointer
whose role cannot be told) stops the generator with a message naming it, so nothing is guessed.

What is generated depends only on declarations (names, types, order), never on comments: an edit of
the header's prose leaves the generated files unchanged. Like Gmsh's GenApi, each C type is mapped
once to its form in every language (TYPES below) and each output is written from that table.

Outputs (each starts with a line saying it is generated and from what):
  bindings/python/wefm/_structs.py      constants (enums, #defines) and ctypes struct classes
  bindings/python/wefm/_prototypes.py   callback types and argtypes/restype of every function
  bindings/fortran/wefm_types.inc       integer parameters and bind(C) derived types
  bindings/fortran/wefm_interfaces.inc  bind(C) interfaces of every function and callback
  tests/python/c/struct_layout.c        offsets as the C compiler lays the structs out, and
  tests/fortran/struct_layout.f90       as gfortran does, for tests/python/test_layout.py
The idiomatic layers (wefm.Face, _checked.py, _api.py's loader, the wefm_f_* Fortran wrappers) are
hand-written on top of these.
"""
import argparse
import difflib
import os
import re
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEADER = "capi/include/wefm/wefm.h"
REGENERATE = "/usr/bin/python3 scripts/gen_bindings.py"
PREFIX = "wefm_"

# Each C scalar type once: (ctypes name, Fortran type).
TYPES = {
    "size_t": ("c_size_t", "integer(c_size_t)"),
    "int": ("c_int", "integer(c_int)"),
    "int32_t": ("c_int32", "integer(c_int32_t)"),
    "int64_t": ("c_int64", "integer(c_int64_t)"),
    "double": ("c_double", "real(c_double)"),
}
# Short ctypes names for pointers to numbers in the prototype table.
POINTER_ALIASES = {"double": "_d", "int32_t": "_i32", "int64_t": "_i64"}

# A non-const pointer to a number that no `capacity` parameter follows is either one value the call
# writes (Fortran: a scalar with intent(out)) or an array of `n` values (Fortran: type(c_ptr), value,
# so c_null_ptr may be passed). Types cannot tell which; the header's parameter names do.
SCALAR_OUTPUT_NAMES = {"count", "repeated", "solved", "loop", "value"}  # and every name ending in _id
PER_POINT_OUTPUT_NAMES = {"xyz", "uv", "point_status", "triangles"}


class HeaderError(Exception):
    """The header has a declaration this generator does not understand."""


# ---- parsing ------------------------------------------------------------------------------------

def strip_comments(text):
    """Text without /* */ and // comments (a comment becomes one space)."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def split_declaration(decl, where):
    """'const wefm_face* face' -> (const, base type, pointer depth, name)."""
    decl = " ".join(decl.replace("*", " * ").split())
    m = re.fullmatch(r"(const )?(\w+)((?: \*)*) (\w+)", decl)
    if not m:
        raise HeaderError("%s: cannot read the declaration %r" % (where, decl))
    return bool(m.group(1)), m.group(2), m.group(3).count("*"), m.group(4)


def parse_enums(text):
    enums = []
    for m in re.finditer(r"typedef\s+enum\s+\w+\s*\{(.*?)\}\s*(\w+)\s*;", text, re.S):
        members, value = [], -1
        for item in filter(None, (s.strip() for s in m.group(1).split(","))):
            name, _, expr = (s.strip() for s in item.partition("="))
            try:
                value = int(expr, 0) if expr else value + 1
            except ValueError:
                raise HeaderError("%s: the value of %s is not an integer literal" % (m.group(2), name))
            members.append((name, value))
        enums.append((m.group(2), members))
    return enums


def parse_defines(text):
    """Object-like macros whose value is an integer expression of literals and earlier macros."""
    defines, values = [], {}
    for m in re.finditer(r"^[ \t]*#[ \t]*define[ \t]+(WEFM_\w+)[ \t]+([^\n]+)$", text, re.M):
        name, expr = m.group(1), " ".join(m.group(2).split())
        tokens = re.findall(r"\w+|\S", expr)
        if not all(t.isdigit() or t in values or t in "()+-*" for t in tokens):
            continue  # not an integer constant (WEFM_API and the like)
        values[name] = eval(" ".join(str(values.get(t, t)) for t in tokens), {"__builtins__": {}})
        defines.append((name, expr, values[name]))
    return defines


def parse_structs(text):
    structs, opaque = [], set()
    for m in re.finditer(r"typedef\s+struct\s+(\w+)\s+(\w+)\s*;", text):
        opaque.add(m.group(2))
    for m in re.finditer(r"typedef\s+struct\s+\w+\s*\{(.*?)\}\s*(\w+)\s*;", text, re.S):
        name, fields = m.group(2), []
        for decl in filter(None, (s.strip() for s in m.group(1).split(";"))):
            first = re.match(r"(\w+)\s+(.*)", decl, re.S)
            ctype = first.group(1) if first else decl
            if ctype not in TYPES:
                raise HeaderError("%s: field type %r of %r has no mapping in gen_bindings.py TYPES"
                                  % (name, ctype, decl))
            for item in first.group(2).split(","):
                f = re.fullmatch(r"\s*(\w+)\s*(?:\[\s*(\d+)\s*\])?\s*", item)
                if not f:
                    raise HeaderError("%s: cannot read the field %r" % (name, item.strip()))
                fields.append((f.group(1), ctype, int(f.group(2)) if f.group(2) else None))
        structs.append((name, fields))
    return structs, opaque


def parse_callbacks(text):
    out = []
    for m in re.finditer(r"typedef\s+([\w\s\*]+?)\(\s*\*\s*(\w+)\s*\)\s*\((.*?)\)\s*;", text, re.S):
        out.append((m.group(2), m.group(1).strip(), split_params(m.group(3), m.group(2))))
    return out


def split_params(params, where):
    params = " ".join(params.split())
    if params in ("", "void"):
        return []
    return [split_declaration(p, where) for p in params.split(",")]


def parse_functions(text):
    out = []
    for m in re.finditer(r"\bWEFM_API\s+([^;(]*?)\s*\b(wefm_\w+)\s*\(([^)]*)\)\s*;", text):
        out.append((m.group(2), " ".join(m.group(1).split()), split_params(m.group(3), m.group(2))))
    if not out:
        raise HeaderError("no WEFM_API function found")
    return out


class Api:
    """Everything the generators need, in header order."""

    def __init__(self, header_text):
        text = strip_comments(header_text)
        self.defines = parse_defines(text)
        self.enums = parse_enums(text)
        self.structs, self.opaque = parse_structs(text)
        self.callbacks = parse_callbacks(text)
        self.functions = parse_functions(text)
        self.enum_names = {name for name, _ in self.enums}
        self.struct_names = {name for name, _ in self.structs}
        self.callback_names = {name for name, _, _ in self.callbacks}
        for fn, _, params in self.functions:  # every parameter understood, or a HeaderError now
            self.roles(fn, params)

    def classify(self, fn, index, params):
        """Role of parameter `index` of `fn`: value, enum, handle, handle_out, struct_in, struct_inout,
        string, array, scalar_out, callback, pointer."""
        const, base, depth, name = params[index]
        where = "%s: parameter %s" % (fn, name)
        if depth == 0:
            if base in TYPES:
                return "value"
            if base in self.enum_names:
                return "enum"
            if base in self.callback_names:
                return "callback"
        elif base == "void" and depth == 1:
            return "pointer"
        elif base in self.opaque:
            return {1: "handle", 2: "handle_out"}.get(depth) or self.unknown(where)
        elif depth == 1 and base in self.struct_names:
            return "struct_in" if const else "struct_inout"
        elif depth == 1 and base == "char" and const:
            return "string"
        elif depth == 1 and base in POINTER_ALIASES:
            if const:
                return "array"
            following = params[index + 1] if index + 1 < len(params) else None
            if following and following[3] == "capacity":
                return "array"
            if name in SCALAR_OUTPUT_NAMES or name.endswith("_id"):
                return "scalar_out"
            if name in PER_POINT_OUTPUT_NAMES:
                return "array"
            raise HeaderError("%s: %s* is one output value or an array? Add %r to SCALAR_OUTPUT_NAMES "
                              "or PER_POINT_OUTPUT_NAMES in scripts/gen_bindings.py"
                              % (where, base, name))
        return self.unknown(where)

    @staticmethod
    def unknown(where):
        raise HeaderError("%s has a type gen_bindings.py does not map" % where)

    def roles(self, fn, params):
        return [self.classify(fn, i, params) for i in range(len(params))]


def short(name):
    """wefm_face_solve -> face_solve."""
    return name[len(PREFIX):] if name.startswith(PREFIX) else name


def class_name(struct):
    """wefm_mesh_info -> MeshInfo."""
    return "".join(w.capitalize() for w in short(struct).split("_"))


def constant_name(name):
    """WEFM_ERROR_IO -> ERROR_IO (the package is the namespace in Python)."""
    return name[len(PREFIX):] if name.lower().startswith(PREFIX) else name


# ---- Python ---------------------------------------------------------------------------------------

def banner(comment, source, purpose):
    return ["%s Generated by scripts/gen_bindings.py from %s: do not edit." % (comment, source),
            "%s Regenerate with %s; %s" % (comment, REGENERATE, purpose)]


def python_structs(api):
    used = sorted({TYPES[t][0] for _, fields in api.structs for _, t, _ in fields})
    out = banner("#", HEADER, "constants and ctypes structs.")
    out += ['"""Constants and ctypes structs of wefm.h.', "",
            "Fields are in header order: the library reads these structs by layout",
            '(tests/python/test_layout.py compares every offset with the C compiler\'s).', '"""',
            "import ctypes", "from ctypes import %s" % ", ".join(used), ""]
    for name, expr, value in api.defines:
        out.append("%s = %d  # %s" % (constant_name(name), value, expr) if not expr.isdigit()
                   else "%s = %s" % (constant_name(name), expr))
    for enum, members in api.enums:
        out += ["", "# %s" % enum] + ["%s = %d" % (constant_name(n), v) for n, v in members]
    for struct, fields in api.structs:
        out += ["", "", "class %s(ctypes.Structure):" % class_name(struct),
                '    """struct %s."""' % struct, "    _fields_ = ["]
        for field, ctype, length in fields:
            t = TYPES[ctype][0] + (" * %d" % length if length else "")
            out.append('        ("%s", %s),' % (field, t))
        out.append("    ]")
    out += ["", "", "# {C name: ctypes class}", "STRUCTS = {"]
    out += ['    "%s": %s,' % (s, class_name(s)) for s, _ in api.structs] + ["}"]
    return "\n".join(out) + "\n"


def python_argtype(param, role):
    base = param[1]
    if role in ("handle", "pointer"):
        return "c_void_p"
    if role in ("struct_in", "struct_inout"):
        return "POINTER(%s)" % class_name(base)
    if role in ("array", "scalar_out"):
        return POINTER_ALIASES[base]
    return {"value": TYPES.get(base, ("",))[0], "enum": "c_int", "callback": short(base).upper(),
            "handle_out": "_vpp", "string": "c_char_p"}[role]


def python_restype(api, ret, where):
    if ret == "void":
        return "None"
    if ret == "const char*" or ret == "const char *":
        return "c_char_p"
    if ret in api.enum_names:
        return "_S" if ret == "wefm_status" else "c_int"
    if ret in TYPES:
        return TYPES[ret][0]
    raise HeaderError("%s: return type %r has no mapping in gen_bindings.py" % (where, ret))


def python_callback(api, name, ret, params):
    types = [python_restype(api, ret, name)]
    for const, base, depth, pname in params:
        if depth == 1 and base == "void":
            types.append("c_void_p")
        elif depth == 1 and base == "char" and const:
            types.append("c_char_p")
        elif depth == 0 and base in TYPES:
            types.append(TYPES[base][0])
        else:
            raise HeaderError("%s: callback parameter %s has no mapping" % (name, pname))
    sig = ", ".join("%s%s %s" % ("const " if c else "", b + "*" * d, n) for c, b, d, n in params)
    return ["# %s (*%s)(%s)" % (ret, name, sig),
            "%s = ctypes.CFUNCTYPE(%s)" % (short(name).upper(), ", ".join(types))]


def python_prototypes(api):
    structs = ", ".join(sorted(class_name(s) for s, _ in api.structs))
    out = banner("#", HEADER, "function prototypes.")
    out += ['"""Callback types and the prototype of every function of wefm.h, for _api to apply.', "",
            "PROTOTYPES maps the name without wefm_ to (restype, \"parameter names as in wefm.h\", [argtypes]).",
            "Handles are c_void_p; pointers to numbers are POINTER(...) whether they point at one value or",
            'an array.', '"""',
            "import ctypes",
            "from ctypes import POINTER, c_char_p, c_double, c_int, c_int32, c_int64, c_size_t, c_void_p",
            "", "from ._structs import %s" % structs, ""]
    for name, ret, params in api.callbacks:
        out += python_callback(api, name, ret, params)
    out += ["", "_d = POINTER(c_double)", "_i32 = POINTER(c_int32)", "_i64 = POINTER(c_int64)",
            "_vpp = POINTER(c_void_p)", "_S = c_int  # wefm_status: a C enum, int-sized on every ABI we target",
            "", "PROTOTYPES = {"]
    for fn, ret, params in api.functions:
        roles = api.roles(fn, params)
        argtypes = ", ".join(python_argtype(p, r) for p, r in zip(params, roles))
        line = '    "%s": (%s, "%s", [%s]),' % (short(fn), python_restype(api, ret, fn),
                                                 " ".join(p[3] for p in params), argtypes)
        if len(line) > 110:
            head = '    "%s": (%s, "%s",' % (short(fn), python_restype(api, ret, fn),
                                             " ".join(p[3] for p in params))
            line = head + "\n" + " " * (len(short(fn)) + 8) + "[%s])," % argtypes
        out.append(line)
    out.append("}")
    return "\n".join(out) + "\n"


# ---- Fortran --------------------------------------------------------------------------------------

def fortran_constant_names(api):
    """C name -> Fortran name: Fortran is case-insensitive, so a constant spelled like a function
    (WEFM_VERSION_NUMBER, wefm_version_number) becomes WEFM_HEADER_..."""
    taken = {fn.lower() for fn, _, _ in api.functions} | {s.lower() for s in api.struct_names}
    names = [n for n, _, _ in api.defines] + [n for _, members in api.enums for n, _ in members]
    return {n: ("WEFM_HEADER_" + n[len("WEFM_"):] if n.lower() in taken else n) for n in names}


def fortran_types(api):
    rename = fortran_constant_names(api)
    out = banner("!", HEADER, "included by wefm.f90.")
    out.append("! Field order and kinds follow the header exactly: the library reads the structs by layout.")
    out += ["", "! ---- #define ----"]
    for name, expr, _ in api.defines:
        expr = re.sub(r"\w+", lambda t: rename.get(t.group(0), t.group(0)), expr)
        out += fortran_wrap("integer(c_int), parameter :: %s = %s" % (rename[name], expr))
    for enum, members in api.enums:
        out += ["", "! ---- %s ----" % enum]
        out += ["integer(c_int), parameter :: %s = %d" % (rename[n], v) for n, v in members]
    for struct, fields in api.structs:
        out += ["", "type, bind(C) :: %s" % struct]
        for field, ctype, length in fields:
            out.append("  %s :: %s%s" % (TYPES[ctype][1], field, "(%d)" % length if length else ""))
        out.append("end type %s" % struct)
    return "\n".join(out) + "\n"


def fortran_wrap(line, width=100):
    """A statement as free-form lines of at most `width` characters, continued with '&' at spaces
    (gfortran refuses lines past 132)."""
    out = []
    while len(line) > width:
        cut = line.rindex(" ", 0, width - 2)
        out.append(line[:cut] + " &")
        line = "    " + line[cut + 1:]
    return out + [line]


def fortran_kind(decl):
    """'integer(c_int64_t)' -> 'c_int64_t'."""
    return decl[decl.index("(") + 1:-1]


def fortran_dummy(api, param, role):
    """(declaration, names to import) of one dummy argument."""
    _, base, _, name = param
    if role == "value":
        return "%s, value :: %s" % (TYPES[base][1], name), {fortran_kind(TYPES[base][1])}
    if role == "enum":
        return "integer(c_int), value :: %s" % name, {"c_int"}
    if role == "callback":  # c_funloc of a procedure with the callback's abstract interface
        return "type(c_funptr), value :: %s" % name, {"c_funptr"}
    if role in ("handle", "array", "pointer"):
        return "type(c_ptr), value :: %s" % name, {"c_ptr"}
    if role == "handle_out":
        return "type(c_ptr), intent(out) :: %s" % name, {"c_ptr"}
    if role in ("struct_in", "struct_inout"):
        return "type(%s), intent(%s) :: %s" % (base, role[len("struct_"):], name), {base}
    if role == "string":
        return "character(kind=c_char), intent(in) :: %s(*)" % name, {"c_char"}
    if role == "scalar_out":
        return "%s, intent(out) :: %s" % (TYPES[base][1], name), {fortran_kind(TYPES[base][1])}
    raise HeaderError("no Fortran form for role %s" % role)


def fortran_result(api, ret, where):
    """(declaration type, import) of a function result; None for void."""
    if ret == "void":
        return None
    if ret in ("const char*", "const char *"):
        return "type(c_ptr)", "c_ptr"
    if ret in api.enum_names:
        return "integer(c_int)", "c_int"
    if ret in TYPES:
        return TYPES[ret][1], fortran_kind(TYPES[ret][1])
    raise HeaderError("%s: return type %r has no Fortran mapping" % (where, ret))


def fortran_procedure(name, ret, dummies, bind):
    """One interface body: dummies as (declaration, imports)."""
    kind = "function" if ret else "subroutine"
    imports = set().union(*(i for _, i in dummies)) | ({ret[1]} if ret else set())
    args = ", ".join(d[0].split("::")[1].strip().split("(")[0] for d in dummies)
    first = "  %s %s(%s) bind(C%s)" % (kind, name, args, ', name="%s"' % name if bind else "")
    if len(first) > 100:
        first = "  %s %s(%s) &\n      bind(C%s)" % (kind, name, args, ', name="%s"' % name if bind else "")
    out = [first]
    if imports:
        out.append("    import :: %s" % ", ".join(sorted(imports)))
    out += ["    " + d for d, _ in dummies]
    if ret:
        out.append("    %s :: %s" % (ret[0], name))
    out.append("  end %s" % kind)
    return out


def fortran_interfaces(api):
    out = banner("!", HEADER, "included by wefm.f90.")
    out += ["! Handles and arrays are type(c_ptr) by value (c_loc(x), or c_null_ptr where the header allows",
            "! NULL); single outputs and structs are passed by reference; const char* inputs are",
            "! NUL-terminated character arrays (trim(s)//c_null_char); const char* results are type(c_ptr)",
            "! (wefm_f_string turns them into Fortran strings); a callback is type(c_funptr): c_funloc of a",
            "! bind(C) procedure with the abstract interface of its type below.", ""]
    if api.callbacks:
        out.append("abstract interface")
        for name, ret, params in api.callbacks:
            dummies = [fortran_dummy(api, p, "pointer" if p[2] == 1 else "value") for p in params
                       if p[2] == 1 or p[1] in TYPES or api.unknown("%s: parameter %s" % (name, p[3]))]
            out += fortran_procedure(name, fortran_result(api, ret, name), dummies, bind=False)
        out += ["end interface", ""]
    out.append("interface")
    for fn, ret, params in api.functions:
        roles = api.roles(fn, params)
        dummies = [fortran_dummy(api, p, r) for p, r in zip(params, roles)]
        out += fortran_procedure(fn, fortran_result(api, ret, fn), dummies, bind=True)
    out.append("end interface")
    return "\n".join(out) + "\n"


# ---- layout helpers of the tests ------------------------------------------------------------------

def c_layout(api):
    out = ["/* Generated by scripts/gen_bindings.py from %s: do not edit." % HEADER,
           " * Regenerate with %s." % REGENERATE,
           " * Prints sizeof and every field offset of the public structs, as the C compiler lays them out,",
           " * for tests/python/test_layout.py to compare with the ctypes mirrors and the Fortran types. */",
           "#include <stddef.h>", "#include <stdio.h>", "#include <wefm/wefm.h>", "",
           '#define SIZE(s) printf(#s " sizeof %zu\\n", sizeof(s))',
           '#define FIELD(s, f) printf(#s " " #f " %zu\\n", offsetof(s, f))', "", "int main(void) {"]
    for struct, fields in api.structs:
        out.append("  SIZE(%s);" % struct)
        out += ["  FIELD(%s, %s);" % (struct, f) for f, _, _ in fields]
    out += ["  return 0;", "}"]
    return "\n".join(out) + "\n"


def fortran_layout(api):
    out = banner("!", HEADER, "a test helper.")
    out += ["! Prints sizeof and field offsets of the bind(C) types of module wefm in the format of",
            "! tests/python/c/struct_layout.c, for tests/python/test_layout.py.",
            "program struct_layout", "  use wefm", "  implicit none"]
    out += ["  type(%s), target :: v%d" % (s, i) for i, (s, _) in enumerate(api.structs)]
    for i, (struct, fields) in enumerate(api.structs):
        v = "v%d" % i
        out += ["", "  print '(a,i0)', '%s sizeof ', c_sizeof(%s)" % (struct, v)]
        out += ["  call at('%s %s', c_loc(%s), c_loc(%s%%%s))" % (struct, f, v, v, f) for f, _, _ in fields]
    out += ["", "contains", "", "  subroutine at(label, base, field)",
            "    character(len=*), intent(in) :: label", "    type(c_ptr), intent(in) :: base, field",
            "    integer(c_intptr_t) :: b, f", "    b = transfer(base, b)", "    f = transfer(field, f)",
            "    print '(a,1x,i0)', label, f - b", "  end subroutine", "", "end program struct_layout"]
    return "\n".join(out) + "\n"


# ---- driver ---------------------------------------------------------------------------------------

OUTPUTS = {
    "bindings/python/wefm/_structs.py": python_structs,
    "bindings/python/wefm/_prototypes.py": python_prototypes,
    "bindings/fortran/wefm_types.inc": fortran_types,
    "bindings/fortran/wefm_interfaces.inc": fortran_interfaces,
    "tests/python/c/struct_layout.c": c_layout,
    "tests/fortran/struct_layout.f90": fortran_layout,
}


def generate(header_path, out_root):
    with open(header_path, encoding="utf-8") as f:
        api = Api(f.read())
    texts = {rel: writer(api) for rel, writer in OUTPUTS.items()}  # all or nothing is written
    for rel, text in texts.items():
        path = os.path.join(out_root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)


def check(header_path, committed_root):
    """0 if every committed output equals a fresh one, else 1 with a unified diff per stale file."""
    stale = 0
    with tempfile.TemporaryDirectory(prefix="wefm_gen_") as tmp:
        generate(header_path, tmp)
        for rel in OUTPUTS:
            with open(os.path.join(tmp, rel), encoding="utf-8") as f:
                fresh = f.read().splitlines(keepends=True)
            try:
                with open(os.path.join(committed_root, rel), encoding="utf-8") as f:
                    committed = f.read().splitlines(keepends=True)
            except FileNotFoundError:
                committed = []
            if fresh != committed:
                stale += 1
                sys.stdout.writelines(difflib.unified_diff(committed, fresh, "committed/" + rel, "generated/" + rel))
    if stale:
        print("\n%d generated file(s) are stale: run %s and commit them." % (stale, REGENERATE))
        return 1
    print("all %d generated files are current" % len(OUTPUTS))
    return 0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--header", default=os.path.join(ROOT, HEADER), help="the C header (default: %s)" % HEADER)
    parser.add_argument("--out", default=ROOT, help="root the outputs are written under (default: the source tree)")
    parser.add_argument("--check", action="store_true",
                        help="generate into a temporary folder and diff with the files under --out")
    args = parser.parse_args(argv)
    try:
        if args.check:
            return check(args.header, args.out)
        generate(args.header, args.out)
    except (HeaderError, OSError) as e:
        print("gen_bindings.py: %s" % e, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
