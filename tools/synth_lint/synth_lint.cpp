// voxcast_synth_lint: the rules a vendor HLS front end (Vitis HLS, Catapult)
// applies to a synthesizable design, checked on the compiler's own view of the
// code (libclang's AST of the translation unit), not on its text.
//
//   voxcast_synth_lint --top NAME [--top NAME...] --root DIR [--root DIR...]
//                      [--exempt PATH...] [--region NAME --port NAME...] [--verbose]
//                      [--latencies]
//                      -- COMPILER_ARGS... FILE.cpp
//
// The translation unit is parsed as the synthesis compile sees it (the caller
// passes -D__SYNTHESIS__ among the compiler arguments). From each top function
// the call graph is followed through calls to functions, the instantiations
// of function templates, constructors, operators and lambdas' call operators,
// into every header; each reachable function whose definition is in a file
// under a --root (and not under an --exempt path) is checked for:
//
//   no-dynamic-memory   new/delete, malloc/calloc/realloc/free/aligned_alloc
//   no-recursion        a cycle in the call graph reachable from a top
//   no-virtual          virtual functions of reachable classes, virtual calls
//   no-function-pointer taking a function's address, calls through function
//                       or member function pointers (a lambda handed to a
//                       template is fine: its call operator is a direct call)
//   no-exceptions       throw, try/catch
//   no-rtti             typeid, dynamic_cast
//   no-std-containers   any variable, member, parameter, return or expression
//                       type that is (or has as a template argument) a std
//                       container, std::string, an iostream, std::function or a
//                       smart pointer. std::array is allowed: it is a fixed-size
//                       aggregate, which Vitis HLS synthesizes like a C array.
//   no-float-datapath   any expression or variable of type float, double or
//                       long double
//   static-loop-bound   every loop compares its induction variable with a
//                       compile-time constant (and starts from one), or holds
//                       VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT ...) in its own body
//   interface-pragma    every parameter of a top, and `return`, is named in a
//                       VOXCAST_HLS_PRAGMA(HLS INTERFACE ... port = NAME) in the
//                       top's own body (Vitis ignores INTERFACE pragmas in
//                       sub-functions)
//   sample-loop-ports   with --region NAME and --port NAME...: the top calls
//                       the function NAME (the per-sample pipeline) and passes
//                       it none of its pointer parameters but the --port ones
//                       (as themselves, not through a local pointer or
//                       reference), so the region can reach no external memory
//                       but those ports; and no function reachable from the
//                       region reads or writes a mutable global variable. The
//                       region's other arguments are the top's values and its
//                       locals (the on-chip copies of the load phase).
//   latency-pragma      an HLS LATENCY pragma gives min and max as one name,
//                       a namespace-scope integer constant (the unit's declared
//                       pipeline depth), never a number typed again; and it is
//                       not in a function with HLS INLINE, whose pragmas Vitis
//                       ignores (UG1399, "Inline")
//
// Set-up tables: the tables the host builds in double (reflectance map,
// classification, rsqrt seeds) live in host-only code, namespace `host` inside
// `#ifndef __SYNTHESIS__`. That code is not in the synthesis compile at all,
// so it is neither parsed here nor reachable from a top; a double that a
// kernel reaches is a finding. Constant-evaluated code is skipped: the
// initializer of a `constexpr` variable, static_assert, sizeof/alignof.
//
// --exempt: the vendor's own type headers (ap_fixed, ac_fixed) are outside
// the rules; voxcast's stand-in for them (hls/fixed_point.hpp) is passed with
// --exempt so its host conversions (to_double, from double) are not findings.
// Calls into it are still followed, and a kernel that passes it a double is
// still a finding at the kernel's call.
//
// Output: `path:line:col: error: [rule] message`, one per rule and source
// line, then per top `N functions reachable from TOP, M violations`. With
// --latencies, first one line per checked reachable function with an HLS
// LATENCY pragma of that form: `latency: FUNCTION NAME VALUE` (the function's
// qualified name, the constant's name and its value as the compiler evaluates
// it), sorted. Exit 0
// when clean, 1 on violations, 2 when the translation unit does not parse, a
// top is missing or the arguments are wrong: never a silent pass.
#include <clang-c/Index.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------
// libclang helpers
// ---------------------------------------------------------------------------

std::string take(CXString s) {
  const char* c = clang_getCString(s);
  std::string out = c ? c : "";
  clang_disposeString(s);
  return out;
}

std::string spelling(CXCursor c) { return take(clang_getCursorSpelling(c)); }
std::string type_spelling(CXType t) { return take(clang_getTypeSpelling(t)); }

struct CursorHash {
  std::size_t operator()(const CXCursor& c) const { return clang_hashCursor(c); }
};
struct CursorEq {
  bool operator()(const CXCursor& a, const CXCursor& b) const {
    return clang_equalCursors(a, b) != 0;
  }
};
template <class V>
using CursorMap = std::unordered_map<CXCursor, V, CursorHash, CursorEq>;
using CursorSet = std::unordered_set<CXCursor, CursorHash, CursorEq>;

std::vector<CXCursor> children(CXCursor c) {
  std::vector<CXCursor> out;
  clang_visitChildren(
      c,
      [](CXCursor child, CXCursor, CXClientData data) {
        static_cast<std::vector<CXCursor>*>(data)->push_back(child);
        return CXChildVisit_Continue;
      },
      &out);
  return out;
}

// Where a cursor is: the file (real path), line, column and offset.
struct Where {
  std::string file;
  unsigned line = 0, column = 0, offset = 0;
};

std::string real_path(CXFile f) {
  if (!f) return {};
  std::string p = take(clang_File_tryGetRealPathName(f));
  if (p.empty()) p = take(clang_getFileName(f));
  std::error_code ec;
  const fs::path canon = fs::weakly_canonical(p, ec);
  return ec ? p : canon.string();
}

Where where(CXSourceLocation loc) {
  CXFile f = nullptr;
  Where w;
  clang_getExpansionLocation(loc, &f, &w.line, &w.column, &w.offset);
  w.file = real_path(f);
  return w;
}
Where where(CXCursor c) { return where(clang_getCursorLocation(c)); }

// A source range as [begin, end) offsets in one file (both ends expanded out
// of macros).
struct Span {
  std::string file;
  unsigned begin = 0, end = 0;
  bool contains(const Where& w) const { return w.file == file && w.offset >= begin && w.offset < end; }
  bool contains(const Span& s) const { return s.file == file && s.begin >= begin && s.end <= end; }
};

Span span(CXCursor c) {
  const CXSourceRange r = clang_getCursorExtent(c);
  const Where b = where(clang_getRangeStart(r)), e = where(clang_getRangeEnd(r));
  return {b.file, b.offset, e.offset};
}

// The spellings of the tokens in a cursor's extent.
std::vector<std::string> tokens(CXTranslationUnit tu, CXCursor c) {
  CXToken* toks = nullptr;
  unsigned n = 0;
  clang_tokenize(tu, clang_getCursorExtent(c), &toks, &n);
  std::vector<std::string> out;
  for (unsigned i = 0; i < n; ++i) out.push_back(take(clang_getTokenSpelling(tu, toks[i])));
  clang_disposeTokens(tu, toks, n);
  return out;
}

// Qualified name, without the implementation's inline namespaces
// (std::__cxx11::basic_string is std::basic_string).
std::string qualified_name(CXCursor c) {
  std::vector<std::string> parts;
  for (CXCursor p = c; !clang_Cursor_isNull(p) && p.kind != CXCursor_TranslationUnit;
       p = clang_getCursorSemanticParent(p)) {
    // extern "C" { ... } (libclang 14 shows it as an UnexposedDecl): not a scope of names
    if (p.kind == CXCursor_LinkageSpec || p.kind == CXCursor_UnexposedDecl) continue;
    std::string name = spelling(p);
    if (p.kind == CXCursor_Namespace && (name.empty() || name.rfind("__", 0) == 0)) continue;
    // A lambda's closure type is an unnamed class (an unnamed struct is a StructDecl).
    if (name.empty()) name = p.kind == CXCursor_ClassDecl ? "(lambda)" : "(anonymous)";
    parts.push_back(name);
  }
  std::string out;
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) out += (out.empty() ? "" : "::") + *it;
  return out;
}

bool is_function_kind(CXCursorKind k) {
  return k == CXCursor_FunctionDecl || k == CXCursor_CXXMethod || k == CXCursor_Constructor ||
         k == CXCursor_Destructor || k == CXCursor_ConversionFunction ||
         k == CXCursor_FunctionTemplate;
}

bool is_loop(CXCursorKind k) {
  return k == CXCursor_ForStmt || k == CXCursor_WhileStmt || k == CXCursor_DoStmt ||
         k == CXCursor_CXXForRangeStmt;
}

// Implicit casts and parentheses around an expression (libclang shows
// implicit casts as UnexposedExpr with the operand as the only child).
CXCursor strip_implicit(CXCursor c) {
  while (c.kind == CXCursor_UnexposedExpr || c.kind == CXCursor_ParenExpr) {
    const auto kids = children(c);
    if (kids.size() != 1) break;
    c = kids[0];
  }
  return c;
}

// The integer value of a constant expression (template parameters, constexpr
// variables, literals and arithmetic on them), by clang's own evaluator.
std::optional<long long> constant_value(CXCursor expr) {
  CXEvalResult r = clang_Cursor_Evaluate(expr);
  if (!r) return std::nullopt;
  std::optional<long long> v;
  if (clang_EvalResult_getKind(r) == CXEval_Int) v = clang_EvalResult_getAsLongLong(r);
  clang_EvalResult_dispose(r);
  return v;
}

// The operator of a BinaryOperator cursor (libclang 14 has no accessor): the
// first token after the left operand.
std::string binary_operator(CXTranslationUnit tu, CXCursor op) {
  const auto kids = children(op);
  if (kids.size() != 2) return {};
  const Span lhs = span(kids[0]);
  CXToken* toks = nullptr;
  unsigned n = 0;
  clang_tokenize(tu, clang_getCursorExtent(op), &toks, &n);
  std::string out;
  for (unsigned i = 0; i < n && out.empty(); ++i) {
    if (where(clang_getTokenLocation(tu, toks[i])).offset >= lhs.end)
      out = take(clang_getTokenSpelling(tu, toks[i]));
  }
  clang_disposeTokens(tu, toks, n);
  return out;
}

// A variable declaration that is `constexpr`: its initializer is evaluated by
// the compiler, never synthesized. (libclang 14 has no accessor: the
// declaration's tokens before its name.)
bool is_constexpr_var(CXTranslationUnit tu, CXCursor var) {
  const std::string name = spelling(var);
  for (const std::string& t : tokens(tu, var)) {
    if (t == "constexpr") return true;
    if (t == name) return false;
  }
  return false;
}

// ---------------------------------------------------------------------------
// Options
// ---------------------------------------------------------------------------

struct Options {
  std::vector<std::string> tops;
  std::vector<std::string> roots;    // real paths
  std::vector<std::string> exempts;  // real paths (files or folders)
  std::vector<std::string> compiler_args;
  std::vector<std::string> regions;  // sample-loop-ports: the region functions' names
  std::set<std::string> ports;       // ... and the top's pointer parameters they may take
  bool verbose = false;
  bool latencies = false;  // list the LATENCY pragmas' functions and constants
};

bool under(const std::string& file, const std::string& dir_or_file) {
  if (file == dir_or_file) return true;
  return file.size() > dir_or_file.size() && file.compare(0, dir_or_file.size(), dir_or_file) == 0 &&
         file[dir_or_file.size()] == '/';
}

std::optional<Options> parse_options(int argc, char** argv) {
  Options o;
  int i = 1;
  auto value = [&](const char* flag) -> std::optional<std::string> {
    if (i + 1 >= argc) {
      std::fprintf(stderr, "voxcast_synth_lint: %s needs a value\n", flag);
      return std::nullopt;
    }
    return std::string(argv[++i]);
  };
  auto canon = [](const std::string& p) { return fs::weakly_canonical(fs::absolute(p)).string(); };
  for (; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--") {
      ++i;
      break;
    }
    if (a == "--top" || a == "--root" || a == "--exempt" || a == "--region" || a == "--port") {
      auto v = value(argv[i]);
      if (!v) return std::nullopt;
      if (a == "--region") o.regions.push_back(*v);
      if (a == "--port") o.ports.insert(*v);
      if (a == "--top") o.tops.push_back(*v);
      if (a == "--root") o.roots.push_back(canon(*v));
      if (a == "--exempt") o.exempts.push_back(canon(*v));
    } else if (a == "--verbose") {
      o.verbose = true;
    } else if (a == "--latencies") {
      o.latencies = true;
    } else {
      std::fprintf(stderr, "voxcast_synth_lint: unknown option %s\n", argv[i]);
      return std::nullopt;
    }
  }
  for (; i < argc; ++i) o.compiler_args.emplace_back(argv[i]);
  if (o.regions.empty() != o.ports.empty()) {
    std::fprintf(stderr, "voxcast_synth_lint: --region and --port go together\n");
    return std::nullopt;
  }
  if (o.tops.empty() || o.roots.empty() || o.compiler_args.empty()) {
    std::fprintf(stderr,
                 "usage: voxcast_synth_lint --top NAME [--top NAME...] --root DIR [--root DIR...]\n"
                 "                          [--exempt PATH...] [--region NAME --port NAME...]\n"
                 "                          [--verbose] [--latencies] -- COMPILER_ARGS... FILE\n");
    return std::nullopt;
  }
  return o;
}

// ---------------------------------------------------------------------------
// Pragmas: the VOXCAST_HLS_PRAGMA(...) expansions of the translation unit
// ---------------------------------------------------------------------------

struct Pragma {
  Where at;
  std::vector<std::string> words;  // the tokens between the macro's parentheses
  bool is(std::string_view directive) const {
    return words.size() >= 2 && words[0] == "HLS" && words[1] == directive;
  }
  // The VALUE of `key = VALUE`, if any.
  std::optional<std::string> arg(std::string_view key) const {
    for (std::size_t i = 0; i + 2 < words.size(); ++i)
      if (words[i] == key && words[i + 1] == "=") return words[i + 2];
    return std::nullopt;
  }
  // The NAME of `port = NAME`, if any.
  std::optional<std::string> port() const {
    for (std::size_t i = 0; i + 2 < words.size(); ++i)
      if (words[i] == "port" && words[i + 1] == "=") return words[i + 2];
    return std::nullopt;
  }
};

// Macro expansions are cursors of the translation unit itself when it is
// parsed with a detailed preprocessing record.
std::vector<Pragma> collect_pragmas(CXTranslationUnit tu) {
  std::vector<Pragma> out;
  for (CXCursor c : children(clang_getTranslationUnitCursor(tu))) {
    if (c.kind != CXCursor_MacroExpansion || spelling(c) != "VOXCAST_HLS_PRAGMA") continue;
    const auto toks = tokens(tu, c);  // VOXCAST_HLS_PRAGMA ( words... )
    if (toks.size() < 3) continue;
    out.push_back({where(c), std::vector<std::string>(toks.begin() + 2, toks.end() - 1)});
  }
  return out;
}

// ---------------------------------------------------------------------------
// Diagnostics
// ---------------------------------------------------------------------------

struct Diagnostic {
  Where at;
  std::string rule, message;
};

class Report {
 public:
  // One diagnostic per rule and source line: a template instantiated for
  // three profiles, or one vector used in five sub-expressions of a line, is
  // one finding. Findings about distinct things on one line (two parameters of
  // a top) differ in `subject`.
  void add(const Where& at, std::string rule, std::string message, std::string subject = {}) {
    if (!seen_.insert({at.file, at.line, rule, std::move(subject)}).second) return;
    diags_.push_back({at, std::move(rule), std::move(message)});
  }
  std::size_t size() const { return diags_.size(); }
  void print() const {
    auto sorted = diags_;
    std::stable_sort(sorted.begin(), sorted.end(), [](const Diagnostic& a, const Diagnostic& b) {
      return std::tie(a.at.file, a.at.line, a.at.column) < std::tie(b.at.file, b.at.line, b.at.column);
    });
    for (const auto& d : sorted)
      std::printf("%s:%u:%u: error: [%s] %s\n", d.at.file.c_str(), d.at.line, d.at.column,
                  d.rule.c_str(), d.message.c_str());
  }

 private:
  std::vector<Diagnostic> diags_;
  std::set<std::tuple<std::string, unsigned, std::string, std::string>> seen_;
};

// ---------------------------------------------------------------------------
// Type rules: std library types and floating point
// ---------------------------------------------------------------------------

// The std class templates that have no hardware meaning: dynamic storage,
// streams, type-erased callables, owning pointers. std::array is not here.
const std::set<std::string>& forbidden_std_types() {
  static const std::set<std::string> names = {
      "std::vector", "std::deque", "std::list", "std::forward_list", "std::map",
      "std::multimap", "std::set", "std::multiset", "std::unordered_map",
      "std::unordered_multimap", "std::unordered_set", "std::unordered_multiset",
      "std::queue", "std::priority_queue", "std::stack", "std::basic_string",
      "std::basic_string_view", "std::basic_ios", "std::ios_base", "std::basic_ostream",
      "std::basic_istream", "std::basic_iostream", "std::basic_stringstream",
      "std::basic_istringstream", "std::basic_ostringstream", "std::basic_fstream",
      "std::basic_ifstream", "std::basic_ofstream", "std::basic_streambuf", "std::function",
      "std::unique_ptr", "std::shared_ptr", "std::weak_ptr", "std::any", "std::valarray"};
  return names;
}

// The forbidden std type inside `t` (through pointers, references, arrays and
// template arguments), or empty.
std::string forbidden_std_type(CXType t, int depth = 0) {
  if (depth > 8) return {};
  t = clang_getCanonicalType(t);
  switch (t.kind) {
    case CXType_Pointer:
    case CXType_LValueReference:
    case CXType_RValueReference:
      return forbidden_std_type(clang_getPointeeType(t), depth + 1);
    case CXType_ConstantArray:
    case CXType_IncompleteArray:
      return forbidden_std_type(clang_getArrayElementType(t), depth + 1);
    case CXType_Record: {
      const CXCursor decl = clang_getTypeDeclaration(t);
      std::string name = qualified_name(decl);
      if (forbidden_std_types().count(name)) return name;
      const int n = clang_Type_getNumTemplateArguments(t);
      for (int i = 0; i < n; ++i) {
        const CXType arg = clang_Type_getTemplateArgumentAsType(t, static_cast<unsigned>(i));
        if (arg.kind == CXType_Invalid) continue;
        if (std::string inner = forbidden_std_type(arg, depth + 1); !inner.empty()) return inner;
      }
      return {};
    }
    default:
      return {};
  }
}

bool is_floating(CXType t) {
  t = clang_getCanonicalType(t);
  if (t.kind == CXType_LValueReference || t.kind == CXType_RValueReference)
    t = clang_getCanonicalType(clang_getPointeeType(t));
  return t.kind == CXType_Float || t.kind == CXType_Double || t.kind == CXType_LongDouble ||
         t.kind == CXType_Half || t.kind == CXType_Float16 || t.kind == CXType_Float128;
}

bool has_value_type(CXCursor c) {
  return clang_isExpression(c.kind) || c.kind == CXCursor_VarDecl || c.kind == CXCursor_ParmDecl ||
         c.kind == CXCursor_FieldDecl;
}

// ---------------------------------------------------------------------------
// The call graph
// ---------------------------------------------------------------------------

struct Call {
  CXCursor callee;  // a function node (see node_of)
  Where at;
};

struct Function {
  CXCursor cursor;  // the definition, or the canonical declaration without one
  std::vector<Call> calls;
  bool walked = false;
};

// A function's identity in the graph: its definition (a template's
// instantiation is its own definition), or the declaration when there is none
// (library functions, builtins).
CXCursor node_of(CXCursor decl) {
  const CXCursor def = clang_getCursorDefinition(decl);
  return clang_Cursor_isNull(def) ? clang_getCanonicalCursor(decl) : def;
}

bool has_body(CXCursor fn) { return clang_isCursorDefinition(fn) != 0; }

class Linter {
 public:
  Linter(CXTranslationUnit tu, const Options& opts)
      : tu_(tu), opts_(opts), pragmas_(collect_pragmas(tu)), constants_(collect_constants(tu)) {}

  // Checks one top; returns the number of functions reachable from it.
  std::size_t check_top(CXCursor top) {
    const std::size_t before = report_.size();
    check_interface(top);
    std::vector<CXCursor> reachable = reach(top);
    for (const std::string& region : opts_.regions) check_region(top, region);
    check_recursion(reachable);
    for (CXCursor fn : reachable) check_class_of(fn);
    if (opts_.verbose) list(reachable);
    last_violations_ = report_.size() - before;
    return reachable.size();
  }

  // The violations the last check_top found first (one shared by two tops is
  // counted for the first).
  std::size_t last_violations() const { return last_violations_; }

  const Report& report() const { return report_; }

  // `latency: FUNCTION NAME VALUE` for each LATENCY pragma of the checked form.
  void print_latencies() const {
    for (const auto& [fn, name, value] : latencies_)
      std::printf("latency: %s %s %lld\n", fn.c_str(), name.c_str(), value);
  }

 private:
  // --- scope ---------------------------------------------------------------
  bool checked(const std::string& file) const {
    const bool in_root = std::any_of(opts_.roots.begin(), opts_.roots.end(),
                                     [&](const std::string& r) { return under(file, r); });
    const bool exempt = std::any_of(opts_.exempts.begin(), opts_.exempts.end(),
                                    [&](const std::string& e) { return under(file, e); });
    return in_root && !exempt;
  }
  bool checked(CXCursor fn) const { return has_body(fn) && checked(where(fn).file); }

  std::string name_of(CXCursor fn) const { return qualified_name(fn); }
  std::string in(CXCursor fn) const { return " in '" + name_of(fn) + "'"; }

  // --- graph ---------------------------------------------------------------
  Function& node(CXCursor fn) {
    auto [it, fresh] = graph_.try_emplace(fn, Function{fn, {}, false});
    return it->second;
  }

  // Every function reachable from `top` (breadth first), each walked once:
  // its calls recorded and, when in the checked scope, its body checked.
  std::vector<CXCursor> reach(CXCursor top) {
    std::vector<CXCursor> order{top};
    CursorSet seen{top};
    for (std::size_t i = 0; i < order.size(); ++i) {
      Function& f = node(order[i]);
      if (!f.walked) walk(f);
      for (const Call& c : node(order[i]).calls)
        if (seen.insert(c.callee).second) order.push_back(c.callee);
    }
    return order;
  }

  // Walks a function's declaration and body: calls become edges; the rules
  // run on it when it is in the checked scope.
  void walk(Function& f) {
    f.walked = true;
    const CXCursor fn = f.cursor;
    if (!has_body(fn)) return;
    const bool check = checked(fn);
    if (check) check_signature(fn);
    if (check) check_latency(fn);
    std::vector<CXCursor> stack{fn};
    std::vector<Call> calls;
    visit_body(fn, stack, calls, check);
    node(fn).calls = std::move(calls);  // graph_ may have rehashed: look up again
  }

  struct WalkState {
    Linter* self;
    std::vector<CXCursor>* stack;
    std::vector<Call>* calls;
    bool check;
  };

  void visit_body(CXCursor parent, std::vector<CXCursor>& stack, std::vector<Call>& calls, bool check) {
    WalkState st{this, &stack, &calls, check};
    clang_visitChildren(
        parent,
        [](CXCursor c, CXCursor, CXClientData data) {
          auto* s = static_cast<WalkState*>(data);
          if (s->self->visit(c, *s)) {
            s->stack->push_back(c);
            s->self->visit_body(c, *s->stack, *s->calls, s->check);
            s->stack->pop_back();
          }
          return CXChildVisit_Continue;
        },
        &st);
  }

  // One cursor of a function being walked; returns whether to descend.
  bool visit(CXCursor c, WalkState& s) {
    const CXCursor fn = s.stack->front();
    switch (c.kind) {
      case CXCursor_LambdaExpr:  // its call operator is a node of its own, if called
      case CXCursor_StructDecl:  // a local class's members likewise
      case CXCursor_ClassDecl:
      case CXCursor_StaticAssert:  // constant-evaluated
      case CXCursor_UnaryExpr:     // sizeof / alignof: unevaluated
        return false;
      default:
        break;
    }
    if (c.kind == CXCursor_VarDecl && is_constexpr_var(tu_, c)) {
      if (s.check) check_types(c, fn);
      return false;  // the initializer is evaluated by the compiler
    }
    if (c.kind == CXCursor_CallExpr) record_call(c, fn, s);
    if (c.kind == CXCursor_DeclRefExpr || c.kind == CXCursor_MemberRefExpr) record_reference(c, fn, s);
    if (s.check) {
      check_types(c, fn);
      check_construct(c, fn);
      if (is_loop(c.kind)) check_loop(c, fn);
    }
    return true;
  }

  void record_call(CXCursor call, CXCursor fn, WalkState& s) {
    const CXCursor callee = clang_getCursorReferenced(call);
    if (!clang_Cursor_isNull(callee) && is_function_kind(callee.kind)) {
      const CXCursor target = node_of(callee);
      s.calls->push_back({target, where(call)});
      if (s.check) check_call(call, callee, fn);
      return;
    }
    if (s.check && calls_through_pointer(call, callee))
      report_.add(where(call), "no-function-pointer",
                  "call through a function pointer or member function pointer" + in(fn));
  }

  // A call whose callee is not a function: through a variable, parameter or
  // member of pointer-to-function type, or a pointer-to-member call.
  static bool calls_through_pointer(CXCursor call, CXCursor callee) {
    if (!clang_Cursor_isNull(callee) && callee.kind != CXCursor_VarDecl &&
        callee.kind != CXCursor_ParmDecl && callee.kind != CXCursor_FieldDecl)
      return false;
    const auto kids = children(call);
    if (kids.empty()) return false;
    const CXCursor target = strip_implicit(kids[0]);
    CXType t = clang_getCanonicalType(clang_getCursorType(target));
    if (t.kind == CXType_Pointer || t.kind == CXType_LValueReference) t = clang_getCanonicalType(clang_getPointeeType(t));
    return t.kind == CXType_FunctionProto || t.kind == CXType_FunctionNoProto ||
           t.kind == CXType_MemberPointer || target.kind == CXCursor_BinaryOperator;
  }

  // A reference to a function that is not the callee of the call around it
  // takes the function's address. The function is then reachable too.
  void record_reference(CXCursor ref, CXCursor fn, WalkState& s) {
    const CXCursor target = clang_getCursorReferenced(ref);
    if (clang_Cursor_isNull(target) || !is_function_kind(target.kind)) return;
    if (is_callee(target, *s.stack)) return;
    s.calls->push_back({node_of(target), where(ref)});
    if (s.check)
      report_.add(where(ref), "no-function-pointer",
                  "address of function '" + qualified_name(target) + "' taken" + in(fn));
  }

  // Whether the innermost expression around a reference (past implicit casts
  // and parentheses) is a call of the referenced function.
  static bool is_callee(CXCursor target, const std::vector<CXCursor>& stack) {
    for (auto it = stack.rbegin(); it != stack.rend(); ++it) {
      if (it->kind == CXCursor_UnexposedExpr || it->kind == CXCursor_ParenExpr) continue;
      if (it->kind != CXCursor_CallExpr) return false;
      return clang_equalCursors(clang_getCursorReferenced(*it), target) != 0;
    }
    return false;
  }

  // --- content rules -------------------------------------------------------
  void check_signature(CXCursor fn) {
    const CXType result = clang_getCursorResultType(fn);
    if (std::string t = forbidden_std_type(result); !t.empty())
      report_.add(where(fn), "no-std-containers", "returns " + t + in(fn));
    if (is_floating(result))
      report_.add(where(fn), "no-float-datapath",
                  "returns floating-point type '" + type_spelling(result) + "'" + in(fn));
    if (fn.kind == CXCursor_CXXMethod && clang_CXXMethod_isVirtual(fn))
      report_.add(where(fn), "no-virtual", "virtual function '" + name_of(fn) + "' is reachable");
  }

  void check_types(CXCursor c, CXCursor fn) {
    if (!has_value_type(c)) return;
    const CXType t = clang_getCursorType(c);
    if (std::string std_type = forbidden_std_type(t); !std_type.empty())
      report_.add(where(c), "no-std-containers",
                  "use of " + std_type + " (type '" + type_spelling(t) + "')" + in(fn));
    if (is_floating(t))
      report_.add(where(c), "no-float-datapath",
                  "floating-point " + std::string(clang_isExpression(c.kind) ? "expression" : "variable") +
                      " of type '" + type_spelling(t) + "'" + in(fn));
  }

  void check_construct(CXCursor c, CXCursor fn) {
    switch (c.kind) {
      case CXCursor_CXXNewExpr:
        report_.add(where(c), "no-dynamic-memory", "new expression" + in(fn));
        break;
      case CXCursor_CXXDeleteExpr:
        report_.add(where(c), "no-dynamic-memory", "delete expression" + in(fn));
        break;
      case CXCursor_CXXThrowExpr:
        report_.add(where(c), "no-exceptions", "throw expression" + in(fn));
        break;
      case CXCursor_CXXTryStmt:
        report_.add(where(c), "no-exceptions", "try block" + in(fn));
        break;
      case CXCursor_CXXTypeidExpr:
        report_.add(where(c), "no-rtti", "typeid" + in(fn));
        break;
      case CXCursor_CXXDynamicCastExpr:
        report_.add(where(c), "no-rtti", "dynamic_cast" + in(fn));
        break;
      default:
        break;
    }
  }

  void check_call(CXCursor call, CXCursor callee, CXCursor fn) {
    static const std::set<std::string> allocators = {
        "malloc", "calloc", "realloc", "free", "aligned_alloc",
        "std::malloc", "std::calloc", "std::realloc", "std::free", "std::aligned_alloc"};
    const std::string name = qualified_name(callee);
    if (allocators.count(name))
      report_.add(where(call), "no-dynamic-memory", "call to " + name + in(fn));
    if (callee.kind == CXCursor_CXXMethod && clang_CXXMethod_isVirtual(callee))
      report_.add(where(call), "no-virtual", "call to virtual function '" + name + "'" + in(fn));
  }

  // The class of a reachable member function: its virtual functions and its
  // members of std library types.
  void check_class_of(CXCursor fn) {
    if (fn.kind != CXCursor_CXXMethod && fn.kind != CXCursor_Constructor &&
        fn.kind != CXCursor_Destructor && fn.kind != CXCursor_ConversionFunction)
      return;
    check_class(clang_getCursorSemanticParent(fn));
  }

  // A reachable class and its bases (a base's virtual destructor makes the
  // class polymorphic even when no base member is called).
  void check_class(CXCursor cls) {
    if (clang_Cursor_isNull(cls) || !classes_seen_.insert(cls).second) return;
    const bool check = checked(where(cls).file);
    for (CXCursor m : children(cls)) {
      if (m.kind == CXCursor_CXXBaseSpecifier) {
        const CXCursor base = clang_getCursorDefinition(clang_getTypeDeclaration(clang_getCursorType(m)));
        check_class(base);
      }
      if (!check) continue;
      if ((m.kind == CXCursor_CXXMethod || m.kind == CXCursor_Destructor) && clang_CXXMethod_isVirtual(m))
        report_.add(where(m), "no-virtual",
                    "virtual function '" + qualified_name(m) + "' in a reachable class");
      if (m.kind == CXCursor_FieldDecl)
        if (std::string t = forbidden_std_type(clang_getCursorType(m)); !t.empty())
          report_.add(where(m), "no-std-containers", "member of type " + t + " in a reachable class");
    }
  }

  // --- sample-loop-ports ---------------------------------------------------
  static bool is_pointer(CXType t) {
    return clang_getCanonicalType(t).kind == CXType_Pointer;
  }
  static bool is_reference(CXType t) {
    const CXTypeKind k = clang_getCanonicalType(t).kind;
    return k == CXType_LValueReference || k == CXType_RValueReference;
  }
  static void collect(CXCursor c, CXCursorKind kind, std::vector<CXCursor>& out) {
    if (c.kind == kind) out.push_back(c);
    for (CXCursor k : children(c)) collect(k, kind, out);
  }

  // The calls of `region` in the top's body, and what each passes.
  void check_region(CXCursor top, const std::string& region) {
    std::vector<CXCursor> params;
    for (int i = 0; i < clang_Cursor_getNumArguments(top); ++i)
      params.push_back(clang_Cursor_getArgument(top, static_cast<unsigned>(i)));
    auto top_param = [&](CXCursor decl) -> std::optional<CXCursor> {
      for (CXCursor p : params)
        if (clang_equalCursors(p, decl)) return p;
      return std::nullopt;
    };
    std::vector<CXCursor> calls;
    collect(top, CXCursor_CallExpr, calls);
    int found = 0;
    for (CXCursor call : calls) {
      const CXCursor callee = clang_getCursorReferenced(call);
      if (clang_Cursor_isNull(callee) || spelling(callee) != region) continue;
      ++found;
      const int n = clang_Cursor_getNumArguments(call);
      for (int i = 0; i < n; ++i) check_region_argument(clang_Cursor_getArgument(call, static_cast<unsigned>(i)), i, region, top_param);
      for (CXCursor fn : reach(node_of(callee))) check_globals(fn, region);
    }
    if (found == 0)
      report_.add(where(top), "sample-loop-ports",
                  "the top does not call the region '" + region + "' (--region)");
  }

  template <class TopParam>
  void check_region_argument(CXCursor arg, int index, const std::string& region, TopParam& top_param) {
    const std::string which = "argument " + std::to_string(index + 1) + " of '" + region + "'";
    const CXCursor bare = strip_implicit(arg);
    if (bare.kind == CXCursor_DeclRefExpr) {
      const auto p = top_param(clang_getCursorReferenced(bare));
      if (p && is_pointer(clang_getCursorType(*p)) && opts_.ports.count(spelling(*p))) return;
    }
    std::vector<CXCursor> refs;
    collect(arg, CXCursor_DeclRefExpr, refs);
    for (CXCursor ref : refs) {
      const CXCursor decl = clang_getCursorReferenced(ref);
      const CXType t = clang_getCursorType(decl);
      if (const auto p = top_param(decl)) {
        if (is_pointer(t))
          report_.add(where(ref), "sample-loop-ports",
                      which + " reaches the top's pointer parameter '" + spelling(*p) +
                          "', which is not a port of the sample loop (--port)");
      } else if (decl.kind == CXCursor_VarDecl && (is_pointer(t) || is_reference(t))) {
        report_.add(where(ref), "sample-loop-ports",
                    which + " passes the local '" + spelling(decl) + "' of type '" +
                        type_spelling(t) + "', which may alias external memory");
      }
    }
    if (is_pointer(clang_getCursorType(arg)) && bare.kind != CXCursor_DeclRefExpr)
      report_.add(where(arg), "sample-loop-ports",
                  which + " is a pointer computed in the top, not one of the ports");
  }

  // A function of the region that reads or writes a mutable variable at
  // namespace scope (or a static data member): memory outside the region's
  // arguments. Static locals are the function's own (on-chip) state.
  void check_globals(CXCursor fn, const std::string& region) {
    if (!checked(fn) || !globals_checked_.insert(fn).second) return;
    std::vector<CXCursor> refs;
    collect(fn, CXCursor_DeclRefExpr, refs);
    for (CXCursor ref : refs) {
      const CXCursor decl = clang_getCursorReferenced(ref);
      if (decl.kind != CXCursor_VarDecl) continue;
      const CXCursorKind scope = clang_getCursorSemanticParent(decl).kind;
      const bool global = scope == CXCursor_TranslationUnit || scope == CXCursor_Namespace ||
                          scope == CXCursor_StructDecl || scope == CXCursor_ClassDecl ||
                          scope == CXCursor_ClassTemplate;
      if (!global || is_constexpr_var(tu_, decl) ||
          clang_isConstQualifiedType(clang_getCursorType(decl)))
        continue;
      report_.add(where(ref), "sample-loop-ports",
                  "'" + name_of(fn) + "' in the region '" + region + "' uses the global '" +
                      qualified_name(decl) + "'");
    }
  }

  // --- loops ---------------------------------------------------------------
  void check_loop(CXCursor loop, CXCursor fn) {
    // A defaulted special member (implicit or `= default`) copies a member
    // array element by element: the compiler's loop over a fixed size. Seen
    // with vendor types whose copy is not trivial (ap_fixed).
    if ((fn.kind == CXCursor_CXXMethod || fn.kind == CXCursor_Constructor) &&
        clang_CXXMethod_isDefaulted(fn))
      return;
    if (has_own_tripcount(loop) || has_static_bound(loop)) return;
    report_.add(where(loop), "static-loop-bound",
                "loop without a compile-time bound or HLS LOOP_TRIPCOUNT pragma" + in(fn));
  }

  // A LOOP_TRIPCOUNT pragma in the loop's body that is not in a nested loop.
  bool has_own_tripcount(CXCursor loop) const {
    const CXCursor body = loop_body(loop);
    if (clang_Cursor_isNull(body)) return false;
    const Span b = span(body);
    std::vector<Span> nested;
    collect_loops(body, nested);
    return std::any_of(pragmas_.begin(), pragmas_.end(), [&](const Pragma& p) {
      return p.is("LOOP_TRIPCOUNT") && b.contains(p.at) &&
             std::none_of(nested.begin(), nested.end(), [&](const Span& n) { return n.contains(p.at); });
    });
  }

  static void collect_loops(CXCursor c, std::vector<Span>& out) {
    for (CXCursor k : children(c)) {
      if (is_loop(k.kind)) out.push_back(span(k));
      else if (k.kind != CXCursor_LambdaExpr) collect_loops(k, out);
    }
  }

  static CXCursor loop_body(CXCursor loop) {
    const auto kids = children(loop);
    if (kids.empty()) return clang_getNullCursor();
    return loop.kind == CXCursor_DoStmt ? kids.front() : kids.back();
  }

  // for (int i = CONST; i < CONST; ...), while (i < CONST), do ... while (i < CONST),
  // or a range-for over a fixed-size array.
  bool has_static_bound(CXCursor loop) const {
    const auto kids = children(loop);
    switch (loop.kind) {
      case CXCursor_ForStmt:
        return static_for(loop, kids);
      case CXCursor_WhileStmt:
        return kids.size() == 2 && starts_constant(static_comparison(kids[0]), std::nullopt);
      case CXCursor_DoStmt:
        return kids.size() == 2 && starts_constant(static_comparison(kids[1]), std::nullopt);
      case CXCursor_CXXForRangeStmt: {
        // children: the loop variable, the range, the body
        if (kids.size() < 3) return false;
        const CXType range = clang_getCanonicalType(clang_getCursorType(kids[kids.size() - 2]));
        return range.kind == CXType_ConstantArray ||
               qualified_name(clang_getTypeDeclaration(range)) == "std::array";
      }
      default:
        return false;
    }
  }

  // The for-statement's parts are told apart by the two `;` in its
  // parentheses (libclang lists only the parts present).
  bool static_for(CXCursor loop, const std::vector<CXCursor>& kids) const {
    CXToken* toks = nullptr;
    unsigned n = 0;
    clang_tokenize(tu_, clang_getCursorExtent(loop), &toks, &n);
    std::vector<unsigned> semis;
    int depth = 0;
    for (unsigned i = 0; i < n; ++i) {
      const std::string t = take(clang_getTokenSpelling(tu_, toks[i]));
      if (t == "(") ++depth;
      if (t == ")" && --depth == 0) break;
      if (t == ";" && depth == 1) semis.push_back(where(clang_getTokenLocation(tu_, toks[i])).offset);
    }
    clang_disposeTokens(tu_, toks, n);
    if (semis.size() != 2) return false;
    std::optional<CXCursor> init, cond;
    for (CXCursor k : kids) {
      const Span s = span(k);
      if (s.end <= semis[0]) init = k;
      else if (s.begin > semis[0] && s.end <= semis[1]) cond = k;
    }
    if (!cond) return false;
    return starts_constant(static_comparison(*cond), init);
  }

  // Whether the induction variable `var` starts from a constant: its
  // declaration's initializer (in a for-statement's init or before a while
  // loop), or `var = CONST` as the for-statement's init. A heuristic: an
  // assignment between the declaration and a while loop is not seen.
  bool starts_constant(std::optional<CXCursor> var, std::optional<CXCursor> init) const {
    if (!var) return false;
    if (init && init->kind != CXCursor_DeclStmt) {
      const CXCursor assign = strip_implicit(*init);
      const auto sides = children(assign);
      if (assign.kind == CXCursor_BinaryOperator && sides.size() == 2 &&
          binary_operator(tu_, assign) == "=" &&
          clang_equalCursors(clang_getCursorReferenced(strip_implicit(sides[0])), *var))
        return constant_value(sides[1]).has_value();
    }
    const CXCursor start = clang_Cursor_getVarDeclInitializer(*var);
    return !clang_Cursor_isNull(start) && constant_value(start).has_value();
  }

  // `v OP CONST` or `CONST OP v` with OP a comparison and v a variable: the
  // variable's declaration.
  std::optional<CXCursor> static_comparison(CXCursor cond) const {
    cond = strip_implicit(cond);
    if (cond.kind != CXCursor_BinaryOperator) return std::nullopt;
    static const std::set<std::string> comparisons = {"<", "<=", ">", ">=", "!="};
    if (!comparisons.count(binary_operator(tu_, cond))) return std::nullopt;
    const auto sides = children(cond);
    for (int v = 0; v < 2; ++v) {
      const CXCursor var = strip_implicit(sides[static_cast<std::size_t>(v)]);
      const CXCursor bound = sides[static_cast<std::size_t>(1 - v)];
      if (var.kind != CXCursor_DeclRefExpr) continue;
      const CXCursor decl = clang_getCursorReferenced(var);
      if (decl.kind == CXCursor_VarDecl && !constant_value(var) && constant_value(bound)) return decl;
    }
    return std::nullopt;
  }

  // --- tops: interface pragmas ---------------------------------------------
  void check_interface(CXCursor top) {
    std::set<std::string> ports;
    const Span body = span(top);
    for (const Pragma& p : pragmas_)
      if (p.is("INTERFACE") && body.contains(p.at))
        if (auto port = p.port()) ports.insert(*port);
    const int n = clang_Cursor_getNumArguments(top);
    for (int i = 0; i < n; ++i) {
      const CXCursor param = clang_Cursor_getArgument(top, static_cast<unsigned>(i));
      const std::string name = spelling(param);
      if (!ports.count(name))
        report_.add(where(param), "interface-pragma",
                    "parameter '" + name + "' of top '" + name_of(top) +
                        "' has no HLS INTERFACE pragma in the top's body",
                    name);
    }
    if (!ports.count("return"))
      report_.add(where(top), "interface-pragma",
                  "top '" + name_of(top) + "' has no HLS INTERFACE pragma for port = return in its body",
                  "return");
  }

  // --- latency pragmas -------------------------------------------------------
  // A namespace-scope integer constant: qualified name and value.
  struct Constant {
    std::string qualified;
    long long value;
  };

  // Every const-qualified namespace-scope variable of the translation unit
  // with an integer value, by name.
  static std::multimap<std::string, Constant> collect_constants(CXTranslationUnit tu) {
    std::multimap<std::string, Constant> out;
    clang_visitChildren(
        clang_getTranslationUnitCursor(tu),
        [](CXCursor c, CXCursor, CXClientData data) {
          auto* m = static_cast<std::multimap<std::string, Constant>*>(data);
          if (c.kind == CXCursor_Namespace) return CXChildVisit_Recurse;
          if (c.kind == CXCursor_VarDecl && clang_isConstQualifiedType(clang_getCursorType(c)))
            if (const auto v = constant_value(c)) m->insert({spelling(c), {qualified_name(c), *v}});
          return CXChildVisit_Continue;
        },
        &out);
    return out;
  }

  // The constant `name` as seen from function `fn`: of the constants of that
  // name, the one in the innermost namespace enclosing fn.
  std::optional<Constant> lookup_constant(const std::string& name, CXCursor fn) const {
    const std::string scope = name_of(fn);
    std::optional<Constant> best;
    const auto [lo, hi] = constants_.equal_range(name);
    for (auto it = lo; it != hi; ++it) {
      const std::string& q = it->second.qualified;
      const std::string ns = q.size() > name.size() + 2 ? q.substr(0, q.size() - name.size()) : "";
      if (!ns.empty() && scope.compare(0, ns.size(), ns) != 0) continue;
      if (!best || q.size() > best->qualified.size()) best = it->second;
    }
    return best;
  }

  static bool is_identifier(const std::string& w) {
    return !w.empty() && (std::isalpha(static_cast<unsigned char>(w[0])) || w[0] == '_') &&
           std::all_of(w.begin(), w.end(), [](char ch) {
             return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
           });
  }

  static std::string upper(std::string w) {
    for (char& ch : w) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    return w;
  }

  void check_latency(CXCursor fn) {
    const Span body = span(fn);
    bool inlined = false;
    std::vector<const Pragma*> latency;
    for (const Pragma& p : pragmas_) {
      if (p.words.size() < 2 || p.words[0] != "HLS" || !body.contains(p.at)) continue;
      const std::string directive = upper(p.words[1]);
      if (directive == "INLINE" && (p.words.size() < 3 || upper(p.words[2]) != "OFF"))
        inlined = true;
      if (directive == "LATENCY") latency.push_back(&p);
    }
    for (const Pragma* p : latency) {
      if (inlined)
        report_.add(p->at, "latency-pragma",
                    "HLS LATENCY in an inlined function (HLS INLINE) is ignored by Vitis" + in(fn));
      const auto lo = p->arg("min"), hi = p->arg("max");
      if (!lo || !hi || *lo != *hi || !is_identifier(*lo)) {
        report_.add(p->at, "latency-pragma",
                    "HLS LATENCY must give min and max as one name, the unit's declared depth "
                    "constant" + in(fn));
        continue;
      }
      const auto c = lookup_constant(*lo, fn);
      if (!c) {
        report_.add(p->at, "latency-pragma",
                    "HLS LATENCY names '" + *lo + "', no namespace-scope integer constant" +
                        in(fn));
        continue;
      }
      if (!inlined) latencies_.insert({name_of(fn), c->qualified, c->value});
    }
  }

  // --- recursion -------------------------------------------------------------
  // Tarjan's strongly connected components over the reachable graph; every
  // call inside a component (or to itself) closes a cycle.
  void check_recursion(const std::vector<CXCursor>& reachable) {
    CursorMap<int> index, low;
    CursorSet on_stack;
    std::vector<CXCursor> stack;
    CursorMap<int> component;
    int counter = 0, components = 0;
    std::function<void(CXCursor)> connect = [&](CXCursor v) {
      index[v] = low[v] = counter++;
      stack.push_back(v);
      on_stack.insert(v);
      for (const Call& c : node(v).calls) {
        if (!index.count(c.callee)) {
          connect(c.callee);
          low[v] = std::min(low[v], low[c.callee]);
        } else if (on_stack.count(c.callee)) {
          low[v] = std::min(low[v], index[c.callee]);
        }
      }
      if (low[v] == index[v]) {
        CXCursor w;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack.erase(w);
          component[w] = components;
        } while (!clang_equalCursors(w, v));
        ++components;
      }
    };
    for (CXCursor v : reachable)
      if (!index.count(v)) connect(v);
    for (CXCursor v : reachable) {
      if (!checked(v)) continue;
      for (const Call& c : node(v).calls)
        if (component[c.callee] == component[v])
          report_.add(c.at, "no-recursion",
                      "call to '" + name_of(c.callee) + "' closes a recursion cycle through '" +
                          name_of(v) + "'");
    }
  }

  void list(const std::vector<CXCursor>& reachable) const {
    for (CXCursor fn : reachable) {
      const Where w = where(fn);
      std::printf("  %s %s (%s:%u)\n", checked(fn) ? "checked  " : "unchecked", name_of(fn).c_str(),
                  w.file.c_str(), w.line);
    }
  }

  CXTranslationUnit tu_;
  const Options& opts_;
  std::vector<Pragma> pragmas_;
  std::multimap<std::string, Constant> constants_;
  std::set<std::tuple<std::string, std::string, long long>> latencies_;
  CursorMap<Function> graph_;
  CursorSet classes_seen_;
  CursorSet globals_checked_;
  Report report_;
  std::size_t last_violations_ = 0;
};

// ---------------------------------------------------------------------------
// Driver
// ---------------------------------------------------------------------------

// Reports the translation unit's errors; true when there are none.
bool parsed_cleanly(CXTranslationUnit tu) {
  bool ok = true;
  const unsigned n = clang_getNumDiagnostics(tu);
  for (unsigned i = 0; i < n; ++i) {
    CXDiagnostic d = clang_getDiagnostic(tu, i);
    if (clang_getDiagnosticSeverity(d) >= CXDiagnostic_Error) {
      ok = false;
      std::fprintf(stderr, "%s\n",
                   take(clang_formatDiagnostic(d, clang_defaultDiagnosticDisplayOptions())).c_str());
    }
    clang_disposeDiagnostic(d);
  }
  return ok;
}

// The definition of a top: matched by its plain name, or by its qualified
// name when the option has `::`.
std::optional<CXCursor> find_top(CXTranslationUnit tu, const std::string& name) {
  struct Search {
    std::string name;
    std::optional<CXCursor> found;
  } search{name, std::nullopt};
  clang_visitChildren(
      clang_getTranslationUnitCursor(tu),
      [](CXCursor c, CXCursor, CXClientData data) {
        auto* s = static_cast<Search*>(data);
        if (c.kind == CXCursor_Namespace || c.kind == CXCursor_LinkageSpec) return CXChildVisit_Recurse;
        if (c.kind == CXCursor_FunctionDecl && clang_isCursorDefinition(c)) {
          const bool qualified = s->name.find("::") != std::string::npos;
          if ((qualified ? qualified_name(c) : spelling(c)) == s->name) {
            s->found = c;
            return CXChildVisit_Break;
          }
        }
        return CXChildVisit_Continue;
      },
      &search);
  return search.found;
}

int run(const Options& opts) {
  std::vector<const char*> args;
  for (const auto& a : opts.compiler_args) args.push_back(a.c_str());
  CXIndex index = clang_createIndex(/*excludeDeclarationsFromPCH=*/0, /*displayDiagnostics=*/0);
  CXTranslationUnit tu = nullptr;
  const CXErrorCode err = clang_parseTranslationUnit2(
      index, nullptr, args.data(), static_cast<int>(args.size()), nullptr, 0,
      CXTranslationUnit_DetailedPreprocessingRecord | CXTranslationUnit_KeepGoing, &tu);
  int status = 0;
  if (err != CXError_Success || !tu) {
    std::fprintf(stderr, "voxcast_synth_lint: error: the translation unit could not be parsed (code %d)\n",
                 static_cast<int>(err));
    status = 2;
  } else if (!parsed_cleanly(tu)) {
    std::fprintf(stderr, "voxcast_synth_lint: error: the translation unit has errors; nothing checked\n");
    status = 2;
  } else {
    Linter lint(tu, opts);
    std::vector<std::string> summaries;
    for (const std::string& name : opts.tops) {
      const auto top = find_top(tu, name);
      if (!top) {
        std::fprintf(stderr, "voxcast_synth_lint: error: top function '%s' is not defined in the translation unit\n",
                     name.c_str());
        status = 2;
        continue;
      }
      const std::size_t n = lint.check_top(*top);
      summaries.push_back(std::to_string(n) + " functions reachable from " + name + ", " +
                          std::to_string(lint.last_violations()) + " violations");
    }
    if (opts.latencies) lint.print_latencies();
    lint.report().print();
    for (const auto& line : summaries) std::printf("%s\n", line.c_str());
    if (status == 0 && lint.report().size() > 0) status = 1;
  }
  if (tu) clang_disposeTranslationUnit(tu);
  clang_disposeIndex(index);
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  const auto opts = parse_options(argc, argv);
  if (!opts) return 2;
  return run(*opts);
}
