#include "engine/base/json_errors.h"

#include <google/protobuf/descriptor.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

namespace pfem {

namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;

const FieldDescriptor* find_field(const Descriptor& d, const std::string& key) {
  for (int i = 0; i < d.field_count(); ++i)
    if (d.field(i)->name() == key || d.field(i)->json_name() == key) return d.field(i);
  return nullptr;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (std::tolower(a[i - 1]) != std::tolower(b[j - 1]))});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// Every path below the root message where a field called key exists ("structure.self_weight",
// "structure.materials[].bilinear.fy" in a model).
void paths_of(const Descriptor& d, const std::string& prefix, const std::string& key, int depth,
              std::vector<std::string>& out) {
  for (int i = 0; i < d.field_count(); ++i) {
    const FieldDescriptor* f = d.field(i);
    const std::string path = prefix + f->name() + (f->is_repeated() ? "[]" : "");
    if (f->name() == key || f->json_name() == key) out.push_back(prefix + f->name());
    if (f->message_type() && depth < 6) paths_of(*f->message_type(), path + ".", key, depth + 1, out);
  }
}

// The unknown field `key` of message d: where a field of that name is (the same name in another
// message), or else the closest name of d (at most a third of its letters off, at least one).
std::string unknown_field_message(const Descriptor& root, const Descriptor& d, const std::string& key) {
  const std::string message = "unknown field of " + d.name();
  std::vector<std::string> places;
  paths_of(root, "", key, 0, places);
  if (!places.empty()) {
    std::string where;
    for (std::size_t i = 0; i < places.size() && i < 3; ++i) where += (i ? " or " : "") + places[i];
    return message + "; it belongs in " + where;
  }
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(1, key.size() / 3) + 1;
  for (int i = 0; i < d.field_count(); ++i)
    if (const std::size_t e = edit_distance(key, d.field(i)->name()); e < best_distance)
      best = d.field(i)->name(), best_distance = e;
  return best.empty() ? message : message + "; did you mean '" + best + "'?";
}

// The JSON value v in words, for a message ("the string \"box\"", "a list").
std::string json_kind(const nlohmann::ordered_json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "a list";
    case nlohmann::json::value_t::string: {
      const std::string text = v.get<std::string>();
      return "the string \"" + (text.size() > 24 ? text.substr(0, 24) + "..." : text) + "\"";
    }
    case nlohmann::json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case nlohmann::json::value_t::null: return "null";
    default: return "the number " + v.dump();
  }
}

// A number as proto3 JSON takes it: a JSON number or a string holding one (integral for an
// integer field).
bool is_number(const nlohmann::ordered_json& v, bool integral) {
  double x = 0.0;
  if (v.is_number()) {
    x = v.get<double>();
  } else if (v.is_string()) {
    const std::string text = v.get<std::string>();
    if (!integral && (text == "NaN" || text == "Infinity" || text == "-Infinity")) return true;
    std::istringstream in(text);
    if (!(in >> x) || !(in >> std::ws).eof()) return false;
  } else {
    return false;
  }
  return !integral || (std::isfinite(x) && x == std::floor(x));
}

// What one value of field f must be, in words, or "" when v is such a value (null is: the
// field's default).
std::string expected_instead(const FieldDescriptor& f, const nlohmann::ordered_json& v) {
  if (v.is_null()) return "";
  switch (f.cpp_type()) {
    case FieldDescriptor::CPPTYPE_MESSAGE:
      return v.is_object() ? "" : "an object (" + f.message_type()->name() + ")";
    case FieldDescriptor::CPPTYPE_STRING: return v.is_string() ? "" : "a string";
    case FieldDescriptor::CPPTYPE_BOOL: return v.is_boolean() ? "" : "true or false";
    case FieldDescriptor::CPPTYPE_ENUM: {
      if ((v.is_string() && f.enum_type()->FindValueByName(v.get<std::string>())) || v.is_number_integer()) return "";
      std::string names;
      for (int i = 0; i < f.enum_type()->value_count(); ++i) names += (i ? ", " : "") + f.enum_type()->value(i)->name();
      return "one of " + names;
    }
    case FieldDescriptor::CPPTYPE_DOUBLE:
    case FieldDescriptor::CPPTYPE_FLOAT: return is_number(v, false) ? "" : "a number";
    default: return is_number(v, true) ? "" : "a whole number";
  }
}

// The problems protobuf's parser stops at, in the JSON value v as message d, each with its path:
// unknown fields (with a suggestion) and values of the wrong kind (a list for an object, a
// string for a number); the values inside are checked too.
void field_errors(const nlohmann::ordered_json& v, const Descriptor& root, const Descriptor& d,
                  const std::string& path, std::vector<FieldError>& out) {
  if (!v.is_object()) return;
  for (const auto& [key, value] : v.items()) {
    const std::string here = path.empty() ? key : path + "." + key;
    const FieldDescriptor* f = find_field(d, key);
    if (!f) {
      out.push_back({here, unknown_field_message(root, d, key)});
      continue;
    }
    // A repeated field takes a list (protobuf also takes a single value for a one-entry list,
    // whose path is then that of the entry).
    const bool list = f->is_repeated() && value.is_array();
    for (std::size_t i = 0; i < (list ? value.size() : 1); ++i) {
      const auto& item = list ? value[i] : value;
      const bool entry = f->is_repeated() && (list || item.is_object());
      const std::string at = entry ? here + "[" + std::to_string(i) + "]" : here;
      if (const std::string expected = expected_instead(*f, item); !expected.empty()) {
        const std::string takes = f->is_repeated() && !list ? "a list" : expected;
        out.push_back({at, "expected " + takes + ", found " + json_kind(item)});
      } else if (f->message_type()) {
        field_errors(item, root, *f->message_type(), at, out);
      }
    }
  }
}

}  // namespace

std::vector<FieldError> json_errors(std::string_view json, const Descriptor& root, const std::string& name,
                                    std::string protobuf_message) {
  try {
    const auto value = nlohmann::ordered_json::parse(json.begin(), json.end());  // keys in file order
    std::vector<FieldError> errors;
    field_errors(value, root, root, "", errors);
    if (!errors.empty()) return errors;
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();  // "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
    const std::string marker = "parse error at ";
    if (const auto at = what.find(marker); at != std::string::npos) what = what.substr(at + marker.size());
    return {{name, "invalid JSON at " + what}};
  } catch (const nlohmann::json::exception& e) {  // a number out of range: 2.1e555 (the fuzzer's)
    std::string what = e.what();  // "[json.exception.out_of_range.406] number overflow parsing '...'"
    if (const auto at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
    return {{name, "invalid JSON: " + what}};
  }
  std::replace(protobuf_message.begin(), protobuf_message.end(), '\n', ' ');  // spans lines (text, caret)
  return {{name, "invalid JSON: " + protobuf_message}};
}

}  // namespace pfem
