#!/usr/bin/env python3
"""Converts the WebGL conformance suite's GLSL test pages (`conformance/glsl/**.html` for WebGL 1,
`conformance2/glsl3/**.html` for WebGL 2) into a corpus folder of the form of the shared
`deqp-gles2` corpus: one vertex and one fragment shader file per case, a `manifest.tsv` and a
`README.md`. The manifest has two extra columns: `target` (webgl1 or webgl2) and `webgl_only`
(whether the page tests a WebGL-only rule rather than a GLSL ES one; see WEBGL_ONLY_PATTERNS).

Only the pages listed in the suite's `00_test_list.txt` files are read. Each page's inline
JavaScript runs in Node.js (`node`, run as a subprocess; its `vm` module) with small stubs: a
`document` whose getElementById returns the page's script tags (parsed here), the few
WebGLTestUtils functions that need no WebGL context, and a GLSLConformanceTester that records
the cases handed to runTests/runTest/runRenderTests, resolving shader ids and filling in the
default shaders the way `js/glsl-conformance-test.js` does. The helper scripts
`glsl-constructor-tests-generator.js` and `js/tests/*.js` are loaded as they are. A page that
needs a real WebGL context (creates one, renders and reads pixels, queries limits), or whose
scripts fail, is skipped with a reason; so is a case whose verdict is left to a callback.

Usage: webgl_glsl_to_corpus.py CHECKOUT_DIR OUT_DIR
  CHECKOUT_DIR  root of the WebGL conformance suite (holding conformance/, conformance2/, js/)
  OUT_DIR       corpus folder to write; replaced as a whole (written to OUT_DIR.tmp, then renamed);
                must not lie inside the repository this script belongs to

Exit codes: 0 corpus written, 1 node failed or the output could not be written, 2 usage errors
(bad arguments, CHECKOUT_DIR without the test lists, OUT_DIR inside the repository).
"""
import argparse
import json
import re
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path

from deqp_tests_to_corpus import inside_repository, write_corpus  # the same corpus form

EXIT_FAILED = 1
EXIT_USAGE = 2

REPO_ROOT = Path(__file__).resolve().parents[1]

# Root test lists and the WebGL version their pages belong to.
ROOTS = {"conformance/glsl": "webgl1", "conformance2/glsl3": "webgl2"}

# Pages (path relative to the checkout, without .html) classed as testing WebGL-only rules: the
# WebGL specs' identifier length limits, reserved `webgl_`/`_webgl_` prefixes, character set,
# WebGL 1 Appendix A loop and indexing restrictions, shader packing and size limits, global
# variable initializers (WebGL 1.0 section 6.33), WebGL 2 uniform-block and operator rules.
# Matched against the page's file name (see is_webgl_only). conformance2/glsl3/
# tricky-loop-conditions tests GLSL ES 3.00 loops, which no WebGL rule restricts: it is not
# matched.
WEBGL_ONLY_PATTERNS = [
    r"^conformance/glsl/reserved/",                # webgl_ / _webgl_ prefixes
    r"webgl",                                      # shader-with-(_)webgl-identifier, essl3-...
    r"length-limits",                              # attrib/uniform-location-length-limits
    r"long-variable-names", r"-character-(define|identifier)", r"long-line",
    r"non-ascii", r"invalid-characters", r"character-set",
    r"packing-restrictions", r"too-many-uniforms",
    r"arbitrary-indexing", r"limited-indexing", r"constant-expression-loop-conditions",
    r"uniform-in-loop-condition",
    r"do-loop", r"while-loop", r"for-loop",
    r"forbidden-operators",
    r"uniform-block", r"mis-matching-uniform-block",
    r"large-loop-compile",
    r"struct-nesting-exceeds",                     # WebGL 1 section 6.x struct nesting limit
    r"global-variable-init",                       # WebGL 1 section 6.33 global initializers
    # WebGL makes a 1.00 function body share its parameters' scope (ANGLE does so only for
    # WebGL); dEQP-GLES2 expects the opposite (scoping.valid.local_variable_hides_function_
    # parameter, left out of its must-pass list), so this is no GLSL ES 1.00 rule.
    r"shader-with-functional-scoping",
    r"shader-with-dfdx\.frag",                     # extension usable only after getExtension
]

# <script> types that hold JavaScript (the browser's rule: no type, or a JavaScript MIME type).
JS_TYPES = {"", "text/javascript", "application/javascript", "module"}

# Runs one page per input entry; see the module docstring. Input (stdin, JSON):
# {"checkout": dir, "pages": [{"path", "target", "scripts": [{"src", "type", "id", "text"}],
#  "onload"}]}. Output (stdout, JSON): per page {"cases": [...], "skipped_cases": {...}}
# or {"skip": reason}.
NODE_RUNNER = r"""
const vm = require('vm'), fs = require('fs'), path = require('path');
const input = JSON.parse(fs.readFileSync(0, 'utf8'));
class Skip extends Error {}

// The default shaders, taken from glsl-conformance-test.js itself.
const testerSource = fs.readFileSync(path.join(input.checkout, 'js/glsl-conformance-test.js'), 'utf8');
const DEFAULTS = {};
for (const m of testerSource.matchAll(/var (default\w*Shader) = (\[[\s\S]*?\])\.join\('\\n'\);/g)) {
  DEFAULTS[m[1]] = vm.runInNewContext(m[2]).join('\n');
}
for (const name of ['defaultVertexShader', 'defaultFragmentShader',
                    'defaultESSL3VertexShader', 'defaultESSL3FragmentShader']) {
  if (!(name in DEFAULTS)) throw new Error('glsl-conformance-test.js: no ' + name);
}

let asyncError = null;  // an async page function's failure (a rejected promise nobody awaits)
process.on('unhandledRejection', (e) => { asyncError = asyncError || e; });
const turn = () => new Promise((resolve) => setImmediate(resolve));

async function runPage(page) {
  const elements = {};
  for (const s of page.scripts) {
    if (!s.id) continue;
    // text, textContent, innerHTML and innerText are one value (pages write to them too).
    const element = {id: s.id, type: s.type, value: s.text};
    for (const key of ['text', 'textContent', 'innerHTML', 'innerText']) {
      Object.defineProperty(element, key, {get() { return this.value; },
                                           set(v) { this.value = String(v); }});
    }
    elements[s.id] = element;
  }
  const cases = [], skippedCases = {};
  let called = false;
  const skipCase = (reason) => { skippedCases[reason] = (skippedCases[reason] || 0) + 1; };

  // runOneTest's choice of sources and flags (glsl-conformance-test.js).
  function record(infos, render) {
    called = true;
    for (const original of infos) {
      const info = Object.assign({}, original);
      if (info.ignoreResults) { skipCase('ignoreResults: the page checks nothing'); continue; }
      if (info.vShaderTest || info.fShaderTest) {
        skipCase('verdict left to a vShaderTest/fShaderTest callback'); continue;
      }
      let vDefault = false, fDefault = false;
      if (info.vShaderSource === undefined) {
        if (info.vShaderId) info.vShaderSource = document.getElementById(info.vShaderId).text;
        else vDefault = true;
      }
      if (info.fShaderSource === undefined) {
        if (info.fShaderId) info.fShaderSource = document.getElementById(info.fShaderId).text;
        else fDefault = true;
      }
      if (vDefault) { info.vShaderSource = DEFAULTS.defaultVertexShader; info.vShaderSuccess = true; }
      if (fDefault) { info.fShaderSource = DEFAULTS.defaultFragmentShader; info.fShaderSuccess = true; }
      if (vDefault != fDefault) {
        // The default shader takes the other shader's language version (first line only).
        if (fDefault && info.vShaderSource.split('\n')[0] == '#version 300 es')
          info.fShaderSource = DEFAULTS.defaultESSL3FragmentShader;
        if (vDefault && info.fShaderSource.split('\n')[0] == '#version 300 es')
          info.vShaderSource = DEFAULTS.defaultESSL3VertexShader;
      }
      cases.push({
        vertex: info.vShaderPrep ? info.vShaderPrep(info.vShaderSource) : info.vShaderSource,
        fragment: info.fShaderPrep ? info.fShaderPrep(info.fShaderSource) : info.fShaderSource,
        v: !!info.vShaderSuccess, f: !!info.fShaderSuccess, l: !!info.linkSuccess,
        passMsg: String(info.passMsg || ''), render: !!(render || info.render),
        vDefault, fDefault,
      });
    }
  }
  // setupTest(): the page's 'vertexShader'/'fragmentShader' tags, verdict from the first line.
  function setupTest() {
    const info = {};
    const verdict = (msg) => msg.indexOf('fail') >= 0 ? false : msg.indexOf('succeed') >= 0 ? true : undefined;
    const trim = (s) => s.replace(/^\s*/, '').replace(/\s*$/, '');
    if (elements.vertexShader) {
      info.vShaderSource = trim(elements.vertexShader.text);
      info.passMsg = info.vShaderSource.split('\n')[0].substring(3);
      info.vShaderSuccess = verdict(info.passMsg);
    }
    if (elements.fragmentShader) {
      info.fShaderSource = trim(elements.fragmentShader.text);
      info.passMsg = info.fShaderSource.split('\n')[0].substring(3);
      info.fShaderSuccess = verdict(info.passMsg);
    }
    if (info.passMsg === undefined) throw new Skip('runTest() without a vertexShader/fragmentShader tag');
    if (info.vShaderSuccess === undefined && elements.vertexShader ||
        info.fShaderSuccess === undefined && elements.fragmentShader)
      throw new Skip("runTest(): first line says neither 'fail' nor 'succeed'");
    info.linkSuccess = info.vShaderSuccess !== false && info.fShaderSuccess !== false;
    return info;
  }
  const tester = {
    runTests: (list) => record(list, false),
    runRenderTests: (list) => record(list, true),
    runTest: () => record([setupTest()], false),
    runRenderTest: () => record([setupTest()], true),
  };

  // WebGLTestUtils: the context-free helpers; any other function needs a real WebGL context.
  const wtuBase = {
    getScript(id) {
      if (!elements[id]) throw '*** Error: unknown script element ' + id;
      return elements[id].text;
    },
    replaceParams(str, ...params) {
      return str.replace(/\$\((\w+)\)/g, (whole, name) => {
        for (const p of params) if (p[name] !== undefined) return p[name];
        throw "unknown string param '" + name + "'";
      });
    },
    getDefault3DContextVersion: () => page.target == 'webgl2' ? 2 : 1,
    log() {}, error(msg) { throw new Error(msg); }, getUrlOptions: () => ({}),
  };
  const wtu = new Proxy(wtuBase, {get(base, key) {
    if (key in base) return base[key];
    return () => { throw new Skip('calls wtu.' + String(key) + ' (needs a WebGL context)'); };
  }});
  const noop = () => {};
  const timers = [];
  const document = {
    getElementById: (id) => elements[id] || null,
    createElement: () => ({style: {}, appendChild: noop, setAttribute: noop,
                           getContext() { throw new Skip('creates a canvas context'); }}),
    createTextNode: () => ({}), body: {appendChild: noop}, title: '',
  };
  const sandbox = {
    document, console: {log: noop, error: noop, warn: noop},
    WebGLTestUtils: wtu, GLSLConformanceTester: tester,
    description: noop, debug: noop, testPassed: noop, testFailed: noop, finishTest: noop,
    bufferedLogToConsole: noop, quietMode: () => true, escapeHTML: (s) => s,
    shouldBe: noop, shouldBeTrue: noop, shouldBeFalse: noop, shouldBeNull: noop,
    shouldBeNonNull: noop, shouldBeUndefined: noop, shouldBeEqualToString: noop,
    setTimeout: (fn) => { timers.push(fn); }, requestAnimationFrame: (fn) => { timers.push(fn); },
    location: {href: page.path, pathname: '/' + page.path, search: ''},
    navigator: {userAgent: 'node'},
    Float32Array, Uint8Array, Int32Array, Uint32Array, Math, JSON,
  };
  // A browser makes each element with an id a global of that name (pages rely on it).
  for (const id of Object.keys(elements)) if (!(id in sandbox)) sandbox[id] = elements[id];
  sandbox.window = sandbox;
  sandbox.self = sandbox;
  const context = vm.createContext(sandbox);
  const runFile = (file) => vm.runInContext(fs.readFileSync(path.join(input.checkout, file), 'utf8'),
                                             context, {filename: file});
  // Page-provided helpers run as they are; the suite harness is the stubs above.
  const STUBBED = new Set(['js-test-pre.js', 'js-test-post.js', 'webgl-test-utils.js',
                           'glsl-conformance-test.js', 'desktop-gl-constants.js']);
  for (const s of page.scripts) {
    if (s.src) {
      const name = path.basename(s.src);
      if (STUBBED.has(name)) continue;
      if (name == 'glsl-generator.js')
        throw new Skip('renders with GLSLGenerator and compares images (needs a WebGL context)');
      runFile(path.join(path.dirname(page.path), s.src));
    } else if (s.js) {
      vm.runInContext(s.text, context, {filename: page.path});
    }
  }
  if (typeof sandbox.onload == 'function') sandbox.onload();
  if (page.onload) vm.runInContext(page.onload, context, {filename: page.path + ' (onload)'});
  // Let async page code and its timers run to the end.
  await turn();
  while (timers.length) { timers.shift()(); await turn(); }
  if (asyncError) throw asyncError;
  if (!called) throw new Skip('no GLSLConformanceTester call');
  return {cases, skipped_cases: skippedCases};
}

(async () => {
  const results = [];
  for (const page of input.pages) {
    asyncError = null;
    try {
      results.push(await runPage(page));
    } catch (e) {
      results.push(e instanceof Skip ? {skip: e.message}
                   : {skip: 'script error: ' + String(e && e.message || e).split('\n')[0]});
    }
  }
  process.stdout.write(JSON.stringify(results));
})();
"""


class ScriptTags(HTMLParser):
    """Collects a page's <script> tags (attributes and raw text, in page order) and the
    <body onload> handler."""

    def __init__(self):
        super().__init__(convert_charrefs=False)
        self.scripts = []
        self.onload = ""
        self._open = None

    def handle_starttag(self, tag, attrs):
        attrs = {k: v or "" for k, v in attrs}
        if tag == "script":
            kind = attrs.get("type", "").strip().lower()
            self._open = {"src": attrs.get("src", ""), "type": kind, "id": attrs.get("id", ""),
                          "js": kind in JS_TYPES, "text": ""}
        elif tag == "body":
            self.onload = attrs.get("onload", "")

    def handle_data(self, data):
        if self._open is not None:
            self._open["text"] += data

    def handle_endtag(self, tag):
        if tag == "script" and self._open is not None:
            self.scripts.append(self._open)
            self._open = None


def listed_pages(checkout, list_file):
    """The pages a 00_test_list.txt names, following nested lists (options such as
    `--min-version 2.0.1` are ignored: every listed page is a case)."""
    pages = []
    for raw in list_file.read_text(encoding="utf-8").splitlines():
        line = raw.split("#")[0].split("//")[0].strip()
        if not line:
            continue
        entry = list_file.parent / line.split()[-1]
        if entry.name.endswith(".txt"):
            pages += listed_pages(checkout, entry)
        else:
            pages.append(entry.relative_to(checkout).as_posix())
    return pages


def is_webgl_only(page):
    return any(re.search(p, page) for p in WEBGL_ONLY_PATTERNS)


def run_pages(checkout, pages):
    """Runs the Node runner on every page; returns its per-page results."""
    entries = []
    for page, target in pages:
        tags = ScriptTags()
        tags.feed((checkout / page).read_text(encoding="utf-8"))
        entries.append({"path": page, "target": target, "scripts": tags.scripts,
                        "onload": tags.onload})
    proc = subprocess.run(["node", "-e", NODE_RUNNER], input=json.dumps(
        {"checkout": str(checkout), "pages": entries}), capture_output=True, text=True,
        check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"node failed ({proc.returncode}): {proc.stderr.strip()[:2000]}")
    return json.loads(proc.stdout)


MANIFEST_COLUMNS = ["id", "suite", "glsl_version", "expect", "expect_raw", "case_type",
                    "test_stage", "vertex_file", "fragment_file", "requires", "in_mustpass",
                    "mustpass_issue_list", "test_file", "line", "target", "webgl_only"]


def expectation(case):
    """(expect, test_stage) from the page's flags, as the brief of this corpus maps them."""
    if not case["v"] and not case["f"]:
        return "compile_fail", "program"
    if not case["v"]:
        return "compile_fail", "vertex"
    if not case["f"]:
        return "compile_fail", "fragment"
    return ("pass" if case["l"] else "link_fail"), "program"


def glsl_version(case):
    first = (case["vertex"] + case["fragment"]).lstrip()
    return "300 es" if re.search(r"^\s*#\s*version\s+300\s+es", case["vertex"] + "\n" +
                                 case["fragment"], re.M) or first.startswith("#version 300") \
        else "100 es"


def convert(checkout):
    """Returns (rows, files, counts, page skips {reason: n}, case skips {reason: n},
    webgl-only pages, converted page count)."""
    pages = [(p, target) for root, target in ROOTS.items()
             for p in listed_pages(checkout, checkout / root / "00_test_list.txt")]
    results = run_pages(checkout, pages)
    rows, files, counts, page_skips, case_skips = [], {}, {}, {}, {}
    webgl_only_pages, converted = [], 0
    for (page, target), result in zip(pages, results):
        if "skip" in result:
            page_skips[result["skip"]] = page_skips.get(result["skip"], 0) + 1
            continue
        for reason, n in result["skipped_cases"].items():
            case_skips[reason] = case_skips.get(reason, 0) + n
        if not result["cases"]:
            continue
        converted += 1
        stem = page.removesuffix(".html")
        webgl_only = is_webgl_only(page)
        if webgl_only:
            webgl_only_pages.append(page)
        for index, case in enumerate(result["cases"]):
            expect, stage = expectation(case)
            raw = f"v={int(case['v'])} f={int(case['f'])} l={int(case['l'])}"
            files[f"{stem}/{index}.vert"] = case["vertex"]
            files[f"{stem}/{index}.frag"] = case["fragment"]
            rows.append([f"webgl.{stem.replace('/', '.')}.{index}", "webgl", glsl_version(case),
                         expect, raw, "complete", stage, f"{stem}/{index}.vert",
                         f"{stem}/{index}.frag", "", "True", "", page, "0", target,
                         str(webgl_only)])
            counts[expect] = counts.get(expect, 0) + 1
    return rows, files, counts, page_skips, case_skips, webgl_only_pages, converted, len(pages)


def read_source_note(checkout):
    """The fetch note beside the checkout (SOURCE.txt, else the vendoring moz.yaml), looked for
    in CHECKOUT_DIR and its ancestors (nearest first), or None."""
    for folder in [checkout] + list(checkout.parents)[:3]:
        for name in ("SOURCE.txt", "moz.yaml"):
            note = folder / name
            if note.is_file():
                return note, note.read_text(encoding="utf-8").strip()
    return None


def readme_text(checkout, rows, counts, page_skips, case_skips, webgl_only_pages, converted,
                listed, note):
    by_expect = ", ".join(f"{n:,} {e}" for e, n in sorted(counts.items()))
    by_target = {t: sum(1 for r in rows if r[14] == t) for t in ("webgl1", "webgl2")}
    origin = f"`{checkout}`"
    if note:
        origin += f"; `{note[0]}` says:\n\n    " + note[1].replace("\n", "\n    ") + "\n"
    page_text = "".join(f"- {n:,} page(s): {r}\n" for r, n in sorted(page_skips.items()))
    case_text = "".join(f"- {n:,} case(s): {r}\n" for r, n in sorted(case_skips.items()))
    page_text, case_text = page_text or "- none\n", case_text or "- none\n"
    only_text = "".join(f"- `{p}`\n" for p in webgl_only_pages) or "- none\n"
    patterns = ", ".join(f"`{p}`" for p in WEBGL_ONLY_PATTERNS)
    return f"""# WebGL conformance GLSL cases (external conformance corpus)

{len(rows):,} test cases ({by_expect}; {by_target['webgl1']:,} WebGL 1, {by_target['webgl2']:,}
WebGL 2) from {converted:,} of the {listed:,} GLSL test pages of the WebGL conformance suite
(KhronosGroup/WebGL, licence MIT), from {origin}
Pages: those listed (recursively) in `conformance/glsl/00_test_list.txt` (WebGL 1, GLSL ES 1.00
and the ES 3.00 shaders WebGL 1 must reject) and `conformance2/glsl3/00_test_list.txt` (WebGL 2);
`--min-version` options are ignored. `conformance/ogles` (the OpenGL ES 2.0 conformance tests in
their own format) is not converted.

Written by `bench/webgl_glsl_to_corpus.py` of tidepool. Each page's inline JavaScript was run in
Node.js with stubs, and the cases it hands to `GLSLConformanceTester.runTests`, `runTest`,
`runRenderTests` or `runRenderTest` were recorded as `js/glsl-conformance-test.js` would run
them: shader ids resolved to the script tags' text, a missing stage replaced by that file's
default shader (its `#version 300 es` variant when the other shader's first line is
`#version 300 es`), `vShaderPrep`/`fShaderPrep` applied. Render cases keep only their
compile/link expectation (the pixels they check are not part of this corpus).

Pages left out:
{page_text}
Cases left out of converted pages:
{case_text}
`manifest.tsv` columns (those of the deqp-gles2 corpus, plus `target` and `webgl_only`):
- `id`: `webgl.<page path without .html, / as .>.<index of the case in the page>`; `suite`:
  webgl; `glsl_version`: `300 es` when a shader has `#version 300 es`, else `100 es`.
- `expect`: `compile_fail` when the page expects a shader not to compile (`vShaderSuccess` or
  `fShaderSuccess` false; `test_stage` names it, `program` when both are), `link_fail` when both
  compile but `linkSuccess` is false, else `pass`; `expect_raw`: the flags, e.g. `v=1 f=1 l=0`.
  Note: the suite itself only checks that a shader expected to fail does not compile *or* the
  program does not link (GLSL ES 1.00 section 10.27 lets a compiler defer errors to the link).
- `case_type`: `complete` (both shaders are the page's or the harness's).
- `vertex_file`, `fragment_file`: paths relative to this folder; `requires`: empty.
- `in_mustpass`: `True` and `mustpass_issue_list` empty for every case: every listed page must
  pass for WebGL conformance.
- `test_file`: the page, relative to the checkout; `line`: 0.
- `target`: `webgl1` for pages under `conformance/`, `webgl2` under `conformance2/`.
- `webgl_only`: `True` for pages that test WebGL-only rules (identifier length limits, the
  `webgl_`/`_webgl_` prefixes, character set, WebGL 1 Appendix A loop and indexing restrictions,
  shader size and packing limits, WebGL 2 operator and uniform-block rules), judged from the
  page's path alone: a page is WebGL-only when its path matches one of the regular expressions
  {patterns}. The pages so classed:

{only_text}
The heuristic is coarse: a WebGL-only page may also hold cases that test plain GLSL ES rules
(e.g. the valid loop forms on a loop-restriction page), and other pages may hold single
WebGL-only cases.
"""


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("checkout_dir", type=Path)
    parser.add_argument("out_dir", type=Path)
    args = parser.parse_args(argv)  # exits 2 on bad arguments
    checkout = args.checkout_dir.resolve()
    out_dir = args.out_dir.resolve()
    if inside_repository(out_dir):
        print(f"error: OUT_DIR {out_dir} is inside the repository {REPO_ROOT}; the corpus is "
              "external data and must be written elsewhere", file=sys.stderr)
        return EXIT_USAGE
    missing = [r for r in ROOTS if not (checkout / r / "00_test_list.txt").is_file()]
    if missing or not (checkout / "js/glsl-conformance-test.js").is_file():
        print(f"error: {checkout} is not a WebGL conformance checkout (no "
              f"{', '.join(missing) or 'js'} test list/harness)", file=sys.stderr)
        return EXIT_USAGE
    try:
        rows, files, counts, page_skips, case_skips, only, converted, listed = convert(checkout)
    except (RuntimeError, OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_FAILED
    readme = readme_text(checkout, rows, counts, page_skips, case_skips, only, converted, listed,
                         read_source_note(checkout))
    try:
        write_corpus(out_dir, MANIFEST_COLUMNS, rows, files, readme)
    except OSError as error:
        print(f"error: writing {out_dir}: {error}", file=sys.stderr)
        return EXIT_FAILED
    written = ", ".join(f"{e} {n}" for e, n in sorted(counts.items()))
    print(f"{out_dir}: {len(rows)} cases from {converted} of {listed} pages ({written}); "
          f"pages skipped: {sum(page_skips.values())}; cases skipped: {sum(case_skips.values())}")
    for reason, n in sorted(page_skips.items(), key=lambda item: -item[1]):
        print(f"  {n:4} page(s): {reason}")
    for reason, n in sorted(case_skips.items(), key=lambda item: -item[1]):
        print(f"  {n:4} case(s): {reason}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
