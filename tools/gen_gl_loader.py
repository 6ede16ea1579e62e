#!/usr/bin/python3
"""Generate voxlab's OpenGL 3.3 core-profile loader from the Khronos gl.xml.

Usage: gen_gl_loader.py [--xml /usr/share/khronos-api/gl.xml] [--out DIR]

Writes DIR/voxlab_gl.h and DIR/voxlab_gl.c (default DIR: framework/gl of the
repository holding this script). Python 3 standard library only. The output
depends only on the XML contents, so re-running it on the same gl.xml gives
byte-identical files (tests/check_gl_loader.sh relies on that).
"""
import argparse
import hashlib
import os
import sys
import xml.etree.ElementTree as ET

API, PROFILE, VERSION = "gl", "core", (3, 3)
REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# khrplatform.h types used by gl.xml, mapped straight onto <stdint.h>/<stddef.h>
# so that neither KHR/khrplatform.h nor our own khronos_* typedefs are needed.
KHRONOS_TYPES = {
    "khronos_int8_t": "int8_t", "khronos_uint8_t": "uint8_t",
    "khronos_int16_t": "int16_t", "khronos_uint16_t": "uint16_t",
    "khronos_int32_t": "int32_t", "khronos_uint32_t": "uint32_t",
    "khronos_int64_t": "int64_t", "khronos_uint64_t": "uint64_t",
    "khronos_float_t": "float", "khronos_intptr_t": "intptr_t",
    "khronos_ssize_t": "ptrdiff_t",
}
# Include guards of the system GL headers: we refuse to follow them and then
# define them ourselves so that a later #include <GL/gl.h> is a no-op.
FOREIGN_GUARDS = ["__gl_h_", "__GL_H__", "__glext_h_", "__gl_glext_h_",
                  "__gl_glcorearb_h_"]


def text_of(elem):
    """Flatten an element to C text; <apientry/> becomes APIENTRY."""
    parts = [elem.text or ""]
    for child in elem:
        parts.append("APIENTRY" if child.tag == "apientry" else text_of(child))
        parts.append(child.tail or "")
    return "".join(parts)


def for_api(elem):
    return elem.get("api") in (None, API)


def select_features(root):
    """Return the (types, enums, commands) names of GL <= 3.3 core."""
    wanted = {"type": set(), "enum": set(), "command": set()}
    removed = {"type": set(), "enum": set(), "command": set()}
    for feat in root.findall("feature"):
        if feat.get("api") != API:
            continue
        if tuple(int(x) for x in feat.get("number").split(".")) > VERSION:
            continue
        for block in feat:
            if block.tag not in ("require", "remove") or not for_api(block):
                continue
            if block.get("profile") not in (None, PROFILE):
                continue  # e.g. profile="compatibility"
            target = wanted if block.tag == "require" else removed
            for item in block:
                if item.tag in target:
                    target[item.tag].add(item.get("name"))
    return tuple(sorted(wanted[k] - removed[k]) for k in ("type", "enum", "command"))


def parse_commands(root, names):
    """name -> (return type, [param decl], [ptype names]) for the chosen commands."""
    out = {}
    for cmd in root.iter("command"):
        proto = cmd.find("proto")
        if proto is None or not for_api(cmd):
            continue
        name = proto.find("name").text
        if name not in names:
            continue
        ret = (proto.text or "") + "".join(
            text_of(c) + (c.tail or "") for c in proto if c.tag != "name")
        params = [p for p in cmd.findall("param") if for_api(p)]
        ptypes = [t.text for t in cmd.iter("ptype")]
        out[name] = (" ".join(ret.split()), [" ".join(text_of(p).split()) for p in params], ptypes)
    missing = set(names) - set(out)
    if missing:
        sys.exit("gen_gl_loader: commands without definition: %s" % sorted(missing))
    return out


def parse_types(root, needed):
    """C declarations of the needed types (plus their dependencies), in XML order."""
    decls = {}
    order = []
    for t in root.find("types").findall("type"):
        if not for_api(t):
            continue
        name = t.get("name") or t.find("name").text
        decls[name] = t
        order.append(name)
    todo, closure = list(needed), set()
    while todo:  # follow requires="..." links
        name = todo.pop()
        if name in closure or name not in decls:
            continue
        closure.add(name)
        if decls[name].get("requires"):
            todo.append(decls[name].get("requires"))
    lines = []
    for name in order:
        if name not in closure or name == "khrplatform":
            continue
        decl = text_of(decls[name])
        for khr, std in KHRONOS_TYPES.items():
            decl = decl.replace(khr, std)
        if "khronos_" in decl:
            sys.exit("gen_gl_loader: unmapped khronos type in: %s" % decl)
        lines.append(decl)
    return lines


def parse_enums(root, names):
    """name -> C literal for the chosen enums (value plus u/ull suffix)."""
    out = {}
    for group in root.findall("enums"):
        for e in group.findall("enum"):
            if e.get("name") in names and for_api(e):
                out[e.get("name")] = e.get("value") + (e.get("type") or "")
    missing = set(names) - set(out)
    if missing:
        sys.exit("gen_gl_loader: enums without value: %s" % sorted(missing))
    return out


def banner(digest):
    return ("/* Generated by tools/gen_gl_loader.py from gl.xml (sha256 %s)\n"
            " * for OpenGL %d.%d %s profile. DO NOT EDIT.\n"
            " * Regenerate with: /usr/bin/python3 tools/gen_gl_loader.py "
            "[--xml /usr/share/khronos-api/gl.xml]\n */\n"
            % (digest, VERSION[0], VERSION[1], PROFILE))


def write_header(path, digest, types, enums, commands):
    L = [banner(digest), "#ifndef VOXLAB_GL_H", "#define VOXLAB_GL_H", ""]
    L.append("#if " + " || ".join("defined(%s)" % g for g in FOREIGN_GUARDS))
    L.append('#error "voxlab_gl.h must be included instead of (not after) the system OpenGL headers"')
    L.append("#endif")
    L += ["#define %s 1" % g for g in FOREIGN_GUARDS]
    L += ["", "#include <stddef.h>", "#include <stdint.h>", "",
          "#ifndef APIENTRY", "#if defined(_WIN32) && !defined(__CYGWIN__)",
          "#define APIENTRY __stdcall", "#else", "#define APIENTRY", "#endif", "#endif",
          "", "#ifdef __cplusplus", 'extern "C" {', "#endif", "", "/* Types */"]
    L += types
    L += ["", "/* Enums (%d) */" % len(enums)]
    L += ["#define %s %s" % (n, v) for n, v in sorted(enums.items())]
    L += ["", "/* Command pointer types (%d) */" % len(commands)]
    for name, (ret, params, _) in sorted(commands.items()):
        L.append("typedef %s (APIENTRY *PFN%sPROC)(%s);"
                 % (ret, name.upper(), ", ".join(params) or "void"))
    L += ["", "/* Loaded entry points; filled by voxlabLoadGL(). */",
          "typedef struct VoxlabGLTable {"]
    L += ["    PFN%sPROC %s;" % (n.upper(), n[2:]) for n in sorted(commands)]
    L += ["} VoxlabGLTable;", "extern VoxlabGLTable voxlab_gl;", ""]
    L += ["#define %s voxlab_gl.%s" % (n, n[2:]) for n in sorted(commands)]
    L += ["",
          "/* Any get-proc-address function fits: glfwGetProcAddress,",
          " * OSMesaGetProcAddress, eglGetProcAddress (cast if needed). */",
          "typedef void (*VoxlabGLProc)(void);",
          "typedef VoxlabGLProc (*VoxlabGLGetProc)(const char* name);",
          "",
          "/* Resolves every command; returns how many could not be found (0 = ok). */",
          "int voxlabLoadGL(VoxlabGLGetProc getProc);",
          "/* Name of the index-th unresolved command of the last load, NULL past the end. */",
          "const char* voxlabGLMissing(int index);",
          "/* Number of commands in the table. */",
          "int voxlabGLCommandCount(void);",
          "", "#ifdef __cplusplus", "}", "#endif", "", "#endif /* VOXLAB_GL_H */", ""]
    write(path, L)


def write_source(path, digest, commands):
    names = sorted(commands)
    L = [banner(digest), '#include "voxlab_gl.h"', "", "#include <string.h>", "",
         "#define VOXLAB_GL_COUNT %d" % len(names), "",
         "VoxlabGLTable voxlab_gl;", "",
         "static const char* const voxlab_gl_names[VOXLAB_GL_COUNT] = {"]
    L += ['    "%s",' % n for n in names]
    L += ["};", "",
          "/* Where each name goes in the table (parallel to voxlab_gl_names). */",
          "static const size_t voxlab_gl_offsets[VOXLAB_GL_COUNT] = {"]
    L += ["    offsetof(VoxlabGLTable, %s)," % n[2:] for n in names]
    L += ["};", "",
          "static int voxlab_gl_missing[VOXLAB_GL_COUNT];",
          "static int voxlab_gl_missing_count;", "",
          "int voxlabLoadGL(VoxlabGLGetProc getProc) {",
          "    int i;",
          "    memset(&voxlab_gl, 0, sizeof voxlab_gl);",
          "    voxlab_gl_missing_count = 0;",
          "    for (i = 0; i < VOXLAB_GL_COUNT; ++i) {",
          "        VoxlabGLProc proc = getProc ? getProc(voxlab_gl_names[i]) : NULL;",
          "        if (proc == NULL) {",
          "            voxlab_gl_missing[voxlab_gl_missing_count++] = i;",
          "            continue;",
          "        }",
          "        /* memcpy: all function pointers share one representation. */",
          "        memcpy((char*)&voxlab_gl + voxlab_gl_offsets[i], &proc, sizeof proc);",
          "    }",
          "    return voxlab_gl_missing_count;",
          "}", "",
          "const char* voxlabGLMissing(int index) {",
          "    if (index < 0 || index >= voxlab_gl_missing_count) return NULL;",
          "    return voxlab_gl_names[voxlab_gl_missing[index]];",
          "}", "",
          "int voxlabGLCommandCount(void) { return VOXLAB_GL_COUNT; }", ""]
    write(path, L)


def write(path, lines):
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--xml", default="/usr/share/khronos-api/gl.xml")
    ap.add_argument("--out", default=os.path.join(REPO_ROOT, "framework", "gl"))
    args = ap.parse_args()
    with open(args.xml, "rb") as f:
        data = f.read()
    digest = hashlib.sha256(data).hexdigest()
    root = ET.fromstring(data)

    type_names, enum_names, cmd_names = select_features(root)
    commands = parse_commands(root, set(cmd_names))
    enums = parse_enums(root, set(enum_names))
    needed = set(type_names) | {t for c in commands.values() for t in c[2]}
    types = parse_types(root, needed)

    os.makedirs(args.out, exist_ok=True)
    write_header(os.path.join(args.out, "voxlab_gl.h"), digest, types, enums, commands)
    write_source(os.path.join(args.out, "voxlab_gl.c"), digest, commands)
    print("gen_gl_loader: %d commands, %d enums, %d types -> %s"
          % (len(commands), len(enums), len(types), args.out))


if __name__ == "__main__":
    main()
