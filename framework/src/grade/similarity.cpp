// voxlab: similar stage code across a class (similarity.h).
//
// The method is MOSS's: Schleimer, Wilkerson and Aiken, "Winnowing: local
// algorithms for document fingerprinting", SIGMOD 2003. Code is turned into
// a stream of normalised tokens, every k consecutive tokens are hashed, and
// winnowing keeps, from every window of w consecutive hashes, the smallest
// (the rightmost on ties). Any match of at least w + k - 1 tokens is then
// certain to share a fingerprint, and nothing shorter than k tokens counts.
//
// Tokens. What a student copying a solution changes costs nothing to change:
// names, comments, layout, braces. So
//  - comments and whitespace are dropped;
//  - GLSL and C++ keywords and types are kept as themselves, and so are
//    builtin and library functions where they are called or named through
//    a namespace or object (max(, mix(, glm::length, points.size): which
//    builtins a solution calls is part of how it was written, while a
//    variable named `length` is a name like any other. Every other
//    identifier (variables, the student's helpers, and the framework's
//    functions too) becomes one token class, so renaming hides nothing
//    (keeping `length` as a variable cost the 3D texture-slicing copy 0.03). A
//    swizzle after a dot (.xyz, .rgb) is kept: it cannot be renamed;
//  - numbers are kept by value, spelled one way (1.0, 1., 1.0f, 1e0 are one
//    token). A constant such as -3.4e38 or 1e-4 is a trace of the author, and
//    changing one changes what the code does, which copying avoids. Measured:
//    with every number one token, the obvious independent MIP loop (-1e30)
//    shares 34 tokens with the reference's (-3.4e38) and scores 0.43, not 26
//    and 0.36, while the copies score 0.01-0.02 lower;
//  - braces are dropped (adding them around a one-statement loop body is a
//    free disguise) and so are preprocessor lines (include guards and
//    #include lines are the starter code's);
//  - strings become one token class (GLSL has none; C++ stages barely use
//    them).
//
// Parameters, measured on tests/test_similarity.cpp's corpus: the reference
// solutions of sampling, compositing, 3D texture slicing (C++) and MIP, a disguised
// copy of each, and two solutions of each written independently
// (SimilarityMeasurement prints every pair). k = 8 tokens is about one short
// statement (`maximum = max(maximum, v);` is 9), and w = 4 makes every match
// of 11 tokens or more certain to be seen. Over k in 5..15 and w in 1..8, the
// gap between the lowest copy's score and the highest independent pair's
// (with 30 matching tokens or more) was 0.49 at k 8, w 4 (0.81 against
// 0.32), and 0.51 at k 7, w 6 or 8, where an independent pair (under 30
// tokens) reached 0.5 or more fingerprints were thinned out; k 12 and more
// narrowed it (copies at 0.72 and less). Stage solutions are small (5 to 45
// lines): much larger k or w leaves a short stage a handful of fingerprints.
//
// What is not evidence is removed before comparing:
//  - fingerprints whose k-gram occurs anywhere in the stage's starter code
//    (assignments/<stage>/): every student has that code;
//  - fingerprints found in more than commonLimit submissions (10, MOSS's
//    default): an idiom a large part of the class writes says nothing about
//    any two of them.
//
// Score: shared fingerprints / min(fingerprints of either side). With the
// minimum, a student who copied another's solution and added code of their
// own still scores high. A pair is flagged when the score reaches the
// threshold and each side has at least minMatchedTokens (30) tokens inside
// matching k-grams: below that (a one-line edit of the starter code, the
// obvious five-line MIP loop, which shares 26 tokens with the reference's)
// the code is too short to say anything. A renamed copy of the whole MIP
// stage still has 48 and is flagged.
//
// Threshold 0.5: on the corpus, the disguised copies score 0.81 (3D texture slicing),
// 0.87, 0.92 and 1 (mip); independent pairs at most 0.36 (0.32 among pairs
// with 30 matching tokens or more). 0.5 lies between, nearer the independent
// side: a pair shown needlessly costs a person a minute, a copy missed is
// never looked at.

#include "voxlab/similarity.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "../report/html_text.h"
#include "voxlab/atomic_file.h"
#include "voxlab/error.h"
#include "voxlab/grader.h"
#include "voxlab/grading.h"
#include "voxlab/untrusted_text.h"

namespace voxlab {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// GLSL and C++ words always kept as themselves: keywords, qualifiers, types
// and builtin variables.
const std::unordered_set<std::string_view>& keywords() {
    static const std::unordered_set<std::string_view> words = {
        // C++ keywords
        "alignas", "alignof", "and", "asm", "auto", "bool", "break", "case", "catch", "char", "class", "const",
        "constexpr", "const_cast", "continue", "decltype", "default", "delete", "do", "double", "dynamic_cast",
        "else", "enum", "explicit", "extern", "false", "float", "for", "friend", "goto", "if", "inline", "int",
        "long", "mutable", "namespace", "new", "noexcept", "not", "nullptr", "operator", "or", "private",
        "protected", "public", "reinterpret_cast", "return", "short", "signed", "sizeof", "static",
        "static_assert", "static_cast", "struct", "switch", "template", "this", "throw", "true", "try", "typedef",
        "typename", "union", "unsigned", "using", "virtual", "void", "volatile", "while",
        // GLSL qualifiers and types
        "attribute", "uniform", "varying", "layout", "centroid", "flat", "smooth", "noperspective", "in", "out",
        "inout", "precision", "highp", "mediump", "lowp", "discard", "invariant", "uint", "vec2", "vec3", "vec4",
        "ivec2", "ivec3", "ivec4", "uvec2", "uvec3", "uvec4", "bvec2", "bvec3", "bvec4", "dvec2", "dvec3",
        "dvec4", "mat2", "mat3", "mat4", "mat2x3", "mat2x4", "mat3x2", "mat3x4", "mat4x2", "mat4x3", "dmat3",
        "dmat4", "sampler1D", "sampler2D", "sampler3D", "samplerCube", "isampler3D", "usampler3D",
        "sampler2DArray", "sampler2DShadow", "gl_FragCoord", "gl_FragColor", "gl_FragDepth", "gl_Position",
        "std", "glm", "size_t"};
    return words;
}

// Builtin and library functions: kept where they are called or named
// through a namespace or an object (`max(`, `glm::length`, `points.size`),
// so that a variable called `length` or `step` is a name like any other.
const std::unordered_set<std::string_view>& libraryNames() {
    static const std::unordered_set<std::string_view> words = {
        // GLSL builtin functions
        "radians", "degrees", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "pow", "exp",
        "log", "exp2", "log2", "sqrt", "inversesqrt", "abs", "sign", "floor", "trunc", "round", "roundEven",
        "ceil", "fract", "mod", "modf", "min", "max", "clamp", "mix", "step", "smoothstep", "isnan", "isinf",
        "fma", "length", "distance", "dot", "cross", "normalize", "faceforward", "reflect", "refract",
        "transpose", "determinant", "inverse", "lessThan", "lessThanEqual", "greaterThan", "greaterThanEqual",
        "equal", "notEqual", "any", "all", "texture", "textureLod", "textureSize", "texelFetch", "texture3D",
        "texture2D", "dFdx", "dFdy", "fwidth",
        // C++ standard library and GLM
        "vector", "array", "pair", "swap", "sort", "size", "push_back", "emplace_back",
        "begin", "end", "back", "front", "empty", "erase", "isfinite", "numeric_limits", "infinity", "epsilon",
        "lowest", "fabs", "fmin", "fmax", "hypot", "atan2", "lerp", "remove_if", "unique", "min_element",
        "max_element"};
    return words;
}

bool isSwizzle(std::string_view word) {
    if (word.empty() || word.size() > 4) return false;
    for (const std::string_view set : {"xyzw", "rgba", "stpq"})
        if (word.find_first_not_of(set) == std::string_view::npos) return true;
    return false;
}

bool identStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool identChar(char c) { return identStart(c) || (c >= '0' && c <= '9'); }
bool digit(char c) { return c >= '0' && c <= '9'; }

// A number as written ("1.0f", "0x1F", ".5e-3") spelled by its value.
std::string numberToken(std::string_view written) {
    std::string s(written);
    s.erase(std::remove(s.begin(), s.end(), '\''), s.end());  // C++14 digit separators
    char out[40];
    if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
        while (!s.empty() && std::string_view("uUlL").find(s.back()) != std::string_view::npos) s.pop_back();
        unsigned long long v = 0;
        const auto r = std::from_chars(s.data() + 2, s.data() + s.size(), v, 16);
        if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return "num:" + s;
        std::snprintf(out, sizeof out, "%llu", v);
        return out;
    }
    while (!s.empty() && std::string_view("fFlLuU").find(s.back()) != std::string_view::npos) s.pop_back();
    double v = 0.0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return "num:" + s;
    std::snprintf(out, sizeof out, "%.9g", v);
    return out;
}

// The length of a number starting at text[i] (a digit, or '.' then a digit).
std::size_t numberLength(std::string_view text, std::size_t i) {
    const bool hex = i + 1 < text.size() && text[i] == '0' && (text[i + 1] == 'x' || text[i + 1] == 'X');
    std::size_t j = i;
    while (j < text.size()) {
        const char c = text[j];
        const bool exponent = j > i && (hex ? (text[j - 1] == 'p' || text[j - 1] == 'P')
                                            : (text[j - 1] == 'e' || text[j - 1] == 'E'));
        if (identChar(c) || c == '.' || c == '\'' || ((c == '+' || c == '-') && exponent)) ++j;
        else break;
    }
    return j - i;
}

// Where a comment, string or preprocessor line starting at i ends (the
// index after it); the caller counts its newlines.
std::size_t skipBlockComment(std::string_view text, std::size_t i) {
    const std::size_t end = text.find("*/", i + 2);
    return end == std::string_view::npos ? text.size() : end + 2;
}

std::size_t skipLine(std::string_view text, std::size_t i, bool continuations) {
    while (i < text.size() && text[i] != '\n') {
        if (continuations && text[i] == '\\' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
        else if (continuations && text[i] == '\\' && i + 2 < text.size() && text[i + 1] == '\r' && text[i + 2] == '\n')
            i += 2;
        ++i;
    }
    return i;
}

std::size_t skipQuoted(std::string_view text, std::size_t i) {
    const char quote = text[i++];
    while (i < text.size() && text[i] != quote && text[i] != '\n') i += text[i] == '\\' ? 2 : 1;
    return std::min(text.size(), i + 1);
}

// Operators of more than one character, longest first.
std::size_t operatorLength(std::string_view text, std::size_t i) {
    static const std::string_view three[] = {"<<=", ">>=", "..."};
    static const std::string_view two[] = {"++", "--", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "==",
                                           "!=", "<=", ">=", "&&", "||", "^^", "<<", ">>", "->", "::"};
    const std::string_view rest = text.substr(i);
    for (std::string_view op : three)
        if (rest.substr(0, 3) == op) return 3;
    for (std::string_view op : two)
        if (rest.substr(0, 2) == op) return 2;
    return 1;
}

int newlines(std::string_view text, std::size_t from, std::size_t to) {
    return int(std::count(text.begin() + std::ptrdiff_t(from), text.begin() + std::ptrdiff_t(to), '\n'));
}

}  // namespace

std::vector<SourceToken> tokenizeSource(std::string_view text) {
    std::vector<SourceToken> tokens;
    int line = 1;
    bool lineStart = true;  // only whitespace (or comments) so far on this line
    std::size_t i = 0;
    while (i < text.size()) {
        const char c = text[i];
        std::size_t next = i + 1;
        if (c == '\n') {
            ++line, lineStart = true, ++i;
            continue;
        }
        if (c == '/' && i + 1 < text.size() && (text[i + 1] == '/' || text[i + 1] == '*')) {
            next = text[i + 1] == '/' ? skipLine(text, i, true) : skipBlockComment(text, i);
        } else if (c == '#' && lineStart) {
            next = skipLine(text, i, true);
        } else if (identStart(c)) {
            while (next < text.size() && identChar(text[next])) ++next;
            const std::string_view word = text.substr(i, next - i);
            const std::string& before = tokens.empty() ? std::string() : tokens.back().text;
            const bool member = before == "." || before == "->" || before == "::";
            const std::size_t after = text.find_first_not_of(" \t\r\n", next);
            const bool called = after != std::string_view::npos && text[after] == '(';
            const bool kept = keywords().count(word) || ((called || member) && libraryNames().count(word)) ||
                              (before == "." && isSwizzle(word));
            tokens.push_back({kept ? std::string(word) : std::string("id"), line});
        } else if (digit(c) || (c == '.' && i + 1 < text.size() && digit(text[i + 1]))) {
            next = i + numberLength(text, i);
            tokens.push_back({numberToken(text.substr(i, next - i)), line});
        } else if (c == '"' || c == '\'') {
            next = skipQuoted(text, i);
            tokens.push_back({c == '"' ? "\"str\"" : "'chr'", line});
        } else if (static_cast<unsigned char>(c) > ' ' && static_cast<unsigned char>(c) < 0x7f && c != '{' &&
                   c != '}' && c != '\\' && c != '#') {
            next = i + operatorLength(text, i);
            tokens.push_back({std::string(text.substr(i, next - i)), line});
        }
        // Anything else (whitespace, braces, control or non-ASCII bytes) is skipped.
        if (c != ' ' && c != '\t' && c != '\r' && !(c == '/' && next > i + 1)) lineStart = false;
        line += newlines(text, i, next);
        if (text.substr(i, next - i).find('\n') != std::string_view::npos) lineStart = true;
        i = next;
    }
    return tokens;
}

namespace {

// ---- fingerprints ---------------------------------------------------------

std::uint64_t fnv1a(std::string_view s) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    return h;
}

std::uint64_t mix64(std::uint64_t h) {  // a finaliser (splitmix64's), so that k-gram hashes spread evenly
    h ^= h >> 30, h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 27, h *= 0x94d049bb133111ebull;
    return h ^ (h >> 31);
}

// hashes[i] is the hash of tokens [i, i + k).
std::vector<std::uint64_t> kgramHashes(const std::vector<SourceToken>& tokens, int k) {
    std::vector<std::uint64_t> hashes;
    if (tokens.size() < std::size_t(k)) return hashes;
    std::vector<std::uint64_t> single(tokens.size());
    for (std::size_t i = 0; i < tokens.size(); ++i) single[i] = fnv1a(tokens[i].text);
    hashes.resize(tokens.size() - std::size_t(k) + 1);
    for (std::size_t i = 0; i < hashes.size(); ++i) {
        std::uint64_t h = 0;
        for (int j = 0; j < k; ++j) h = mix64(h * 31 + single[i + std::size_t(j)]);
        hashes[i] = h;
    }
    return hashes;
}

// Winnowing: in every window of w consecutive hashes, the position of the
// smallest (the rightmost of equal ones), each position once. A text with
// fewer than w k-grams is one window.
std::vector<std::size_t> winnow(const std::vector<std::uint64_t>& hashes, int w) {
    std::vector<std::size_t> chosen;
    if (hashes.empty()) return chosen;
    const std::size_t window = std::min(hashes.size(), std::size_t(w));
    for (std::size_t start = 0; start + window <= hashes.size(); ++start) {
        std::size_t best = start;
        for (std::size_t j = start; j < start + window; ++j)
            if (hashes[j] <= hashes[best]) best = j;
        if (chosen.empty() || chosen.back() != best) chosen.push_back(best);
    }
    return chosen;
}

struct Fingerprint {
    std::uint64_t hash;
    int file;
    int pos;  // the k-gram's first token
};

// One submission's code in one stage, cut up.
struct Prints {
    std::vector<std::vector<SourceToken>> tokens;  // per file
    std::vector<Fingerprint> prints;               // winnowed, evidence only
    std::vector<std::uint64_t> hashes;             // their distinct hashes, sorted
};

// ---- reading --------------------------------------------------------------

// A stage file of a submission, read only when it is a plain, small text
// file; otherwise `problem` says why not ("" for a file that is not there).
std::string readSource(const fs::path& path, std::size_t cap, std::string* problem) {
    problem->clear();
    std::error_code ec;
    for (const fs::path& p : {path.parent_path(), path}) {
        const fs::file_status st = fs::symlink_status(p, ec);
        if (ec || st.type() == fs::file_type::not_found) return "";
        if (st.type() == fs::file_type::symlink) return *problem = "a link, not read", "";
    }
    if (!fs::is_regular_file(fs::symlink_status(path, ec))) return *problem = "not a regular file, not read", "";
    std::ifstream in(path, std::ios::binary);
    std::string text(cap + 1, '\0');
    in.read(text.data(), std::streamsize(text.size()));
    if (in.bad()) return *problem = "cannot be read", "";
    text.resize(std::size_t(in.gcount()));
    if (text.size() > cap) return *problem = "larger than " + std::to_string(cap) + " bytes, not read", "";
    if (text.find('\0') != std::string::npos) return *problem = "binary (holds a NUL byte), not read", "";
    return text;
}

StageCode readStage(const std::string& folder, const SimilarityStage& stage, std::size_t cap) {
    StageCode code;
    for (const std::string& file : stage.files) {
        std::string problem;
        code.texts.push_back(readSource(fs::path(folder) / stage.stage / file, cap, &problem));
        code.files.push_back(stage.stage + "/" + file);
        code.problems.push_back(problem);
    }
    return code;
}

// Every k-gram hash of the stage's starter code; nullopt when it has none.
std::optional<std::unordered_set<std::uint64_t>> starterHashes(const std::string& root, const SimilarityStage& stage,
                                                               const SimilarityOptions& o) {
    const StageCode code = readStage(root, stage, o.maxFileBytes);
    std::unordered_set<std::uint64_t> all;
    bool any = false;
    for (const std::string& text : code.texts) {
        any = any || !text.empty();
        for (std::uint64_t h : kgramHashes(tokenizeSource(text), o.kgram)) all.insert(h);
    }
    if (!any) return std::nullopt;
    return all;
}

Prints fingerprint(const StageCode& code, const std::unordered_set<std::uint64_t>& starter,
                   const SimilarityOptions& o) {
    Prints p;
    for (std::size_t f = 0; f < code.texts.size(); ++f) {
        p.tokens.push_back(tokenizeSource(code.texts[f]));
        const std::vector<std::uint64_t> hashes = kgramHashes(p.tokens.back(), o.kgram);
        for (std::size_t pos : winnow(hashes, o.window))
            if (!starter.count(hashes[pos])) p.prints.push_back({hashes[pos], int(f), int(pos)});
    }
    return p;
}

// Drops the fingerprints found in more than `limit` submissions, then lists
// each one's distinct hashes.
void dropCommon(std::vector<Prints>& all, int limit) {
    std::unordered_map<std::uint64_t, int> holders;
    for (Prints& p : all) {
        for (const Fingerprint& f : p.prints) p.hashes.push_back(f.hash);
        std::sort(p.hashes.begin(), p.hashes.end());
        p.hashes.erase(std::unique(p.hashes.begin(), p.hashes.end()), p.hashes.end());
        for (std::uint64_t h : p.hashes) ++holders[h];
    }
    for (Prints& p : all) {
        const auto common = [&](std::uint64_t h) { return holders[h] > limit; };
        p.hashes.erase(std::remove_if(p.hashes.begin(), p.hashes.end(), common), p.hashes.end());
        p.prints.erase(std::remove_if(p.prints.begin(), p.prints.end(),
                                      [&](const Fingerprint& f) { return common(f.hash); }),
                       p.prints.end());
    }
}

// ---- a pair ---------------------------------------------------------------

// How many tokens of each side lie inside a k-gram with a shared hash.
int coveredTokens(const Prints& p, const std::set<std::uint64_t>& shared, int k) {
    std::vector<std::vector<bool>> covered(p.tokens.size());
    for (std::size_t f = 0; f < p.tokens.size(); ++f) covered[f].assign(p.tokens[f].size(), false);
    for (const Fingerprint& fp : p.prints)
        if (shared.count(fp.hash))
            for (int j = 0; j < k; ++j) covered[std::size_t(fp.file)][std::size_t(fp.pos + j)] = true;
    int n = 0;
    for (const auto& file : covered) n += int(std::count(file.begin(), file.end(), true));
    return n;
}

struct Match {
    int fileA, posA, fileB, posB;
};

// Pairs of occurrences of shared fingerprints, in A's order (a hash that
// repeats contributes at most 4 x 4).
std::vector<Match> matchesOf(const Prints& a, const Prints& b, const std::set<std::uint64_t>& shared) {
    std::map<std::uint64_t, std::vector<const Fingerprint*>> inB;
    for (const Fingerprint& f : b.prints)
        if (shared.count(f.hash) && inB[f.hash].size() < 4) inB[f.hash].push_back(&f);
    std::map<std::uint64_t, int> usedA;
    std::vector<Match> matches;
    for (const Fingerprint& f : a.prints) {
        if (!shared.count(f.hash) || usedA[f.hash]++ >= 4) continue;
        for (const Fingerprint* g : inB[f.hash]) matches.push_back({f.file, f.pos, g->file, g->pos});
    }
    std::sort(matches.begin(), matches.end(), [](const Match& x, const Match& y) {
        return std::tie(x.fileA, x.posA, x.fileB, x.posB) < std::tie(y.fileA, y.posA, y.fileB, y.posB);
    });
    return matches;
}

// Chains matches that follow each other in both files (at most w + k tokens
// apart, which winnowing guarantees inside one copied run).
std::vector<std::vector<Match>> chainsOf(const std::vector<Match>& matches, const SimilarityOptions& o) {
    std::vector<std::vector<Match>> chains;
    std::vector<std::size_t> open;
    const int reach = o.kgram + o.window;
    for (const Match& m : matches) {
        open.erase(std::remove_if(open.begin(), open.end(), [&](std::size_t c) {
                       const Match& last = chains[c].back();
                       return last.fileA != m.fileA || m.posA - last.posA > reach;
                   }), open.end());
        bool placed = false;
        for (std::size_t c : open) {
            const Match& last = chains[c].back();
            if (last.fileB == m.fileB && m.posA > last.posA && m.posB > last.posB && m.posB - last.posB <= reach) {
                chains[c].push_back(m), placed = true;
                break;
            }
        }
        if (!placed) chains.push_back({m}), open.push_back(chains.size() - 1);
    }
    return chains;
}

struct Span {  // tokens [first, last] of one file
    int file, first, last;
    int overlap(const Span& s) const {
        return file != s.file ? 0 : std::max(0, std::min(last, s.last) - std::max(first, s.first) + 1);
    }
};

// The chains as regions, longest first; a chain lying mostly (half or more
// of it, on either side) inside a longer one is dropped: it is the same code
// matched a second time (a statement that occurs twice), not more evidence.
std::vector<MatchedRegion> regionsOf(const Prints& a, const Prints& b, const std::vector<Match>& matches,
                                     const SimilarityOptions& o) {
    std::vector<std::pair<Span, Span>> spans;
    for (const std::vector<Match>& c : chainsOf(matches, o))
        spans.push_back({{c.front().fileA, c.front().posA, c.back().posA + o.kgram - 1},
                         {c.front().fileB, c.front().posB, c.back().posB + o.kgram - 1}});
    std::stable_sort(spans.begin(), spans.end(), [](const auto& x, const auto& y) {
        return x.first.last - x.first.first > y.first.last - y.first.first;
    });
    std::vector<std::pair<Span, Span>> kept;
    for (const auto& [sa, sb] : spans) {
        bool inside = false;
        for (const auto& [ka, kb] : kept)
            inside = inside || 2 * sa.overlap(ka) >= sa.last - sa.first + 1 ||
                     2 * sb.overlap(kb) >= sb.last - sb.first + 1;
        if (!inside) kept.push_back({sa, sb});
    }
    std::sort(kept.begin(), kept.end(), [](const auto& x, const auto& y) {
        return std::tie(x.first.file, x.first.first) < std::tie(y.first.file, y.first.first);
    });
    std::vector<MatchedRegion> regions;
    for (const auto& [sa, sb] : kept) {
        const auto& ta = a.tokens[std::size_t(sa.file)];
        const auto& tb = b.tokens[std::size_t(sb.file)];
        regions.push_back({sa.file, ta[std::size_t(sa.first)].line, ta[std::size_t(sa.last)].line, sb.file,
                           tb[std::size_t(sb.first)].line, tb[std::size_t(sb.last)].line, sa.last - sa.first + 1});
    }
    return regions;
}

void comparePair(const std::string& stage, std::size_t ia, std::size_t ib, const Prints& a, const Prints& b,
                 int shared, const SimilarityOptions& o, std::vector<SimilarPair>& flagged) {
    SimilarPair pair{stage, ia, ib, 0.0, shared, int(a.hashes.size()), int(b.hashes.size()), 0, 0, {}};
    pair.score = double(shared) / double(std::min(a.hashes.size(), b.hashes.size()));
    if (pair.score < o.threshold) return;
    std::set<std::uint64_t> common;
    std::set_intersection(a.hashes.begin(), a.hashes.end(), b.hashes.begin(), b.hashes.end(),
                          std::inserter(common, common.end()));
    pair.matchedTokensA = coveredTokens(a, common, o.kgram);
    pair.matchedTokensB = coveredTokens(b, common, o.kgram);
    if (std::min(pair.matchedTokensA, pair.matchedTokensB) < o.minMatchedTokens) return;
    pair.regions = regionsOf(a, b, matchesOf(a, b, common), o);
    flagged.push_back(std::move(pair));
}

// Every pair of one stage that shares a fingerprint, through an index from
// hash to the submissions holding it.
void compareStage(std::size_t s, const std::vector<Prints>& prints, const SimilarityOptions& o,
                  SimilarityReport& report) {
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> holders;
    std::size_t withCode = 0;
    for (std::size_t i = 0; i < prints.size(); ++i) {
        withCode += prints[i].hashes.empty() ? 0 : 1;
        for (std::uint64_t h : prints[i].hashes) holders[h].push_back(i);
    }
    report.pairsCompared += withCode * (withCode - (withCode > 0 ? 1 : 0)) / 2;
    std::map<std::pair<std::size_t, std::size_t>, int> shared;
    for (const auto& [hash, who] : holders)
        for (std::size_t x = 0; x < who.size(); ++x)
            for (std::size_t y = x + 1; y < who.size(); ++y) ++shared[{who[x], who[y]}];
    for (const auto& [pair, count] : shared)
        comparePair(report.stages[s], pair.first, pair.second, prints[pair.first], prints[pair.second], count, o,
                    report.pairs);
}

}  // namespace

SimilarityReport findSimilarCode(const std::vector<SimilaritySubmission>& submissions,
                                 const std::vector<SimilarityStage>& stages, const std::string& starterRoot,
                                 const SimilarityOptions& options) {
    SimilarityOptions o = options;
    o.kgram = std::clamp(o.kgram, 1, 1000);
    o.window = std::clamp(o.window, 1, 1000);
    SimilarityReport report;
    report.options = o;
    for (const SimilaritySubmission& s : submissions) report.names.push_back(s.name);
    for (const SimilarityStage& stage : stages) {
        report.stages.push_back(stage.stage);
        const auto starter = starterHashes(starterRoot, stage, o);
        if (!starter)
            report.notes.push_back(stage.stage + ": no starter code in " +
                                   (fs::path(starterRoot) / stage.stage).string() +
                                   "/, compared without removing it");
        std::vector<StageCode> code;
        std::vector<Prints> prints;
        for (const SimilaritySubmission& s : submissions) {
            code.push_back(readStage(s.folder, stage, o.maxFileBytes));
            for (std::size_t f = 0; f < code.back().files.size(); ++f)
                if (!code.back().problems[f].empty())
                    report.notes.push_back(s.name + ": " + code.back().files[f] + ": " + code.back().problems[f]);
            prints.push_back(fingerprint(code.back(), starter ? *starter : std::unordered_set<std::uint64_t>{}, o));
        }
        dropCommon(prints, o.commonLimit);
        compareStage(report.stages.size() - 1, prints, o, report);
        report.code.push_back(std::move(code));
    }
    std::stable_sort(report.pairs.begin(), report.pairs.end(),
                     [](const SimilarPair& x, const SimilarPair& y) { return x.score > y.score; });
    return report;
}

std::vector<SimilarityStage> similarityStages(const std::string& referenceRoot,
                                              const std::vector<std::string>& stages) {
    std::vector<SimilarityStage> out;
    for (const std::string& s : stages.empty() ? gradedStages(referenceRoot) : stages)
        if (fs::exists(fs::path(referenceRoot) / s / "grading.json"))
            out.push_back({s, loadStageManifest(referenceRoot, s).files});
    return out;
}

std::optional<double> parseSimilarityThreshold(const std::string& text) {
    if (text == "off") return std::nullopt;
    double v = 0.0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !(v > 0.0 && v <= 1.0))
        throw Error("option --similarity-threshold: must be a number in (0, 1] (a share of fingerprints) or off");
    return v;
}

// ---- the report -----------------------------------------------------------

namespace {

const char* const kAbout =
    "Pairs of submissions whose code in a stage is alike after names, comments, layout and the starter code are "
    "set aside. This is evidence for a person to read, not a verdict: short stages have few ways to be written, "
    "and students may have been allowed to work together. Nothing here changes a grade.";

json regionJson(const MatchedRegion& r, const StageCode& a, const StageCode& b) {
    return {{"a", {{"file", a.files[std::size_t(r.fileA)]}, {"lines", {r.firstA, r.lastA}}}},
            {"b", {{"file", b.files[std::size_t(r.fileB)]}, {"lines", {r.firstB, r.lastB}}}},
            {"tokens", r.tokens}};
}

std::size_t stageIndex(const SimilarityReport& report, const std::string& stage) {
    return std::size_t(std::find(report.stages.begin(), report.stages.end(), stage) - report.stages.begin());
}

}  // namespace

json similarityJson(const SimilarityReport& report) {
    const SimilarityOptions& o = report.options;
    json pairs = json::array();
    for (const SimilarPair& p : report.pairs) {
        const auto& code = report.code[stageIndex(report, p.stage)];
        json regions = json::array();
        for (const MatchedRegion& r : p.regions) regions.push_back(regionJson(r, code[p.a], code[p.b]));
        pairs.push_back({{"stage", p.stage}, {"a", report.names[p.a]}, {"b", report.names[p.b]},
                         {"score", p.score}, {"shared_fingerprints", p.shared},
                         {"fingerprints_a", p.fingerprintsA}, {"fingerprints_b", p.fingerprintsB},
                         {"matched_tokens_a", p.matchedTokensA}, {"matched_tokens_b", p.matchedTokensB},
                         {"regions", regions}});
    }
    return {{"about", kAbout},
            {"method", {{"score", "shared fingerprints / min(fingerprints of a, fingerprints of b)"},
                        {"threshold", o.threshold}, {"min_matched_tokens", o.minMatchedTokens},
                        {"k", o.kgram}, {"window", o.window}, {"common_limit", o.commonLimit},
                        {"reference", "Schleimer, Wilkerson, Aiken: Winnowing, SIGMOD 2003"}}},
            {"submissions", report.names}, {"stages", report.stages},
            {"pairs_compared", report.pairsCompared}, {"pairs", pairs}, {"notes", report.notes}};
}

namespace {

const char* const kExtraStyle = R"css(
.verdict { margin: 0 0 10px; padding: 10px 14px; border-left: 5px solid var(--warn); background: var(--warn-bg); }
.sbs { display: grid; grid-template-columns: minmax(0, 1fr) minmax(0, 1fr); gap: 16px; }
.sbs .side > h3 { margin-top: 8px; }
pre.code { margin: 0 0 12px; padding: 8px 0; background: #f6f8fa; border: 1px solid var(--line); border-radius: 6px;
  font-size: 12.5px; line-height: 1.45; overflow-x: auto; }
pre.code .l { display: block; padding: 0 8px; white-space: pre; }
pre.code .ln { display: inline-block; width: 3.5em; color: var(--muted); user-select: none; }
pre.code .tag { display: inline-block; min-width: 1.6em; font-weight: 700; }
.m0 { background: #ffe08a; } .m1 { background: #b6e3ff; } .m2 { background: #c5f0c5; }
.m3 { background: #ffc9d2; } .m4 { background: #e0ccff; } .m5 { background: #ffd8b0; }
)css";

const int kShownLines = 2000;    // per file on the page
const std::size_t kShownColumns = 400;

// One side of a pair: its files, each line marked with the first region
// that covers it on this side.
std::string codeSide(const StageCode& code, const std::vector<MatchedRegion>& regions, bool sideA) {
    std::string out;
    for (std::size_t f = 0; f < code.files.size(); ++f) {
        out += "<h3 class=\"path\">" + html::escape(code.files[f]) + "</h3>";
        if (code.texts[f].empty()) {
            out += "<p class=\"sub\">" + html::escape(code.problems[f].empty() ? "no code" : code.problems[f]) + "</p>";
            continue;
        }
        out += "<pre class=\"code\">";
        std::size_t at = 0;
        for (int line = 1; at <= code.texts[f].size() && line <= kShownLines; ++line) {
            std::size_t end = code.texts[f].find('\n', at);
            if (end == std::string::npos) end = code.texts[f].size();
            int region = -1, starts = -1;  // the first region covering the line, the first starting on it
            for (std::size_t r = 0; r < regions.size(); ++r) {
                const MatchedRegion& m = regions[r];
                const int file = sideA ? m.fileA : m.fileB, lo = sideA ? m.firstA : m.firstB,
                          hi = sideA ? m.lastA : m.lastB;
                if (file == int(f) && line >= lo && line <= hi && region < 0) region = int(r);
                if (file == int(f) && line == lo && starts < 0) starts = int(r);
            }
            const std::string text = code.texts[f].substr(at, std::min(end - at, kShownColumns));
            out += region < 0 ? "<span class=\"l\">" : "<span class=\"l m" + std::to_string(region % 6) +
                                                             "\" title=\"match " + std::to_string(region + 1) + "\">";
            out += "<span class=\"ln\">" + std::to_string(line) + "</span><span class=\"tag\">" +
                   (starts >= 0 ? std::to_string(starts + 1) : std::string()) + "</span>" + html::escape(text) +
                   "</span>";
            at = end + 1;
        }
        if (at < code.texts[f].size())
            out += "<span class=\"l sub\">(the rest of the file, past line " + std::to_string(kShownLines) +
                   ", is not shown)</span>";
        out += "</pre>";
    }
    return out;
}

std::string pairCard(const SimilarityReport& report, const SimilarPair& p, std::size_t index) {
    const auto& code = report.code[stageIndex(report, p.stage)];
    const std::string a = html::escape(report.names[p.a]), b = html::escape(report.names[p.b]);
    std::string out = "<section class=\"card\" id=\"pair-" + std::to_string(index + 1) + "\"><h2>" +
                      std::to_string(index + 1) + ". " + html::escape(p.stage) + ": " + a + " and " + b +
                      " &mdash; score " + html::formatNumber(p.score, 2) + "</h2>";
    out += "<p class=\"about\">" + std::to_string(p.shared) + " shared fingerprints (" + a + " has " +
           std::to_string(p.fingerprintsA) + ", " + b + " " + std::to_string(p.fingerprintsB) + "); " +
           std::to_string(p.matchedTokensA) + " of " + a + "'s tokens and " + std::to_string(p.matchedTokensB) +
           " of " + b + "'s lie in matching code. Each match is numbered and coloured the same on both sides.</p>";
    out += "<table><thead><tr><th>match</th><th>" + a + "</th><th>" + b +
           "</th><th class=\"num\">tokens</th></tr></thead><tbody>";
    for (std::size_t r = 0; r < p.regions.size(); ++r) {
        const MatchedRegion& m = p.regions[r];
        out += "<tr><td class=\"m" + std::to_string(r % 6) + "\">" + std::to_string(r + 1) + "</td><td>" +
               html::escape(code[p.a].files[std::size_t(m.fileA)]) + " lines " + std::to_string(m.firstA) + "&ndash;" +
               std::to_string(m.lastA) + "</td><td>" + html::escape(code[p.b].files[std::size_t(m.fileB)]) +
               " lines " + std::to_string(m.firstB) + "&ndash;" + std::to_string(m.lastB) +
               "</td><td class=\"num\">" + std::to_string(m.tokens) + "</td></tr>";
    }
    out += "</tbody></table><div class=\"sbs\"><div class=\"side\"><h3>" + a + "</h3>" +
           codeSide(code[p.a], p.regions, true) + "</div><div class=\"side\"><h3>" + b + "</h3>";
    return out + codeSide(code[p.b], p.regions, false) + "</div></div></section>\n";
}

std::string pairTable(const SimilarityReport& report) {
    if (report.pairs.empty())
        return "<p>No pair of submissions reached the threshold in any stage.</p>";
    std::string out = "<table><thead><tr><th>#</th><th>stage</th><th>submission</th><th>submission</th>"
                      "<th class=\"num\">score</th><th class=\"num\">matching tokens</th></tr></thead><tbody>";
    for (std::size_t i = 0; i < report.pairs.size(); ++i) {
        const SimilarPair& p = report.pairs[i];
        out += "<tr><td><a href=\"#pair-" + std::to_string(i + 1) + "\">" + std::to_string(i + 1) + "</a></td><td>" +
               html::escape(p.stage) + "</td><td>" + html::escape(report.names[p.a]) + "</td><td>" +
               html::escape(report.names[p.b]) + "</td><td class=\"num\">" + html::formatNumber(p.score, 2) +
               "</td><td class=\"num\">" + std::to_string(p.matchedTokensA) + " / " +
               std::to_string(p.matchedTokensB) + "</td></tr>";
    }
    return out + "</tbody></table>";
}

}  // namespace

std::string similarityHtml(const SimilarityReport& report) {
    const SimilarityOptions& o = report.options;
    std::string body = "<style>" + std::string(kExtraStyle) + "</style>";
    body += "<header class=\"top\"><div><div class=\"kicker\">voxlab grade --batch</div><h1>Similar code</h1>"
            "<dl class=\"meta\"><div><dt>pairs flagged</dt><dd>" + std::to_string(report.pairs.size()) +
            "</dd></div><div><dt>pairs compared</dt><dd>" + std::to_string(report.pairsCompared) +
            "</dd></div><div><dt>threshold</dt><dd>" + html::formatNumber(o.threshold, 3) +
            "</dd></div></dl></div></header><main>";
    body += "<section class=\"card\"><h2>Evidence, not a verdict</h2><p class=\"verdict\">" + html::escape(kAbout) +
            "</p><p class=\"about\">How: each stage's files are cut into tokens (comments, layout, braces and "
            "preprocessor lines dropped, every name that is not a GLSL or C++ keyword or builtin made the same "
            "token, numbers kept by value); every " + std::to_string(o.kgram) + " consecutive tokens are hashed and "
            "winnowed (window " + std::to_string(o.window) + "; Schleimer, Wilkerson and Aiken 2003, the method "
            "of MOSS). Fingerprints also found in the stage's starter code, or in more than " +
            std::to_string(o.commonLimit) + " submissions, are set aside. The score is shared fingerprints / "
            "the smaller side's fingerprints; a pair is listed at " + html::formatNumber(o.threshold, 3) +
            " or more, when each side has at least " + std::to_string(o.minMatchedTokens) +
            " tokens in matching code.</p></section>";
    body += "<section class=\"card\"><h2>Flagged pairs</h2>" + pairTable(report) + "</section>\n";
    for (std::size_t i = 0; i < report.pairs.size(); ++i) body += pairCard(report, report.pairs[i], i);
    if (!report.notes.empty()) {
        body += "<section class=\"card\"><h2>Notes</h2><ul>";
        for (const std::string& n : report.notes) body += "<li>" + html::escape(n) + "</li>";
        body += "</ul></section>";
    }
    return html::page("Similar code", body + "</main>", "");
}

void writeSimilarityReport(const SimilarityReport& report, const std::string& dir) {
    fs::create_directories(dir);
    writeFileAtomically((fs::path(dir) / "similarity.json").string(), reportJsonText(similarityJson(report)));
    writeFileAtomically((fs::path(dir) / "similarity.html").string(), similarityHtml(report));
}

}  // namespace voxlab
