// `lobe shade`'s command line: OSL testshade's options, with testshade's meaning (every option
// with one dash or two; `:key=value` modifiers), plus Lobe's -I/-D/-U. `lobe shade --help`
// lists them; docs/cli.md describes each.
#pragma once

#include "lobe/shadingsys.h"
#include "shade_values.h"

#include <string>
#include <vector>

namespace lobe::cli {

struct ShadeOutput {
  std::string layer; // "" : the last layer that has an output parameter `var`
  std::string var;
  std::string file; // "null": none (still a renderer output)
};

struct ShadeUserDatum {
  std::string name;
  TypedValue value;
};

struct ShadeReparam {
  std::string layer, param;
  InstanceValue value;
};

struct ShadeJob {
  ShaderGroup group;                // layers from the command line or --group, then connections
  std::string group_spec;           // --group's text (a file's contents), which -v echoes
  std::vector<Connection> connects; // from --connect (made after every layer is declared)
  std::vector<ShadeUserDatum> userdata;
  std::vector<ShadeReparam> reparams;
  std::vector<ShadeOutput> outputs;     // -o, in order; the implicit "-o Cout null" when none
  bool outputs_given = false;           // any -o on the command line
  std::vector<std::string> expressions; // --expr, one layer each
  std::vector<std::string> entry_layers, entry_outputs;

  int xres = 1, yres = 1;
  int threads = 0; // 0: one per core
  int iters = 1;
  bool center = false;
  std::string raytype = "camera";
  bool raytype_opt = false;
  std::string dataformat; // -d: "" (the output's own type), "uint8", "half", "float"
  bool print = false;
  float offset_u = 0, offset_v = 0, scale_u = 1, scale_v = 1;
  bool vary_pdxdy = false, vary_udxdy = false, vary_vdxdy = false;
  bool debug_nan = false, debug_uninit = false;
  bool runstats = false, verbose = false, print_groupdata = false, oslquery = false;
  bool userdata_isconnected = false;
  std::string groupname;
  std::string colorspace;
  std::string options, texoptions; // comma-separated name=value lists
  std::string locale;
  std::string archivegroup;
  CompileOptions compile;
  bool error_repeats = false; // --options error_repeats=1
  bool range_checking = true; // --options range_checking=0
};

// Parses argv (argv[0] is "shade"). Returns 0 to shade, -1 after --help (exit 0), or an exit
// status after a usage error (printed).
int parse_shade_args(int argc, char** argv, ShadeJob& job);

// testshade's --help, adapted.
void print_shade_help();

} // namespace lobe::cli
