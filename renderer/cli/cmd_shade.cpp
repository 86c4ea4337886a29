// `lobe shade`: runs a shader group over a grid of points, as OSL's testshade does; its options
// and output follow testshade 1.13.12 (shade_args.h lists them, docs/cli.md describes them).
//
// What it prints, in order: `Connect A.x to B.y` for each --connect (while reading the command
// line); with -v the group; a blank line if any -o was given; `Output VAR to FILE` for each
// output found (not for FILE "null"); with --print a `Pixel (x, y):` block per point; then
// what the shaders said (printf on stdout, warnings and errors on stderr, as OSL words them);
// a blank line when there is exactly one output and its file is "null" (as without -o, whose
// default is `-o Cout null`); then --print-groupdata and --runstats.
//
// Points are shaded on -t threads (default: one per core) and everything a point prints is
// kept with the point, so the output is the same, in row-major order, whatever the threads.
#include "command.h"

#include "diag/diagnostics.h"
#include "grid.h"
#include "image.h"
#include "instance_values.h"
#include "ir/query.h"
#include "lobe/memory.h"
#include "lobe/shadingsys.h"
#include "shade_args.h"
#include "shade_services.h"
#include "shader_source.h"
#include "threads.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <locale>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace lobe::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Stops the grid: set by Ctrl-C (the signal handler may touch nothing else) or by a shade
// stopped in a loop. Shading stops at the next point, and running shaders at their next loop
// check (it is every ShadingContext's `cancel`).
std::atomic<bool> g_cancel{false};
extern "C" void on_shade_sigint(int) { g_cancel.store(true); }
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// One -o once the group is compiled: the layer it reads, its type, and its image.
struct Output {
  ShadeOutput spec;
  std::string layer; // resolved
  DataType type;
  bool closure = false;
  image::Image img; // allocated only when written (written())

  // Whether the output goes to an image file (not "null", not --print, a number type).
  bool written(bool print) const {
    return spec.file != "null" && !print && !closure && type.base != DataType::Base::String;
  }
};

// What one point's shaders said, in order.
struct Said {
  ShadingContext::MessageKind kind;
  std::string text;
};

// The shader testshade's --expr builds around an expression (OSL 1.13.12's text).
std::string expression_shader(const std::string& name, const std::string& expr) {
  return "shader " + name +
         " (\n"
         "    float s = u [[ int interpolated=1 ]],\n"
         "    float t = v [[ int interpolated=1 ]],\n"
         "    output color result = 0,\n"
         "    output float alpha = 1,\n"
         "  )\n"
         "{\n    " +
         expr + "\n    ;\n}\n";
}

// A layer's shader named as testshade names them: `x`, `x.oso` or `dir/x` (Lobe reads x.osl).
std::string shader_name(std::string s) {
  if (s.size() > 4 && s.compare(s.size() - 4, 4, ".oso") == 0) s.resize(s.size() - 4);
  return s;
}

// A compiler warning as oslc prints it, without column or source line: `file:line: warning:
// message`, an ambiguous call with oslc's words and its candidates (a built-in one without a
// place). `notes` are the warning's own notes; `prefix` leads its first line (testshade's
// "WARNING: " before the warnings of an --expr shader, which it compiles itself).
void print_oslc_warning(const Diagnostic& d, const std::vector<const Diagnostic*>& notes,
                        const std::string& prefix = "") {
  std::string place = prefix;
  if (!d.file.empty()) place.append(d.file).append(":").append(std::to_string(d.line)).append(": ");
  if (d.id != "warn_ambiguous_call") {
    std::fprintf(stderr, "%swarning: %s\n", place.c_str(), d.message.c_str());
    bool first = true; // the earlier definition or declaration, in oslc's layout
    for (const Diagnostic* n : notes) {
      bool builtin = n->id == "note_previous_builtin" && d.id == "warn_function_redefined";
      if (!builtin && (n->id != "note_previous_decl" || n->file.empty())) continue;
      std::string at = builtin ? "built-in" : n->file + ":" + std::to_string(n->line);
      if (d.id == "warn_function_redefined")
        std::fprintf(stderr, "%s    %s\n", first ? "  Previous definitions:\n" : "", at.c_str());
      else if (d.id == "warn_param_hides_function")
        std::fprintf(stderr, "\t\tprevious declaration was at %s\n", at.c_str());
      first = false;
    }
    return;
  }
  std::string call = d.message; // call to 'f(args)' is ambiguous
  size_t a = call.find('\''), b = call.rfind('\'');
  if (a != std::string::npos && b > a) call = call.substr(a + 1, b - a - 1);
  std::fprintf(stderr, "%swarning: Ambiguous call to '%s'\n", place.c_str(),
               diag::oslc_signature(call).c_str());
  bool others = false;
  for (const Diagnostic* n : notes) {
    bool chosen = n->id == "note_chosen_candidate";
    if (!chosen && n->id != "note_other_candidate") continue;
    if (chosen) std::fprintf(stderr, "  Chosen function is:\n");
    if (!chosen && !others) std::fprintf(stderr, "  Other candidates are:\n");
    others = others || !chosen;
    std::string sig = n->message.substr(n->message.find(':') + 2);
    bool builtin = n->file.empty() || n->file.ends_with("stdosl.h");
    std::string at;
    if (!builtin) at.append(n->file).append(":").append(std::to_string(n->line)).append("\t");
    std::fprintf(stderr, "    %s%s\n", at.c_str(), diag::oslc_signature(sig).c_str());
  }
}

// Warning `i` of `diags` with the notes that follow it, as often as oslc prints it.
void print_oslc_warning_at(const DiagnosticList& diags, size_t i, const std::string& prefix = "") {
  std::vector<const Diagnostic*> own;
  for (size_t k = i + 1; k < diags.size() && diags[k].severity == Diagnostic::Severity::Note; ++k)
    own.push_back(&diags[k]);
  for (int r = 0; r < std::max(1, diags[i].oslc_repeat); ++r)
    print_oslc_warning(diags[i], own, prefix);
}

// `group`: the group's name, which testshade prints after a connection error. `compiler`: the
// compiler's own warnings (a shader's source compiled here) as Lobe renders them (caret and
// notes); otherwise as oslc prints them, since a testshade run follows oslc's (OSL's testsuite
// records both in one output).
void print_diagnostics(const DiagnosticList& diags, bool notes, const std::string& group = "",
                       bool compiler = true) {
  bool connect_error = false;
  std::set<std::string> said;       // group-level warnings given
  for (const Diagnostic& d : diags) // testshade has printed its "Connect ..." lines by then
    if (d.id.rfind("connect_", 0) == 0) std::fflush(stdout);
  for (const Diagnostic& d : diags) {
    if (d.severity == Diagnostic::Severity::Note && !notes) continue;
    std::string t = d.text;
    if (!compiler && d.severity != Diagnostic::Severity::Error && t.rfind("warning: ", 0) != 0) {
      if (d.severity == Diagnostic::Severity::Warning) // a compiler warning, then its notes
        print_oslc_warning_at(diags, size_t(&d - diags.data()));
      continue;
    }
    // Group-level warnings print as testshade prints them: "WARNING: ...", and so do
    // connection errors (OSL's ConnectShaders words, "ERROR: ...").
    if (d.severity == Diagnostic::Severity::Warning && t.rfind("warning: ", 0) == 0) {
      // A texture or noise option dropped at set-up: testshade says "ERROR: ", and shades on.
      t = (d.id == "builtin_option" ? "ERROR: " : "WARNING: ") + t.substr(9);
      // As OSL's shading system, which does not repeat a warning it has just given.
      if (!said.insert(t).second) continue;
    }
    if (d.severity == Diagnostic::Severity::Error && d.id.rfind("connect_", 0) == 0 &&
        t.rfind("error: ", 0) == 0) {
      t = "ERROR: " + t.substr(7);
      connect_error = true;
    }
    std::fprintf(stderr, "%s%s", t.c_str(), !t.empty() && t.back() == '\n' ? "" : "\n");
  }
  if (connect_error && !group.empty()) std::fprintf(stderr, "        group: %s\n", group.c_str());
}

// One layer's instance values as OSL's group text prints them (ShaderGroup serialisation, as
// `testshade -v` shows it): the values its shader took, in the order the shader declares its
// parameters (a struct's fields flattened, `st.a`), each with the parameter's type (`float[3]`
// for an unsized array given three), floats as %.9g, strings quoted and escaped, and
// ` [[int interpolated=1]]` when the value or the parameter is not locked to the geometry (its
// `[[int lockgeom = 0]]`, the option `lockgeom=0`, or the value's own `lockgeom=0` or
// `interpolated=1`; OSL prints it whatever the value's `lockgeom=1` says) and
// ` [[int interactive=1]]`; values OSL refused (no such parameter, the wrong type: the last
// value it took is printed) and values of connected parameters are left out. Without the
// shader's IR, the values as given.
std::string group_params(const ShaderGroup::Layer& l, const ir::Shader* sh,
                         const std::vector<Connection>& connections, bool lockgeom_default) {
  std::string out;
  if (!sh) {
    for (const InstanceValue& v : l.values)
      out += "param " + v.type + " " + v.name + " " + v.value + " ;\n";
    return out;
  }
  for (const ir::Symbol& s : sh->symbols) {
    if (s.kind != ir::SymKind::Param && s.kind != ir::SymKind::OutputParam) continue;
    bool connected = false; // a connected parameter's value is the connection's
    for (const Connection& c : connections)
      connected = connected || (c.dst_layer == l.name &&
                                (c.dst_param == s.name || s.name.rfind(c.dst_param + ".", 0) == 0));
    if (connected) continue;
    const InstanceValue* given = nullptr; // the last value given for it that fits is used
    group::ValueFit fit;
    for (auto v = l.values.rbegin(); v != l.values.rend() && !given; ++v)
      if (v->name == s.name && (fit = group::fit_instance_value(*v, s.type)).ok) given = &*v;
    if (!given) continue;
    bool unlocked = !lockgeom_default || given->interpolated || given->lockgeom == 0 ||
                    group::metadata_lockgeom(s) == 0;
    ir::Type t = s.type;
    if (t.arraylen < 0) t.arraylen = fit.arraylen;
    out += "param " + ir::to_string(t) + " " + s.name;
    for (const ir::ConstValue& c : fit.values) {
      char num[32];
      if (t.base == ir::BaseType::String) {
        out += " " + ir::c_quote(c.s);
        continue;
      }
      if (t.base == ir::BaseType::Int)
        std::snprintf(num, sizeof(num), "%d", c.i);
      else
        std::snprintf(num, sizeof(num), "%.9g", double(c.f));
      out += std::string(" ") + num;
    }
    if (unlocked) out += " [[int interpolated=1]]";
    if (given->interactive) out += " [[int interactive=1]]";
    out += " ;\n";
  }
  return out;
}

// The group as -v prints it (in OSL's group-text form), each layer's shader as it was named;
// with `params` (--oslquery), each layer's parameters under its name.
void print_group(const ShaderGroup& g, const std::vector<std::string>& shaders,
                 const std::vector<const ir::Shader*>& irs, bool lockgeom_default,
                 const std::vector<std::string>* params) {
  std::printf("Shader group:\n---\n");
  for (size_t k = 0; k < g.layers.size(); ++k) {
    const ShaderGroup::Layer& l = g.layers[k];
    std::printf("%s", group_params(l, irs[k], g.connections, lockgeom_default).c_str());
    std::printf("shader %s %s ;\n", shaders[k].c_str(), l.name.c_str());
    for (const Connection& c : g.connections) { // after the layer they lead into, as OSL's text
      if (c.dst_layer != l.name) continue;
      // A whole struct connects (and prints) leaf by leaf: "connect A.s.f B.t.f ;".
      const ir::Shader* src = nullptr;
      for (size_t j = 0; j < g.layers.size(); ++j)
        if (g.layers[j].name == c.src_layer) src = irs[j];
      std::vector<std::string> leaves;
      if (src && src->find_symbol(c.src_param) < 0)
        for (const ir::Symbol& s : src->symbols)
          if (s.name.size() > c.src_param.size() + 1 && s.name.rfind(c.src_param + ".", 0) == 0)
            leaves.push_back(s.name.substr(c.src_param.size()));
      if (leaves.empty()) leaves.push_back("");
      for (const std::string& leaf : leaves)
        std::printf("connect %s.%s%s %s.%s%s ;\n", c.src_layer.c_str(), c.src_param.c_str(),
                    leaf.c_str(), c.dst_layer.c_str(), c.dst_param.c_str(), leaf.c_str());
    }
  }
  std::printf("\n---\n\nShader group \"%s\" layers are:\n", g.name.c_str());
  for (size_t k = 0; k < g.layers.size(); ++k) {
    std::printf("    %s\n", g.layers[k].name.c_str());
    if (params) std::printf("%s", (*params)[k].c_str());
  }
  std::printf("\n");
}

std::vector<std::string> channel_names(int n) {
  if (n == 1) return {"Y"};
  std::vector<std::string> names;
  const char* first[] = {"R", "G", "B", "A"};
  for (int k = 0; k < n; ++k) names.push_back(k < 4 ? first[k] : "channel" + std::to_string(k));
  return names;
}

// One output's value at a point, as --print shows it ("0.5 1 2"; ints as ints).
std::string value_text(const DataType& t, const std::vector<unsigned char>& bytes) {
  std::string s;
  size_t n = size_t(t.elements() * t.components());
  for (size_t k = 0; k < n; ++k) {
    char buf[32];
    if (t.base == DataType::Base::Int) {
      int32_t v;
      std::memcpy(&v, bytes.data() + 4 * k, 4);
      std::snprintf(buf, sizeof buf, "%d", v);
    } else {
      float v;
      std::memcpy(&v, bytes.data() + 4 * k, 4);
      std::snprintf(buf, sizeof buf, "%g", double(v));
    }
    if (k) s += ' ';
    s += buf;
  }
  return s;
}

// Prints what the shaders said: printf text as is; errors and warnings once each (an identical
// one among the recent ones is not repeated, as OSL's error handler does, unless
// error_repeats), each with its prefix and a newline.
class Journal {
public:
  explicit Journal(bool repeats) : repeats_(repeats) {}
  void print(const Said& s) {
    if (s.kind == ShadingContext::MessageKind::Print) {
      std::fputs(s.text.c_str(), stdout);
      return;
    }
    bool error = s.kind == ShadingContext::MessageKind::Error;
    std::deque<std::string>& recent = error ? errors_ : warnings_;
    if (!repeats_) {
      for (const std::string& r : recent)
        if (r == s.text) return;
      recent.push_back(s.text);
      // OSL 1.13.12 remembers the last 25 errors (and 25 warnings): a 26th distinct one since
      // prints the first again.
      if (recent.size() > 25) recent.pop_front();
    }
    std::fflush(stdout);
    std::fprintf(stderr, "%s%s\n", error ? "ERROR: " : "WARNING: ", s.text.c_str());
  }

private:
  bool repeats_;
  std::deque<std::string> errors_, warnings_;
};

class Shade {
public:
  explicit Shade(ShadeJob& job) : job_(job) {}
  int run();

private:
  bool compile(const ShaderGroup& g, std::shared_ptr<const Material>& out);
  bool reparameter(ShaderGroup::Layer& l, const ShadeReparam& r);
  const ir::Shader* layer_ir(const ShaderGroup::Layer& l);
  bool resolve_outputs();
  void shade_grid(const Material& m, bool last_iteration);
  int write_outputs();
  void print_stats(double setup, double run, double write) const;

  ShadeJob& job_;
  ShadingSystem ss_;
  std::map<std::string, std::string> expr_sources_; // --expr shaders' text, by shader name
  std::map<std::string, std::optional<ir::Shader>> layer_irs_; // layer_ir's, by shader name
  std::shared_ptr<const Material> mat_;
  std::vector<Output> outputs_;
  // What the points said, keyed by iteration * points + point; in order once sorted (stably:
  // one point's messages come from one thread, in order).
  std::vector<std::pair<size_t, Said>> said_;
  // Bounded memory for messages: their bytes are counted against `said_budget_` (a quarter of
  // the memory available when shading starts); messages past it are counted in `said_dropped_`
  // and reported after the ones kept.
  std::atomic<uint64_t> said_bytes_{0}, said_dropped_{0};
  uint64_t said_budget_ = 0;
  std::vector<std::string> pixel_blocks_; // --print, per point of the last iteration
  // Bounded execution: `stopped_`: a shade was stopped in a loop (its error is in its point's
  // messages; g_cancel is set too); `shaded_` counts the points that finished.
  std::atomic<bool> stopped_{false};
  std::atomic<size_t> shaded_{0};
  size_t shaded_iterations_ = 0; // shade_grid calls so far
  bool missing_shader_ = false;  // a layer's shader was not found (left out; exit status 1)
};

// A layer's shader as IR (for what testshade asks of a layer's parameters): an --expr
// layer's from its text, any other from its file; null if it does not compile. Each shader is
// compiled once, however many layers and options ask.
const ir::Shader* Shade::layer_ir(const ShaderGroup::Layer& l) {
  auto [it, fresh] = layer_irs_.try_emplace(l.shader);
  if (fresh) {
    DiagnosticList d;
    CompileStats stats;
    auto src = expr_sources_.find(l.shader);
    it->second = src != expr_sources_.end()
                     ? group::compile_osl_source(src->first, src->second, ss_.options(), d, stats)
                     : group::compile_shader_file(l.shader, ss_.options(), d, stats);
  }
  return it->second ? &*it->second : nullptr;
}

// --reparam as testshade's ReParameter: an interactive parameter (`-param:interactive=1`, or
// the shader's own `[[ int interactive = 1 ]]`) takes the new value; one of another type is
// ignored without a word, except a float for a triple, which sets its first component only
// (OSL copies the float's bytes into the triple). True when the layer changed.
bool Shade::reparameter(ShaderGroup::Layer& l, const ShadeReparam& r) {
  const ir::Shader* sh = layer_ir(l);
  int si = sh ? sh->find_symbol(r.param) : -1;
  if (si < 0) return false;
  const ir::Symbol& s = sh->symbols[size_t(si)];
  if (s.kind != ir::SymKind::Param && s.kind != ir::SymKind::OutputParam) return false;
  InstanceValue* current = nullptr;
  for (InstanceValue& v : l.values)
    if (v.name == r.param) current = &v;
  // Interactive as the group build takes it (group::interactive_param): by the instance
  // value's mark when one was given (a plain value overrides the metadata), else by the
  // shader's `[[ int interactive = 1 ]]`.
  bool interactive = group::interactive_param(l, s);
  if (!interactive) {
    // testshade's error, for a parameter the group still has: any at -O0 and -O1; at -O2 one
    // that stays a parameter (an output, a connection's destination, one taking user data),
    // not one folded to a constant (OSL 1.13.12: `--reparam L h 5.0` on a lockgeom = 0 `h`
    // prints it at every level, on a plain `m` only below -O2).
    bool kept = ss_.options().opt_level < 2 || !ss_.options().specialize ||
                s.kind == ir::SymKind::OutputParam || !ss_.options().lockgeom_default ||
                group::metadata_lockgeom(s) == 0 ||
                (current && (current->interpolated || current->lockgeom == 0));
    for (const Connection& c : job_.group.connections)
      kept = kept || (c.dst_layer == l.name && c.dst_param == r.param);
    if (kept) {
      std::fflush(stdout); // after the "Connect ..." lines, as testshade's output comes
      std::fprintf(stderr,
                   "ERROR: ReParameter cannot adjust %s.%s, which was not declared interactive\n",
                   l.name.c_str(), r.param.c_str());
    }
    return false;
  }
  std::string declared = ir::to_string(s.type);
  InstanceValue v = r.value;
  bool triple_value =
      v.type == "color" || v.type == "point" || v.type == "vector" || v.type == "normal";
  if (s.type.is_triple() && !s.type.is_array() && v.type == "float") {
    std::vector<float> comps; // the value until now: the instance value's, else the default's
    group::ValueFit fit;
    if (current && (fit = group::fit_instance_value(*current, s.type)).ok)
      for (const ir::ConstValue& c : fit.values) comps.push_back(c.f);
    else
      for (const ir::ConstValue& c : s.init) comps.push_back(c.f);
    if (comps.size() != 3) return false;
    comps[0] = std::strtof(v.value.c_str(), nullptr);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g %.9g %.9g", comps[0], comps[1], comps[2]);
    v = param_value(declared, r.param, buf);
  } else if (s.type.base == ir::BaseType::Float && s.type.arraylen == 3 && triple_value) {
    // Three floats either way: OSL takes a value of the same base type and size (an untyped
    // `7,8,9`, read as a vector, for a float[3]).
    v = param_value(declared, r.param, v.value);
  } else if (v.type != declared && !(s.type.is_triple() && !s.type.is_array() && triple_value)) {
    return false;
  }
  v.interactive = true;
  if (current)
    *current = v;
  else
    l.values.push_back(v);
  return true;
}

bool Shade::compile(const ShaderGroup& g, std::shared_ptr<const Material>& out) {
  DiagnosticList diags;
  out = ss_.compile(g, diags);
  print_diagnostics(diags, job_.verbose || !out, g.name, job_.verbose || !out);
  return out != nullptr;
}

// Each -o reads its layer's output (the last layer that has one, unless named); outputs that
// no layer has are skipped silently, as testshade does.
bool Shade::resolve_outputs() {
  const ShaderGroup& g = job_.group;
  for (const ShadeOutput& o : job_.outputs) {
    Output out{o, "", {}, false, {}};
    for (size_t i = g.layers.size(); i-- > 0 && out.layer.empty();) {
      if (!o.layer.empty() && g.layers[i].name != o.layer) continue;
      if (auto info = mat_->output_info(g.layers[i].name, o.var)) {
        out.layer = g.layers[i].name;
        out.type = info->type;
        out.closure = info->closure;
      }
    }
    if (out.layer.empty()) continue;
    outputs_.push_back(std::move(out));
  }
  // What the grid will cost, checked before any of it is allocated: per point its --print
  // block and each output's pixel (image and written copy). Messages cost what they say.
  double points = double(job_.xres) * double(job_.yres);
  double per_point = 0;
  if (job_.print) per_point += sizeof(std::string) + 64;
  for (const Output& o : outputs_)
    if (o.written(job_.print)) per_point += 2.0 * 4 * o.type.elements() * o.type.components();
  std::string setting = "-g " + std::to_string(job_.xres) + " " + std::to_string(job_.yres);
  if (std::string e = check_memory(setting, points * per_point, "the grid's outputs and messages");
      !e.empty()) {
    std::fprintf(stderr, "lobe shade: %s\n", e.c_str());
    return false;
  }
  said_budget_ = available_memory_bytes() / 4;
  for (Output& o : outputs_)
    if (o.written(job_.print))
      o.img = image::Image(job_.xres, job_.yres,
                           channel_names(o.type.elements() * o.type.components()));
  for (const Output& o : outputs_)
    if (o.spec.file != "null")
      std::printf("Output %s%s%s to %s\n", o.spec.layer.c_str(), o.spec.layer.empty() ? "" : ".",
                  o.spec.var.c_str(), o.spec.file.c_str()); // as named: `-o layer.var file`
  for (const Output& o : outputs_)
    if (o.closure)
      std::printf("No output copy for closure color %s because of type mismatch vs "
                  "symloc=pointer\n",
                  o.spec.var.c_str());
  // An image that cannot be written is known before anything is shaded.
  for (const Output& o : outputs_) {
    if (o.spec.file == "null" || job_.print || o.closure) continue;
    std::string err = image::check_writable(o.spec.file);
    if (!err.empty()) {
      std::fprintf(stderr, "lobe shade: %s\n", err.c_str());
      return false;
    }
  }
  return true;
}

void Shade::shade_grid(const Material& m, bool last_iteration) {
  group::GridSpec grid;
  grid.width = job_.xres;
  grid.height = job_.yres;
  grid.center = job_.center;
  grid.raytype = group::raytype_from_name(job_.raytype);
  grid.offset_u = job_.offset_u;
  grid.offset_v = job_.offset_v;
  grid.scale_u = job_.scale_u;
  grid.scale_v = job_.scale_v;
  grid.vary_pdxdy = job_.vary_pdxdy;
  grid.vary_udxdy = job_.vary_udxdy;
  grid.vary_vdxdy = job_.vary_vdxdy;
  ShadeServices services(job_.userdata, job_.xres, job_.yres);
  size_t points = size_t(job_.xres) * size_t(job_.yres), first = shaded_iterations_ * points;
  ++shaded_iterations_;
  if (last_iteration && job_.print) pixel_blocks_.assign(points, "");
  // Each output looked up once: where `m` keeps it (an offset into m.output_data).
  std::vector<std::optional<size_t>> offsets(outputs_.size());
  for (size_t i = 0; i < outputs_.size(); ++i) {
    const Output& o = outputs_[i];
    if (o.closure || o.type.base == DataType::Base::String) continue;
    if (auto info = m.output_info(o.layer, o.spec.var)) offsets[i] = info->offset;
  }
  // The outputs a point's values go to (an image or --print); a "null" one was computed and
  // is not copied anywhere.
  std::vector<size_t> kept;
  for (size_t i = 0; i < outputs_.size(); ++i)
    if (job_.print || outputs_[i].written(false)) kept.push_back(i);
  tbb::enumerable_thread_specific<ShadingContext> contexts;
  tbb::enumerable_thread_specific<std::vector<unsigned char>> scratch;
  tbb::enumerable_thread_specific<std::vector<std::pair<size_t, Said>>> said;
  // Points x0 .. x1 - 1 of row y.
  auto shade_row = [&](int y, int x0, int x1) {
    ShadingContext& ctx = contexts.local();
    std::vector<unsigned char>& bytes = scratch.local();
    std::vector<std::pair<size_t, Said>>& row_said = said.local();
    size_t key = 0; // the point being shaded, for its messages
    ctx.renderer = &services;
    ctx.cancel = &g_cancel;
    group::GridGlobals globals(grid, &ctx);
    ctx.report = [this, &row_said, &key](ShadingContext::MessageKind k, const std::string& t) {
      uint64_t cost = sizeof(std::pair<size_t, Said>) + t.size() + 32;
      if (said_bytes_.fetch_add(cost, std::memory_order_relaxed) + cost > said_budget_) {
        said_dropped_.fetch_add(1, std::memory_order_relaxed);
        return;
      }
      try {
        row_said.push_back({key, {k, t}});
      } catch (const std::bad_alloc&) {
        said_dropped_.fetch_add(1, std::memory_order_relaxed);
      }
    };
    size_t finished = 0;
    ShaderGlobals sg;
    for (int x = x0; x < x1; ++x) {
      if (g_cancel.load(std::memory_order_relaxed)) break;
      size_t p = size_t(y) * size_t(job_.xres) + size_t(x);
      key = first + p;
      ctx.order = key;
      ctx.reset();
      globals.at(x, y, sg);
      m.shade(sg);
      if (ctx.stopped) {
        // Past max_loop_iterations (the error is in this point's messages), or cancelled.
        if (ctx.errors) stopped_.store(true);
        g_cancel.store(true);
        break;
      }
      ++finished;
      if (!last_iteration || (kept.empty() && !job_.print)) continue;
      std::string block;
      if (job_.print) block = "Pixel (" + std::to_string(x) + ", " + std::to_string(y) + "):\n";
      const unsigned char* data = m.output_data(ctx);
      for (size_t i : kept) {
        Output& o = outputs_[i];
        const unsigned char* value;
        if (data && offsets[i]) {
          value = data + *offsets[i];
        } else {
          if (o.closure || !m.read_output_bytes(ctx, o.layer, o.spec.var, bytes)) continue;
          if (o.type.base == DataType::Base::String) continue;
          value = bytes.data();
        }
        if (job_.print) {
          bytes.assign(value, value + o.type.bytes());
          block += "  " + o.spec.var + " : " + value_text(o.type, bytes) + "\n";
        }
        if (!o.written(job_.print)) continue;
        float* px = o.img.pixel(x, y);
        for (int c = 0; c < o.img.nchannels(); ++c) {
          if (o.type.base == DataType::Base::Int) {
            int32_t v;
            std::memcpy(&v, value + 4 * size_t(c), 4);
            px[c] = float(v);
          } else {
            std::memcpy(&px[c], value + 4 * size_t(c), 4);
          }
        }
      }
      if (job_.print) pixel_blocks_[p] = std::move(block);
    }
    shaded_.fetch_add(finished, std::memory_order_relaxed);
    ctx.report = nullptr; // it refers to this row's locals
  };
  // The first point alone, then the rest in parallel: what a run does once, first in time (the
  // "errormessage" of a texture file that cannot be opened: its words once, then "unknown"),
  // goes to the first point when every point does it, as on one thread.
  auto all_rows = [&] {
    if (job_.xres <= 0 || job_.yres <= 0) return; // an empty grid shades nothing
    shade_row(0, 0, 1);
    tbb::parallel_for(0, job_.yres, [&](int y) { shade_row(y, y == 0 ? 1 : 0, job_.xres); });
  };
  if (job_.threads > 0) {
    auto allowed = render::allow_threads(job_.threads);
    tbb::task_arena arena(job_.threads);
    arena.execute(all_rows);
  } else {
    all_rows();
  }
  for (auto& part : said) said_.insert(said_.end(), part.begin(), part.end());
  std::stable_sort(said_.begin(), said_.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
}

int Shade::write_outputs() {
  int status = 0;
  for (const Output& o : outputs_) {
    if (!o.written(job_.print)) continue;
    std::string format =
        job_.dataformat == "uint8" || job_.dataformat == "half" || job_.dataformat == "float"
            ? job_.dataformat
        : o.type.base == DataType::Base::Int ? "int"
                                             : "float";
    std::string err =
        image::write_channels(o.spec.file, o.img, format, o.type.base == DataType::Base::Int);
    if (!err.empty()) {
      std::fprintf(stderr, "lobe shade: %s\n", err.c_str());
      status = 1;
    }
  }
  return status;
}

void Shade::print_stats(double setup, double run, double write) const {
  const CompileStats& s = mat_->stats();
  std::printf("\nSetup : %.4fs\nWarmup: %.4fs\nRun   : %.4fs\nWrite : %.4fs\n\n", setup, 0.0, run,
              write);
  std::printf("Lobe %s\n", "0.1.0");
  std::printf("  compile: preprocess %.3f ms, parse %.3f ms, sema %.3f ms, ir %.3f ms, specialize "
              "%.3f ms, llvm-ir %.3f ms, optimize %.3f ms, codegen %.3f ms%s\n",
              s.preprocess_ms, s.parse_ms, s.sema_ms, s.ir_ms, s.specialize_ms, s.llvm_ir_ms,
              s.optimize_ms, s.codegen_ms,
              s.cache_hit          ? " (cache hit)"
              : s.object_from_disk ? " (machine code from the disk cache)"
                                   : "");
  if (s.noise_batched > 0)
    std::printf("  %d noise calls evaluated side by side in vector lanes\n", s.noise_batched);
  size_t points = size_t(job_.xres) * size_t(job_.yres) * size_t(std::max(1, job_.iters));
  std::printf("  shade: %zu points, %.3f us per point, %d threads\n", points,
              points ? 1e6 * run / double(points) : 0.0,
              job_.threads > 0 ? job_.threads : tbb::this_task_arena::max_concurrency());
}

int Shade::run() {
  auto t0 = Clock::now();
  if (!job_.locale.empty()) {
    try {
      std::locale::global(std::locale(job_.locale));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "lobe shade: --locale %s: %s\n", job_.locale.c_str(), e.what());
      return 1;
    }
    if (job_.verbose)
      std::printf("lobe shade: locale '%s', floats look like: %g\n", job_.locale.c_str(), 3.5);
  }
  ss_.options() = job_.compile;
  ss_.options().debug_nan = job_.debug_nan;
  ss_.options().debug_uninit = job_.debug_uninit;
  ss_.options().range_checking = job_.range_checking;
  ss_.options().userdata_isconnected = job_.userdata_isconnected;
  if (!job_.colorspace.empty()) { // an unknown name: testshade's message once, then Rec709
    ss_.options().colorspace = job_.colorspace;
    if (std::string e = colorspace_error(job_.colorspace); !e.empty())
      std::fprintf(stderr, "ERROR: %s\n", e.c_str());
  }
  for (size_t k = 0; k < job_.expressions.size(); ++k) {
    std::string name = "expr_" + std::to_string(k);
    std::string text = expression_shader(name, job_.expressions[k]);
    if (job_.verbose) std::printf("Expression-based shader text is:\n---\n%s---\n", text.c_str());
    DiagnosticList diags;
    expr_sources_[name] = text;
    if (!ss_.add_shader_source(name, text, "<buffer>", diags)) {
      print_diagnostics(diags, true);
      std::fprintf(stderr, "Could not compile \"%s\"\n", name.c_str());
      return 1;
    }
    for (size_t i = 0; i < diags.size(); ++i) // its warnings, as testshade's compile gives them
      if (diags[i].severity == Diagnostic::Severity::Warning)
        print_oslc_warning_at(diags, i, "WARNING: ");
  }
  ShaderGroup& g = job_.group;
  // A shader named without a path resolves on the search path here, so that one found in the
  // working directory is `x.osl` in diagnostics and __FILE__ (as for lobe compile and OSL).
  std::vector<std::string> named; // as given (x.oso names x), for -v
  // Every shader not found is reported, in testshade's words, and its layer left out: as
  // testshade, the others shade (a connection from or into it is then an error), and the exit
  // status is 1 once they have.
  std::vector<size_t> missing;
  for (ShaderGroup::Layer& l : g.layers) {
    l.shader = shader_name(l.shader);
    named.push_back(l.shader);
    std::string p = group::find_shader_file(l.shader, ss_.options());
    if (p.rfind("./", 0) == 0) p.erase(0, 2);
    if (!p.empty()) l.shader = p;
    if (p.empty() && !expr_sources_.count(l.shader)) {
      std::fprintf(stderr,
                   "ERROR: No .oso file could be found for shader \"%s\"\n"
                   "ERROR: Could not find shader \"%s\"\n        group: %s\n",
                   l.shader.c_str(), l.shader.c_str(), g.name.c_str());
      missing.push_back(size_t(&l - g.layers.data()));
    }
  }
  for (size_t k = missing.size(); k-- > 0;) {
    g.layers.erase(g.layers.begin() + std::ptrdiff_t(missing[k]));
    named.erase(named.begin() + std::ptrdiff_t(missing[k]));
  }
  missing_shader_ = !missing.empty();
  if (g.layers.empty() && missing_shader_) { // nothing to shade: testshade's closing blank line
    std::fflush(stderr);
    std::fputs("\n", stdout);
    return 1;
  }
  for (const ShadeOutput& o : job_.outputs)
    g.renderer_outputs.push_back(o.layer.empty() ? o.var : o.layer + "." + o.var);
  for (const std::string& e : job_.entry_layers) g.entry_layers.push_back(e);
  // --entryoutput: as testshade, a parameter the group keeps: a layer's output parameter of that
  // name that a connection reads or the renderer reads (-o; any, at -O0, where nothing is
  // optimised away), or an input parameter a connection leads into; "layer.name" names one
  // layer's. The names found are announced after compiling; the first not found stops
  // there ("Entry output NAME not found. Abording.", exit status 1).
  std::string entry_outputs = "Entry outputs:", missing_output;
  std::set<std::string> output_layers; // the layers the entry outputs were found in
  if (!job_.entry_outputs.empty()) {
    std::vector<const ir::Shader*> shaders;
    for (const ShaderGroup::Layer& l : g.layers) shaders.push_back(layer_ir(l));
    for (const std::string& entry : job_.entry_outputs) {
      bool kept = false;
      // "layer.param" names one layer's; a plain name is looked for in every layer.
      std::string only_layer, name = entry;
      if (size_t dot = entry.find('.'); dot != std::string::npos)
        for (const ShaderGroup::Layer& l : g.layers)
          if (l.name == entry.substr(0, dot)) only_layer = l.name, name = entry.substr(dot + 1);
      auto leads = [&](const std::string& param, const std::string& p) {
        return param == p || param.rfind(p + ".", 0) == 0 || param.rfind(p + "[", 0) == 0;
      };
      // From the last layer back, as OSL's ShaderGroup::find_symbol looks a plain name up.
      for (size_t k = g.layers.size(); k-- > 0 && !kept;) {
        const std::string& layer = g.layers[k].name;
        if (!only_layer.empty() && layer != only_layer) continue;
        int si = shaders[k] ? shaders[k]->find_symbol(name) : -1;
        if (si < 0) continue;
        ir::SymKind kind = shaders[k]->symbols[size_t(si)].kind;
        if (kind != ir::SymKind::OutputParam && kind != ir::SymKind::Param) continue;
        kept = ss_.options().opt_level == 0;
        for (const Connection& c : g.connections) // connected from, or (an input) into
          kept = kept || (c.src_layer == layer && leads(c.src_param, name)) ||
                 (kind == ir::SymKind::Param && c.dst_layer == layer && leads(c.dst_param, name));
        for (const std::string& r : g.renderer_outputs)
          kept = kept || r == name || r == layer + "." + name;
        if (kept) output_layers.insert(layer);
      }
      const std::string& name_given = entry;
      if (!kept) {
        missing_output = name_given;
        break;
      }
      entry_outputs += " " + name_given;
    }
  }
  // With both --entry and --entryoutput, testshade 1.13.12 runs only the entry layers that hold
  // an entry output (their upstream layers as reads need them): `--entry A --entry B
  // --entryoutput A.o` runs A alone, `--entry A --entryoutput B.x` nothing at all.
  bool shade_none = false;
  if (!g.entry_layers.empty() && !job_.entry_outputs.empty() && missing_output.empty()) {
    std::vector<std::string> running;
    for (const std::string& e : g.entry_layers)
      if (output_layers.count(e)) running.push_back(e);
    shade_none = running.empty();
    if (!shade_none) g.entry_layers = running;
  }
  if (job_.verbose || job_.oslquery) {
    std::vector<std::string> params; // --oslquery: each layer's, as OSLQuery lists them
    std::vector<const ir::Shader*> irs;
    for (const ShaderGroup::Layer& l : g.layers) {
      irs.push_back(layer_ir(l));
      params.push_back(job_.oslquery && irs.back() ? ir::oslquery_params(*irs.back()) : "");
    }
    if (job_.verbose && !job_.group_spec.empty())
      std::printf("Processing group specification:\n---\n%s\n---\n", job_.group_spec.c_str());
    print_group(g, named, irs, ss_.options().lockgeom_default, job_.oslquery ? &params : nullptr);
  }
  // Ctrl-C from here on: compiling finishes, then nothing is shaded; shading stops promptly.
  std::signal(SIGINT, on_shade_sigint);
  if (!compile(g, mat_)) return 1;
  if (g_cancel.load()) {
    std::fprintf(stderr, "lobe shade: interrupted (Ctrl-C) while compiling; nothing shaded\n");
    return 130;
  }
  if (job_.outputs_given) std::printf("\n");
  if (!job_.entry_layers.empty()) {
    std::string line = "Entry layers:";
    for (const std::string& e : job_.entry_layers) {
      int at = -1;
      for (size_t i = 0; i < g.layers.size(); ++i)
        if (g.layers[i].name == e) at = int(i);
      line += " " + e + "(" + std::to_string(at) + ")";
      if (at < 0) {
        std::printf("%s\n", line.c_str());
        std::fprintf(stderr, "lobe shade: --entry %s: no such layer\n", e.c_str());
        return 1;
      }
    }
    std::printf("%s\n", line.c_str());
  }
  if (!resolve_outputs()) return 1; // prints the Output lines
  if (!job_.entry_outputs.empty()) {
    std::printf("%s\n", entry_outputs.c_str());
    if (!missing_output.empty()) {
      std::printf("Entry output %s not found. Abording.\n", missing_output.c_str());
      return 1;
    }
  }
  double setup = seconds_since(t0);

  auto t1 = Clock::now();
  std::shared_ptr<const Material> reparam; // --reparam's values, from the second iteration
  for (int it = 0; it < job_.iters; ++it) {
    if (it == 1 && !job_.reparams.empty()) {
      ShaderGroup changed = g;
      bool any = false;
      for (const ShadeReparam& r : job_.reparams)
        for (ShaderGroup::Layer& l : changed.layers)
          if (l.name == r.layer) any = reparameter(l, r) || any;
      if (any && !compile(changed, reparam)) return 1;
    }
    if (!shade_none) shade_grid(reparam ? *reparam : *mat_, it + 1 == job_.iters);
    if (g_cancel.load()) break;
  }
  std::signal(SIGINT, SIG_DFL);
  double run = seconds_since(t1);
  std::fflush(stdout);
  for (const std::string& b : pixel_blocks_) std::fputs(b.c_str(), stdout);
  Journal journal(job_.error_repeats);
  for (const auto& [point, s] : said_) journal.print(s);
  std::fflush(stdout);
  if (uint64_t n = said_dropped_.load())
    std::fprintf(stderr,
                 "lobe shade: %llu more shader messages not shown: the grid's messages passed "
                 "the %s of memory kept for them (a quarter of what was available)\n",
                 (unsigned long long)n, format_bytes(double(said_budget_)).c_str());
  if (ss_.strings_exhausted())
    std::fprintf(stderr,
                 "lobe shade: the shaders' strings passed the %s of memory kept for them (a "
                 "quarter of what was available): a string that did not fit was made empty\n",
                 format_bytes(double(ss_.strings_budget_bytes())).c_str());
  if (job_.outputs.size() == 1 && job_.outputs[0].file == "null") std::printf("\n");
  size_t total = size_t(job_.xres) * size_t(job_.yres) * size_t(std::max(1, job_.iters));
  std::fflush(stdout);
  if (stopped_.load()) { // a shader ran away: the error above names it; nothing is written
    std::fprintf(stderr, "lobe shade: stopped after %zu of %zu points; no output written\n",
                 shaded_.load(), total);
    return 1;
  }
  bool interrupted = g_cancel.load();
  if (interrupted)
    std::fprintf(stderr,
                 "lobe shade: interrupted (Ctrl-C) after %zu of %zu points; writing the finished "
                 "points\n",
                 shaded_.load(), total);
  auto t2 = Clock::now();
  int status = write_outputs();
  if (interrupted) return 130;
  if (job_.print_groupdata) std::printf("Groupdata size: %zu\n", mat_->groupdata_bytes());
  if (job_.runstats) print_stats(setup, run, seconds_since(t2));
  return status ? status : missing_shader_ || ss_.strings_exhausted() ? 1 : 0;
}

int run_shade(int argc, char** argv) {
  ShadeJob job;
  int st = parse_shade_args(argc, argv, job);
  if (st) return st < 0 ? 0 : st;
  return Shade(job).run();
}

} // namespace
} // namespace lobe::cli

LOBE_COMMAND(shade, "run a shader group over a grid of points (OSL testshade)",
             lobe::cli::run_shade);
