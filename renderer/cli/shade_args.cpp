// `lobe shade`'s command line (see shade_args.h): one table of testshade's options, read with
// one dash or two.
#include "shade_args.h"

#include "group_text.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

namespace lobe::cli {
namespace {

// What a handler sees: the option's modifiers (`--param:type=color` gives {type: color}) and
// its arguments.
struct Use {
  std::map<std::string, std::string> mods;
  std::vector<std::string> args;
  std::string mod(const std::string& k) const {
    auto it = mods.find(k);
    return it == mods.end() ? "" : it->second;
  }
};

// The state of a parse: the job, the parameters waiting for their shader, the name waiting for
// the next layer, and testshade's count of groups begun (unnamed_group_N).
struct Parser {
  ShadeJob& job;
  std::vector<InstanceValue> pending;
  std::string pending_layer;
  std::vector<std::vector<InstanceValue>> expr_values; // per --expr: the --param before it
  int groups_begun = 0;
  bool group_open = false; // a group from positional shaders or --group is being built
  int status = 0;          // non-zero: stop with this exit status

  void add_layer(const std::string& shader, std::string name) {
    if (!group_open) {
      groups_begun += 1;
      group_open = true;
      job.group = ShaderGroup{};
    }
    if (name.empty()) name = pending_layer;
    if (name.empty()) { // testshade's: the file name without folder or .oso (Lobe: or .osl)
      std::filesystem::path f = std::filesystem::path(shader).filename();
      if (f.extension() == ".oso" || f.extension() == ".osl") f.replace_extension();
      name = f.string() + "_" + std::to_string(job.group.layers.size());
    }
    pending_layer.clear();
    job.group.layers.push_back({shader, name, std::move(pending)});
    pending.clear();
  }

  void group(const std::string& cmd) {
    std::string text = cmd;
    std::error_code ec;
    bool file = std::filesystem::is_regular_file(cmd, ec);
    if (file) { // a file, else the text itself
      std::ifstream in(cmd);
      std::stringstream ss;
      ss << in.rdbuf();
      text = ss.str();
    }
    DiagnosticList diags;
    auto g = group::parse_group_text(text, file ? cmd : "--group", diags);
    for (const Diagnostic& d : diags) std::fprintf(stderr, "%s\n", d.text.c_str());
    if (!g) {
      std::fprintf(stderr, "ERROR: Invalid shader group. Exiting lobe shade.\n");
      status = 1;
      return;
    }
    groups_begun += 2; // testshade counts a --group twice (unnamed_group_2 for the first)
    group_open = true;
    job.group = std::move(*g);
    job.group_spec = text;
  }
};

float to_f(const std::string& s) { return float(std::atof(s.c_str())); }
int to_i(const std::string& s) { return std::atoi(s.c_str()); }

// --options: name=value items separated by commas; a value may be "quoted".
std::vector<std::pair<std::string, std::string>> option_list(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> out;
  size_t i = 0;
  while (i < text.size()) {
    size_t eq = text.find('=', i), comma = text.find(',', i);
    if (eq == std::string::npos || (comma != std::string::npos && comma < eq)) {
      i = comma == std::string::npos ? text.size() : comma + 1; // junk: ignored, as testshade
      continue;
    }
    std::string name = text.substr(i, eq - i), value;
    size_t j = eq + 1;
    if (j < text.size() && text[j] == '"') {
      size_t close = text.find('"', j + 1);
      value = text.substr(j + 1, (close == std::string::npos ? text.size() : close) - j - 1);
      j = close == std::string::npos ? text.size() : close + 1;
    } else {
      size_t end = text.find(',', j);
      value = text.substr(j, (end == std::string::npos ? text.size() : end) - j);
      j = end == std::string::npos ? text.size() : end;
    }
    out.push_back({name, value});
    i = j < text.size() && text[j] == ',' ? j + 1 : j;
  }
  return out;
}

// The ShadingSystem options testshade's --options sets that change what Lobe does; the rest
// are accepted and ignored, as testshade ignores names it does not know.
void apply_options(ShadeJob& job) {
  for (const auto& [name, value] : option_list(job.options)) {
    if (name == "optimize") {
      job.compile.opt_level = std::clamp(to_i(value), 0, 2);
      job.compile.specialize = job.compile.opt_level > 0;
    } else if (name == "opt_constant_fold" || name == "opt_simplify_param") {
      if (to_i(value) == 0) job.compile.specialize = false;
    } else if (name == "lockgeom") {
      job.compile.lockgeom_default = to_i(value) != 0;
    } else if (name == "range_checking") {
      job.range_checking = to_i(value) != 0;
    } else if (name == "lazylayers") {
      job.compile.lazy_layers = to_i(value) != 0;
    } else if (name == "lazyglobals") {
      job.compile.lazy_globals = to_i(value) != 0;
    } else if (name == "lazyunconnected") {
      job.compile.lazy_unconnected = to_i(value) != 0;
    } else if (name == "lazyerror") {
      job.compile.lazy_error = to_i(value) != 0;
    } else if (name == "opt_merge_instances") {
      job.compile.merge_instances = to_i(value) != 0;
    } else if (name == "userdata_isconnected") {
      job.userdata_isconnected = to_i(value) != 0;
    } else if (name == "error_repeats") {
      job.error_repeats = to_i(value) != 0;
    } else if (name == "debug_nan") {
      job.debug_nan = to_i(value) != 0;
    } else if (name == "debug_uninit") {
      job.debug_uninit = to_i(value) != 0;
    } else if (name == "fast_math") {
      job.compile.fast_math = to_i(value) != 0;
    } else if (name == "max_loop_iterations") { // Lobe's: 0 unlimited (CompileOptions)
      job.compile.max_loop_iterations = std::max(-1LL, std::atoll(value.c_str()));
    } else if (name == "searchpath:shader") {
      std::stringstream dirs(value);
      for (std::string d; std::getline(dirs, d, ':');)
        if (!d.empty()) job.compile.include_dirs.push_back(d);
    }
  }
}

using Handler = std::function<void(Parser&, const Use&)>;
struct Option {
  const char* name;
  int nargs;
  Handler handle;
};

// testshade's options (OSL 1.13.12's --help), in its order, then Lobe's. Options that only
// tune OSL's own machinery (OptiX, batched shading, LLVM debugging, the journal buffer) are
// accepted and do nothing here.
const std::vector<Option>& options() {
  auto flag = [](bool ShadeJob::*f) { return [f](Parser& p, const Use&) { p.job.*f = true; }; };
  auto none = [](Parser&, const Use&) {};
  static const std::vector<Option> kOptions = {
      {"help", 0, [](Parser& p, const Use&) { print_shade_help(), p.status = -1; }},
      {"v", 0, flag(&ShadeJob::verbose)},
      {"t", 1, [](Parser& p, const Use& u) { p.job.threads = std::max(0, to_i(u.args[0])); }},
      {"optix", 0, none},
      {"debug", 0, none},
      {"debug2", 0, none},
      {"llvm_debug", 0, none},
      {"runstats", 0, flag(&ShadeJob::runstats)},
      {"stats", 0, flag(&ShadeJob::runstats)},
      {"batched", 0, none},
      {"vary_pdxdy", 0, flag(&ShadeJob::vary_pdxdy)},
      {"vary_udxdy", 0, flag(&ShadeJob::vary_udxdy)},
      {"vary_vdxdy", 0, flag(&ShadeJob::vary_vdxdy)},
      {"profile", 0, none},
      {"saveptx", 0, none},
      {"warmup", 0, none},
      {"res", 2,
       [](Parser& p, const Use& u) {
         // A negative size shades nothing, as in testshade.
         p.job.xres = std::max(0, to_i(u.args[0]));
         p.job.yres = std::max(0, to_i(u.args[1]));
       }},
      {"g", 2,
       [](Parser& p, const Use& u) {
         // A negative size shades nothing, as in testshade; one past int's range is refused
         // (read as an int it wrapped round: 4294967297 was 1).
         for (const std::string& a : u.args) {
           long long v = std::atoll(a.c_str());
           if (v > std::numeric_limits<int>::max()) {
             std::fprintf(stderr, "lobe shade: error: -g %s %s: %s is too large a grid size\n",
                          u.args[0].c_str(), u.args[1].c_str(), a.c_str());
             p.status = 1;
             return;
           }
         }
         p.job.xres = std::max(0, to_i(u.args[0]));
         p.job.yres = std::max(0, to_i(u.args[1]));
       }},
      {"options", 1,
       [](Parser& p, const Use& u) {
         if (!p.job.options.empty()) p.job.options += ',';
         p.job.options += u.args[0];
       }},
      {"texoptions", 1, [](Parser& p, const Use& u) { p.job.texoptions = u.args[0]; }},
      {"colorspace", 1, [](Parser& p, const Use& u) { p.job.colorspace = u.args[0]; }},
      {"o", 2,
       [](Parser& p, const Use& u) {
         ShadeOutput o{"", u.args[0], u.args[1]};
         if (size_t dot = o.var.find('.'); dot != std::string::npos) {
           o.layer = o.var.substr(0, dot);
           o.var = o.var.substr(dot + 1);
         }
         p.job.outputs.push_back(o);
         p.job.outputs_given = true;
       }},
      {"d", 1, [](Parser& p, const Use& u) { p.job.dataformat = u.args[0]; }},
      {"od", 1, [](Parser& p, const Use& u) { p.job.dataformat = u.args[0]; }},
      {"print", 0, flag(&ShadeJob::print)},
      {"groupname", 1, [](Parser& p, const Use& u) { p.job.groupname = u.args[0]; }},
      {"layer", 1, [](Parser& p, const Use& u) { p.pending_layer = u.args[0]; }},
      {"param", 2,
       [](Parser& p, const Use& u) {
         InstanceValue v = param_value(u.mod("type"), u.args[0], u.args[1]);
         // testshade 1.13.12's :interpolated=1 and :lockgeom=0 mark the value interpolated (as
         // -v prints it) but bind no user data to it, and :lockgeom=1 locks nothing: the
         // shader's metadata decides (group text's hints do bind, InstanceValue::lockgeom).
         v.interpolated = u.mod("interpolated") == "1" || u.mod("lockgeom") == "0";
         v.interactive = u.mod("interactive") == "1";
         p.pending.push_back(v);
       }},
      {"shader", 2, [](Parser& p, const Use& u) { p.add_layer(u.args[0], u.args[1]); }},
      {"connect", 4,
       [](Parser& p, const Use& u) {
         std::printf("Connect %s.%s to %s.%s\n", u.args[0].c_str(), u.args[1].c_str(),
                     u.args[2].c_str(), u.args[3].c_str());
         p.job.connects.push_back({u.args[0], u.args[1], u.args[2], u.args[3]});
       }},
      {"reparam", 3,
       [](Parser& p, const Use& u) {
         p.job.reparams.push_back(
             {u.args[0], u.args[1], param_value(u.mod("type"), u.args[1], u.args[2])});
       }},
      {"group", 1, [](Parser& p, const Use& u) { p.group(u.args[0]); }},
      {"archivegroup", 1, [](Parser& p, const Use& u) { p.job.archivegroup = u.args[0]; }},
      {"raytype", 1, [](Parser& p, const Use& u) { p.job.raytype = u.args[0]; }},
      {"raytype_opt", 0, flag(&ShadeJob::raytype_opt)},
      {"iters", 1, [](Parser& p, const Use& u) { p.job.iters = std::max(0, to_i(u.args[0])); }},
      {"O0", 0,
       [](Parser& p, const Use&) {
         p.job.compile.opt_level = 0, p.job.compile.specialize = false;
       }},
      {"O1", 0,
       [](Parser& p, const Use&) { p.job.compile.opt_level = 1, p.job.compile.specialize = true; }},
      {"O2", 0,
       [](Parser& p, const Use&) { p.job.compile.opt_level = 2, p.job.compile.specialize = true; }},
      {"llvm_opt", 1, none},
      {"optix_no_inline", 0, none},
      {"optix_no_inline_layer_funcs", 0, none},
      {"optix_no_merge_layer_funcs", 0, none},
      {"optix_no_inline_rend_lib", 0, none},
      {"optix_no_rend_lib_bitcode", 0, none},
      {"optix_no_inline_thresh", 1, none},
      {"optix_force_inline_thresh", 1, none},
      {"optix_register_inline_funcs", 0, none},
      {"entry", 1, [](Parser& p, const Use& u) { p.job.entry_layers.push_back(u.args[0]); }},
      {"entryoutput", 1, [](Parser& p, const Use& u) { p.job.entry_outputs.push_back(u.args[0]); }},
      {"center", 0, flag(&ShadeJob::center)},
      {"debugnan", 0, flag(&ShadeJob::debug_nan)},
      {"debuguninit", 0, flag(&ShadeJob::debug_uninit)},
      {"groupoutputs", 0, none}, // renderer outputs on the group: what Lobe always does
      {"oslquery", 0, flag(&ShadeJob::oslquery)},
      {"print-groupdata", 0, flag(&ShadeJob::print_groupdata)},
      {"inbuffer", 0, none}, // Lobe always compiles the source in memory
      {"no-output-placement", 0, none},
      {"shadeimage", 0, none},
      {"noshadeimage", 0, none},
      {"expr", 1,
       [](Parser& p, const Use& u) { // the parameters given before it are its, as testshade's
         p.job.expressions.push_back(u.args[0]);
         p.expr_values.push_back(std::move(p.pending));
         p.pending.clear();
       }},
      // testshade 1.13.12 takes --offsetuv and sets nothing with it (its --offsetst offsets):
      // accepted and ignored, so that a command line prints what testshade's prints.
      {"offsetuv", 2, none},
      {"offsetst", 2,
       [](Parser& p, const Use& u) {
         p.job.offset_u = to_f(u.args[0]);
         p.job.offset_v = to_f(u.args[1]);
       }},
      {"scaleuv", 2,
       [](Parser& p, const Use& u) {
         p.job.scale_u = to_f(u.args[0]);
         p.job.scale_v = to_f(u.args[1]);
       }},
      {"scalest", 2,
       [](Parser& p, const Use& u) {
         p.job.scale_u = to_f(u.args[0]);
         p.job.scale_v = to_f(u.args[1]);
       }},
      {"userdata", 2,
       [](Parser& p, const Use& u) {
         p.job.userdata.push_back({u.args[0], read_typed_value(u.mod("type"), u.args[1])});
       }},
      {"userdata_isconnected", 0, flag(&ShadeJob::userdata_isconnected)},
      {"locale", 1, [](Parser& p, const Use& u) { p.job.locale = u.args[0]; }},
      {"use_rs_bitcode", 0, none},
      {"jbufferMB", 1, none},
  };
  return kOptions;
}

// -I dir, -Idir, -D NAME[=v], -U NAME: Lobe's preprocessor options (oslc's spellings).
bool preprocessor_option(ShadeJob& job, int argc, char** argv, int& i) {
  std::string a = argv[i];
  if (a.size() < 2 || a[0] != '-' || !std::strchr("IDU", a[1])) return false;
  std::string v = a.size() > 2 ? a.substr(2) : (i + 1 < argc ? argv[++i] : "");
  (a[1] == 'I'   ? job.compile.include_dirs
   : a[1] == 'D' ? job.compile.defines
                 : job.compile.undefines)
      .push_back(v);
  return true;
}

} // namespace

void print_shade_help() {
  std::printf(
      "lobe shade -- run a shader group over a grid of points, as OSL's testshade\n\n"
      "Usage: lobe shade [options] shader...\n\n"
      "Every option takes one dash or two; --param, --userdata and --reparam take modifiers\n"
      "(--param:type=color:interpolated=1).\n\n"
      "    --help                       Print this message\n"
      "    -v                           Verbose: print the group before shading\n"
      "    -t NTHREADS                  Threads (default 0: one per core); output order never\n"
      "                                 depends on it\n"
      "    --res XRES YRES, -g X Y      Grid size (default 1 1)\n"
      "    --options LIST               ShadingSystem options, name=value[,...]\n"
      "    --texoptions LIST            TextureSystem options (accepted)\n"
      "    --colorspace NAME            Colour space (Rec709, ACEScg, ...)\n"
      "    -o VARIABLE FILENAME         An output image (FILENAME 'null': none)\n"
      "    -d uint8|half|float          Pixel type of output images\n"
      "    --print                      Print the outputs at every point instead of saving them\n"
      "    --groupname NAME             The group's name\n"
      "    --layer NAME                 Name of the next layer\n"
      "    --param NAME VALUE           An instance value for the next layer (type=T,\n"
      "                                 interpolated=1, interactive=1, lockgeom=0|1)\n"
      "    --shader SHADER LAYERNAME    Declare a layer\n"
      "    --connect FROMLAYER FROMOUTPUT TOLAYER TOINPUT\n"
      "    --reparam LAYER PARAM VALUE  Change an interactive parameter from the 2nd iteration\n"
      "    --group CMD                  A whole group (text or a file)\n"
      "    --archivegroup FILE          Accepted (Lobe writes no archive)\n"
      "    --raytype NAME               Ray type (default camera)\n"
      "    --raytype_opt                Specialise on the ray type\n"
      "    --iters N                    Shade the grid N times\n"
      "    -O0 -O1 -O2                  Optimisation (-O0: no specialisation)\n"
      "    --entry LAYER                Run this layer (repeatable) instead of the group\n"
      "    --entryoutput NAME           An output the group must keep (repeatable)\n"
      "    --center                     Shade pixel centres\n"
      "    --debugnan                   Report NaN and Inf results of every op\n"
      "    --debuguninit                Report reads of uninitialised values\n"
      "    --groupoutputs               Accepted (outputs are per group in Lobe)\n"
      "    --expr EXPR                  A layer from an expression\n"
      "    --offsetst U V, --scaleuv U V  Offset and scale u and v (and P)\n"
      "    --offsetuv U V               Accepted and ignored, as testshade 1.13.12 does\n"
      "    --userdata NAME VALUE        User data (type=T)\n"
      "    --userdata_isconnected       isconnected() is 1 for parameters that take user data\n"
      "    --vary_pdxdy --vary_udxdy --vary_vdxdy  Varying derivatives\n"
      "    --runstats, --stats          Timing and compile statistics\n"
      "    --print-groupdata            Print the group data size\n"
      "    --oslquery                   Print the layers' parameters\n"
      "    --locale NAME                Set the locale\n"
      "    -I DIR, -D NAME[=V], -U NAME Include/search directory, preprocessor definitions\n"
      "Accepted without effect (OSL's own machinery): --optix*, --batched, --debug, --debug2,\n"
      "--llvm_debug, --llvm_opt N, --profile, --saveptx, --warmup, --inbuffer,\n"
      "--no-output-placement, --shadeimage, --noshadeimage, --use_rs_bitcode, --jbufferMB N.\n");
}

int parse_shade_args(int argc, char** argv, ShadeJob& job) {
  Parser p{job};
  for (int i = 1; i < argc && p.status == 0; ++i) {
    std::string a = argv[i];
    if (a.size() > 1 && a[0] == '-' && !std::isdigit(static_cast<unsigned char>(a[1]))) {
      if (preprocessor_option(job, argc, argv, i)) continue;
      std::string body = a.substr(a[1] == '-' ? 2 : 1);
      Use use;
      std::string name = body.substr(0, body.find(':'));
      for (size_t c = body.find(':'); c != std::string::npos;) { // :key=value modifiers
        size_t next = body.find(':', c + 1);
        std::string m =
            body.substr(c + 1, next == std::string::npos ? std::string::npos : next - c - 1);
        size_t eq = m.find('=');
        use.mods[m.substr(0, eq)] = eq == std::string::npos ? "" : m.substr(eq + 1);
        c = next;
      }
      const Option* opt = nullptr;
      for (const Option& o : options())
        if (name == o.name) opt = &o;
      if (!opt) {
        std::fprintf(stderr,
                     "lobe shade: error: Invalid option \"%s\" (lobe shade --help lists them)\n",
                     a.c_str());
        return 1;
      }
      for (int k = 0; k < opt->nargs; ++k) {
        if (i + 1 >= argc) {
          std::fprintf(stderr, "lobe shade: error: Missing parameter %d from option \"%s\"\n",
                       k + 1, a.c_str());
          return 1;
        }
        use.args.push_back(argv[++i]);
      }
      opt->handle(p, use);
    } else {
      p.add_layer(a, "");
    }
  }
  if (p.status) return p.status;
  if (job.group.layers.empty() && job.expressions.empty()) {
    std::fprintf(stderr, "ERROR: No shader or group was specified.\n\n"
                         "Try `lobe shade --help` for an explanation of all arguments\n");
    return 1;
  }
  if (!p.pending.empty()) {
    std::string names;
    for (const InstanceValue& v : p.pending) {
      if (!names.empty()) names += ' ';
      names += v.name;
    }
    std::fprintf(stderr,
                 "ERROR: Pending parameters without a shader: %s\n"
                 "Did you mistakenly put --param after the shader declaration?\n",
                 names.c_str());
    return 1;
  }
  for (size_t k = 0; k < job.expressions.size(); ++k) // --expr layers come after the others,
    job.group.layers.push_back(
        {"expr_" + std::to_string(k), // named as any layer is (expr_0_0)
         "expr_" + std::to_string(k) + "_" + std::to_string(job.group.layers.size()),
         std::move(p.expr_values[k])});
  for (const Connection& c : job.connects) job.group.connections.push_back(c);
  if (!job.groupname.empty())
    job.group.name = job.groupname;
  else if (job.group.name.empty())
    job.group.name = "unnamed_group_" + std::to_string(std::max(1, p.groups_begun));
  if (!job.outputs_given) job.outputs.push_back({"", "Cout", "null"});
  apply_options(job);
  return 0;
}

} // namespace lobe::cli
