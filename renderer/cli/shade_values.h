// How `lobe shade` reads the value after --param, --reparam and --userdata, as OSL's testshade
// 1.13 does (measured against it):
//
// - `:type=T` names the type; without it (or with a name that is no type) the type is guessed
//   from the text: 16 comma-separated numbers are a matrix, 3 a vector ("1,2,3", "1, 2, 3"),
//   a whole int an int, a whole float a float ("2.", "1e3", "0x10"), anything else a string;
// - numbers are separated by spaces or commas and read as C's atof/atoi read them (junk after
//   a number is ignored); missing values are 0 and extra ones ignored (no broadcast:
//   `type=color 0.5` is 0.5 0 0);
// - a string is the whole text; a string array is split at commas exactly ("x, y" is "x" and
//   " y").
#pragma once

#include "lobe/renderer_services.h"
#include "lobe/shadingsys.h"

#include <optional>
#include <string>
#include <vector>

namespace lobe::cli {

// testshade's type guess for an untyped value ("matrix", "vector", "int", "float", "string").
std::string guess_type(const std::string& text);

// The declared type: `type_name` if it names one, else the guess.
DataType value_type(const std::string& type_name, const std::string& text);

// The words of a value of `type`, per the rules above (one word for a scalar string).
std::vector<std::string> value_words(const std::string& text, const DataType& type);

// An instance value for --param (OSL's rules, lobe/shadingsys.h).
InstanceValue param_value(const std::string& type_name, const std::string& name,
                          const std::string& text);

// A typed value with its numbers read: `type`'s elements x components scalars, missing 0.
struct TypedValue {
  DataType type;
  std::vector<float> floats;      // float-based types
  std::vector<int32_t> ints;      // int
  std::vector<std::string> words; // string (and every type: the words as read)
};
TypedValue read_typed_value(const std::string& type_name, const std::string& text);

} // namespace lobe::cli
